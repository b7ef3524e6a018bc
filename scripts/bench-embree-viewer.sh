#!/usr/bin/env bash
# The `deferred` frame side by side with Embree's own `viewer_stream` tutorial (Debian
# embree-tools) drawing the exported atrium from the same camera at the same size and thread
# count: the issue-12 figure "deferred <= 0.6x viewer_stream". viewer_stream traces one primary
# ray per pixel in streams and shades it with its eye-light default; Tandem's frame is the whole
# `deferred` pipeline (rasterized G-buffer, textures, six lights, tonemap).
# Usage: scripts/bench-embree-viewer.sh [WIDTH] [HEIGHT] [PIPELINE]   (default 1280 720 deferred)
set -euo pipefail
W="${1:-1280}"
H="${2:-720}"
P="${3:-deferred}"
# shellcheck source=scripts/embree-side-by-side.sh
source "$(dirname "$0")/embree-side-by-side.sh" viewer_stream
D="$SCENE_DIR"
echo "atrium, ${W}x${H}, 2 threads, camera (-11, 2.2, 9) -> (4, 2.5, -3), 60 deg"
embree_out=$(viewer_stream -i "$D/atrium.obj" --size "$W" "$H" --vp -11 2.2 9 --vi 4 2.5 -3 \
  --vu 0 1 0 --fov 60 --threads 2 --benchmark 2 10 -o "$D/embree.ppm" 2>&1)
fps=$(awk '/BENCHMARK_RENDER_AVG / {print $2}' <<<"$embree_out")
embree_ms=$(awk -v f="$fps" 'BEGIN {printf "%.2f", 1000 / f}')
tandem_ms=$("$T" bench atrium --pipeline "$P" --width "$W" --height "$H" --camera-pos -11,2.2,9 \
  --look-at 4,2.5,-3 --vfov 60 --threads 2 --frames 10 --warmup 2 2>&1 |
  awk '$1 == "frame" {print $2}')
echo "embree viewer_stream:   $embree_ms ms a frame (mean of 10 after 2)"
echo "tandem $P:  $tandem_ms ms a frame (median of 10 after 2)"
awk -v a="$tandem_ms" -v b="$embree_ms" 'BEGIN {printf "ratio: %.2fx viewer_stream'"'"'s frame time\n", a / b}'
