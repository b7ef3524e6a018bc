#!/usr/bin/env bash
# Installs dependencies, builds (Release) and renders the built-in Cornell-style scene to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
./build/release/apps/tandem/tandem render --scene cornell --out out/ --aov depth,normal,object_id "$@"
