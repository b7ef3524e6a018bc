// tandem reference: a converged ground-truth image of a scene — progressive path tracing to a
// sample count or a time limit, with thin lens / polygonal aperture and motion blur — cached on
// disk by a hash of everything that determines it. Under `mpirun -n K` the rows are split over
// K processes and rank 0 writes the same image a single process would.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli_options.h"
#include "core/error.h"
#include "core/file_commit.h"
#include "core/image_io.h"
#include "eval/reference/reference_cache.h"
#include "mpi_cluster.h"
#include "pipeline/aov.h"
#include "pipeline/render_limits.h"
#include "rt/diffuse_gi.h"
#include "verbs.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

struct ReferenceVerb {
  RenderOptions opts;
  int spp = 1024, maxDepth = -1;  // -1: 16 path bounces, 10 Whitted levels
  double timeLimit = 0;
  std::string integrator = "path";
  float time = 0;
  bool cameraPath = false, noCache = false, quiet = false;
  std::string cache;

  void validate() {
    validateRenderOptions(opts);
    checkSpp("command line", "--spp", spp);
    if (maxDepth == -1) maxDepth = integrator == "whitted" ? 10 : 16;
    if (maxDepth < 1 || maxDepth > 1024)
      throw InputError("command line", "--max-depth", "must be in [1, 1024]");
    if (!(timeLimit >= 0)) throw InputError("command line", "--time-limit", "must be >= 0 seconds");
    if (integrator != "path" && integrator != "whitted" && integrator != "diffuse-gi")
      throw InputError("command line", "--integrator", "expected path, whitted or diffuse-gi");
    checkTime("command line", "--time", time);
  }

  int run() {
    validate();
    auto threads = limitThreads(opts);
    std::unique_ptr<SampleCluster> cluster = makeMpiCluster();
    const bool root = !cluster || cluster->rank() == 0;
    std::string out = opts.out.empty() ? "out" : opts.out;
    const bool isFile = hasExtension(out, ".png") || hasExtension(out, ".exr");
    Scene scene = loadSceneToRender(opts);
    ReferenceJob job;
    job.scene = &scene;
    CameraDesc cam = cameraFor(scene, opts);  // with --aperture, --focus, --blades
    const float shutter = opts.shutter;
    job.camera = cameraPath ? pathCameraAt(scene, cam, time) : cam;
    job.shutterCamera = cameraPath ? pathCameraAt(scene, cam, time + shutter) : job.camera;
    job.time = time;
    job.shutter = shutter;
    job.width = opts.width;
    job.height = opts.height;
    job.stereo = stereoFor(scene, opts);
    job.settings.spp = spp;
    job.settings.timeLimitS = timeLimit;
    job.settings.path.maxDepth = maxDepth;
    if (integrator == "whitted") {
      job.settings.integrator = Integrator::Whitted;
      job.settings.whitted.maxDepth = std::min(maxDepth, 64);
    }
    if (integrator == "diffuse-gi") {
      job.settings.integrator = Integrator::DiffuseGI;
      if (const std::string note = DiffuseGI::blackMaterialsNote(scene); !note.empty())
        std::fprintf(stderr, "tandem: warning: %s\n", note.c_str());
    }
    job.settings.seed = opts.seed;
    job.gpu = deviceFor(opts);
    job.settings.progress = !quiet;
    const fs::path dir = isFile ? fs::path(out).parent_path() : fs::path(out);
    const std::string stem = isFile ? fs::path(out).stem().string() : scene.name + "_reference";
    if (root && !dir.empty() && !fs::exists(dir)) fs::create_directories(dir);

    ReferenceImage img = referenceImage(job, noCache ? "" : cache, cluster.get());
    if (!root) return 0;
    std::printf("reference %s %dx%d: %d spp%s, key %s\n", scene.name.c_str(), opts.width,
                opts.height, img.spp, img.fromCache ? " (from cache)" : "", img.key.c_str());
    if (!img.fromCache)
      std::printf(
          "  %.2f s (sampling %.2f s), %.2f Mrays/s%s, noise %.2f %% (median relative "
          "standard error)\n",
          img.seconds, img.samplingSeconds, double(img.rays) / img.samplingSeconds * 1e-6,
          cluster ? " (all processes)" : "", 100.0 * img.relativeError);
    if (cluster) std::printf("  %d MPI processes\n", cluster->ranks());
    const fs::path base = dir / stem;
    const std::string png = isFile && hasExtension(out, ".png") ? out : base.string() + ".png";
    const std::string exr = isFile && hasExtension(out, ".exr") ? out : base.string() + ".exr";
    FileCommit files;                              // all three or none
    files.stage(png, encodeBuffer(png, img.hdr));  // ACES, as the reference pipeline's tonemap
    files.stage(exr, encodeExr(exr, img.hdr));
    files.stage(base.string() + ".variance.exr",
                encodeExr(base.string() + ".variance.exr", img.variance));
    files.commit();
    std::printf("wrote %s\nwrote %s\nwrote %s\n", png.c_str(), exr.c_str(),
                (base.string() + ".variance.exr").c_str());
    return 0;
  }
};

}  // namespace

VerbRunner addReferenceVerb(CLI::App& app) {
  auto v = std::make_shared<ReferenceVerb>();
  v->opts.width = 640;
  v->opts.height = 360;
  const char* env = std::getenv("TANDEM_REFERENCE_CACHE");
  v->cache = env && *env ? env : "out/reference-cache";
  CLI::App* sub = app.add_subcommand(
      "reference", "Render a converged path-traced ground truth (cached; mpirun splits it)");
  addSceneOptions(sub, v->opts);
  sub->add_option("--spp", v->spp, "Target samples per pixel (default 1024)");
  sub->add_option("--time-limit", v->timeLimit, "Stop after this many seconds (0 = none)");
  sub->add_option("--max-depth", v->maxDepth,
                  "Maximum path length in bounces (default 16); whitted: recursion depth (default "
                  "10, as rt-only; at most 64)");
  sub->add_option("--integrator", v->integrator,
                  "path (global illumination, default); whitted: distributed ray tracing of the "
                  "hybrids' shading (shadows, mirrors, glass), the ground truth of a technique "
                  "such as depth of field with the same light transport; diffuse-gi: the "
                  "foveated pipelines' path tracer (one random light, one diffuse bounce) at "
                  "pixel centres, their ground truth");
  sub->add_option("--time", v->time, "Scene time in seconds (animation)");
  sub->add_flag("--camera-path", v->cameraPath,
                "Camera from the scene's camera path at --time (moving while the shutter is open)");
  addLensOptions(sub, v->opts);
  addDeviceOption(sub, v->opts);
  sub->add_option("--cache", v->cache,
                  "Cache folder (default $TANDEM_REFERENCE_CACHE or out/reference-cache)");
  sub->add_flag("--no-cache", v->noCache, "Always render; do not read or write the cache");
  sub->add_flag("--quiet", v->quiet, "No progress bar");
  return [v] { return v->run(); };
}

}  // namespace tandem
