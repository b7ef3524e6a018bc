#include "eval/reference/supersample.h"

namespace tandem {

std::string outputSource(const Pipeline& p) {
  for (const auto& pass : p.passes)
    for (const BufferSlot& o : pass->outputs())
      if (pass->bufferName(o.slot) == p.output && pass->inputSlot("hdr"))
        return pass->bufferName("hdr");
  return p.output;
}

Buffer supersample(const Scene& scene, const std::string& pipeline, const CameraDesc& camera,
                   const RenderSettings& settings, int n, const std::string& bufferName) {
  RenderSettings fine = settings;
  fine.textureFootprint = settings.textureFootprint / float(std::max(n, 1));
  Renderer r(scene, Pipeline::load(pipeline), fine);
  const std::string buffer = bufferName.empty() ? outputSource(r.pipeline()) : bufferName;
  Buffer sum;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 jitter{(float(i) + 0.5f) / float(n) - 0.5f, (float(j) + 0.5f) / float(n) - 0.5f};
      r.cut();  // independent renders
      // A zero jitter means "none requested": nudge the centre cell (n odd) off exactly 0.
      r.renderFrame(0, camera, jitter.x == 0 && jitter.y == 0 ? Vec2{1e-6f, 0} : jitter);
      const Buffer& b = r.context().input(buffer);
      if (sum.data.empty()) sum = Buffer(b.width, b.height, b.channels, 0.0f, b.kind);
      for (size_t k = 0; k < b.data.size(); ++k) sum.data[k] += b.data[k];
    }
  const float inv = 1.0f / float(n * n);
  for (float& v : sum.data) v *= inv;
  return sum;
}

}  // namespace tandem
