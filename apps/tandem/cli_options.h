// Options shared by every verb that renders (render, bench, later view/experiment).
#pragma once
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/gpu_device.h"
#include "pipeline/pipeline.h"
#include "scene/scene.h"
#include "scene/scene_camera.h"

namespace tandem {

struct RenderOptions {
  std::string scene = "cornell";  // path or built-in name
  // The best-looking interactive pipeline: ray-traced shadows, reflections and refractions on
  // the raster G-buffer where the heuristic sends rays, anti-aliased over frames (TAA).
  std::string pipeline = "hybrid-heuristic-taa";
  int width = 1280, height = 720;  // [1, 16384]
  std::string resolution;          // --resolution: a named size (fhd, quest2), applied when parsed
  std::string out;                 // image file or folder
  std::string aov;                 // comma-separated buffer names
  int frames = 1;                  // [1, 1000000]
  uint64_t seed = 0;
  int threads = 0;  // 0 = all cores
  std::string cameraPos, lookAt, up;
  float vfov = 0;  // 0 = scene's
  std::vector<std::string> pointLights, sunLights;
  std::string emissiveLights = "auto";  // auto | on | off
  std::string defaultLights = "auto";   // auto (a rig when the scene has no lights) | off
  std::vector<std::string> set;         // pass parameters: label.param=value
  bool stereo = false;                  // two eyes side by side (--width is one eye)
  float ipd = 0;                        // > 0: interpupillary distance (implies --stereo)
  float convergence = 0;                // > 0: converged axes meeting this far ahead
  // Lens and shutter (render, bench, view): unset keeps the scene camera's.
  float shutter = 0;  // seconds the shutter stays open (motion blur)
  std::optional<float> aperture, focus;
  std::optional<int> blades;
  std::string device = "auto";  // auto | cpu | gpu (render, bench, view, reference)
};

// Scene, size, output, seed, threads, camera overrides and lights (every rendering verb).
void addSceneOptions(CLI::App* app, RenderOptions& o);
// --shutter, --aperture, --focus, --blades.
void addLensOptions(CLI::App* app, RenderOptions& o);
// --device (auto, cpu, gpu).
void addDeviceOption(CLI::App* app, RenderOptions& o);
// addSceneOptions, addLensOptions, pipeline, AOVs, frames and --set.
void addRenderOptions(CLI::App* app, RenderOptions& o);
// Validates option values; throws InputError naming the option.
void validateRenderOptions(const RenderOptions& o);
// Loads the scene, adds command-line lights, and the default lighting rig (announced on
// stderr) when nothing lights it and --default-lights is auto.
Scene loadSceneFor(const RenderOptions& o);
// loadSceneFor, then an InputError naming the scene file when rendering it at the requested
// size would need more memory than the machine has (checkSceneFits).
Scene loadSceneToRender(const RenderOptions& o);
// The scene's stereo settings with --stereo, --ipd and --convergence applied.
StereoDesc stereoFor(const Scene& s, const RenderOptions& o);
// Width, height, seed, stereo and the device (--device; which one is said on stderr) as render
// settings.
struct RenderSettings;
RenderSettings renderSettingsFor(const Scene& s, const RenderOptions& o);
// The device --device asks for (null: the CPU), said on stderr.
std::shared_ptr<GpuDevice> deviceFor(const RenderOptions& o);
// Loads the pipeline and applies --set parameters.
Pipeline loadPipelineFor(const RenderOptions& o);
// The scene camera with command-line overrides applied (a default view when it has none).
CameraDesc cameraFor(const Scene& s, const RenderOptions& o);
std::vector<std::string> splitList(const std::string& s);
// Caps oneTBB's worker count for the lifetime of the returned object (null: all cores).
std::unique_ptr<tbb::global_control> limitThreads(const RenderOptions& o);

}  // namespace tandem
