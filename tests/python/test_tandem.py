"""The Python module through the package users import: buffers equal to what the CLI writes,
settings checked as --set is, errors with the CLI's messages, the GIL released while rendering,
flat memory over many renders, references, metrics, experiments and multi-layer EXR."""
import os
import subprocess
import sys
import threading

import numpy as np
import OpenImageIO as oiio
import pytest

import tandem

SRC = os.environ.get("TANDEM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("TANDEM", "tandem")
SCRATCH = os.environ.get("TANDEM_TEST_SCRATCH", "/tmp/tandem-python-tests")


def scratch(name):
    d = os.path.join(SCRATCH, name)
    os.makedirs(d, exist_ok=True)
    return d


def read_exr(path):
    """{channel name: (h, w) float32} of an EXR, read by OpenImageIO."""
    inp = oiio.ImageInput.open(path)
    assert inp, oiio.geterror()
    spec = inp.spec()
    pixels = inp.read_image(0, 0, 0, spec.nchannels, "float")
    inp.close()
    return {name: pixels[:, :, k] for k, name in enumerate(spec.channelnames)}


def test_render_returns_named_float32_buffers():
    r = tandem.Renderer("cornell", pipeline="deferred", width=64, height=36)
    out = r.render()
    for name in ("hdr", "output", "depth", "normal", "object_id"):
        assert name in out, name
        assert out[name].dtype == np.float32
        assert out[name].shape[:2] == (36, 64)
        assert np.isfinite(out[name]).all()
    assert out["hdr"].shape == (36, 64, 3) and out["depth"].shape == (36, 64)
    assert out["hdr"].mean() > 0.02, "the Cornell box is lit"
    assert set(r.buffers()) <= set(out)
    only = r.render(buffers=["output", "depth"])
    assert set(only) == {"output", "depth"}
    with pytest.raises(tandem.Error, match="no buffer 'nope'"):
        r.render(buffers=["nope"])
    assert r.frame == 3
    t = r.timings()
    assert t["frame"] > 0 and "vbuffer_shading" in t["passes"]


def test_buffers_equal_what_the_cli_writes():
    d = scratch("cli_equal")
    subprocess.run([BINARY, "render", "cornell", "--pipeline", "hybrid-heuristic", "--width", "48",
                    "--height", "27", "--aov", "depth,normal", "--exr-layers",
                    os.path.join(d, "layers.exr"), "--out", os.path.join(d, "x.exr")],
                   check=True, capture_output=True)
    out = tandem.Renderer("cornell", pipeline="hybrid-heuristic", width=48, height=27).render()
    layers = read_exr(os.path.join(d, "layers.exr"))
    for k, c in enumerate("RGB"):
        np.testing.assert_array_equal(layers[c], out["hdr"][:, :, k])
    np.testing.assert_array_equal(layers["depth.Z"], out["depth"])
    for k, c in enumerate("XYZ"):
        np.testing.assert_array_equal(layers["normal." + c], out["normal"][:, :, k])
    # The single-file output is the display image; its AOV files hold the raw buffers.
    single = read_exr(os.path.join(d, "x.exr"))
    np.testing.assert_array_equal(single["R"], out["output"][:, :, 0])
    np.testing.assert_array_equal(read_exr(os.path.join(d, "x_depth.exr"))["Y"], out["depth"])
    # A buffer wider than four channels keeps them all, named as its pass declares them.
    subprocess.run([BINARY, "render", "cornell", "--pipeline", "hybrid-heuristic", "--width", "48",
                    "--height", "27", "--aov", "fallback", "--exr-layers",
                    os.path.join(d, "wide.exr"), "--out", os.path.join(d, "w.exr")],
                   check=True, capture_output=True)
    names = ["reflection_r", "reflection_g", "reflection_b", "refraction_r", "refraction_g",
             "refraction_b", "shadow_r", "shadow_g", "shadow_b", "covers_effect", "covers_shadow"]
    wide, alone = read_exr(os.path.join(d, "wide.exr")), read_exr(os.path.join(d, "w_fallback.exr"))
    assert out["fallback"].shape[2] == len(names)
    for k, n in enumerate(names):
        np.testing.assert_array_equal(wide["fallback." + n], out["fallback"][:, :, k])
        np.testing.assert_array_equal(alone[n], out["fallback"][:, :, k])


def test_settings_are_checked_as_set_is():
    r = tandem.Renderer("spheres", pipeline="hybrid-heuristic", width=32, height=18)
    r.set("heuristic.budget", 0)
    r.set("heuristic.budget=1000")
    with pytest.raises(tandem.Error, match="budget"):
        r.set("heuristic.budget", -1)
    with pytest.raises(tandem.Error, match="no_such_pass"):
        r.set("no_such_pass.x", 1)
    with pytest.raises(ValueError):  # tandem.Error is a ValueError
        r.set("heuristic.no_such_param", 1)


def test_budget_zero_traces_no_secondary_rays():
    r = tandem.Renderer("spheres", pipeline="hybrid-heuristic", width=64, height=36)
    r.set("deferred_shading.shadows=off")  # unshadowed: the shadows come from rays
    r.set("heuristic.shadows=budget")  # shadows traced with their objects (the paper's rule)
    r.set("heuristic.budget", 0)
    r.render()
    c = r.counters()
    assert c["heuristic/selected"] == 0 and c["rt_secondary/shadow_rays_per_pixel"] == 0
    r.set("heuristic.budget", 1e9)
    r.render()
    c = r.counters()
    assert c["heuristic/selected"] > 0 and c["rt_secondary/shadow_rays_per_pixel"] > 0
    # The default leaves every shadow to ss_fallback's maps: a budget buys no shadow ray.
    r.set("heuristic.shadows=maps")
    r.render()
    c = r.counters()
    assert c["heuristic/selected"] > 0 and c["rt_secondary/shadow_rays_per_pixel"] == 0


def test_counters_are_read_by_declared_name():
    r = tandem.Renderer("spheres", pipeline="hybrid-heuristic", width=32, height=18)
    assert "heuristic/selected" in r.declared_counters()
    assert r.counter("heuristic/selected") is None  # declared, nothing rendered yet
    r.render()
    assert r.counter("heuristic/selected") == r.counters()["heuristic/selected"]
    with pytest.raises(tandem.Error, match="heuristic/selectd"):
        r.counter("heuristic/selectd")


def test_scene_and_pipeline_as_dicts():
    scene = {"base": "cornell",
             "objects": [{"name": "statue", "shape": "knot", "material": "red",
                          "position": [0, 0.5, 0], "scale": [0.3, 0.3, 0.3]}]}
    with open(os.path.join(SRC, "pipelines", "deferred.json")) as f:
        import json
        pipeline = json.load(f)
    a = tandem.Renderer(scene, pipeline=pipeline, width=48, height=27).render()
    b = tandem.Renderer("cornell", pipeline="deferred", width=48, height=27).render()
    assert (a["object_id"] != b["object_id"]).any(), "the knot is drawn"
    with pytest.raises(tandem.Error, match=r"objects\[0\]\.shape"):
        tandem.Renderer({"objects": [{"shape": "teapot"}]}, pipeline="deferred")
    with pytest.raises(tandem.Error, match="passes"):
        tandem.Renderer("cornell", pipeline={"name": "x"})


def test_camera_lights_shutter_and_stereo():
    r = tandem.Renderer("cornell", pipeline="deferred", width=48, height=27)
    first = r.render()["output"]
    cam = r.camera
    assert "position" in cam and "lookAt" in cam
    r.set_camera(position=[0.5, 1.2, 3.0])
    moved = r.render()["output"]
    assert np.abs(moved - first).mean() > 1e-3
    assert r.camera["position"] == pytest.approx([0.5, 1.2, 3.0])
    r.lights = [{"type": "directional", "direction": [0, -1, 0], "intensity": 2}]
    assert len(r.lights) == 1 and r.lights[0]["type"] == "directional"
    with pytest.raises(tandem.Error, match=r"lights\[0\]"):
        r.lights = [{"type": "lamp"}]
    r.shutter = 0.05
    assert r.shutter == pytest.approx(0.05)
    r.stereo = True
    assert r.render()["output"].shape == (27, 96, 3), "both eyes side by side"


def test_errors_carry_the_cli_message():
    with pytest.raises(tandem.Error, match="file not found"):
        tandem.Renderer("/nonexistent/model.obj")
    with pytest.raises(tandem.Error, match="not a built-in"):
        tandem.Renderer("cornell", pipeline="no-such-pipeline")
    with pytest.raises(tandem.Error, match="width"):
        tandem.Renderer("cornell", width=0)
    with pytest.raises(tandem.Error, match="not an experiment"):
        tandem.experiment("no-such-experiment")
    with pytest.raises(TypeError):
        tandem.Renderer(42)


def test_rendering_releases_the_gil():
    r = tandem.Renderer("atrium", pipeline="rt-only", width=160, height=90)
    r.render()  # the BVH is built on the first frame
    done = threading.Event()

    def work():
        r.render(frames=3)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    spins = 0
    while not done.is_set():
        spins += 1
    t.join()
    # With the GIL held the loop would not run while the frames render.
    assert spins > 10000, spins


def rss_mib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


@pytest.mark.skipif("asan" in os.environ.get("LD_PRELOAD", ""),
                    reason="AddressSanitizer's quarantine holds freed memory")
def test_a_thousand_renders_keep_memory_flat():
    r = tandem.Renderer("cornell", pipeline="deferred", width=16, height=16)
    for _ in range(100):
        r.render()
    base = rss_mib()
    for _ in range(900):
        r.render()
    for _ in range(20):
        tandem.Renderer("spheres", pipeline="deferred", width=16, height=16).render()
    grown = rss_mib() - base
    assert grown < 16, f"resident memory grew {grown:.1f} MiB over 900 renders"


def test_reference_and_compare():
    ref = tandem.reference("cornell", integrator="whitted", spp=8, width=128, height=72, cache="")
    assert ref["hdr"].shape == (72, 128, 3) and ref["spp"] == 8 and not ref["from_cache"]
    out = tandem.Renderer("cornell", pipeline="rt-only", width=128, height=72).render()
    same = tandem.compare(out["output"], out["output"])
    assert same["rmse"] == 0 and same["ssim"] == pytest.approx(1.0)
    m = tandem.compare(ref["output"], out["output"], maps=True)
    # The same shading, a box filter of 8 samples against one sample at each pixel's centre.
    assert m["ssim"] > 0.95 and m["psnr"] > 28, m
    assert m["ssim_map"].shape == (72, 128) and m["flip_map"].shape[:2] == (72, 128)
    with pytest.raises(tandem.Error, match="shape"):
        tandem.compare(out["output"], out["output"][:10])
    cached_dir = scratch("reference_cache")
    first = tandem.reference("cornell", integrator="whitted", spp=2, width=16, height=9,
                             cache=cached_dir)
    again = tandem.reference("cornell", integrator="whitted", spp=2, width=16, height=9,
                             cache=cached_dir)
    assert again["from_cache"] and np.array_equal(first["hdr"], again["hdr"])


def test_experiment_returns_its_tables():
    res = tandem.experiment("demo", out=scratch("demo"), width=32, height=18, frames=2, spp=2)
    rows = res["tables"]["demo"]
    assert os.path.isfile(os.path.join(res["out"], "contact_sheet.png"))
    pipelines = {row["pipeline"] for row in rows}
    assert {"hybrid-heuristic-taa", "hybrid-dof", "foveated-nh3ld-temporal",
            "hybrid-motion-blur"} <= pipelines
    measured = [row for row in rows if row["pipeline"] != "reference" and row["SSIM"] != ""]
    assert all(isinstance(row["SSIM"], float) and 0 < row["SSIM"] <= 1 for row in measured)
    assert "demo" in dict(tandem.experiments())
    assert "hybrid-heuristic" in tandem.pipelines()


def test_experiment_device_is_checked():
    for device, says in ((3, "device: expected auto, cpu or gpu"),
                         ("cuda", "device: expected auto, cpu or gpu")):
        with pytest.raises(tandem.Error, match=says):
            tandem.experiment("heuristic", out=scratch("bad_device"), device=device)


def run_example(script, *args):
    """Runs examples/SCRIPT from a scratch folder that sees the repository's scenes."""
    d = scratch("example_" + script)
    if not os.path.exists(os.path.join(d, "scenes")):
        os.symlink(os.path.join(SRC, "scenes"), os.path.join(d, "scenes"))
    env = dict(os.environ, MPLBACKEND="Agg")
    res = subprocess.run([sys.executable,
                          os.path.join(SRC, "examples", script), *args], cwd=d, env=env,
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    return d, res.stdout


def test_readme_example_is_the_budget_sweep_script_and_runs():
    with open(os.path.join(SRC, "README.md")) as f:
        readme = f.read()
    with open(os.path.join(SRC, "examples", "budget_sweep.py")) as f:
        script = f.read()
    body = script[script.index("import matplotlib"):]
    assert body in readme, "README's Python example is examples/budget_sweep.py as written"
    d, out = run_example("budget_sweep.py")
    assert os.path.getsize(os.path.join(d, "budget_sweep.png")) > 1000
    assert out.count("SSIM") == 5


@pytest.mark.parametrize("script", ["walewski2019_table5.py", "tan2022_table2.py", "peres2022_table5.py",
                                    "foster2015_motion_blur.py"])
def test_seed_examples_print_their_table(script):
    args = ["--width", "48", "--height", "27", "--frames", "2"]
    if script != "walewski2019_table5.py":
        args += ["--spp", "2"]
    _, out = run_example(script, *args)
    rows = [line for line in out.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) >= 4, out
    assert all("nan" not in row for row in rows), out


def test_one_renderer_shared_by_threads_renders_whole_frames():
    # A static, non-temporal shot: every frame is the same picture, whoever renders it.
    r = tandem.Renderer("cornell", pipeline="deferred", width=48, height=27)
    expected = r.render()["output"].copy()
    errors, frames = [], []

    def work():
        try:
            for _ in range(15):
                frames.append(r.render(buffers=["output"])["output"].copy())
        except Exception as e:  # noqa: BLE001 - any failure fails the test below
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(frames) == 30
    for f in frames:
        assert np.array_equal(f, expected)
    assert r.frame == 31


def test_setters_wait_for_a_render_in_another_thread():
    r = tandem.Renderer("cornell", pipeline="deferred", width=48, height=27)
    shapes, errors = [], []

    def render():
        try:
            for _ in range(20):
                shapes.append(r.render(buffers=["output"])["output"].shape)
        except Exception as e:  # noqa: BLE001
            errors.append(e)

    t = threading.Thread(target=render)
    t.start()
    for i in range(20):
        r.stereo = i % 2 == 0
        r.shutter = 0.01 * i
    t.join()
    assert not errors
    # Each frame is whole: the mono or the stereo (side-by-side) image, never a mix.
    assert set(shapes) <= {(27, 48, 3), (27, 96, 3)}


def test_device_gpu_gives_the_cpu_image():
    try:
        gpu = tandem.Renderer("spheres", pipeline="deferred", width=64, height=36, device="gpu")
    except tandem.Error as e:
        pytest.skip(f"no Vulkan device: {e}")
    cpu = tandem.Renderer("spheres", pipeline="deferred", width=64, height=36, device="cpu")
    assert cpu.device == "cpu" and gpu.device != "cpu"
    a, b = cpu.render()["output"], gpu.render()["output"]
    # `deferred` runs on the device whole: nothing goes up, its buffers come back (Python reads
    # every one).
    moved = gpu.timings()["bytes"]
    assert moved["download:output"] == 64 * 36 * 3 * 4
    assert all(name.startswith("download:") for name in moved)
    assert cpu.timings()["bytes"] == {}
    # GLSL's rounding against C++'s, in shading and in the tonemap's exp and log.
    assert np.abs(a - b).max() <= 1e-3


def test_reference_on_the_gpu_gives_the_cpu_image():
    try:
        gpu = tandem.reference("cornell", integrator="diffuse-gi", spp=4, width=48, height=32,
                               cache="", device="gpu")
    except tandem.Error as e:
        pytest.skip(f"no Vulkan device: {e}")
    cpu = tandem.reference("cornell", integrator="diffuse-gi", spp=4, width=48, height=32,
                           cache="", device="cpu")
    # The same Sobol samples of the same paths: equal but for rounding and a few near-ties of
    # the traversal (a ray within rounding of two surfaces).
    diff = np.abs(gpu["hdr"] - cpu["hdr"])
    assert np.mean(diff <= 1e-3) >= 0.99
    assert abs(gpu["hdr"].mean() - cpu["hdr"].mean()) <= 0.01 * cpu["hdr"].mean()


def test_rt_only_on_the_gpu_counts_its_rays():
    try:
        gpu = tandem.Renderer("spheres", pipeline="rt-only", width=64, height=36, device="gpu")
    except tandem.Error as e:
        pytest.skip(f"no Vulkan device: {e}")
    cpu = tandem.Renderer("spheres", pipeline="rt-only", width=64, height=36, device="cpu")
    a, b = cpu.render()["output"], gpu.render()["output"]
    # The whole pipeline on the device: only the output comes back, and the kernel counts the
    # rays the CPU pass traces.
    assert "upload:hdr" not in gpu.timings()["bytes"]
    assert gpu.timings()["rays"]["rt_whitted"] == cpu.timings()["rays"]["rt_whitted"]
    mse = float(np.mean((a - b) ** 2))
    assert mse == 0 or 10 * np.log10(1 / mse) >= 45
    # New lights in the same scene reach the device too, and nothing drawn for the old lights
    # (the BVH, the GPU's scene) is taken for the new frame's: the same image as a renderer that
    # had the new lights from the start, at the same frame.
    lights = [{"type": "point", "position": [2, 3, 2], "intensity": 40}]
    for r in (cpu, gpu):
        r.lights = lights
    c, d = cpu.render()["output"], gpu.render()["output"]
    assert np.abs(c - a).max() > 0.1
    fresh = tandem.Renderer("spheres", pipeline="rt-only", width=64, height=36, device="cpu")
    fresh.lights = lights
    fresh.render()
    assert np.array_equal(fresh.render()["output"], c)
    mse = float(np.mean((c - d) ** 2))
    assert mse == 0 or 10 * np.log10(1 / mse) >= 45


def test_a_scene_that_names_itself_is_an_error():
    d = scratch("self_scene")
    with open(os.path.join(d, "a.json"), "w") as f:
        f.write('{"base": "b.json"}')
    with open(os.path.join(d, "b.json"), "w") as f:
        f.write('{"base": "a.json"}')
    with pytest.raises(tandem.Error, match=r"refers to itself \(a.json -> b.json -> a.json\)"):
        tandem.Renderer(os.path.join(d, "a.json"))


@pytest.mark.parametrize("call", [
    "tandem.Renderer('cornell', pipeline='deferred', width=32, height=18).render(frames=10**9)",
    "tandem.reference('cornell', spp=1000000, width=64, height=36, cache='')",
    "tandem.experiment('taa', out=sys.argv[1], cache='')",
    "tandem.compare(*[__import__('numpy').full((3000, 3000, 3), 0.5, 'f4')] * 2)"])
def test_ctrl_c_stops_a_long_call(call):
    # The child notes when the KeyboardInterrupt reached Python (CLOCK_MONOTONIC is the
    # machine's, so both processes read one clock), then lets it end the process: the stop is
    # timed, not the interpreter's teardown of a loaded machine.
    code = ("import tandem, sys, time\n"
            "print('ready', flush=True)\n"
            "try:\n"
            f"    {call}\n"
            "except KeyboardInterrupt:\n"
            "    print('stopped', time.monotonic(), flush=True)\n"
            "    raise\n")
    out = os.path.join(scratch("ctrl_c"), "exp")
    p = subprocess.Popen([sys.executable, "-c", code, out], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "ready"
    import signal
    import time
    time.sleep(1.5)  # well inside the call (each takes 5 s or more on a fast 2-core machine)
    start = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=30)
    finally:
        p.kill()
    stopped = [float(line.split()[1]) for line in out.splitlines() if line.startswith("stopped")]
    assert stopped, f"no KeyboardInterrupt reached Python: {err[-500:]}"
    assert stopped[0] - start < 2.0
    assert p.returncode != 0 and "KeyboardInterrupt" in err
    # An experiment stopped early leaves neither its folder nor its staging folder.
    assert not os.path.exists(out) and not os.path.exists(out + ".partial")


BAD_ARGUMENTS = [
    (lambda: tandem.Renderer(width=2.7), "Renderer: width: expected an integer"),
    (lambda: tandem.Renderer(width=10**10), "Renderer: width: must be in [1, 16384]"),
    (lambda: tandem.Renderer(height=0), "Renderer: height: must be in [1, 16384]"),
    (lambda: tandem.Renderer(stereo="no"), "Renderer: stereo: expected True or False"),
    (lambda: tandem.Renderer(shutter=float("nan")), "Renderer: shutter: must be finite"),
    (lambda: tandem.Renderer(shutter=-1), "Renderer: shutter: must be in [0, 1000] seconds"),
    (lambda: tandem.Renderer(seed=-5), "Renderer: seed: must be in [0, 2^64)"),
    (lambda: tandem.Renderer(lights=5), "Renderer: lights: expected a list of lights"),
    (lambda: tandem.Renderer(camera=[1, 2, 3]), "Renderer: camera: expected a dict"),
    (lambda: tandem.Renderer(sets=[1, 2]), "Renderer: sets: expected a dict"),
    (lambda: tandem.Renderer(device="cuda"), "Renderer: device: expected auto, cpu or gpu"),
    (lambda: tandem.Renderer(device=3), "Renderer: device: expected auto, cpu or gpu"),
    (lambda: tandem.reference(time=float("nan")), "reference: time: must be finite"),
    (lambda: tandem.reference(shutter=-1), "reference: shutter: must be in [0, 1000] seconds"),
    (lambda: tandem.reference(spp=0), "reference: spp: must be in [1, 1048576]"),
    (lambda: tandem.reference(width=2.5), "reference: width: expected an integer"),
    (lambda: tandem.reference(stereo=1), "reference: stereo: expected True or False"),
    (lambda: tandem.reference(device="cuda"), "reference: device: expected auto, cpu or gpu"),
    (lambda: tandem.reference(device=0), "reference: device: expected auto, cpu or gpu"),
    (lambda: tandem.experiment("taa", width=-5), "experiment: width: must be in [1, 16384]"),
    (lambda: tandem.experiment("taa", frames=1.5), "experiment: frames: expected an integer"),
]


@pytest.mark.parametrize("call,message", BAD_ARGUMENTS)
def test_bad_arguments_raise_errors_naming_them(call, message):
    with pytest.raises(tandem.Error) as e:
        call()
    assert message in str(e.value)


def test_bad_render_and_camera_arguments_are_named():
    r = tandem.Renderer("cornell", pipeline="deferred", width=16, height=9)
    for call, message in [
            (lambda: r.render(frames=1.9), "render: frames: expected an integer"),
            (lambda: r.render(frames=0), "render: frames: must be at least 1"),
            (lambda: r.render(buffers="output"), "render: buffers: expected a list of names"),
            (lambda: r.set_camera(position=[float("nan"), 0, 0]), "camera: values must be finite"),
            (lambda: setattr(r, "stereo", "yes"), "Renderer: stereo: expected True or False"),
            (lambda: setattr(r, "lights", [1]), "lights: expected a list of light dicts")]:
        with pytest.raises(tandem.Error) as e:
            call()
        assert message in str(e.value)
    assert r.frame == 0  # nothing rendered


def test_compare_refuses_non_finite_pixels_by_count():
    a = np.zeros((2, 2, 3), np.float32)
    b = a.copy()
    b[0, 1, 2] = np.nan
    with pytest.raises(tandem.Error, match=r"compare: b: 1 of 4 pixels are not finite"):
        tandem.compare(a, b)
