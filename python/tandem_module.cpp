// The `tandem._tandem` extension: the renderer, the reference path tracer, the metrics and the
// experiments, for the `tandem` Python package (python/tandem/__init__.py), which turns Python
// values into the JSON the scene and pipeline formats already define and back. Every long call
// releases the GIL; InputError becomes tandem.Error with the CLI's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_runner.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "pipeline/aov.h"
#include "pipeline/render_limits.h"
#include "pipeline/renderer.h"
#include "scene/camera_json.h"
#include "scene/default_lights.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace py = pybind11;
using namespace tandem;

namespace {

Json parseJson(const std::string& text, const std::string& what) {
  Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded()) throw InputError(what, "", "not valid JSON");
  return j;
}

// A scene by file or built-in name, or (when `json` is not empty) a scene-file object whose
// relative paths start at the working directory; lit by the default rig when it has no lights,
// as `tandem render` does.
Scene loadSceneSpec(const std::string& spec, const std::string& json) {
  Scene s;
  if (json.empty()) {
    s = loadScene(spec);
  } else {
    s = loadSceneJson(parseJson(json, "scene dict"), "scene dict",
                      std::filesystem::current_path().string());
    if (s.lights.empty()) addLightsForEmissiveMeshes(s);
  }
  if (needsDefaultLights(s)) addDefaultLightRig(s, defaultCamera(s));
  return s;
}

Pipeline loadPipelineSpec(const std::string& spec, const std::string& json) {
  if (json.empty()) return Pipeline::load(spec);
  Pipeline p = Pipeline::fromJson(parseJson(json, "pipeline dict"), "pipeline dict");
  p.validate("pipeline dict");
  return p;
}

// A buffer as a float32 array of shape (height, width, channels), or (height, width) for one
// channel; a copy, so it outlives the next frame.
py::array_t<float> toArray(const Buffer& b) {
  std::vector<py::ssize_t> shape{b.height, b.width};
  if (b.channels > 1) shape.push_back(b.channels);
  py::array_t<float> a(shape);
  if (!b.data.empty()) std::memcpy(a.mutable_data(), b.data.data(), b.data.size() * sizeof(float));
  return a;
}

Buffer fromArray(const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                 const char* name) {
  if (a.ndim() != 2 && a.ndim() != 3)
    throw InputError(name, "shape", "expected (height, width) or (height, width, channels)");
  const int h = int(a.shape(0)), w = int(a.shape(1)), c = a.ndim() == 3 ? int(a.shape(2)) : 1;
  if (h < 1 || w < 1 || c < 1 || c > 4)
    throw InputError(name, "shape", "needs at least one pixel and 1 to 4 channels");
  Buffer b(w, h, c);
  std::memcpy(b.data.data(), a.data(), b.data.size() * sizeof(float));
  return b;
}

// Ctrl-C during a long call: the poll the frame loop and the reference's batches call
// (core/interrupt.h) takes the GIL back, lets Python run its SIGINT handler and raises
// KeyboardInterrupt (through error_already_set) when it did.
void raiseOnCtrlC() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

class PyRenderer {
 public:
  // Sizes and the shutter come as doubles (Python checked they are integral / real numbers) so
  // that the CLI's checks (render_limits.h) decide their ranges, before the scene loads.
  PyRenderer(const std::string& scene, const std::string& sceneJson, const std::string& pipeline,
             const std::string& pipelineJson, double width, double height, bool stereo,
             double shutter, uint64_t seed, const std::string& device)
      : scene_((checkFrameSize("Renderer", "width", "height", width, height, stereo),
                checkShutter("Renderer", "shutter", shutter), loadSceneSpec(scene, sceneJson))),
        camera_(defaultCamera(scene_)) {
    checkSceneFits("Renderer", "scene", scene_, width, height, stereo);
    settings_.width = int(width);
    settings_.height = int(height);
    settings_.seed = seed;
    settings_.gpu =
        GpuDevice::forChoice(parseDeviceChoice(device, "Renderer", "device"), "Renderer");
    setShutter(shutter);
    setStereo(stereo);
    renderer_ =
        std::make_unique<Renderer>(scene_, loadPipelineSpec(pipeline, pipelineJson), settings_);
  }

  // The GPU's name, or "cpu".
  std::string device() const {
    return settings_.gpu ? settings_.gpu->info().name : std::string("cpu");
  }

  void set(const std::string& assignment) {
    const auto lock = exclusive();
    renderer_->pipeline().setParam(assignment, "set");
  }

  std::string cameraJson() const {
    const auto lock = exclusive();
    return cameraToJson(camera_).dump();
  }
  void setCamera(const std::string& json) {
    const auto lock = exclusive();
    camera_ = cameraFromJson(parseJson(json, "camera"), "camera", camera_);
    fitNearPlane(camera_);
  }

  std::vector<py::dict> lights() const {
    const auto lock = exclusive();
    std::vector<py::dict> out;
    for (const Light& l : scene_.lights) {
      py::dict d;
      d["type"] = l.type == LightType::Directional ? "directional"
                  : l.type == LightType::Spot      ? "spot"
                                                   : "point";
      d["name"] = l.name;
      d["position"] = std::vector<float>{l.position.x, l.position.y, l.position.z};
      d["direction"] = std::vector<float>{l.direction.x, l.direction.y, l.direction.z};
      d["intensity"] = l.intensity;
      d["color"] = std::vector<float>{l.color.x, l.color.y, l.color.z};
      out.push_back(d);
    }
    return out;
  }
  // Replaces the scene's lights (scene-file "lights" entries); temporal history starts over.
  void setLights(const std::string& json) {
    const auto lock = exclusive();
    const Json arr = parseJson(json, "lights");
    if (!arr.is_array()) throw InputError("lights", "", "expected a list of lights");
    std::vector<Light> lights;
    for (size_t i = 0; i < arr.size(); ++i) lights.push_back(lightFromJson(arr[i], "lights", i));
    scene_.lights = std::move(lights);
    validateScene(scene_, "lights");
    renderer_->setScene(scene_);
  }

  float shutter() const {
    const auto lock = exclusive();
    return settings_.shutter;
  }
  void setShutter(double s) {
    const auto lock = exclusive();
    checkShutter("Renderer", "shutter", s);
    settings_.shutter = s;
    rebuildIfLive();
  }
  bool stereo() const {
    const auto lock = exclusive();
    return settings_.stereo.enabled;
  }
  void setStereo(bool on) {
    const auto lock = exclusive();
    StereoDesc st = scene_.stereo;
    st.enabled = on;
    settings_.stereo = fitStereoToModel(scene_, camera_, st, false);
    rebuildIfLive();
  }

  // Renders `frames` frames (the frame counter carries on across calls, as in `tandem render
  // --frames`), without the GIL; returns the named buffers of the last one (all when `names` is
  // empty).
  py::dict render(int frames, const std::vector<std::string>& names) {
    const auto lock = exclusive();
    if (frames < 1) throw InputError("render", "frames", "must be at least 1");
    {
      py::gil_scoped_release release;
      const InterruptPoll ctrlC(raiseOnCtrlC);  // polled before each frame
      for (int i = 0; i < frames; ++i) last_ = renderer_->renderFrame(frame_++, camera_);
    }
    // Records (typed values passes hand each other) have no pixels to return.
    std::map<std::string, const Buffer*> buffers;
    for (const auto& [name, buffer] : renderer_->context().buffers)
      if (buffer.kind != BufferKind::Record) buffers[name] = &buffer;
    py::dict out;
    if (names.empty())
      for (const auto& [name, buffer] : buffers) out[name.c_str()] = toArray(*buffer);
    for (const std::string& n : names) {
      auto it = buffers.find(n);
      if (it == buffers.end()) {
        std::string list;
        for (const auto& [name, b] : buffers) list += (list.empty() ? "" : ", ") + name;
        throw InputError("render", "buffers", "no buffer '" + n + "' (has: " + list + ")");
      }
      out[n.c_str()] = toArray(*it->second);
    }
    return out;
  }

  py::dict timings() const {
    const auto lock = exclusive();
    py::dict passes, moved, rays;
    for (const PassTiming& p : last_.passes) {
      passes[p.name.c_str()] = p.ms;
      if (p.bytes > 0) moved[p.name.c_str()] = p.bytes;
      if (p.rays > 0) rays[p.name.c_str()] = p.rays;
    }
    py::dict d;
    d["frame"] = last_.totalMs;
    d["passes"] = passes;
    d["bytes"] = moved;
    d["rays"] = rays;
    return d;
  }
  std::map<std::string, double> counters() const {
    const auto lock = exclusive();
    return renderer_->context().counters;
  }
  // One counter by its declared name: an error when no pass of the pipeline reports it, None
  // when none did in the last frame (before the first, or a branch that did not run).
  std::optional<double> counter(const std::string& name) const {
    const auto lock = exclusive();
    renderer_->pipeline().requireCounter(name, "counter");
    const auto& c = renderer_->context().counters;
    auto it = c.find(name);
    return it == c.end() ? std::nullopt : std::optional<double>(it->second);
  }
  // Every counter the pipeline's passes declare, with its description.
  std::map<std::string, std::string> declaredCounters() const {
    const auto lock = exclusive();
    std::map<std::string, std::string> d;
    for (const auto& p : renderer_->pipeline().passes)
      for (const CounterDesc& c : p->counters()) d[c.name] = c.doc;
    return d;
  }
  std::vector<std::string> buffers() const {
    const auto lock = exclusive();
    return renderer_->pipeline().producedBuffers();
  }
  int frame() const {
    const auto lock = exclusive();
    return frame_;
  }
  void cut() {
    const auto lock = exclusive();
    renderer_->cut();
  }
  const Scene& scene() const { return scene_; }
  const CameraDesc& camera() const { return camera_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  // One call at a time on one Renderer: another Python thread's call waits for it (with the GIL
  // released while it waits, so the running call can take it back to return its result).
  std::unique_lock<std::mutex> exclusive() const {
    py::gil_scoped_release release;
    return std::unique_lock<std::mutex>(mutex_);
  }
  void rebuildIfLive() {
    if (!renderer_) return;
    const Json current = renderer_->pipeline().toJson();  // keeps the parameters set so far
    renderer_ =
        std::make_unique<Renderer>(scene_, Pipeline::fromJson(current, "pipeline"), settings_);
    frame_ = 0;
  }

  Scene scene_;
  CameraDesc camera_;
  RenderSettings settings_;
  std::unique_ptr<Renderer> renderer_;
  FrameTimings last_;
  int frame_ = 0;
  mutable std::mutex mutex_;
};

py::dict reference(const std::string& scene, const std::string& sceneJson,
                   const std::string& integrator, double spp, double width, double height,
                   const std::string& cameraJson, double time, double shutter, bool stereo,
                   const std::string& cache, uint64_t seed, const std::string& device) {
  // The CLI's checks (render_limits.h), before the scene loads.
  checkFrameSize("reference", "width", "height", width, height, stereo);
  checkSpp("reference", "spp", spp);
  checkTime("reference", "time", time);
  checkShutter("reference", "shutter", shutter);
  const Scene s = loadSceneSpec(scene, sceneJson);
  checkSceneFits("reference", "scene", s, width, height, stereo);
  ReferenceJob job;
  job.scene = &s;
  CameraDesc cam = defaultCamera(s);
  if (!cameraJson.empty()) cam = cameraFromJson(parseJson(cameraJson, "camera"), "camera", cam);
  job.camera = job.shutterCamera = cam;  // the renderer's camera: a still one
  job.time = float(time);
  job.shutter = float(shutter);
  job.width = int(width);
  job.height = int(height);
  StereoDesc st = s.stereo;
  st.enabled = stereo;
  job.stereo = fitStereoToModel(s, cam, st, false);
  job.settings.spp = int(spp);
  job.settings.seed = seed;
  if (integrator == "whitted")
    job.settings.integrator = Integrator::Whitted;
  else if (integrator == "diffuse-gi")
    job.settings.integrator = Integrator::DiffuseGI;
  else if (integrator != "path")
    throw InputError("reference", "integrator", "expected path, whitted or diffuse-gi");
  job.gpu = GpuDevice::forChoice(parseDeviceChoice(device, "reference", "device"), "reference");
  ReferenceImage img;
  {
    py::gil_scoped_release release;
    const InterruptPoll ctrlC(raiseOnCtrlC);  // polled between sample batches
    img = referenceImage(job, cache);
  }
  py::dict d;
  d["hdr"] = toArray(img.hdr);
  d["output"] = toArray(visualizeBuffer(img.hdr));
  d["variance"] = toArray(img.variance);
  d["spp"] = img.spp;
  d["seconds"] = img.seconds;
  d["from_cache"] = img.fromCache;
  return d;
}

py::dict compare(const py::array_t<float, py::array::c_style | py::array::forcecast>& a,
                 const py::array_t<float, py::array::c_style | py::array::forcecast>& b, bool hdr,
                 bool maps) {
  Buffer ba = fromArray(a, "a"), bb = fromArray(b, "b");
  if (ba.width != bb.width || ba.height != bb.height || ba.channels != bb.channels)
    throw InputError("compare", "b", "shape differs from a's");
  requireFinitePixels(ba, "compare", "a");
  requireFinitePixels(bb, "compare", "b");
  Buffer ssimMap, flipMap;
  ImageMetrics m;
  double f = 0;
  {
    py::gil_scoped_release release;
    const InterruptPoll ctrlC(raiseOnCtrlC);  // polled every 64 rows and between filters
    m = compareImages(ba, bb, maps ? &ssimMap : nullptr);
    // FLIP compares what a viewer sees: HDR images tonemapped as `render` writes them.
    f = hdr ? flip(visualizeBuffer(ba), visualizeBuffer(bb), maps ? &flipMap : nullptr)
            : flip(ba, bb, maps ? &flipMap : nullptr);
  }
  py::dict d;
  d["rmse"] = m.rmse;
  d["psnr"] = m.psnr;
  d["ssim"] = m.ssim;
  d["flip"] = f;
  if (maps) {
    d["ssim_map"] = toArray(ssimMap);
    d["flip_map"] = toArray(flipMap);
  }
  return d;
}

std::string runExperimentPy(const std::string& name, const std::string& out,
                            const std::vector<std::string>& scenes, int width, int height,
                            int warmup, int frames, int spp, const std::string& cache, bool noCache,
                            int staticFrames, int pathFrames, double budget, double budgetMs,
                            int threads, const std::string& device) {
  ExperimentRequest r;
  r.fromPython = true;
  r.name = name;
  r.o.out = out;
  r.o.scenes = scenes;
  r.o.width = width;
  r.o.height = height;
  r.o.warmup = warmup;
  r.o.frames = frames;
  r.o.spp = spp;
  r.o.cache = cache;
  r.o.noCache = noCache;
  r.staticFrames = staticFrames;
  r.pathFrames = pathFrames;
  r.budget = budget;
  r.budgetMs = budgetMs;
  r.threads = threads;
  r.device = device;
  const std::string dir = experimentOutDir(r);
  int status = 0;
  {
    py::gil_scoped_release release;
    const InterruptPoll ctrlC(raiseOnCtrlC);  // polled before each frame and reference batch
    status = runExperiment(r);
  }
  if (status != 0)
    throw InputError(name, "", "the experiment failed (status " + std::to_string(status) + ")");
  return dir;
}

}  // namespace

PYBIND11_MODULE(_tandem, m) {
  m.doc() = "Tandem's renderer, reference path tracer, metrics and experiments";
  static py::exception<InputError> error =
      py::register_exception<InputError>(m, "Error", PyExc_ValueError);
  // The device's limits (out of device memory) are the caller's to handle too: tandem.Error.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const GpuError& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  py::class_<PyRenderer>(m, "Renderer")
      .def(py::init<const std::string&, const std::string&, const std::string&, const std::string&,
                    double, double, bool, double, uint64_t, const std::string&>(),
           py::arg("scene"), py::arg("scene_json"), py::arg("pipeline"), py::arg("pipeline_json"),
           py::arg("width"), py::arg("height"), py::arg("stereo"), py::arg("shutter"),
           py::arg("seed"), py::arg("device"))
      .def_property_readonly("device", &PyRenderer::device)
      .def("set", &PyRenderer::set)
      .def("camera_json", &PyRenderer::cameraJson)
      .def("set_camera", &PyRenderer::setCamera)
      .def("lights", &PyRenderer::lights)
      .def("set_lights", &PyRenderer::setLights)
      .def_property("shutter", &PyRenderer::shutter, &PyRenderer::setShutter)
      .def_property("stereo", &PyRenderer::stereo, &PyRenderer::setStereo)
      .def("render", &PyRenderer::render, py::arg("frames") = 1,
           py::arg("buffers") = std::vector<std::string>{})
      .def("timings", &PyRenderer::timings)
      .def("counters", &PyRenderer::counters)
      .def("counter", &PyRenderer::counter)
      .def("declared_counters", &PyRenderer::declaredCounters)
      .def("buffers", &PyRenderer::buffers)
      .def_property_readonly("frame", &PyRenderer::frame)
      .def("cut", &PyRenderer::cut);

  m.def("reference", &reference, py::arg("scene"), py::arg("scene_json"), py::arg("integrator"),
        py::arg("spp"), py::arg("width"), py::arg("height"), py::arg("camera_json"),
        py::arg("time"), py::arg("shutter"), py::arg("stereo"), py::arg("cache"), py::arg("seed"),
        py::arg("device"));
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::arg("hdr"), py::arg("maps"));
  m.def("run_experiment", &runExperimentPy);
  m.def("experiments", &listExperiments);
  m.def("pipelines", &Pipeline::builtinNames);
}
