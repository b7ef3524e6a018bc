#include "eval/reference/reference_cache.h"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/file_commit.h"
#include "core/image_io.h"
#include "passes/baselines/pt_reference.h"
#include "pipeline/pass_edit.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "scene/scene_hash.h"

namespace tandem {
namespace fs = std::filesystem;

std::string referenceKey(const ReferenceJob& job) {
  Hasher h;
  h.pod(kReferenceVersion);
  hashScene(h, *job.scene);
  hashCamera(h, job.camera);
  hashCamera(h, job.shutterCamera);
  const ReferenceSettings& s = job.settings;
  h.pod(job.time).pod(job.shutter).pod(job.width).pod(job.height);
  h.pod(s.spp).pod(s.timeLimitS).pod(s.path.maxDepth).pod(s.path.rouletteDepth).pod(s.seed);
  if (s.integrator == Integrator::Whitted)  // keeps the keys of path-traced references
    h.pod(int(s.integrator)).pod(s.whitted.maxDepth).pod(s.whitted.importanceCutoff);
  // 2: lights picked by the visibility-probed grid (the same expectation, less noise).
  if (s.integrator == Integrator::DiffuseGI) h.pod(int(s.integrator)).pod(int(2));
  if (job.stereo.enabled)  // keeps the keys of mono references as they were
    h.pod(job.stereo.ipd).pod(job.stereo.converged).pod(job.stereo.convergence);
  return h.hex();
}

namespace {

bool loadCached(const fs::path& base, ReferenceImage& out) {
  const fs::path meta = base.string() + ".json";
  if (!fs::exists(meta)) return false;  // written last: its presence means the entry is whole
  try {
    std::ifstream in(meta);
    nlohmann::json j = nlohmann::json::parse(in);
    out.hdr = loadImage(base.string() + ".exr");
    out.variance = loadImage(base.string() + ".variance.exr");
    out.spp = j.at("spp").get<int>();
    out.seconds = j.at("seconds").get<double>();
    out.relativeError = j.at("relativeError").get<double>();
    out.rays = j.at("rays").get<uint64_t>();
  } catch (const std::exception&) {
    return false;  // a damaged entry is rendered again and overwritten
  }
  out.fromCache = true;
  return true;
}

}  // namespace

ReferenceImage referenceImage(const ReferenceJob& job, const std::string& cacheDir,
                              SampleCluster* cluster) {
  ReferenceImage img;
  img.key = referenceKey(job);
  const fs::path base = cacheDir.empty() ? fs::path() : fs::path(cacheDir) / img.key;
  // Every rank decides alike: rank 0 looks in the cache and tells the others.
  int cached = 0;
  if (!cacheDir.empty() && (!cluster || cluster->rank() == 0)) cached = loadCached(base, img);
  if (cluster) cached = cluster->broadcast(cached);
  if (cached) {
    img.fromCache = true;
    return img;
  }

  Pipeline p = Pipeline::load("reference");
  const ReferenceSettings& s = job.settings;
  editPass<PTReferencePass>([&](PTReferenceSettings& pt) {
    pt.spp = s.spp;
    pt.timeLimit = s.timeLimitS;
    pt.maxDepth = s.path.maxDepth;
    pt.integrator = s.integrator;
    if (s.integrator == Integrator::Whitted) pt.whittedDepth = s.whitted.maxDepth;
    pt.progress = s.progress;
  })(p);
  RenderSettings rs{
      .width = job.width, .height = job.height, .seed = s.seed, .shutter = job.shutter};
  rs.stereo = job.stereo;
  rs.gpu = job.gpu;
  Renderer r(*job.scene, std::move(p), rs);
  for (auto& pass : r.pipeline().passes)
    if (auto* pt = dynamic_cast<PTReferencePass*>(pass.get())) pt->distribute(cluster);
  const auto start = Clock::now();
  FrameTimings ft = r.renderFrameAt(0, job.time, job.camera, job.shutterCamera);
  img.seconds = msSince(start) * 1e-3;
  // Throughput counts the sampling only (not the BVH build), as Embree's benchmark does.
  const PassTimes times(r.pipeline(), ft);
  img.rays = uint64_t(times.raysOf("pt_reference"));
  img.samplingSeconds = times.partOf("pt_reference", "sampling") * 1e-3;
  img.spp = int(r.context().counter(PTReferenceCounters::spp));
  img.hdr = r.context().input("hdr");
  img.variance = r.context().input("variance");
  img.relativeError = relativeNoise(img.hdr, img.variance);
  if (!cacheDir.empty() && (!cluster || cluster->rank() == 0)) {
    fs::create_directories(cacheDir);
    // Image, variance and metadata committed together: a cache entry is whole or absent.
    FileCommit files;
    files.stage(base.string() + ".exr", encodeExr(base.string() + ".exr", img.hdr));
    files.stage(base.string() + ".variance.exr",
                encodeExr(base.string() + ".variance.exr", img.variance));
    nlohmann::json j = {{"scene", job.scene->name},
                        {"width", job.width},
                        {"height", job.height},
                        {"spp", img.spp},
                        {"targetSpp", s.spp},
                        {"timeLimit", s.timeLimitS},
                        {"maxDepth", s.path.maxDepth},
                        {"integrator", integratorName(s.integrator)},
                        {"seed", s.seed},
                        {"time", job.time},
                        {"shutter", job.shutter},
                        {"seconds", img.seconds},
                        {"rays", img.rays},
                        {"relativeError", img.relativeError}};
    files.stage(base.string() + ".json", j.dump(2) + "\n");
    files.commit();
  }
  return img;
}

}  // namespace tandem
