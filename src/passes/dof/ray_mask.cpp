#include "passes/dof/ray_mask.h"

#include <optional>

#include <cmath>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"

namespace tandem {

std::vector<BufferSlot> RayMaskPass::inputs() const {
  BufferSlot variance{Slots::dofVariance, 1, BufferKind::Variance, Extent::any()};
  variance.history = true;
  BufferSlot bokeh = dof::BokehChannels::slot();
  bokeh.optional = true;
  return {{Slots::position, 3, BufferKind::Position},
          {Slots::normal, 3, BufferKind::Normal},
          {Slots::depth, 1, BufferKind::Depth},
          {Slots::coc, 1, BufferKind::Signed},
          variance,
          bokeh};
}

const ParamTable<RayMaskSettings>& RayMaskPass::tableFor() const {
  using S = RayMaskSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::m,
               {.name = "m", .min = 0, .max = 1024, .doc = "ray budget: most lens rays per pixel"})
          .add(&S::s, {.name = "s",
                       .min = 0,
                       .max = 1,
                       .doc = "eq. 2: scale of the depth + normal gradient"})
          .add(&S::varianceWeight, {.name = "variance_weight",
                                    .min = 0,
                                    .max = 1e9,
                                    .doc = "eq. 4: weight of the accumulated luminance variance"})
          .add(&S::dilate, {.name = "dilate",
                            .doc = "one ray within the near field's CoC radius around it (beyond "
                                   "the paper, Fig. 8b)"})
          .add(&S::mode, {.name = "mode",
                          .doc = "adaptive: eq. 2-4; all: m rays in every pixel (rt-dof)",
                          .choices = {"adaptive", "all"}})
          .add(&S::fineCoc,
               dof::fineCocParam(
                   "no rays where dof_composite gathers the sharp image instead (|CoC| below "
                   "half of this, no foreground over the pixel: keep equal to "
                   "dof_composite.fine_coc; 0 = off)"))
          .add(&S::resolution, {.name = "resolution",
                                .doc = "of the mask and the ray-traced DoF (the paper: half)",
                                .choices = {"half", "full"},
                                .invalidatesHistory = true});
  return table;
}

namespace {

// Inverse depth relative to the focus distance, d / z (a depth buffer's kind of value: a slanted
// floor in the distance has almost no gradient, a near silhouette against what is behind it a
// large one; the sky is 0, nearer than d / 8 clamps at 8), and normals, Gaussian-filtered, at
// the mask's resolution; their 5x5 Sobel gradients (a unit step gives 48, the kernel's
// half-sum, so / 48 reads as the step height).
void gradients(const Buffer& position, const Buffer& normal, const Buffer& depth, const Camera& cam,
               int scale, Buffer (&out)[4]) {
  const int W = position.width, H = position.height;
  const float focus = cam.desc.focusDistance;
  Buffer g(W, H, 4);
  parallelRows(H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const float* p = position.at(x, y);
      const float z = dot(Vec3(p[0], p[1], p[2]) - cam.eye, cam.forward);
      const float zr = depth.at(x, y)[0] > 0 ? std::min(focus / std::max(z, 1e-6f), 8.0f) : 0.0f;
      float* o = g.at(x, y);
      o[0] = zr;
      o[1] = normal.at(x, y)[0];
      o[2] = normal.at(x, y)[1];
      o[3] = normal.at(x, y)[2];
    }
  });
  Buffer low = gaussianBlur(g, 1.0f);
  if (scale == 2) low = downsampleBox(low);
  for (int c = 0; c < 4; ++c) out[c] = sobel5x5(low, c);
}

// Dilation of the near field: a summed-area table of near-field pixels answers "any within
// radius r?" per pixel; r is the largest near radius in the surrounding 16x16-pixel tiles (3x3
// of them).
class NearDilation {
 public:
  explicit NearDilation(const Buffer& nearRadius)
      : w(nearRadius.width), h(nearRadius.height), tw((w + kT - 1) / kT), th((h + kT - 1) / kT) {
    sat.assign(size_t(w + 1) * (h + 1), 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        sat[size_t(y + 1) * (w + 1) + x + 1] =
            (nearRadius.at(x, y)[0] > 0 ? 1 : 0) + sat[size_t(y) * (w + 1) + x + 1] +
            sat[size_t(y + 1) * (w + 1) + x] - sat[size_t(y) * (w + 1) + x];
    std::vector<float> t(size_t(tw) * th, 0.0f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        float& r = t[size_t(y / kT) * tw + size_t(x / kT)];
        r = std::max(r, nearRadius.at(x, y)[0]);
      }
    tileR.assign(t.size(), 0.0f);
    for (int ty = 0; ty < th; ++ty)
      for (int tx = 0; tx < tw; ++tx)
        for (int j = std::max(ty - 1, 0); j <= std::min(ty + 1, th - 1); ++j)
          for (int i = std::max(tx - 1, 0); i <= std::min(tx + 1, tw - 1); ++i)
            tileR[size_t(ty) * tw + tx] =
                std::max(tileR[size_t(ty) * tw + tx], t[size_t(j) * tw + i]);
  }
  bool nearAt(int x, int y) const {
    const int r = int(std::ceil(tileR[size_t(y / kT) * tw + size_t(x / kT)]));
    if (r <= 0) return false;
    const int x0 = std::max(x - r, 0), x1 = std::min(x + r + 1, w);
    const int y0 = std::max(y - r, 0), y1 = std::min(y + r + 1, h);
    return sat[size_t(y1) * (w + 1) + x1] - sat[size_t(y0) * (w + 1) + x1] -
               sat[size_t(y1) * (w + 1) + x0] + sat[size_t(y0) * (w + 1) + x0] >
           0;
  }

 private:
  static constexpr int kT = 16;
  int w, h, tw, th;
  std::vector<int> sat;
  std::vector<float> tileR;
};

}  // namespace

std::vector<CounterDesc> RayMaskPass::counters() const {
  return {
      {RayMaskCounters::raysPerPixel, "lens rays per pixel, averaged over the frame"},
      {RayMaskCounters::maskedShare, "share of pixels that get lens rays"},
  };
}

void RayMaskPass::execute(FrameContext& ctx) {
  const Buffer& position = ctx.input(*this, Slots::position);
  const Buffer& normal = ctx.input(*this, Slots::normal);
  const Buffer& depth = ctx.input(*this, Slots::depth);
  const Buffer& coc = ctx.input(*this, Slots::coc);
  const RayMaskSettings& cfg = settings();
  const int scale = cfg.resolution == RayMaskSettings::Resolution::Half ? 2 : 1;
  const int W = ctx.width, H = ctx.height, w = (W + scale - 1) / scale, h = (H + scale - 1) / scale;
  Buffer& mask = ctx.output(*this, Slots::rayMask, w, h);
  const float m = float(cfg.m);
  if (cfg.mode == RayMaskSettings::Mode::All) {
    mask.fill(m);
    return;
  }
  Buffer grads[4];
  gradients(position, normal, depth, ctx.camera(), scale, grads);

  // Near-field pixels (at the mask's resolution) and, for the dilation, their CoC radius; and
  // the pixels whose every frame pixel the composite takes wholly from its full-resolution gather
  // of the sharp image (|CoC| below half of fine_coc, no foreground share in the post-process
  // gather): rays there would not be seen (beyond the paper).
  const Buffer* bokeh = ctx.optionalInput(*this, Slots::bokeh);
  const float fineCoc = bokeh ? 0.5f * cfg.fineCoc : 0.0f;
  Buffer nearRadius(w, h, 1);
  std::vector<unsigned char> gathered(size_t(w) * size_t(h), 0);
  parallelRows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float c = 0.0f;
      bool fine = fineCoc > 0;
      for (int j = 0; j < scale; ++j)
        for (int i = 0; i < scale; ++i) {
          const int px = std::min(x * scale + i, W - 1), py = std::min(y * scale + j, H - 1);
          const float cp = coc.at(px, py)[0];
          c = std::min(c, cp);
          fine = fine && std::abs(cp) < fineCoc &&
                 bokeh->at(px, py)[dof::BokehChannels::kForeground] <= dof::kSilhouette;
        }
      nearRadius.at(x, y)[0] = c < -dof::kZoneOfFocusCoc ? -0.5f * c / float(scale) : 0.0f;
      gathered[size_t(y) * size_t(w) + size_t(x)] = fine;
    }
  });
  const bool dilate = cfg.dilate;
  std::optional<NearDilation> dilation;
  if (dilate) dilation.emplace(nearRadius);

  const Buffer* variance = ctx.previous(*this, Slots::dofVariance);
  if (variance && (variance->width != w || variance->height != h)) variance = nullptr;
  const float s = cfg.s, vw = cfg.varianceWeight;
  parallelRows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float* gd = grads[0].at(x, y);
      const float dd = std::sqrt(gd[0] * gd[0] + gd[1] * gd[1]) / 48.0f;
      float nn = 0.0f;
      for (int c = 1; c < 4; ++c) {
        const float* gn = grads[c].at(x, y);
        nn += gn[0] * gn[0] + gn[1] * gn[1];
      }
      const float xe = (dd + std::sqrt(nn) / 48.0f) * s;          // eq. 2
      const float xn = dof::saturate(1.0f - 1.0f / (xe + 1.0f));  // eq. 3
      const float var = variance ? variance->at(x, y)[0] : 0.0f;
      float rays = std::round(dof::saturate(xn + var * vw) * m);  // eq. 4
      bool near = nearRadius.at(x, y)[0] > 0;
      if (!near && dilate) near = dilation->nearAt(x, y);
      if (near && m > 0) rays = std::max(rays, 1.0f);
      mask.at(x, y)[0] = gathered[size_t(y) * size_t(w) + size_t(x)] ? 0.0f : rays;
    }
  });
  double total = 0, masked = 0;
  for (size_t i = 0; i < mask.pixelCount(); ++i) total += mask.data[i], masked += mask.data[i] > 0;
  ctx.report(*this, RayMaskCounters::raysPerPixel, total / double(mask.pixelCount()));
  ctx.report(*this, RayMaskCounters::maskedShare, masked / double(mask.pixelCount()));
}

}  // namespace tandem
