// tandem render: renders frames of a scene through a pipeline and writes the output image
// (PNG tonemapped + EXR linear) and any requested AOVs. Per-pass timings are printed.
#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_options.h"
#include "core/error.h"
#include "core/file_commit.h"
#include "core/image_io.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"
#include "verbs.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

// The channel names the pass that produces `buffer` declared (an EXR names channels beyond four
// by them).
std::vector<std::string> declaredChannels(const Pipeline& p, const std::string& buffer) {
  for (const auto& pass : p.passes)
    for (const BufferSlot& s : pass->outputs())
      if (pass->bufferName(s.slot) == buffer) return channelNamesOf(s);
  return {};
}

struct RenderVerb {
  RenderOptions opts;

  std::string exrLayers;  // --exr-layers: hdr and every --aov buffer in one multi-layer EXR

  // The frame's hdr (or output) as R, G, B and each AOV of the frame's size as a layer named
  // after it; other sizes are left to their own files.
  std::vector<unsigned char> layeredExr(const FrameContext& ctx, const Pipeline& pipeline,
                                        const std::vector<std::string>& aovs) const {
    const Buffer& main = ctx.buffers.count("hdr") ? ctx.input("hdr") : ctx.input("output");
    std::vector<ExrLayer> layers{{"", &main}};
    for (const std::string& a : aovs) {
      const Buffer& b = ctx.input(a);
      if (b.width == main.width && b.height == main.height)
        layers.push_back({a, &b, declaredChannels(pipeline, a)});
      else
        std::fprintf(stderr,
                     "tandem: --exr-layers: '%s' is %dx%d, not the frame's size: only "
                     "in its own file\n",
                     a.c_str(), b.width, b.height);
    }
    return encodeExrLayers(exrLayers, layers);
  }

  int run() {
    validateRenderOptions(opts);
    auto threads = limitThreads(opts);
    Pipeline pipeline = loadPipelineFor(opts);
    std::vector<std::string> aovs = splitList(opts.aov);
    std::vector<std::string> produced = pipeline.producedBuffers();
    for (const std::string& a : aovs)
      if (std::find(produced.begin(), produced.end(), a) == produced.end()) {
        std::string list;
        for (auto& p : produced) list += (list.empty() ? "" : ", ") + p;
        throw InputError(
            "command line", "--aov",
            "pipeline '" + pipeline.name + "' has no buffer '" + a + "' (has: " + list + ")");
      }
    if (!exrLayers.empty() && !hasExtension(exrLayers, ".exr"))
      throw InputError("command line", "--exr-layers", "must name an .exr file");
    // Work out every output path before rendering, so bad paths fail fast and nothing is written.
    std::string out = opts.out.empty() ? "out" : opts.out;
    bool isFile = hasExtension(out, ".png") || hasExtension(out, ".exr");
    fs::path dir = isFile ? fs::path(out).parent_path() : fs::path(out);
    Scene scene = loadSceneToRender(opts);
    CameraDesc camera = cameraFor(scene, opts);
    // Only once every input has been validated does the output folder appear.
    if (!dir.empty() && !fs::exists(dir)) fs::create_directories(dir);
    std::string stem = isFile ? fs::path(out).stem().string() : scene.name + "_" + pipeline.name;
    fs::path base = dir / stem;

    Renderer renderer(scene, std::move(pipeline), renderSettingsFor(scene, opts));
    // Only what is written, or read by a pass, is produced.
    renderer.context().keepAllOutputs = false;
    renderer.context().wanted = {aovs.begin(), aovs.end()};
    renderer.context().wanted.insert("hdr");
    FrameTimings last;
    for (int f = 0; f < opts.frames; ++f) last = renderer.renderFrame(f, camera);
    FrameContext& ctx = renderer.context();
    std::printf("scene %s (%zu triangles, %zu lights), pipeline %s, %dx%d%s, %d frame(s)\n",
                scene.name.c_str(), scene.triangleCount(), scene.lights.size(),
                renderer.pipeline().name.c_str(), ctx.width, ctx.height,
                ctx.views.size() > 1 ? " (stereo)" : "", opts.frames);
    for (const PassTiming& p : last.passes) {
      std::printf("  %-28s %9.2f ms", p.name.c_str(), p.ms);
      if (p.rays > 0) std::printf("  %8.2f Mrays/s", p.rays / (p.ms * 1e3));
      if (p.bytes > 0) std::printf("  %8.2f MiB", p.bytes / 1048576.0);
      std::printf("\n");
    }
    std::printf("  %-28s %9.2f ms\n", "frame", last.totalMs);

    if (ctx.counters.count(RasterCounters::trianglesBinned))
      std::printf("  raster: %.0f triangles, %.0f culled, %.0f clipped, %.0f set up and binned\n",
                  ctx.counter(RasterCounters::trianglesIn),
                  ctx.counter(RasterCounters::trianglesCulled),
                  ctx.counter(RasterCounters::trianglesClipped),
                  ctx.counter(RasterCounters::trianglesBinned));
    else if (ctx.counters.count(RasterCounters::trianglesIn))  // the graphics pipeline's draw
      std::printf("  raster: %.0f triangles, %.0f of objects outside the frustum\n",
                  ctx.counter(RasterCounters::trianglesIn),
                  ctx.counter(RasterCounters::trianglesCulled));
    // Every output is staged first and renamed into place together: all files or none.
    const std::string& outName = renderer.pipeline().output;
    FileCommit files;
    std::vector<std::string> written;
    auto stage = [&](const std::string& path, const std::vector<unsigned char>& bytes) {
      files.stage(path, bytes);
      written.push_back(path);
    };
    if (isFile) {
      stage(out, encodeBuffer(out, ctx.input(outName)));
    } else {
      std::string png = base.string() + ".png";
      stage(png, encodeBuffer(png, ctx.input(outName)));
      if (ctx.buffers.count("hdr")) {
        std::string exr = base.string() + ".exr";
        stage(exr, encodeExr(exr, ctx.input("hdr")));
      }
    }
    for (const std::string& a : aovs) {
      std::string ext = isFile && hasExtension(out, ".exr") ? ".exr" : ".png";
      std::string p = base.string() + "_" + a + ext;
      stage(p, encodeBuffer(p, ctx.input(a), declaredChannels(renderer.pipeline(), a)));
    }
    if (!exrLayers.empty()) stage(exrLayers, layeredExr(ctx, renderer.pipeline(), aovs));
    files.commit();
    for (const std::string& p : written) std::printf("wrote %s\n", p.c_str());
    return 0;
  }
};

}  // namespace

VerbRunner addRenderVerb(CLI::App& app) {
  auto verb = std::make_shared<RenderVerb>();
  CLI::App* sub = app.add_subcommand("render", "Render a scene through a pipeline to PNG/EXR");
  sub->add_option("scene", verb->opts.scene, "Scene (same as --scene)");
  addRenderOptions(sub, verb->opts);
  sub->add_option("--exr-layers", verb->exrLayers,
                  "Also write hdr and every --aov buffer as layers of one EXR (layer.channel "
                  "names, as pbrt-v4 and Mitsuba write them)");
  return [verb] { return verb->run(); };
}

}  // namespace tandem
