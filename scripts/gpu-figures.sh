#!/usr/bin/env bash
# The GPU figures of docs/benchmarks.md in one run, each measured side by side with the same binary
# on the machine's CPU cores (issue: "side by side in one run"): frame times of the heuristic
# hybrid's pipelines, the depth-of-field, foveated and motion-blur pipelines, the hybrid's SSIM
# against rt-only on the GPU, the graphics pipeline's visibility draw against the compute
# rasterizer, and the reference's ray rate (a still and an open shutter).
# Prepared for a lent GPU machine, where one `run` of the device tool must measure everything:
#
#   bash ../shared/tools/device-pack.sh
#   (device tool) run, carry [".dev"]:  TANDEM="bash .dev/on-device.sh" bash scripts/gpu-figures.sh
#
# TANDEM: how to run tandem (default: tandem on PATH). OUT: where the table (figures.md) and every
# raw report go (default out/gpu-figures; the device tool brings $OUT back). --quick: tiny sizes,
# to check the script itself (on lavapipe nothing it prints is a figure).
set -euo pipefail
T=${TANDEM:-tandem}
out=${OUT:-out/gpu-figures}
mkdir -p "$out"
out=$(cd "$out" && pwd)  # tandem may run from another folder (.dev/on-device.sh)
W=1280 H=720 frames=8 warm=2 spp=64 RW=640 RH=360
if [ "${1:-}" = --quick ]; then W=64 H=36 frames=1 warm=0 spp=2 RW=32 RH=18; fi

table="$out/figures.md"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
$T info --devices > "$out/devices.txt" 2>&1 || true
{
  echo "GPU figures, commit $commit, $(nproc) CPU cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
  echo
  sed 's/^/    /' "$out/devices.txt"
  echo
  echo "| pipeline | scene | CPU ms (all cores) | GPU ms | CPU / GPU |"
  echo "| --- | --- | ---: | ---: | ---: |"
} > "$table"

# The median frame of a bench report.
median() { awk '$1 == "frame" {print $2}' "$1"; }

row() {  # pipeline scene [more bench arguments]
  local name="$1-$(basename "$2" .json)" cpu gpu
  for d in cpu gpu; do
    $T bench "$2" --pipeline "$1" --device "$d" --width $W --height $H --frames $frames \
      --warmup $warm --json "$out/$name-$d.json" "${@:3}" > "$out/$name-$d.txt" 2>&1 ||
      echo "gpu-figures: bench $1 $2 on $d failed (see $out/$name-$d.txt)" >&2
  done
  cpu=$(median "$out/$name-cpu.txt")
  gpu=$(median "$out/$name-gpu.txt")
  awk -v p="$1" -v s="$(basename "$2" .json)" -v c="${cpu:-nan}" -v g="${gpu:-nan}" \
    'BEGIN { printf "| `%s` | %s | %.2f | %.2f | %.1fx |\n", p, s, c, g, (g > 0 ? c / g : 0) }' >> "$table"
}

row deferred atrium
row rt-only scenes/atrium_spheres.json
row hybrid-heuristic scenes/atrium_spheres.json
row hybrid-heuristic-taa scenes/atrium_spheres.json
row hybrid-budget scenes/atrium_spheres.json
row hybrid-all scenes/atrium_spheres.json
# Tan et al. 2022's depth of field, every pass on the GPU (issue 44's first figure).
row postfx-dof scenes/dof_fg.json
row hybrid-dof scenes/dof_fg.json
row rt-dof scenes/dof_fg.json
# Peres 2022's foveated stereo path tracing (both eyes, W x H each), every pass on the GPU.
row foveated-base scenes/foveated_pink_room.json
row foveated-nh3ld-temporal scenes/foveated_pink_room.json
# Interleaved sampling (traced and rasterized), the motion-blur baseline, the post-process, the
# hybrid.
row interleaved-rt scenes/interleaved_motion.json --shutter 0.1
row interleaved-raster scenes/interleaved_motion.json --shutter 0.1
row postfx-motion-blur scenes/interleaved_motion.json --shutter 0.1
row accumulation-motion-blur scenes/interleaved_motion.json --shutter 0.1
row hybrid-motion-blur scenes/interleaved_motion.json --shutter 0.1

# The hybrid against ray tracing everything, both on the GPU: the same frame, SSIM.
for p in hybrid-heuristic rt-only; do
  $T render scenes/atrium_spheres.json --pipeline "$p" --device gpu --width $W --height $H \
    --out "$out/$p.png" > "$out/render-$p.txt" 2>&1
done
$T compare "$out/hybrid-heuristic.png" "$out/rt-only.png" > "$out/ssim.txt" 2>&1 || true
{
  echo
  echo "hybrid-heuristic against rt-only (GPU, atrium_spheres ${W}x${H}): $(grep -E '^(ssim|psnr)' "$out/ssim.txt" | tr '\n' ' ')"
} >> "$table"

# Issue 43: the graphics pipeline's visibility draw against the compute rasterizer, both on the
# GPU, the visibility part of `deferred` (vbuffer_shading) on the atrium.
echo >> "$table"
for r in compute graphics; do
  $T bench atrium --pipeline deferred --device gpu --width $W --height $H --frames $frames \
    --warmup $warm --set vbuffer_shading.gpu_rasterizer=$r > "$out/rasterizer-$r.txt" 2>&1 || true
  echo "deferred atrium ${W}x${H} on the GPU, $r rasterizer: visibility $(awk '$1 == "vbuffer_shading/visibility" {print $2}' "$out/rasterizer-$r.txt") ms, frame $(median "$out/rasterizer-$r.txt") ms (medians)" >> "$table"
done

# The reference's ray rate on both devices (cornell, path tracer).
echo >> "$table"
for d in cpu gpu; do
  $T reference --scene cornell --device "$d" --spp $spp --width $RW --height $RH --no-cache \
    --out "$out/reference-$d.exr" > "$out/reference-$d.txt" 2>&1 || true
  echo "reference cornell ${RW}x${RH} ${spp} spp on $d: $(grep -o '[0-9.]* s (sampling[^)]*), [0-9.]* Mrays/s' "$out/reference-$d.txt")" >> "$table"
done
# The motion-blur experiments' ground truth: Whitted through an open shutter (moving objects).
for d in cpu gpu; do
  $T reference --scene scenes/interleaved_motion.json --shutter 0.1 --integrator whitted \
    --device "$d" --spp $spp --width $RW --height $RH --no-cache \
    --out "$out/reference-shutter-$d.exr" > "$out/reference-shutter-$d.txt" 2>&1 || true
  echo "reference interleaved_motion (0.1 s shutter, whitted) ${RW}x${RH} ${spp} spp on $d: $(grep -o '[0-9.]* s (sampling[^)]*), [0-9.]* Mrays/s' "$out/reference-shutter-$d.txt")" >> "$table"
done
cat "$table"
