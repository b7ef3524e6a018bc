#include "cli_options.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "pipeline/render_limits.h"
#include "pipeline/renderer.h"
#include "scene/default_lights.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

namespace {

std::vector<float> parseNumbers(const std::string& opt, const std::string& text, size_t minN,
                                size_t maxN) {
  std::vector<float> v;
  for (const std::string& part : splitList(text)) {
    char* end = nullptr;
    float f = std::strtof(part.c_str(), &end);
    if (end == part.c_str() || *end != '\0' || !std::isfinite(f))
      throw InputError("command line", opt, "'" + part + "' is not a finite number");
    v.push_back(f);
  }
  if (v.size() < minN || v.size() > maxN)
    throw InputError("command line", opt,
                     "expected " + std::to_string(minN) +
                         (maxN > minN ? "-" + std::to_string(maxN) : "") +
                         " comma-separated numbers, got '" + text + "'");
  return v;
}

Vec3 parseVec3(const std::string& opt, const std::string& text) {
  auto v = parseNumbers(opt, text, 3, 3);
  return {v[0], v[1], v[2]};
}

// "x,y,z[,intensity[,r,g,b]]": a point light's position or a sun's travel direction.
Light parseCliLight(const std::string& opt, const std::string& text, LightType type) {
  auto v = parseNumbers(opt, text, 3, 7);
  if (v.size() == 5 || v.size() == 6)
    throw InputError("command line", opt, "colour needs 3 numbers");
  Light l;
  l.type = type;
  Vec3 xyz{v[0], v[1], v[2]};
  if (type == LightType::Point) {
    l.name = "cli-point";
    l.position = xyz;
    l.intensity = 10.0f;
  } else {
    if (length(xyz) == 0) throw InputError("command line", opt, "direction must not be zero");
    l.name = "cli-sun";
    l.direction = normalize(xyz);
    l.intensity = 3.0f;
  }
  if (v.size() > 3) l.intensity = v[3];
  if (l.intensity < 0) throw InputError("command line", opt, "intensity must be >= 0");
  if (v.size() == 7) l.color = {v[4], v[5], v[6]};
  return l;
}

}  // namespace

std::unique_ptr<tbb::global_control> limitThreads(const RenderOptions& o) {
  if (o.threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               o.threads);
}

void addSceneOptions(CLI::App* app, RenderOptions& o) {
  app->add_option("--scene", o.scene,
                  "Scene: .gltf/.glb/.obj/.json file or built-in (cornell, spheres, atrium)");
  app->add_option("--width", o.width, "Image width in pixels");
  app->add_option("--height", o.height, "Image height in pixels");
  app->add_option_function<std::string>(
      "--resolution",
      [&o](const std::string& name) {
        // Peres 2022's Table 2 sizes are per eye of a head-mounted display: stereo.
        if (name == "fhd") {
          o.width = 960, o.height = 1080, o.stereo = true;
        } else if (name == "quest2") {
          o.width = 1832, o.height = 1920, o.stereo = true;
        }
        o.resolution = name;  // validateRenderOptions refuses an unknown name
      },
      "Named size: fhd (960x1080 per eye) or quest2 (1832x1920 per eye), both stereo; sets "
      "--width, --height and --stereo");
  app->add_option("--out", o.out, "Output image (.png/.exr) or folder");
  app->add_option("--seed", o.seed, "Random seed");
  app->add_option("--threads", o.threads, "Worker threads (0 = all cores)");
  app->add_option("--camera-pos", o.cameraPos, "Camera position x,y,z");
  app->add_option("--look-at", o.lookAt, "Camera target x,y,z");
  app->add_option("--up", o.up, "Camera up vector x,y,z");
  app->add_option("--vfov", o.vfov, "Vertical field of view in degrees");
  app->add_option("--point-light", o.pointLights,
                  "Add a point light: x,y,z[,intensity[,r,g,b]] (W/sr)");
  app->add_option(
      "--sun-light", o.sunLights,
      "Add a directional light: dx,dy,dz[,intensity[,r,g,b]] (travel direction, W/m^2)");
  app->add_option("--emissive-lights", o.emissiveLights,
                  "Emissive meshes as punctual lights: auto (when the scene has none), on, off");
  app->add_option("--default-lights", o.defaultLights,
                  "Scenes with no lights: auto (light them with a sun-and-sky rig) or off");
  app->add_flag("--stereo", o.stereo,
                "Stereo: both eyes side by side (--width and --height give one eye)");
  app->add_option("--ipd", o.ipd, "Stereo interpupillary distance in metres (default 0.064)");
  app->add_option("--convergence", o.convergence,
                  "Stereo: converged axes meeting this many metres ahead (default: parallel)");
}

StereoDesc stereoFor(const Scene& s, const RenderOptions& o) {
  StereoDesc st = s.stereo;
  if (o.stereo || o.ipd > 0 || o.convergence > 0) st.enabled = true;
  if (o.ipd > 0) st.ipd = o.ipd;
  if (o.convergence > 0) {
    st.converged = true;
    st.convergence = o.convergence;
  }
  return fitStereoToModel(s, defaultCamera(s), st, o.ipd > 0);
}

std::shared_ptr<GpuDevice> deviceFor(const RenderOptions& o) {
  const DeviceChoice choice = parseDeviceChoice(o.device, "command line", "--device");
  std::shared_ptr<GpuDevice> gpu = GpuDevice::forChoice(choice, "command line: --device");
  if (gpu)
    std::fprintf(stderr, "tandem: device: %s (%s, Vulkan %s)\n", gpu->info().name.c_str(),
                 gpu->info().type.c_str(), gpu->info().apiText().c_str());
  else if (choice == DeviceChoice::Auto)
    std::fprintf(stderr, "tandem: device: cpu (no hardware GPU with Vulkan 1.3 compute found)\n");
  return gpu;
}

RenderSettings renderSettingsFor(const Scene& s, const RenderOptions& o) {
  RenderSettings r{.width = o.width, .height = o.height, .seed = o.seed};
  r.shutter = o.shutter;
  r.stereo = stereoFor(s, o);
  r.gpu = deviceFor(o);
  return r;
}

void addDeviceOption(CLI::App* app, RenderOptions& o) {
  app->add_option("--device", o.device,
                  "auto (a GPU when there is one, else the CPU), cpu, or gpu (also a CPU Vulkan "
                  "such as lavapipe); passes without a GPU version run on the CPU");
}

void addLensOptions(CLI::App* app, RenderOptions& o) {
  app->add_option("--shutter", o.shutter,
                  "Motion blur: seconds the shutter stays open from the frame time");
  app->add_option("--aperture", o.aperture, "Thin lens aperture diameter in metres (0 = pinhole)");
  app->add_option("--focus", o.focus, "Focus distance in metres");
  app->add_option("--blades", o.blades, "Polygonal aperture with this many blades (0 = circle)");
}

void addRenderOptions(CLI::App* app, RenderOptions& o) {
  addSceneOptions(app, o);
  std::string names;
  for (const std::string& n : Pipeline::builtinNames()) names += (names.empty() ? "" : ", ") + n;
  app->add_option("--pipeline", o.pipeline, "Pipeline: built-in name (" + names + ") or JSON file");
  app->add_option("--aov", o.aov,
                  "Extra buffers to write, comma-separated (depth,normal,object_id,...)");
  app->add_option("--frames", o.frames, "Frames to render (scene time advances 1/30 s per frame)");
  addLensOptions(app, o);
  addDeviceOption(app, o);
  app->add_option("--set", o.set,
                  "Set a pass parameter: pass.param=value (e.g. heuristic.budget_ms=40); "
                  "repeatable");
}

Pipeline loadPipelineFor(const RenderOptions& o) {
  Pipeline p = Pipeline::load(o.pipeline);
  for (const std::string& a : o.set) p.setParam(a, "--set");
  p.checkShadows("--set");  // once all are applied: their order does not matter
  return p;
}

void validateRenderOptions(const RenderOptions& o) {
  if (!o.resolution.empty() && o.resolution != "fhd" && o.resolution != "quest2")
    throw InputError("command line", "--resolution",
                     "expected fhd or quest2, got '" + o.resolution + "'");
  checkFrameSize("command line", "--width", "--height", o.width, o.height, o.stereo);
  if (o.frames < 1 || o.frames > 1000000)
    throw InputError("command line", "--frames", "must be in [1, 1000000]");
  if (o.threads < 0 || o.threads > 4096)
    throw InputError("command line", "--threads", "must be in [0, 4096]");
  if (o.vfov != 0 && !(o.vfov > 0 && o.vfov < 180))
    throw InputError("command line", "--vfov", "must be in (0, 180)");
  checkShutter("command line", "--shutter", o.shutter);
  if (o.aperture && !(*o.aperture >= 0 && *o.aperture <= 1000))
    throw InputError("command line", "--aperture", "must be in [0, 1000] metres");
  if (o.focus && !(*o.focus > 0 && *o.focus <= 1e9))
    throw InputError("command line", "--focus", "must be a positive distance in metres");
  if (o.blades && (*o.blades < 0 || *o.blades == 1 || *o.blades == 2 || *o.blades > 64))
    throw InputError("command line", "--blades", "must be 0 (circle) or 3 to 64");
  if (o.ipd < 0 || o.ipd > 1000 || !std::isfinite(o.ipd))
    throw InputError("command line", "--ipd", "must be in (0, 1000] metres");
  if (o.convergence < 0 || !std::isfinite(o.convergence))
    throw InputError("command line", "--convergence", "must be a positive distance in metres");
  if (o.emissiveLights != "auto" && o.emissiveLights != "on" && o.emissiveLights != "off")
    throw InputError("command line", "--emissive-lights", "expected auto, on or off");
  parseDeviceChoice(o.device, "command line", "--device");
  if (o.defaultLights != "auto" && o.defaultLights != "off")
    throw InputError("command line", "--default-lights", "expected auto or off");
  // An output file is .png or .exr; anything else with an extension is not a folder name either.
  if (!o.out.empty() && o.out.back() != '/') {
    const std::string ext = std::filesystem::path(o.out).extension().string();
    if (!ext.empty() && !hasExtension(o.out, ".png") && !hasExtension(o.out, ".exr"))
      throw InputError(
          "command line", "--out",
          "'" + o.out + "': Tandem writes .png and .exr files (or a folder: end it with /)");
  }
}

Scene loadSceneFor(const RenderOptions& o) {
  LoadOptions lo;
  lo.emissiveLights = o.emissiveLights == "on"    ? LoadOptions::EmissiveLights::On
                      : o.emissiveLights == "off" ? LoadOptions::EmissiveLights::Off
                                                  : LoadOptions::EmissiveLights::Auto;
  // Command-line lights count as the scene's own for the 'auto' rule.
  if (!o.pointLights.empty() || !o.sunLights.empty()) {
    if (lo.emissiveLights == LoadOptions::EmissiveLights::Auto)
      lo.emissiveLights = LoadOptions::EmissiveLights::Off;
  }
  Scene s = loadScene(o.scene, lo);
  for (const std::string& p : o.pointLights)
    s.lights.push_back(parseCliLight("--point-light", p, LightType::Point));
  for (const std::string& p : o.sunLights)
    s.lights.push_back(parseCliLight("--sun-light", p, LightType::Directional));
  if (o.defaultLights == "auto" && needsDefaultLights(s)) {
    addDefaultLightRig(s, cameraFor(s, o));  // around the view the user will see
    std::fprintf(stderr,
                 "tandem: %s has no lights: lit by the default rig (sun, sky, fill); "
                 "--default-lights off renders it unlit\n",
                 s.name.c_str());
  }
  return s;
}

CameraDesc cameraFor(const Scene& s, const RenderOptions& o) {
  CameraDesc c = defaultCamera(s);
  if (!o.cameraPos.empty()) c.position = parseVec3("--camera-pos", o.cameraPos);
  if (!o.lookAt.empty()) c.lookAt = parseVec3("--look-at", o.lookAt);
  if (!o.up.empty()) c.up = parseVec3("--up", o.up);
  if (o.vfov > 0) c.vfovDeg = o.vfov;
  if (length(c.lookAt - c.position) == 0)
    throw InputError("command line", "--look-at", "must differ from the camera position");
  if (length(cross(normalize(c.lookAt - c.position), normalize(c.up))) < 1e-6f)
    throw InputError("command line", "--up", "must not be parallel to the view direction");
  fitNearPlane(c);  // sensible for tiny models seen from close up
  if (o.aperture) c.apertureDiameter = *o.aperture;
  if (o.focus) c.focusDistance = *o.focus;
  if (o.blades) c.apertureBlades = *o.blades;
  return c;
}

Scene loadSceneToRender(const RenderOptions& o) {
  Scene s = loadSceneFor(o);
  checkSceneFits(o.scene, "memory", s, o.width, o.height, o.stereo || o.ipd > 0);
  return s;
}

}  // namespace tandem
