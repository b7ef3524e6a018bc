// tandem export: writes a scene (built-in, file or scene description) as world-space OBJ + MTL,
// so other renderers (Embree's path tracer tutorial, for the throughput comparison) can render
// exactly the same geometry.
#include <cstdio>
#include <filesystem>

#include "cli_options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "scene/obj_writer.h"
#include "verbs.h"

namespace tandem {

VerbRunner addExportVerb(CLI::App& app) {
  struct Args {
    RenderOptions opts;
    float time = 0;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("export", "Write a scene as world-space OBJ + MTL");
  sub->add_option("--scene", a->opts.scene, "Scene: file or built-in (cornell, spheres, atrium)");
  sub->add_option("--out", a->opts.out, "Output .obj file (the .mtl goes beside it)")->required();
  sub->add_option("--time", a->time, "Scene time in seconds (animation)");
  return [a] {
    if (!hasExtension(a->opts.out, ".obj"))
      throw InputError("command line", "--out", "must name an .obj file");
    Scene s = loadSceneFor(a->opts);
    const std::filesystem::path dir = std::filesystem::path(a->opts.out).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
    const size_t tris = writeObj(s, a->opts.out, a->time);
    std::printf("wrote %s (%zu triangles, %zu materials; lights and textures are not exported)\n",
                a->opts.out.c_str(), tris, s.materials.size());
    return 0;
  };
}

}  // namespace tandem
