"""Tandem from Python: render through any pipeline and get its buffers as numpy arrays, render
references, compare images and run the papers' experiments.

    import tandem
    r = tandem.Renderer("scenes/atrium_spheres.json", pipeline="hybrid-heuristic",
                        width=640, height=360)
    r.set("heuristic.budget", 2e5)
    out = r.render(frames=4)          # {"hdr": (360, 640, 3) float32, "output": ..., "depth": ...}
    truth = r.render_reference(integrator="whitted", spp=16)
    print(tandem.compare(out["output"], truth["output"]))

Scenes are files, built-in names ("cornell", "spheres", "atrium") or dicts shaped like the scene
JSON (docs/scene-format.md); pipelines are built-in names, files or dicts shaped like the pipeline
JSON (docs/pipelines.md). Bad input raises tandem.Error (a ValueError) with the message the CLI
prints. Rendering releases the GIL. See docs/python.md.
"""
import csv
import math
import numbers
import json
import os

from . import _tandem
from ._tandem import Error

__all__ = ["Renderer", "Error", "reference", "compare", "experiment", "experiments", "pipelines",
           "default_cache"]


# Arguments are checked for their type here (an integer that is integral, a bool that is a
# bool, a finite number, a dict or a list where one belongs), each failure a tandem.Error
# naming the call and the argument as the CLI names its options; their ranges are checked by
# the same C++ code the CLI runs (render_limits.h).
def _fail(where, field, problem):
    raise Error(f"{where}: {field}: {problem}" if field else f"{where}: {problem}")


def _integer(value, where, field):
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return int(value)
    if (isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)
            and float(value).is_integer()):
        return int(value)
    _fail(where, field, f"expected an integer, got {value!r}")


def _real(value, where, field):
    if not isinstance(value, numbers.Real) or isinstance(value, bool):
        _fail(where, field, f"expected a number, got {value!r}")
    if not math.isfinite(value):
        _fail(where, field, f"must be finite, got {value!r}")
    return float(value)


def _boolean(value, where, field):
    if isinstance(value, bool) or type(value).__name__ == "bool_":  # numpy's too
        return bool(value)
    _fail(where, field, f"expected True or False, got {value!r}")


def _seed(value, where):
    seed = _integer(value, where, "seed")
    if not 0 <= seed < 2**64:
        _fail(where, "seed", f"must be in [0, 2^64), got {seed}")
    return seed


def _size(value, where, field):
    """A width or height: integral here, its range in C++ (passed on as a float)."""
    return float(_integer(value, where, field))


def _strings(value, where, field):
    if isinstance(value, (str, bytes)) or not isinstance(value, (list, tuple)) or not all(
            isinstance(v, str) for v in value):
        _fail(where, field, f"expected a list of names, got {value!r}")
    return list(value)


def _mapping(value, where, field):
    if not isinstance(value, dict):
        _fail(where, field, f"expected a dict, got {value!r}")
    return value


def _json(value, where):
    """JSON text of a dict or list from Python, NaN and Inf refused by name (JSON has neither)."""
    try:
        return json.dumps(value, allow_nan=False)
    except ValueError:
        _fail(where, "", "values must be finite numbers (NaN and Inf are not)")
    except TypeError as e:
        _fail(where, "", str(e))


def _spec(value, what):
    """(name or path, JSON text) for a scene or pipeline given as a string, a path or a dict."""
    if isinstance(value, dict):
        return "", json.dumps(value)
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value), ""
    raise TypeError(f"{what} must be a name, a path or a dict, not {type(value).__name__}")


def _json_value(value):
    """A parameter value as --set writes it: JSON, or a bare enum choice."""
    if isinstance(value, str):
        return value
    return json.dumps(value)


def default_cache():
    """The reference cache folder the CLI uses: $TANDEM_REFERENCE_CACHE or out/reference-cache."""
    return os.environ.get("TANDEM_REFERENCE_CACHE") or "out/reference-cache"


class Renderer:
    """A scene rendered through a pipeline, kept alive across renders (temporal passes carry
    their history from one render() to the next, as frames of `tandem render --frames`)."""

    def __init__(self, scene="cornell", pipeline="hybrid-heuristic", width=640, height=360,
                 stereo=False, shutter=0.0, seed=0, camera=None, lights=None, sets=None,
                 device="auto"):
        scene_name, scene_json = _spec(scene, "scene")
        if not isinstance(device, str):
            _fail("Renderer", "device", f"expected auto, cpu or gpu, got {device!r}")
        pipe_name, pipe_json = _spec(pipeline, "pipeline")
        w, h = _size(width, "Renderer", "width"), _size(height, "Renderer", "height")
        stereo = _boolean(stereo, "Renderer", "stereo")
        shutter = _real(shutter, "Renderer", "shutter")
        seed = _seed(seed, "Renderer")
        if camera is not None:
            _mapping(camera, "Renderer", "camera")
        if lights is not None and not isinstance(lights, (list, tuple)):
            _fail("Renderer", "lights", f"expected a list of lights, got {lights!r}")
        if sets is not None:
            _mapping(sets, "Renderer", "sets")
        self._scene = (scene_name, scene_json)
        self._r = _tandem.Renderer(scene_name, scene_json, pipe_name, pipe_json, w, h, stereo,
                                   shutter, seed, device)
        self.width, self.height = int(w), int(h)
        if camera:
            self.set_camera(**camera)
        if lights is not None:
            self.lights = lights
        for name, value in (sets or {}).items():
            self.set(name, value)

    def set(self, name, value=None):
        """Sets a pass parameter, checked as --set is: set("heuristic.budget", 1e5) or
        set("heuristic.budget=1e5")."""
        if not isinstance(name, str):
            _fail("set", "name", f"expected \"pass.param\", got {name!r}")
        if isinstance(value, float) and not math.isfinite(value):
            _fail("set", name, f"must be finite, got {value!r}")
        self._r.set(name if value is None else f"{name}={_json_value(value)}")

    @property
    def camera(self):
        """The camera as a scene-file "camera" object (position, lookAt, up, vfov, aperture, ...)."""
        return json.loads(self._r.camera_json())

    @camera.setter
    def camera(self, fields):
        self.set_camera(**fields)

    def set_camera(self, **fields):
        """Changes the given camera fields (scene-file names: position, lookAt, up, vfov,
        aperture, focalLength, focusDistance, sensorWidth, blades, ...); the rest stay."""
        self._r.set_camera(_json(fields, "camera"))

    @property
    def lights(self):
        return self._r.lights()

    @lights.setter
    def lights(self, lights):
        """Replaces the scene's lights with scene-file "lights" entries (history starts over)."""
        if not isinstance(lights, (list, tuple)) or not all(isinstance(l, dict) for l in lights):
            _fail("lights", "", f"expected a list of light dicts, got {lights!r}")
        self._r.set_lights(_json(list(lights), "lights"))

    @property
    def device(self):
        """Where passes with a GPU version run: the GPU's name, or "cpu"."""
        return self._r.device

    @property
    def shutter(self):
        return self._r.shutter

    @shutter.setter
    def shutter(self, seconds):
        self._r.shutter = _real(seconds, "Renderer", "shutter")

    @property
    def stereo(self):
        return self._r.stereo

    @stereo.setter
    def stereo(self, on):
        self._r.stereo = _boolean(on, "Renderer", "stereo")

    @property
    def frame(self):
        """How many frames this renderer has rendered."""
        return self._r.frame

    def render(self, frames=1, buffers=None):
        """Renders `frames` more frames; returns the last one's buffers by name as float32 arrays
        (height, width[, channels]): "hdr", "output" (display-encoded, what the PNG holds),
        "depth", "normal", "object_id" and every other buffer the pipeline's passes write, or
        only those named in `buffers` (each a copy: naming few saves the copying)."""
        frames = _integer(frames, "render", "frames")
        if frames < 1:
            _fail("render", "frames", f"must be at least 1, got {frames}")
        names = [] if buffers is None else _strings(buffers, "render", "buffers")
        return self._r.render(min(frames, 2**31 - 1), names)

    def timings(self):
        """Milliseconds of the last frame: {"frame": total, "passes": {label: ms}, "bytes":
        {move: bytes}, "rays": {label: rays}} (the moves between host and GPU,
        "upload:NAME" / "download:NAME"; the rays each tracing pass traced)."""
        return self._r.timings()

    def counters(self):
        """The figures the passes reported for the last frame (rays per pixel, shares, ...)."""
        return self._r.counters()

    def counter(self, name):
        """One counter of the last frame by its declared name ("heuristic/selected"); None when
        no pass reported it that frame. Raises tandem.Error when no pass of the pipeline
        declares it (see declared_counters())."""
        return self._r.counter(str(name))

    def declared_counters(self):
        """{name: description} of every counter the pipeline's passes report."""
        return self._r.declared_counters()

    def buffers(self):
        """Names of the buffers the pipeline's passes write."""
        return self._r.buffers()

    def cut(self):
        """Starts every temporal pass over (an unrelated next camera)."""
        self._r.cut()

    def render_reference(self, integrator="path", spp=64, cache=None, seed=0):
        """The reference of this renderer's scene, camera, size, shutter and stereo pair."""
        return reference(_scene_arg(self._scene), integrator=integrator, spp=spp,
                         width=self.width, height=self.height, camera=self.camera,
                         shutter=self.shutter, stereo=self.stereo, cache=cache, seed=seed)


def _scene_arg(scene):
    """The scene as given to the Renderer: its name or path, or its dict."""
    name, text = scene
    return json.loads(text) if text else name


def reference(scene="cornell", integrator="path", spp=64, width=640, height=360, camera=None,
              time=0.0, shutter=0.0, stereo=False, cache=None, seed=0, device="auto"):
    """A reference render (`tandem reference`): integrator "path", "whitted" (the same shading
    as the pipelines, with lens and shutter) or "diffuse-gi" (the foveated path tracer,
    converged). Cached as the CLI caches (cache="" renders anew). `device`: where it renders
    (auto, cpu or gpu), as the CLI's --device. Returns {"hdr", "output", "variance", "spp",
    "seconds", "from_cache"}."""
    name, text = _spec(scene, "scene")
    where = "reference"
    if not isinstance(integrator, str):
        _fail(where, "integrator", f"expected path, whitted or diffuse-gi, got {integrator!r}")
    if camera is not None:
        _mapping(camera, where, "camera")
    if cache is not None and not isinstance(cache, (str, os.PathLike)):
        _fail(where, "cache", f"expected a folder, got {cache!r}")
    if not isinstance(device, str):
        _fail(where, "device", f"expected auto, cpu or gpu, got {device!r}")
    return _tandem.reference(
        name, text, integrator, float(_integer(spp, where, "spp")),
        _size(width, where, "width"), _size(height, where, "height"),
        _json(camera, "camera") if camera else "", _real(time, where, "time"),
        _real(shutter, where, "shutter"), _boolean(stereo, where, "stereo"),
        os.fspath(default_cache() if cache is None else cache), _seed(seed, where), device)


def compare(a, b, hdr=False, maps=False):
    """RMSE, PSNR, SSIM and FLIP between two images (a is the reference for FLIP). `hdr`:
    FLIP sees both tonemapped as `render` writes them. `maps`: also "ssim_map" and "flip_map"."""
    return _tandem.compare(a, b, _boolean(hdr, "compare", "hdr"),
                           _boolean(maps, "compare", "maps"))


def _number(text):
    try:
        return int(text)
    except ValueError:
        try:
            return float(text)
        except ValueError:
            return text


def experiment(name, out=None, scenes=None, width=0, height=0, warmup=-1, frames=0, spp=0,
               cache=None, no_cache=False, static_frames=-1, path_frames=-1, budget=-1.0,
               budget_ms=-1.0, threads=0, device="auto"):
    """Runs `tandem experiment NAME` with the same overrides; returns {"out": folder,
    "tables": {table: [row dicts]}}, the tables it wrote as CSV, numbers as numbers. `device`:
    where its renders run (auto, cpu or gpu), as the CLI's --device."""
    where = "experiment"

    def count(value, field):
        # Integral here; the range is checked in C++ (the CLI's check), as far as an int holds.
        v = _integer(value, where, field)
        if not -2**31 <= v < 2**31:
            _fail(where, field, f"out of range, got {v}")
        return v

    if not isinstance(name, (str, os.PathLike)):
        _fail(where, "name", f"expected an experiment name or file, got {name!r}")
    if out is not None and not isinstance(out, (str, os.PathLike)):
        _fail(where, "out", f"expected a folder, got {out!r}")
    if cache is not None and not isinstance(cache, (str, os.PathLike)):
        _fail(where, "cache", f"expected a folder, got {cache!r}")
    if not isinstance(device, str):
        _fail(where, "device", f"expected auto, cpu or gpu, got {device!r}")
    folder = _tandem.run_experiment(
        os.fspath(name), os.fspath(out or ""),
        [] if scenes is None else _strings(scenes, where, "scenes"), count(width, "width"),
        count(height, "height"), count(warmup, "warmup"), count(frames, "frames"),
        count(spp, "spp"), os.fspath(default_cache() if cache is None else cache),
        _boolean(no_cache, where, "no_cache"), count(static_frames, "static_frames"),
        count(path_frames, "path_frames"), _real(budget, where, "budget"),
        _real(budget_ms, where, "budget_ms"), count(threads, "threads"), device)
    tables = {}
    for entry in sorted(os.listdir(folder)):
        if entry.endswith(".csv"):
            with open(os.path.join(folder, entry), newline="") as f:
                tables[entry[:-4]] = [{k: _number(v) for k, v in row.items()}
                                      for row in csv.DictReader(f)]
    return {"out": folder, "tables": tables}


def experiments():
    """The built-in experiments: [(name, title)]."""
    return _tandem.experiments()


def pipelines():
    """The built-in pipeline names."""
    return _tandem.pipelines()
