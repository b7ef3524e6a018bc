#!/usr/bin/env bash
# Builds the libFuzzer targets (clang) and runs each loader fuzzer for a bounded time.
# Usage: scripts/fuzz.sh [seconds-per-target, default 60]
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${1:-60}"
TANDEM_FUZZ_DEPS=1 bash scripts/install-deps.sh
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$(nproc)"
for t in scene_file obj gltf; do
  corpus="fuzz-corpus/$t"
  mkdir -p "$corpus"
  cp -n fuzz/seeds/$t/* "$corpus"/ 2>/dev/null || true
  echo "== fuzz_$t for ${secs}s"
  ./build/fuzz/fuzz/fuzz_$t -max_total_time="$secs" -rss_limit_mb=4096 -timeout=10 "$corpus"
done
