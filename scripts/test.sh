#!/usr/bin/env bash
# Installs dependencies, builds (Release) and runs every test with CTest.
# TANDEM_PRESET=asan runs the same suite under AddressSanitizer + UBSan; TANDEM_PRESET=tsan the
# Python concurrency tests under ThreadSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
preset="${TANDEM_PRESET:-release}"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
ctest --preset "$preset" -j "$(nproc)"
