#!/usr/bin/env bash
# The GPU figures of docs/benchmarks.md in one run, each measured side by side with the same binary
# on the machine's CPU cores (issue: "side by side in one run"): frame times of the heuristic
# hybrid's pipelines at 1280x720, the depth-of-field pipelines at 1920x1080, the foveated ones in
# stereo at the Quest 2's 1832x1920 per eye, the motion-blur ones at 1280x720; the hybrid's SSIM
# against rt-only on the GPU; the graphics pipeline's visibility draw against the compute
# rasterizer; the frame read back to the host (bench leaves it on the device); the reference's
# ray rate (a still and an open shutter); then, while time is left, the demo and the experiments
# on the GPU.
# Prepared for a lent GPU machine, where one `run` of the device tool must measure everything:
#
#   bash ../shared/tools/device-pack.sh
#   (device tool) run, carry [".dev"], timeout_s 600:
#     TANDEM="bash .dev/on-device.sh" bash scripts/gpu-figures.sh
#
# TANDEM: how to run tandem (default: tandem on PATH). OUT: where the results go (default
# out/gpu-figures; the device tool brings $OUT back, at most 8 files): figures.md, the table, is
# written line by line, and raw.tar.gz, every raw report, is repacked after each step,
# so a run stopped at its limit still returns what it measured. DEADLINE: seconds after which no
# new step starts (default 500, inside the tool's 600 s a command). --quick: tiny sizes, to check
# the script itself (on lavapipe nothing it prints is a figure).
set -euo pipefail
T=${TANDEM:-tandem}
out=${OUT:-out/gpu-figures}
mkdir -p "$out"
out=$(cd "$out" && pwd)  # tandem may run from another folder (.dev/on-device.sh)
# Raw reports and images outside $OUT (only 8 files come back from there): packed into
# raw.tar.gz, left in place for a local look.
raw=$(mktemp -d "${TMPDIR:-/tmp}/gpu-figures.XXXXXX")
echo "gpu-figures: raw reports in $raw" >&2
deadline=$((SECONDS + ${DEADLINE:-500}))
# Sizes: Walewski et al.'s tables, Tan et al.'s DoF shots, one Quest 2 eye; reference size; frames.
W=1280 H=720 DW=1920 DH=1080 FW=1832 FH=1920 RW=640 RH=360 frames=8 warm=2 spp=64
if [ "${1:-}" = --quick ]; then
  W=64 H=36 DW=64 DH=36 FW=32 FH=36 RW=32 RH=18 frames=1 warm=0 spp=2
fi

table="$out/figures.md"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
$T info --devices > "$raw/devices.txt" 2>&1 || true
{
  echo "GPU figures, commit $commit, $(nproc) CPU cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
  echo
  sed 's/^/    /' "$raw/devices.txt"
  echo
  echo "| pipeline | scene | size | CPU ms (all cores) | GPU ms | CPU / GPU |"
  echo "| --- | --- | --- | ---: | ---: | ---: |"
} > "$table"

# Every raw report into one archive (written aside, then moved: never half a file); EXR files and
# the experiments' pictures stay behind (a file comes back only under 16 MiB).
pack() {
  tar -czf "$out/raw.tar.gz.part" --exclude='*.exr' --exclude='exp-*/*.png' -C "$raw" . &&
    mv "$out/raw.tar.gz.part" "$out/raw.tar.gz"
}
# True while a new step may start; says once what was skipped when not.
left() {
  if [ $SECONDS -lt $deadline ]; then return 0; fi
  echo "gpu-figures: deadline reached, skipped: $*" | tee -a "$table" >&2
  return 1
}
# The median frame of a bench report.
median() { awk '$1 == "frame" {print $2}' "$1"; }

row() {  # width height pipeline scene [more bench arguments]
  local w=$1 h=$2 p=$3 scene=$4 name cpu gpu
  shift 4
  name="$p-$(basename "$scene" .json)"
  left "$name" || return 0
  for d in cpu gpu; do
    $T bench "$scene" --pipeline "$p" --device "$d" --width "$w" --height "$h" --frames $frames \
      --warmup $warm --json "$raw/$name-$d.json" "$@" > "$raw/$name-$d.txt" 2>&1 ||
      echo "gpu-figures: bench $p $scene on $d failed (see $name-$d.txt in raw.tar.gz)" >&2
  done
  cpu=$(median "$raw/$name-cpu.txt")
  gpu=$(median "$raw/$name-gpu.txt")
  awk -v p="$p" -v s="$(basename "$scene" .json)" -v z="${w}x${h}$(grep -q -- --stereo <<<"$*" && echo ' per eye, stereo')" \
    -v c="${cpu:-nan}" -v g="${gpu:-nan}" \
    'BEGIN { printf "| `%s` | %s | %s | %.2f | %.2f | %.1fx |\n", p, s, z, c, g, (g > 0 ? c / g : 0) }' >> "$table"
  pack
}

# Walewski et al. 2019's heuristic hybrid and its baselines (issue 43).
row $W $H deferred atrium
row $W $H rt-only scenes/atrium_spheres.json
row $W $H hybrid-heuristic scenes/atrium_spheres.json
row $W $H hybrid-heuristic-taa scenes/atrium_spheres.json
row $W $H hybrid-budget scenes/atrium_spheres.json
row $W $H hybrid-all scenes/atrium_spheres.json
# Tan et al. 2022's depth of field at the paper's 1920x1080 (issue 44: hybrid-dof <= 7 ms).
row $DW $DH hybrid-dof scenes/dof_fg.json
row $DW $DH rt-dof scenes/dof_fg.json
row $DW $DH postfx-dof scenes/dof_fg.json
# Peres 2022's foveated stereo path tracing, both eyes at the Quest 2's size (<= 11.1 ms).
row $FW $FH foveated-nh3ld-temporal scenes/foveated_pink_room.json --stereo
row $FW $FH foveated-base scenes/foveated_pink_room.json --stereo
# Interleaved sampling and hybrid motion blur (<= 8 ms), and their baselines.
row $W $H hybrid-motion-blur scenes/interleaved_motion.json --shutter 0.1
row $W $H interleaved-rt scenes/interleaved_motion.json --shutter 0.1
row $W $H interleaved-raster scenes/interleaved_motion.json --shutter 0.1
row $W $H postfx-motion-blur scenes/interleaved_motion.json --shutter 0.1
row $W $H accumulation-motion-blur scenes/interleaved_motion.json --shutter 0.1

# The hybrid against ray tracing everything, both on the GPU: the same frame, SSIM.
if left "hybrid-heuristic against rt-only"; then
  for p in hybrid-heuristic rt-only; do
    $T render scenes/atrium_spheres.json --pipeline "$p" --device gpu --width $W --height $H \
      --out "$raw/$p.png" > "$raw/render-$p.txt" 2>&1 || true
  done
  $T compare "$raw/hybrid-heuristic.png" "$raw/rt-only.png" > "$raw/ssim.txt" 2>&1 || true
  {
    echo
    echo "hybrid-heuristic against rt-only (GPU, atrium_spheres ${W}x${H}): $(grep -E '^(ssim|psnr)' "$raw/ssim.txt" | tr '\n' ' ')"
  } >> "$table"
  pack
fi

# Issue 43: the graphics pipeline's visibility draw against the compute rasterizer, both on the
# GPU, the visibility part of `deferred` (vbuffer_shading) on the atrium.
echo >> "$table"
for r in compute graphics; do
  left "rasterizer $r" || continue
  $T bench atrium --pipeline deferred --device gpu --width $W --height $H --frames $frames \
    --warmup $warm --set vbuffer_shading.gpu_rasterizer=$r > "$raw/rasterizer-$r.txt" 2>&1 || true
  echo "deferred atrium ${W}x${H} on the GPU, $r rasterizer: visibility $(awk '$1 == "vbuffer_shading/visibility" {print $2}' "$raw/rasterizer-$r.txt") ms, frame $(median "$raw/rasterizer-$r.txt") ms (medians)" >> "$table"
done
# What reading the frame back to the host costs (bench leaves it on the device by default).
if left "read-output"; then
  $T bench atrium --pipeline deferred --device gpu --width $W --height $H --frames $frames \
    --warmup $warm --read-output > "$raw/read-output.txt" 2>&1 || true
  echo "deferred atrium ${W}x${H} on the GPU with the output read back every frame: frame $(median "$raw/read-output.txt") ms, download:output $(awk '$1 == "download:output" {print $2}' "$raw/read-output.txt") ms (medians)" >> "$table"
fi
pack

# The reference's ray rate on both devices (cornell, path tracer).
echo >> "$table"
for d in cpu gpu; do
  left "reference on $d" || continue
  $T reference --scene cornell --device "$d" --spp $spp --width $RW --height $RH --no-cache \
    --out "$raw/reference-$d.exr" > "$raw/reference-$d.txt" 2>&1 || true
  echo "reference cornell ${RW}x${RH} ${spp} spp on $d: $(grep -o '[0-9.]* s (sampling[^)]*), [0-9.]* Mrays/s' "$raw/reference-$d.txt")" >> "$table"
done
# The motion-blur experiments' ground truth: Whitted through an open shutter (moving objects).
for d in cpu gpu; do
  left "shutter reference on $d" || continue
  $T reference --scene scenes/interleaved_motion.json --shutter 0.1 --integrator whitted \
    --device "$d" --spp $spp --width $RW --height $RH --no-cache \
    --out "$raw/reference-shutter-$d.exr" > "$raw/reference-shutter-$d.txt" 2>&1 || true
  echo "reference interleaved_motion (0.1 s shutter, whitted) ${RW}x${RH} ${spp} spp on $d: $(grep -o '[0-9.]* s (sampling[^)]*), [0-9.]* Mrays/s' "$raw/reference-shutter-$d.txt")" >> "$table"
done
pack

# While time is left: the demo and the experiments with every render on the GPU (their tables,
# results.md, into the archive), each stopped at the deadline.
quick=()
if [ "${1:-}" = --quick ]; then quick=(--width 64 --height 36 --warmup 0); fi
for e in demo hybrid-dof interleaved heuristic foveated; do
  left "experiment $e" || continue
  timeout $((deadline - SECONDS)) $T experiment "$e" --device gpu --out "$raw/exp-$e" \
    --cache "$raw/reference-cache" "${quick[@]}" > "$raw/exp-$e.txt" 2>&1 ||
    echo "gpu-figures: experiment $e stopped or failed (see exp-$e.txt in raw.tar.gz)" >&2
  rm -rf "$raw/reference-cache"
  echo "experiment $e on the GPU: $(ls "$raw/exp-$e"/*.md 2>/dev/null | wc -l) tables (exp-$e/ in raw.tar.gz)" >> "$table"
  pack
done
cat "$table"
