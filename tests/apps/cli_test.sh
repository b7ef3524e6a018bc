#!/usr/bin/env bash
# Command-line behaviour: success paths write images; bad input exits non-zero with a message
# naming the problem and writes nothing.
set -u
T="$TANDEM"
D="$1"
rm -rf "$D" && mkdir -p "$D"
fail=0
check() { if ! eval "$2"; then echo "FAIL: $1"; fail=1; else echo "ok: $1"; fi; }
SRC="$(cd "$(dirname "$0")/../.." && pwd)"
# Third-party scenes: checks on them run when they are there and are named as skipped otherwise.
ASSETS="${TANDEM_ASSETS:-${DEFAULT_ASSETS:-$SRC/../shared/scenes}}"
skip() { echo "skip: $1 (third-party asset $2 not found; set TANDEM_ASSETS)"; }

# Expect a non-zero exit, a message containing $2, and an empty output folder.
expect_error() {
  local name="$1" fragment="$2"; shift 2
  local out
  out=$("$@" 2>&1); local rc=$?
  check "$name: non-zero exit" "[ $rc -ne 0 ]"
  check "$name: message names '$fragment'" "grep -qF -- \"$fragment\" <<<\"\$out\""
  check "$name: nothing written" "[ -z \"\$(ls -A $D/err 2>/dev/null)\" ]"
}

"$T" --help >/dev/null; check "help" "[ $? -eq 0 ]"
for v in render reference info compare bench experiment export view; do "$T" $v --help >/dev/null; check "$v --help" "[ $? -eq 0 ]"; done

"$T" render --width 160 --height 90 --out "$D/demo" --aov depth,normal,object_id,motion >/dev/null
# The default pipeline is the hybrid (ray-traced effects on the raster G-buffer, TAA).
check "render writes png+exr+aovs (default pipeline: the hybrid)" "[ -s $D/demo/cornell_hybrid-heuristic-taa.png ] && [ -s $D/demo/cornell_hybrid-heuristic-taa.exr ] && [ -s $D/demo/cornell_hybrid-heuristic-taa_object_id.png ]"
"$T" render cornell --width 160 --height 90 --pipeline deferred-rt-gbuffer --out "$D/rt.png" >/dev/null
check "rt pipeline renders" "[ -s $D/rt.png ]"
"$T" render "$SRC/scenes/dof_fg.json" --pipeline hybrid-dof --width 96 --height 54 --frames 3 \
  --aov coc,ray_mask,rt_hit --out "$D/dof/" >/dev/null
check "hybrid-dof renders with its buffers" "[ -s $D/dof/dof_fg_hybrid-dof.png ] && [ -s $D/dof/dof_fg_hybrid-dof_ray_mask.png ]"
out=$("$T" reference --scene "$SRC/scenes/dof_fg.json" --integrator whitted --spp 2 --width 48 --height 27 --no-cache --quiet --out "$D/dofref.png" 2>&1)
check "whitted reference renders" "[ -s $D/dofref.png ] && grep -q '2 spp' <<<\"\$out\""
"$T" render "$SRC/scenes/foveated_pink_room.json" --pipeline foveated-nh3ld --width 64 --height 72 \
  --aov pt_noisy,fov_layer,fov_mask --out "$D/fov/" >/dev/null
check "foveated-nh3ld renders the dual image with its buffers" \
  "[ -s $D/fov/foveated_pink_room_foveated-nh3ld.png ] && [ -s $D/fov/foveated_pink_room_foveated-nh3ld_fov_layer.png ]"
out=$("$T" reference --scene "$SRC/scenes/foveated_pink_room.json" --integrator diffuse-gi --spp 2 --width 32 --height 36 --no-cache --quiet --out "$D/fovref.png" 2>&1)
check "diffuse-gi reference renders" "[ -s $D/fovref.png ] && grep -q '2 spp' <<<\"\$out\""
"$T" render "$SRC/scenes/interleaved_both.json" --pipeline interleaved-raster --shutter 0.1 --width 64 --height 36 \
  --aov sample_time_lens,tile_layout,velocity --out "$D/il/" >/dev/null
check "interleaved-raster renders with its sample and tile views" \
  "[ -s $D/il/interleaved_both_interleaved-raster.png ] && [ -s $D/il/interleaved_both_interleaved-raster_tile_layout.png ] && [ -s $D/il/interleaved_both_interleaved-raster_sample_time_lens.png ]"
"$T" render "$SRC/scenes/interleaved_motion.json" --pipeline hybrid-motion-blur --shutter 0.1 --width 64 --height 36 \
  --aov mb_mask --out "$D/il/" >/dev/null
check "hybrid-motion-blur renders with its mask" "[ -s $D/il/interleaved_motion_hybrid-motion-blur_mb_mask.png ]"
"$T" render cornell --pipeline deferred --width 160 --height 90 --out "$D/deferred.png" >/dev/null
out=$("$T" compare "$D/deferred.png" "$D/rt.png" --heatmap "$D/heat.png" --flip-map "$D/flip.png")
check "compare raster vs rt output" "grep -q ssim <<<\"\$out\" && grep -q '^flip ' <<<\"\$out\" && [ -s $D/heat.png ] && [ -s $D/flip.png ]"
ssim=$(awk '/^ssim/ {print $2}' <<<"$out")
check "raster and rt images agree (SSIM >= 0.98, got $ssim)" "awk -v s=$ssim 'BEGIN{exit !(s >= 0.98)}'"
# A model of our own: two triangles of a floor and an emissive quad (MTL Ke) above it.
mkdir -p "$D/model"
printf 'newmtl floor\nKd 0.8 0.8 0.8\nnewmtl lamp\nKd 0 0 0\nKe 5 5 5\n' >"$D/model/m.mtl"
printf 'mtllib m.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\nusemtl floor\nf 1 4 3\nf 1 3 2\nusemtl lamp\nf 5 6 7\nf 5 7 8\n' >"$D/model/m.obj"
out=$("$T" info "$D/model/m.obj")
check "info counts triangles" "grep -q 'triangles    4' <<<\"\$out\""
check "info shows the converted light" "grep -q 'lights       1' <<<\"\$out\""
if [ -f "$ASSETS/CornellBox/CornellBox-Original.obj" ]; then
  out=$("$T" info "$ASSETS/CornellBox/CornellBox-Original.obj")
  check "info counts the Cornell box's triangles" "grep -q 'triangles    36' <<<\"\$out\""
else
  skip "info on the Cornell box" CornellBox/CornellBox-Original.obj
fi
"$T" bench --scene cornell --frames 3 --warmup 1 --width 64 --height 48 --json "$D/bench.json" >/dev/null
check "bench writes json" "grep -q median_ms $D/bench.json"
"$T" render "$D/model/m.obj" --width 96 --height 96 --sun-light -0.3,-1,-0.5,3 \
  --camera-pos 0,1.5,3 --look-at 0,0.3,0 --vfov 45 --out "$D/model.png" >/dev/null
check "camera and light overrides" "[ -s $D/model.png ]"

"$T" render "$SRC/scenes/cornell_statue.json" --width 96 --height 54 --out "$D/cb.png" >/dev/null
check "shipped scene file renders" "[ -s $D/cb.png ]"

"$T" render spheres --pipeline hybrid-budget --width 96 --height 54 --set heuristic.budget_ms=5 \
  --aov heuristic_mask --out "$D/hb/" >/dev/null
check "--set and the effect mask AOV" "[ -s $D/hb/spheres_hybrid-budget_heuristic_mask.png ]"

# The Walewski et al. 2019 experiment, tiny: every table, CSV and image it promises.
"$T" experiment heuristic --scenes spheres,"$SRC/scenes/cornell_spheres.json" --width 64 --height 36 \
  --warmup 1 --static-frames 1 --path-frames 3 --out "$D/exp" >/dev/null
check "experiment writes results.md with Tables 5 and 6" \
  "grep -q 'Table 5' $D/exp/results.md && grep -q 'Table 6' $D/exp/results.md && grep -q 'RAYT ONLY FRAME' $D/exp/results.md"
check "experiment records machine, build, commit and device" "grep -q 'hardware threads; [A-Za-z]* build; commit .*; device CPU' $D/exp/results.md"
check "experiment CSVs have a row per scene / frame" \
  "[ \$(wc -l < $D/exp/table5.csv) -eq 3 ] && [ \$(wc -l < $D/exp/table6.csv) -eq 3 ] && [ \$(wc -l < $D/exp/budget_frames.csv) -eq 7 ]"
check "experiment writes images" \
  "[ -s $D/exp/spheres_hybrid-heuristic.png ] && [ -s $D/exp/cornell_spheres_rt-only.png ] && [ -s $D/exp/spheres_heuristic_mask.png ] && [ -s $D/exp/spheres_hybrid-heuristic-fallbacks.png ]"
check "heuristic experiment reports the fallbacks against rt-only" \
  "grep -q 'SSIM with fallbacks vs rt-only' $D/exp/results.md && [ \$(head -1 $D/exp/table5.csv | tr ',' '\\n' | grep -c fallbacks) -eq 3 ]"
check "experiment: hybrid-all agrees with rt-only" \
  "awk -F, 'NR>1 && \$14 < 0.97 {bad=1} END {exit bad}' $D/exp/table5.csv"
check "heuristic experiment has an index page" "grep -q budget_tracking $D/exp/results.md && [ -s $D/exp/index.html ]"

# A data-driven sweep: one row per pipeline x value, plots, index, metrics against the reference.
"$T" experiment reference-convergence --scenes cornell --width 32 --height 18 --spp 32 \
  --cache "$D/cache-rc" --out "$D/rc" >/dev/null
check "sweep writes a row per swept value" "[ \$(wc -l < $D/rc/results.csv) -eq 5 ] && grep -q '^cornell,reference,4,' $D/rc/results.csv"
check "sweep writes index, images and flip maps" "[ -s $D/rc/index.html ] && [ -s $D/rc/cornell_reference_16.png ] && [ -s $D/rc/cornell_reference_16_flip.png ]"
if command -v gnuplot >/dev/null; then
  check "sweep draws plots" "[ -s $D/rc/cornell_rmse.png ] && [ -s $D/rc/cornell_ssim.png ]"
fi
check "more samples, less error" "awk -F, 'NR==2 {a=\$5} NR==5 {b=\$5} END {exit !(b < a)}' $D/rc/results.csv"

# Ground truth: rendered once, then served from the cache; split over 2 MPI processes it is the
# same image, byte for byte.
"$T" reference --scene cornell --width 64 --height 36 --spp 16 --cache "$D/cache" --out "$D/ref/" --quiet >/dev/null
check "reference writes png, exr and variance" "[ -s $D/ref/cornell_reference.png ] && [ -s $D/ref/cornell_reference.exr ] && [ -s $D/ref/cornell_reference.variance.exr ]"
check "reference fills the cache" "[ \$(ls $D/cache/*.json | wc -l) -eq 1 ]"
out=$("$T" reference --scene cornell --width 64 --height 36 --spp 16 --cache "$D/cache" --out "$D/ref2/" --quiet)
check "second reference comes from the cache" "grep -q 'from cache' <<<\"\$out\" && cmp -s $D/ref/cornell_reference.exr $D/ref2/cornell_reference.exr"
out=$("$T" reference --scene cornell --width 64 --height 36 --spp 16 --seed 5 --cache "$D/cache" --out "$D/ref3/" --quiet)
check "another seed is another cache entry" "! grep -q 'from cache' <<<\"\$out\""
if command -v mpirun >/dev/null; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -n 2 \
    "$T" reference --scene cornell --width 64 --height 36 --spp 16 --no-cache --out "$D/mpi/" --quiet >"$D/mpi.log" 2>&1
  check "mpirun -n 2 writes the single-process image" "grep -q '2 MPI processes' $D/mpi.log && cmp -s $D/ref/cornell_reference.exr $D/mpi/cornell_reference.exr"
else
  echo "skip: mpirun not installed (scripts/install-deps.sh installs it)"
fi

# The viewer, under a virtual display: a few frames of cornell, a screenshot of the output and
# a capture of the window itself, both matching `render` of the same view. A pipeline without
# temporal accumulation: with TAA the image depends on how many frames the viewer had drawn when
# it took the shot (SSIM 0.989-0.997 against one rendered frame, run to run).
if command -v xvfb-run >/dev/null && "$T" view --help >/dev/null 2>&1; then
  # Under ASan, LeakSanitizer reports ~112 bytes that Mesa's software GL driver allocates and
  # leaves behind when it is unloaded (the stack ends in "<unknown module>"), so leak checking is
  # off for this one run; the render worker's leaks are checked by the ViewerSupport unit tests.
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
  xvfb-run -a -s "-screen 0 1024x768x24" "$T" view --scene cornell --pipeline hybrid-heuristic \
    --width 320 --height 180 --frames 4 --screenshot "$D/view/shot.png" --window-capture "$D/view/window.png" --hide-ui --exit \
    >"$D/view.log" 2>&1
  check "view exits 0 with a screenshot and a window capture" "[ \$? -eq 0 ] && [ -s $D/view/shot.png ] && [ -s $D/view/window.png ]"
  "$T" render cornell --pipeline hybrid-heuristic --width 320 --height 180 \
    --out "$D/view/render.png" >/dev/null
  for f in shot window; do
    s=$("$T" compare "$D/view/render.png" "$D/view/$f.png" 2>/dev/null | awk '/^ssim/ {print $2}')
    check "view $f matches render (SSIM >= 0.99, got $s)" "awk -v s=${s:-0} 'BEGIN{exit !(s >= 0.99)}'"
  done
  check "view reports fps and its own cost" "grep -q 'viewer cost (upload + UI)' $D/view.log"
  # Stereo in the viewer: both eyes side by side (leak checking off for Mesa, as above).
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
  xvfb-run -a -s "-screen 0 1024x768x24" "$T" view --scene cornell --width 320 --height 90 \
    --stereo --frames 3 --screenshot "$D/view/stereo.png" --hide-ui --exit >"$D/view_stereo.log" 2>&1
  check "view --stereo writes a screenshot" "[ \$? -eq 0 ] && [ -s $D/view/stereo.png ]"
else
  echo "skip: xvfb-run not installed (scripts/install-deps.sh installs it)"
fi

# Stereo: --width and --height give one eye; the image holds both side by side.
"$T" render cornell --stereo --width 96 --height 64 --out "$D/stereo.png" >"$D/stereo.log"
check "render --stereo writes the dual image" "grep -q '192x64 (stereo)' $D/stereo.log && [ -s $D/stereo.png ]"
"$T" render cornell --pipeline deferred-taa --frames 4 --width 96 --height 64 --out "$D/taa.png" >/dev/null
check "deferred-taa renders" "[ -s $D/taa.png ]"
"$T" render cornell --pipeline accumulation-dof --aperture 0.3 --focus 3.9 --set accumulation.samples=4 --width 96 --height 64 --out "$D/accdof.png" >/dev/null
check "accumulation-dof renders" "[ -s $D/accdof.png ]"
"$T" experiment taa --width 64 --height 36 --frames 4 --path-frames 3 --out "$D/taa-exp" >/dev/null
check "taa experiment writes static and path tables" "[ -s $D/taa-exp/static.csv ] && [ -s $D/taa-exp/path.csv ] && grep -q deferred-taa $D/taa-exp/static.csv"
expect_error "negative ipd" "--ipd" "$T" render --ipd -1 --out "$D/err/x.png"
expect_error "bad blades on render" "--blades" "$T" render --blades 2 --out "$D/err/x.png"
expect_error "negative shutter on render" "--shutter" "$T" render --shutter -1 --out "$D/err/x.png"
echo '{"runner": "taa", "pairs": [["deferred"]]}' > "$D/badtaa.json"
expect_error "taa experiment bad pair" "pairs" "$T" experiment "$D/badtaa.json" --out "$D/err/exp"

mkdir -p "$D/err"
out=$(env -u DISPLAY -u WAYLAND_DISPLAY "$T" view --scene cornell 2>&1); rc=$?
check "view without a display fails and suggests render" "[ $rc -ne 0 ] && grep -q 'tandem render' <<<\"\$out\""
expect_error "reference bad spp" "--spp" "$T" reference --spp 0 --out "$D/err/r/"
expect_error "reference bad blades" "--blades" "$T" reference --blades 2 --out "$D/err/r/"
expect_error "negative aperture" "--aperture" "$T" render --pipeline hybrid-dof --aperture -0.1 --out "$D/err/x.png"
expect_error "zero focus distance" "--focus" "$T" render --pipeline hybrid-dof --focus 0 --out "$D/err/x.png"
expect_error "negative blades" "--blades" "$T" render --pipeline postfx-dof --blades -4 --out "$D/err/x.png"
expect_error "reference bad integrator" "--integrator" "$T" reference --integrator direct --out "$D/err/r/"
echo '{"base": "cornell", "camera": {"aperture": 0.1, "focusDistance": -1}}' > "$D/badlens.json"
expect_error "scene focus distance" "camera.focusDistance" "$T" render --scene "$D/badlens.json" --pipeline hybrid-dof --out "$D/err/x.png"
expect_error "reference negative shutter" "--shutter" "$T" reference --shutter -1 --out "$D/err/r/"
expect_error "--set unknown parameter" "unknown parameter" "$T" render --pipeline hybrid-heuristic --set heuristic.nope=1 --out "$D/err/x.png"
expect_error "--set out of range" "out of range" "$T" render --pipeline hybrid-heuristic --set heuristic.budget_ms=-3 --out "$D/err/x.png"
expect_error "--set unknown pass" "no pass labelled" "$T" render --set nopass.x=1 --out "$D/err/x.png"
expect_error "--set shadows taken twice" "shades with shadow maps already" "$T" render --pipeline hybrid-heuristic --set heuristic.shadows=budget --out "$D/err/x.png"
"$T" render --pipeline hybrid-heuristic --width 32 --height 18 --set heuristic.shadows=budget --set deferred_shading.shadows=off --out "$D/paper_rule.png" >/dev/null 2>&1
check "--set the paper's rule, deferred shadows off in either order" "[ -s $D/paper_rule.png ]"
expect_error "--set malformed" "pass.param=value" "$T" render --set budget --out "$D/err/x.png"
expect_error "experiment bad scene" "not found" "$T" experiment heuristic --scenes /nonexistent.json --out "$D/err/exp"
echo '{"runner": "sweep", "scenes": ["cornell"], "pipelines": ["deferred"], "widht": 3}' > "$D/badexp.json"
expect_error "experiment unknown field" "widht: unknown field" "$T" experiment "$D/badexp.json" --out "$D/err/exp"
echo '{"runner": "sweep", "scenes": ["cornell"], "pipelines": ["deferred"], "sweep": {"param": "nope.x", "values": [1]}}' > "$D/badexp2.json"
expect_error "experiment sweep of a missing pass" "no pipeline has" "$T" experiment "$D/badexp2.json" --out "$D/err/exp"
expect_error "unknown experiment" "not an experiment file" "$T" experiment nosuch --out "$D/err/exp"
expect_error "experiment bad frames" "--path-frames" "$T" experiment heuristic --path-frames 0 --out "$D/err/exp"
# Devices: a bad --device names the option; with no Vulkan driver at all (the loader pointed at
# none) `gpu` exits 2 saying so and `auto` renders on the CPU; with one (lavapipe in CI) `gpu`
# gives the CPU's image.
expect_error "bad device" "--device: expected auto, cpu or gpu" "$T" render --device cuda --out "$D/err/x.png"
expect_error "bad experiment device" "--device: expected auto, cpu or gpu" "$T" experiment heuristic --device cuda --out "$D/err/exp"
out=$(VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=/nonexistent.json "$T" render --device gpu --width 32 --height 18 --out "$D/err/x.png" 2>&1); rc=$?
check "--device gpu with no Vulkan driver: exit 2, says none was found, nothing written" \
  "[ $rc -eq 2 ] && grep -q 'no usable Vulkan device' <<<\"\$out\" && [ -z \"\$(ls -A $D/err 2>/dev/null)\" ]"
out=$(VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=/nonexistent.json "$T" render --device auto --pipeline deferred --width 32 --height 18 --out "$D/auto_cpu.png" 2>&1)
check "--device auto with no Vulkan driver renders on the CPU and says so" \
  "[ -s $D/auto_cpu.png ] && grep -q 'device: cpu' <<<\"\$out\""
out=$("$T" info --devices 2>&1); rc=$?
check "info --devices lists what Vulkan sees" "[ $rc -eq 0 ] && grep -q -- '--device gpu' <<<\"\$out\""
if grep -q '^--device gpu:  none' <<<"$out"; then
  echo "skip: --device gpu renders (no Vulkan device here)"
else
  "$T" render cornell --pipeline deferred --device gpu --width 96 --height 54 --out "$D/dev_gpu.exr" >/dev/null 2>&1
  "$T" render cornell --pipeline deferred --device cpu --width 96 --height 54 --out "$D/dev_cpu.exr" >/dev/null 2>&1
  out=$("$T" compare "$D/dev_gpu.exr" "$D/dev_cpu.exr" 2>&1)
  psnr=$(awk '/^psnr/ {print $2}' <<<"$out")
  check "--device gpu gives the CPU's image (PSNR >= 45 dB, got $psnr)" \
    "[ \"$psnr\" = inf ] || awk -v p=$psnr 'BEGIN{exit !(p >= 45)}'"
  out=$("$T" bench cornell --pipeline deferred --device gpu --width 64 --height 36 --frames 2 --warmup 0 --read-output 2>/dev/null)
  check "bench --read-output names the GPU and the moves' bytes" "grep -q 'device llvmpipe\|device .*GPU' <<<\"\$out\" && grep -q 'download:output.*MiB moved' <<<\"\$out\""
  out=$("$T" bench cornell --pipeline deferred --device gpu --width 64 --height 36 --frames 2 --warmup 0 2>/dev/null)
  check "bench on the GPU leaves the output there by default" "grep -q 'output left there' <<<\"\$out\" && ! grep -q 'download:output' <<<\"\$out\""
  # The reference on the GPU takes the CPU's Sobol samples: the same image to rounding.
  "$T" reference --scene cornell --device gpu --width 32 --height 18 --spp 4 --no-cache --quiet --out "$D/ref_gpu.exr" >/dev/null 2>&1
  "$T" reference --scene cornell --device cpu --width 32 --height 18 --spp 4 --no-cache --quiet --out "$D/ref_cpu.exr" >/dev/null 2>&1
  psnr=$(awk '/^psnr/ {print $2}' <<<"$("$T" compare "$D/ref_gpu.exr" "$D/ref_cpu.exr" 2>&1)")
  check "reference --device gpu takes the CPU's samples (PSNR >= 45 dB, got $psnr)" \
    "[ \"$psnr\" = inf ] || awk -v p=$psnr 'BEGIN{exit !(p >= 45)}'"
  # Split over 2 MPI processes, each tracing its stripes on the device: the same image, byte for
  # byte (each pixel's sums come from one process; the others add 0).
  if command -v mpirun >/dev/null; then
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -n 2 \
      "$T" reference --scene cornell --device gpu --width 32 --height 18 --spp 4 --no-cache --quiet \
      --out "$D/ref_gpu_mpi.exr" >"$D/mpi_gpu.log" 2>&1
    check "mpirun -n 2 --device gpu writes the single-process GPU image" \
      "grep -q '2 MPI processes' $D/mpi_gpu.log && cmp -s $D/ref_gpu.exr $D/ref_gpu_mpi.exr"
  fi
  "$T" experiment heuristic --device gpu --scenes spheres --width 32 --height 18 --warmup 0 \
    --static-frames 1 --path-frames 2 --out "$D/exp_gpu" >/dev/null 2>&1
  check "experiment --device gpu renders there and names the device" \
    "grep -q 'device llvmpipe\|device .*GPU' $D/exp_gpu/results.md && [ \$(wc -l < $D/exp_gpu/table5.csv) -eq 2 ]"
fi
expect_error "missing scene file" "not found" "$T" render --scene /nonexistent.obj --out "$D/err/x.png"
expect_error "unknown builtin" "not a file and not a built-in" "$T" render --scene nosuchscene --out "$D/err/x.png"
expect_error "zero width" "--width" "$T" render --width 0 --out "$D/err/x.png"
expect_error "absurd height" "--height" "$T" render --height 100000 --out "$D/err/x.png"
expect_error "unknown pipeline" "not a built-in pipeline" "$T" render --pipeline nope --out "$D/err/x.png"
expect_error "unknown aov" "has no buffer 'nope'" "$T" render --aov nope --out "$D/err/x.png"
expect_error "bad camera vector" "--camera-pos" "$T" render --camera-pos 1,2 --out "$D/err/x.png"
expect_error "parallel up" "--up" "$T" render --camera-pos 0,5,0 --look-at 0,0,0 --up 0,1,0 --out "$D/err/x.png"
expect_error "bad scene leaves no new folder" "not found" "$T" render --scene /nonexistent.obj --out "$D/err/newdir/"
echo '{"objects": [{"shape": "cube", "rotaton": [0,0,0]}]}' > "$D/bad.json"
expect_error "unknown scene field" "objects[0].rotaton: unknown field" "$T" render --scene "$D/bad.json" --out "$D/err/x.png"
expect_error "compare size mismatch" "differs" "$T" compare "$D/demo/cornell_hybrid-heuristic-taa.png" "$D/model.png"
expect_error "compare missing file" "not found" "$T" compare "$D/nope.png" "$D/bunny.png"
expect_error "info missing" "not found" "$T" info /nonexistent.gltf
expect_error "unknown named resolution" "--resolution" "$T" render cornell --resolution 8k --out "$D/err/x.png"
expect_error "foveation r1 below r0" "r1" "$T" render cornell --pipeline foveated-nh3ld --width 32 --height 18 \
  --set foveation.r0=40 --set foveation.r1=20 --out "$D/err/x.png"
out=$("$T" render --width abc 2>&1); rc=$?
check "a CLI parse error exits 2 naming the option" "[ $rc -eq 2 ] && grep -qF -- '--width' <<<\"\$out\""
expect_error "unwritable output extension" "--out" "$T" render cornell --width 32 --height 18 --out "$D/err/x.jpg"
# A full disk, simulated by a file-size limit: the run exits 2 naming the file and leaves nothing
# (no truncated PNG, no PNG without its EXR, no temporary).
expect_error "a PNG cut short by a full disk" "write failed" bash -c "ulimit -f 8; \"$T\" render cornell --width 320 --height 180 --out \"$D/err/\""
expect_error "PNG written but its EXR not: neither kept" ".exr" bash -c "ulimit -f 100; \"$T\" render cornell --width 320 --height 180 --out \"$D/err/\""
# A model with no lights: lit by the default rig (announced), or unlit on request.
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n' > "$D/quad.obj"
out=$("$T" render "$D/quad.obj" --pipeline deferred --width 64 --height 36 --out "$D/quad.png" 2>&1); rc=$?
check "unlit model: the default rig is announced" "[ $rc -eq 0 ] && grep -q 'default rig' <<<\"\$out\""
out=$("$T" info "$D/quad.obj" 2>/dev/null)
check "info names the default rig" "grep -q 'the default rig' <<<\"\$out\""
out=$("$T" info "$D/quad.obj" --default-lights off 2>&1)
check "--default-lights off leaves it unlit" "grep -q '^lights       0' <<<\"\$out\" && ! grep -q 'default rig' <<<\"\$out\""
expect_error "--default-lights value" "--default-lights" "$T" render "$D/quad.obj" --default-lights maybe --out "$D/err/x.png"
# A pipeline's passes and buffers, and its graph.
out=$("$T" pipeline hybrid-dof --dot "$D/hybrid-dof.dot")
check "pipeline lists its passes and history" "grep -q 'rt_dof' <<<\"\$out\" && grep -q '^history' <<<\"\$out\" && grep -q '^digraph' $D/hybrid-dof.dot"
expect_error "unknown pipeline" "no-such-pipeline" "$T" pipeline no-such-pipeline --dot "$D/err/x.dot"
expect_error "--dot names a graph file" "--dot" "$T" pipeline deferred --dot "$D/err/x.png"

# The demo gallery (what scripts/demo.sh shows), tiny: a contact sheet and index.html.
"$T" experiment demo --width 64 --height 36 --frames 2 --out "$D/gallery" >/dev/null
check "demo gallery writes its contact sheet and index" "[ -s $D/gallery/contact_sheet.png ] && [ -s $D/gallery/index.html ] && grep -q rt-dof $D/gallery/demo.csv"
expect_error "a size the machine cannot hold" "GiB" "$T" render cornell --width 16384 --height 16384 --stereo --out "$D/err/x.png"
expect_error "interleaved N not a multiple of k" "multiple" "$T" render cornell --pipeline interleaved-raster \
  --width 32 --height 18 --set interleaved_raster.samples=6 --set interleaved_raster.spp=4 --out "$D/err/x.png"
expect_error "interleaved k below 1" "out of range" "$T" render cornell --pipeline interleaved-rt \
  --width 32 --height 18 --set interleaved_rt.spp=0 --out "$D/err/x.png"
cat > "$D/tinyil.json" <<JSON
{"runner": "interleaved", "scenes": [["motion", "$SRC/scenes/cornell_motion_blur.json"]],
 "shutter": 0.5, "width": 32, "height": 18, "referenceSpp": 2, "seeds": 1, "pairCounts": [4, 8],
 "sweepSpp": 1, "sppCounts": [1], "sweepPairs": 4, "timingWidth": 32, "timingHeight": 18,
 "timingFrames": 1, "timingWarmup": 0, "timingPairs": 4, "timingSpp": 1, "strobePairs": 4}
JSON
"$T" experiment "$D/tinyil.json" --out "$D/tinyil" --no-cache >/dev/null 2>&1
check "interleaved experiment writes its tables" \
  "grep -q 'Figure check' $D/tinyil/results.md && [ -s $D/tinyil/tile_quality.csv ] && [ -s $D/tinyil/hybrid_motion_blur.csv ] && [ -s $D/tinyil/mb_motion_reference.png ]"
# The same experiment on a full disk (a 64 KiB tmpfs in a private mount namespace, where the
# machine allows mounting): exit 2 naming the file it could not write, and nothing left there.
mkdir -p "$D/tfs"
if unshare -m true 2>/dev/null; then
  out=$(unshare -m bash -c "mount -t tmpfs -o size=64k tmpfs '$D/tfs' && { '$T' experiment '$D/tinyil.json' --out '$D/tfs/exp' --no-cache >/dev/null; rc=\$?; echo \"left:\$(ls -A '$D/tfs')\"; exit \$rc; }" 2>&1); rc=$?
  check "experiment on a full tmpfs: exit 2 naming the file, nothing left (exit $rc)" \
    "[ $rc -eq 2 ] && grep -q 'No space left' <<<\"\$out\" && grep -q 'exp.partial/' <<<\"\$out\" && grep -qx 'left:' <<<\"\$out\""
else
  echo "skipped: experiment on a full tmpfs (this machine does not allow a private mount)"
fi
echo '{"runner": "interleaved", "scenes": [["m", "cornell"]], "pairCounts": [6], "sweepSpp": 4}' > "$D/badil.json"
expect_error "interleaved experiment bad N" "pairCounts / sweepSpp" "$T" experiment "$D/badil.json" --out "$D/err/exp"
echo '{"runner": "interleaved", "scenes": [["m", "cornell"]], "sequenceFrames": 1}' > "$D/badseq.json"
expect_error "interleaved experiment bad sequence" "sequenceFrames" "$T" experiment "$D/badseq.json" --out "$D/err/exp"
expect_error "a heuristic flag for another runner" "--static-frames" "$T" experiment hybrid-dof \
  --static-frames 3 --out "$D/err/exp"
expect_error "--path-frames for the DoF runner" "--path-frames" "$T" experiment hybrid-dof \
  --path-frames 3 --out "$D/err/exp"

expect_error "--set beyond a double" "'1e400' is not a finite number" "$T" render cornell \
  --pipeline hybrid-heuristic --width 16 --height 9 --set heuristic.budget=1e400 --out "$D/err/x.png"
echo '{"base": "cornell", "materials": {"m": {"emission": [1e39, 0, 0]}}}' > "$D/inf.json"
expect_error "a number beyond a float" "within +-3.4e38" "$T" render "$D/inf.json" --out "$D/err/x.png"
echo '{"base": "self.json"}' > "$D/self.json"
expect_error "a scene that names itself" "refers to itself" "$T" info "$D/self.json"

# Ctrl-C: a long reference or experiment stops before its next sample batch or frame (exit 130),
# leaving no output file, no experiment folder and no staging folder behind.
interrupt() {
  local name="$1"; shift
  "$@" >/dev/null 2>"$D/int.err" &
  local pid=$!
  sleep "${INTERRUPT_AFTER:-2}"
  local t0=$(date +%s%N)
  kill -INT $pid
  wait $pid; local rc=$?
  local ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  check "$name: stops on SIGINT within 2 s (took $ms ms, exit $rc)" "[ $rc -eq 130 ] && [ $ms -lt 2000 ]"
}
mkdir -p "$D/int"
interrupt "reference" "$T" reference --scene cornell --spp 1000000 --width 64 --height 36 --no-cache --quiet --out "$D/int/ref.png"
check "reference: nothing written" "[ ! -e $D/int/ref.png ]"
interrupt "experiment" "$T" experiment taa --no-cache --out "$D/int/exp"
check "experiment: no folder, no staging folder" "[ ! -e $D/int/exp ] && [ ! -e $D/int/exp.partial ]"
# On a CPU Vulkan one frame of rt-only at 720p runs for tens of seconds: the pass is submitted in
# bands and stops between them. The signal comes once the kernel is compiled and running (a
# compile, ~1 s on lavapipe and more under ASan, is not interruptible).
if grep -q '^--device gpu:  none' <<<"$("$T" info --devices 2>&1)"; then
  echo "skip: Ctrl-C during a GPU pass (no Vulkan device here)"
else
  INTERRUPT_AFTER=6 interrupt "render on the GPU" "$T" render atrium --pipeline rt-only --device gpu --width 1280 --height 720 --frames 1000 --out "$D/int/gpu.png"
  check "render on the GPU: nothing written" "[ ! -e $D/int/gpu.png ]"
fi

if [ $fail -ne 0 ]; then echo "cli tests failed"; exit 1; fi
echo "cli tests passed"
