// tandem info SCENE: what a scene holds (triangles, objects, materials, textures, lights,
// bounds, memory, degenerate triangles skipped).
#include <cstdio>
#include <memory>

#include "cli_options.h"
#include "core/error.h"
#include "gpu/gpu_device.h"
#include "rt/diffuse_gi.h"
#include "verbs.h"

namespace tandem {

namespace {
const char* lightTypeName(LightType t) {
  return t == LightType::Directional ? "directional" : t == LightType::Point ? "point" : "spot";
}
int listDevices() {
  std::string why;
  const std::vector<GpuDeviceInfo> list = listGpuDevices(&why);
  if (list.empty()) {
    std::printf("no Vulkan device: %s\n--device auto renders on the CPU; --device gpu fails\n",
                why.c_str());
    return 0;
  }
  std::printf("Vulkan devices (%zu)\n", list.size());
  for (size_t i = 0; i < list.size(); ++i) {
    const GpuDeviceInfo& d = list[i];
    std::printf("  %zu  %s (%s), Vulkan %s, %s, subgroups of %u, %.1f GiB device-local\n", i,
                d.name.c_str(), d.type.c_str(), d.apiText().c_str(), d.driver.c_str(),
                d.subgroupSize, double(d.deviceLocalBytes) / double(1ull << 30));
    if (!d.usable) std::printf("     not usable: lacks %s\n", d.missing.c_str());
  }
  auto named = [&](DeviceChoice c) -> std::string {
    try {
      auto g = GpuDevice::forChoice(c, "info");
      return g ? g->info().name : std::string("the CPU");
    } catch (const InputError&) {
      return "none (no usable device)";
    }
  };
  std::printf("--device auto: %s\n--device gpu:  %s\n", named(DeviceChoice::Auto).c_str(),
              named(DeviceChoice::Gpu).c_str());
  return 0;
}

}  // namespace

VerbRunner addInfoVerb(CLI::App& app) {
  auto opts = std::make_shared<RenderOptions>();
  auto verbose = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "info", "Describe a scene: triangles, objects, materials, lights, bounds, memory");
  sub->add_option("scene", opts->scene, "Scene file or built-in name");
  sub->add_option("--scene", opts->scene, "Scene file or built-in name");
  sub->add_option("--emissive-lights", opts->emissiveLights, "auto, on or off");
  sub->add_option("--default-lights", opts->defaultLights,
                  "auto (a sun-and-sky rig when the scene has no lights) or off");
  sub->add_flag("--objects", *verbose, "List every object");
  auto devices = std::make_shared<bool>(false);
  sub->add_flag("--devices", *devices,
                "List the Vulkan devices and which one --device auto and gpu would use");
  return [opts, verbose, devices] {
    if (*devices) return listDevices();
    validateRenderOptions(*opts);
    Scene s = loadSceneFor(*opts);
    Bounds3 b = s.bounds();
    size_t lightsByType[3] = {0, 0, 0};
    for (const Light& l : s.lights) ++lightsByType[int(l.type)];
    size_t emissive = 0;
    for (const Object& o : s.objects)
      if (maxComponent(s.materials[o.material].emission) > 0) ++emissive;
    std::printf("scene        %s\n", s.name.c_str());
    for (const auto& src : s.stats.sources) std::printf("source       %s\n", src.c_str());
    std::printf("triangles    %zu\n", s.triangleCount());
    std::printf("degenerate   %zu (skipped while loading)\n", s.stats.degenerateTriangles);
    if (s.stats.skippedPrimitives)
      std::printf("skipped      %zu glTF point or line primitives (nothing to shade)\n",
                  s.stats.skippedPrimitives);
    std::printf("objects      %zu (%zu emissive, %zu animated)\n", s.objects.size(), emissive,
                size_t(std::count_if(s.objects.begin(), s.objects.end(),
                                     [](const Object& o) { return o.animated(); })));
    std::printf("meshes       %zu\n", s.meshes.size());
    std::printf("materials    %zu\n", s.materials.size());
    std::printf("textures     %zu\n", s.textures.size());
    std::printf("lights       %zu (%zu directional, %zu point, %zu spot)%s\n", s.lights.size(),
                lightsByType[0], lightsByType[1], lightsByType[2],
                s.stats.defaultLightRig ? ", the default rig: the scene has none" : "");
    std::printf("bounds       (%.4g, %.4g, %.4g) - (%.4g, %.4g, %.4g)\n", b.lo.x, b.lo.y, b.lo.z,
                b.hi.x, b.hi.y, b.hi.z);
    std::printf("camera       %s, path with %zu keys\n",
                s.hasCamera ? "from scene" : "none (auto-framed)", s.cameraPath.size());
    std::printf("memory       %.2f MiB (meshes, textures, materials)\n",
                s.memoryBytes() / 1048576.0);
    if (const std::string note = DiffuseGI::blackMaterialsNote(s); !note.empty())
      std::printf("lambert-only %s\n", note.c_str());
    for (const Light& l : s.lights)
      std::printf("  light %-24s %-11s intensity %g\n", l.name.c_str(), lightTypeName(l.type),
                  l.intensity);
    if (*verbose)
      for (const Object& o : s.objects)
        std::printf("  object %-32s %7zu tris  material %s\n", o.name.c_str(),
                    s.meshes[o.mesh].triangleCount(), s.materials[o.material].name.c_str());
    return 0;
  };
}

}  // namespace tandem
