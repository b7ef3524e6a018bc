#!/usr/bin/env bash
# Reference path tracing throughput, side by side with Embree's own path tracer tutorial
# (Debian embree-tools) on the same OBJ scene, camera, lights, resolution, path length and
# thread count. Both count every ray traced (camera, bounce, shadow) over the sampling only.
# Usage: scripts/bench-embree-pathtracer.sh [SPP] [MAX_PATH_LENGTH]   (default 32 4)
set -euo pipefail
SPP="${1:-32}"
DEPTH="${2:-4}"
# shellcheck source=scripts/embree-side-by-side.sh
source "$(dirname "$0")/embree-side-by-side.sh" pathtracer
W="$SCENE_DIR"
# The built-in atrium's camera and its sun and four lamps (spot omitted: Embree's tutorial has
# none); Embree takes intensity x colour.
CAM_T=(--camera-pos -11,2.2,9 --look-at 4,2.5,-3 --vfov 60)
CAM_E=(--vp -11 2.2 9 --vi 4 2.5 -3 --vu 0 1 0 --fov 60)
LIGHTS_T=(--sun-light -0.3,-1,-0.4,3,1,0.93,0.8)
LIGHTS_E=(--directionallight -0.3 -1 -0.4 3 2.79 2.4)
for p in "-8 3 -5" "8 3 -5" "-8 3 5" "8 3 5"; do
  set -- $p
  LIGHTS_T+=(--point-light "$1,$2,$3,15,1,0.7,0.4")
  LIGHTS_E+=(--pointlight $1 $2 $3 15 10.5 6)
done
echo "atrium (exported OBJ, $(grep -c '^f ' "$W/atrium.obj") triangles), 640x360, path length $DEPTH, 2 threads"
tandem_out=$("$T" reference --scene "$W/atrium.obj" --width 640 --height 360 --spp "$SPP" \
  --max-depth "$DEPTH" "${CAM_T[@]}" "${LIGHTS_T[@]}" --threads 2 --no-cache --quiet --out "$W/tandem.png")
tandem=$(grep -o '[0-9.]* Mrays/s' <<<"$tandem_out" | cut -d' ' -f1)
embree_out=$(pathtracer -i "$W/atrium.obj" --size 640 360 "${CAM_E[@]}" --spp 1 \
  --max-path-length "$DEPTH" --threads 2 "${LIGHTS_E[@]}" --benchmark 1 "$SPP" -o "$W/embree.ppm" 2>&1)
embree=$(awk '/BENCHMARK_RENDER_MRAYPS_AVG / {print $2}' <<<"$embree_out")
echo "tandem reference ($SPP spp):      $tandem Mrays/s"
echo "embree pathtracer ($SPP frames):  $embree Mrays/s"
awk -v a="$tandem" -v b="$embree" 'BEGIN {printf "ratio: %.1f %% of Embree'"'"'s rate\n", 100 * a / b}'
