// tandem bench: runs the scene's camera path after warm-up frames and reports per-pass
// median/mean/min/max milliseconds, frame time and fps (and rays/s for passes that trace). On a
// GPU the output stays on the device, as a real-time renderer presents it, unless --read-output.
#include <tbb/global_control.h>

#include <cstdio>
#include <map>
#include <memory>
#include <thread>

#include "cli_options.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "pipeline/renderer.h"
#include "verbs.h"

namespace tandem {

namespace {

struct BenchVerb {
  RenderOptions opts;
  int warmup = 5;
  std::string json;
  bool readOutput = false;

  int run() {
    if (opts.frames == 1) opts.frames = 60;
    validateRenderOptions(opts);
    if (warmup < 0 || warmup > 10000)
      throw InputError("command line", "--warmup", "must be in [0, 10000]");
    auto threads = limitThreads(opts);
    Pipeline pipeline = loadPipelineFor(opts);
    Scene scene = loadSceneToRender(opts);
    CameraDesc base = cameraFor(scene, opts);
    RenderSettings settings = renderSettingsFor(scene, opts);
    Renderer renderer(scene, std::move(pipeline), settings);
    renderer.context().keepAllOutputs = false;  // nothing is written: what no pass reads is skipped
    renderer.context().outputToHost = readOutput;
    for (int f = 0; f < warmup; ++f)
      renderer.renderFrame(f, pathCamera(scene, base, 0, opts.frames));
    std::vector<std::string> order;
    std::map<std::string, std::vector<double>> ms;
    std::map<std::string, double> rays, rayMs, bytes;
    std::vector<double> total;
    for (int f = 0; f < opts.frames; ++f) {
      FrameTimings ft = renderer.renderFrame(warmup + f, pathCamera(scene, base, f, opts.frames));
      for (const PassTiming& p : ft.passes) {
        if (!ms.count(p.name)) order.push_back(p.name);
        ms[p.name].push_back(p.ms);
        rays[p.name] += p.rays;
        rayMs[p.name] += p.ms;
        bytes[p.name] = p.bytes;  // a move's bytes are the same every frame
      }
      total.push_back(ft.totalMs);
    }
    unsigned cores = std::thread::hardware_concurrency();
    const std::string device =
        settings.gpu ? settings.gpu->info().name + " (" + settings.gpu->info().type + ")"
                     : std::string("cpu");
    std::printf(
        "bench: scene %s, pipeline %s, %dx%d, %d frames after %d warm-up, %s threads (%u cores), "
        "device %s%s\n",
        scene.name.c_str(), renderer.pipeline().name.c_str(), opts.width, opts.height, opts.frames,
        warmup, opts.threads ? std::to_string(opts.threads).c_str() : "all", cores, device.c_str(),
        settings.gpu && !readOutput ? " (output left there, as presented)" : "");
    std::printf("  %-28s %9s %9s %9s %9s %12s\n", "pass", "median", "mean", "min", "max",
                "Mrays/s");
    Json report;
    report["scene"] = scene.name;
    report["pipeline"] = renderer.pipeline().name;
    report["width"] = opts.width;
    report["height"] = opts.height;
    report["frames"] = opts.frames;
    report["warmup"] = warmup;
    report["threads"] = opts.threads;
    report["cores"] = cores;
    report["device"] = device;
    report["output_read_back"] = !settings.gpu || readOutput;
    report["passes"] = Json::object();
    for (const std::string& name : order) {
      TimingStats s = summarize(ms[name]);
      double mrays = rays[name] > 0 ? rays[name] / (rayMs[name] * 1e3) : 0.0;
      std::printf("  %-28s %9.3f %9.3f %9.3f %9.3f", name.c_str(), s.median, s.mean, s.min, s.max);
      if (mrays > 0) std::printf(" %12.2f", mrays);
      if (bytes[name] > 0) std::printf(" %9.2f MiB moved", bytes[name] / 1048576.0);
      std::printf("\n");
      Json pj = {
          {"median_ms", s.median}, {"mean_ms", s.mean}, {"min_ms", s.min}, {"max_ms", s.max}};
      if (mrays > 0) pj["mrays_per_s"] = mrays;
      if (bytes[name] > 0) pj["bytes"] = bytes[name];
      pj["frame_ms"] = ms[name];  // every timed frame, in order (e.g. budget tracking)
      report["passes"][name] = pj;
    }
    TimingStats t = summarize(total);
    std::printf("  %-28s %9.3f %9.3f %9.3f %9.3f\n", "frame", t.median, t.mean, t.min, t.max);
    std::printf("  fps (from median frame) %.2f\n", t.median > 0 ? 1000.0 / t.median : 0.0);
    // What the passes reported of the last frame (rays per pixel, masked share, spp, ...).
    const auto& counters = renderer.context().counters;
    if (!counters.empty()) std::printf("  counters (last frame)\n");
    for (const auto& [name, value] : counters) std::printf("    %-34s %.6g\n", name.c_str(), value);
    report["counters"] = counters;
    report["total"] = {{"median_ms", t.median},
                       {"mean_ms", t.mean},
                       {"min_ms", t.min},
                       {"max_ms", t.max},
                       {"fps", t.median > 0 ? 1000.0 / t.median : 0.0}};
    if (!json.empty()) {
      writeTextFile(json, report.dump(2) + "\n");
      std::printf("wrote %s\n", json.c_str());
    }
    return 0;
  }
};

}  // namespace

VerbRunner addBenchVerb(CLI::App& app) {
  auto verb = std::make_shared<BenchVerb>();
  // The base frame every speed figure is quoted against (render and view default to the hybrid).
  verb->opts.pipeline = "deferred";
  CLI::App* sub = app.add_subcommand("bench", "Time a pipeline along the scene's camera path");
  sub->add_option("scene", verb->opts.scene, "Scene (same as --scene)");
  addRenderOptions(sub, verb->opts);
  sub->add_option("--warmup", verb->warmup, "Warm-up frames not timed");
  sub->add_option("--json", verb->json, "Write the report as JSON");
  sub->add_flag("--read-output", verb->readOutput,
                "On a GPU, read the output back to the host every frame (timed as "
                "download:output); by default it stays on the device, as a presented frame");
  return [verb] { return verb->run(); };
}

}  // namespace tandem
