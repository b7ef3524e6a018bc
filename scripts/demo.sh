#!/usr/bin/env bash
# What Tandem is for, in one picture: installs dependencies, builds (Release), then renders the
# demo gallery (experiments/demo.json) into out/: ray-traced shadows, reflections and
# refractions on a raster G-buffer next to the raster-only and the fully ray-traced frame, and
# hybrid depth of field next to the post-process gather and lens rays everywhere, each with its
# frame time. Open out/index.html, or out/contact_sheet.png. Extra arguments go to
# `tandem experiment` (e.g. --width 1280 --height 720, --frames 16).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
./build/release/apps/tandem/tandem experiment demo --out out/ "$@"
