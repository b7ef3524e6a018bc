#include "passes/interleaved/postfx_motion_blur.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

const ParamTable<PostfxMotionBlurSettings>& PostfxMotionBlurPass::tableFor() const {
  using S = PostfxMotionBlurSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::tileSize, {.name = "tile_size",
                              .min = 2,
                              .max = 128,
                              .doc = "K: tile size and largest blur radius (px)"})
          .add(
              &S::samples,
              {.name = "samples", .min = 3, .max = 101, .doc = "S: gather samples per pixel (odd)"})
          .add(&S::softZ, {.name = "soft_z",
                           .min = 0.001,
                           .max = 100,
                           .doc = "soft depth comparison extent (m)"})
          .add(&S::maskThreshold,
               {.name = "mask_threshold",
                .min = 0,
                .max = 100,
                .doc = "mask tiles whose neighbourhood's blur radii differ by more than this (px)"})
          .add(&S::mask,
               {.name = "mask",
                .doc = "spread: radii anywhere in the 3 x 3 tiles differ; edges: adjacent "
                       "pixels' radii jump (a motion boundary) somewhere in them, so "
                       "smooth motion (a camera pan's parallax) stays out",
                .choices = {"spread", "edges"}});
  return table;
}

namespace {

float lengthOf(Vec2 v) {
  return std::sqrt(v.x * v.x + v.y * v.y);
}

float cone(float dist, float speed) {
  return speed <= 0 ? 0.0f : std::clamp(1.0f - dist / speed, 0.0f, 1.0f);
}
float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}
float cylinder(float dist, float speed) {
  if (speed <= 0) return dist <= 0 ? 1.0f : 0.0f;  // a still pixel covers only itself
  return 1.0f - smoothstep(0.95f * speed, 1.05f * speed, dist);
}
// 1 where depth a is (softly) in front of depth b (distances along the view axis).
float softFront(float a, float b, float extent) {
  return std::clamp(1.0f - (a - b) / extent, 0.0f, 1.0f);
}

// One view's blur (McGuire et al.): velocity tiles, their neighbourhoods, the mask of mixed
// motion, and the gather.
struct ViewBlur {
  const Buffer &C, &V, &Z;
  int W, H, ox, oy, K, S;
  float softZ, threshold;
  bool edgesOnly;
  int TX = (W + K - 1) / K, TY = (H + K - 1) / K;
  std::vector<Vec2> tileMax = std::vector<Vec2>(size_t(TX) * TY), neighborMax = tileMax;
  std::vector<float> tileMinSpeed = std::vector<float>(tileMax.size());
  std::vector<uint8_t> tileEdge = std::vector<uint8_t>(tileMax.size(), 0);  // a jump > threshold
  std::vector<float> tileMask = std::vector<float>(tileMax.size(), 0.0f);

  // Blur radius: half the displacement over the shutter, at most K.
  Vec2 radiusAt(int x, int y) const {
    const float* v = V.at(x + ox, y + oy);
    Vec2 r{0.5f * v[0], 0.5f * v[1]};
    const float l = lengthOf(r);
    if (l > float(K)) r = r * (float(K) / l);
    return r;
  }
  // TileMax: each tile's largest radius, smallest speed and whether its velocities jump.
  void tiles() {
    for (int ty = 0; ty < TY; ++ty)
      for (int tx = 0; tx < TX; ++tx) {
        Vec2 best{0, 0};
        float bestL = -1, minL = 1e30f;
        for (int y = ty * K; y < std::min(H, ty * K + K); ++y)
          for (int x = tx * K; x < std::min(W, tx * K + K); ++x) {
            const Vec2 r = radiusAt(x, y);
            const float l = lengthOf(r);
            if (l > bestL) bestL = l, best = r;
            minL = std::min(minL, l);
            if (edgesOnly && ((x + 1 < W && lengthOf(radiusAt(x + 1, y) - r) > threshold) ||
                              (y + 1 < H && lengthOf(radiusAt(x, y + 1) - r) > threshold)))
              tileEdge[size_t(ty) * TX + size_t(tx)] = 1;
          }
        tileMax[size_t(ty) * TX + size_t(tx)] = best;
        tileMinSpeed[size_t(ty) * TX + size_t(tx)] = minL;
      }
  }
  // NeighborMax and the mask of mixed motion: the neighbourhood's largest radius against the
  // velocities in it (the spread between its tiles' largest and smallest radii, and between
  // their largest velocities' directions).
  void neighbours() {
    for (int ty = 0; ty < TY; ++ty)
      for (int tx = 0; tx < TX; ++tx) {
        Vec2 best{0, 0};
        float bestL = -1, minL = 1e30f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = tx + dx, y = ty + dy;
            if (x < 0 || y < 0 || x >= TX || y >= TY) continue;
            const Vec2 r = tileMax[size_t(y) * TX + size_t(x)];
            if (lengthOf(r) > bestL) bestL = lengthOf(r), best = r;
            minL = std::min(minL, tileMinSpeed[size_t(y) * TX + size_t(x)]);
          }
        float spread = bestL - minL;
        bool edge = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = tx + dx, y = ty + dy;
            if (x < 0 || y < 0 || x >= TX || y >= TY) continue;
            spread = std::max(spread, lengthOf(tileMax[size_t(y) * TX + size_t(x)] - best));
            edge = edge || tileEdge[size_t(y) * TX + size_t(x)];
          }
        neighborMax[size_t(ty) * TX + size_t(tx)] = best;
        const bool mixed = edgesOnly ? edge : spread > threshold;
        tileMask[size_t(ty) * TX + size_t(tx)] = bestL > 0.5f && mixed ? 1.0f : 0.0f;
      }
  }
  // The mask: tile values bilinearly between tile centres, 1 wherever a masked tile is.
  float maskAt(int x, int y) const {
    const float fx = (float(x) + 0.5f) / float(K) - 0.5f, fy = (float(y) + 0.5f) / float(K) - 0.5f;
    const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
    const float ax = fx - float(ix), ay = fy - float(iy);
    auto at = [&](int tx, int ty) {
      tx = std::clamp(tx, 0, TX - 1);
      ty = std::clamp(ty, 0, TY - 1);
      return tileMask[size_t(ty) * TX + size_t(tx)];
    };
    float m = (1 - ay) * ((1 - ax) * at(ix, iy) + ax * at(ix + 1, iy)) +
              ay * ((1 - ax) * at(ix, iy + 1) + ax * at(ix + 1, iy + 1));
    if (at(x / K, y / K) > 0) m = 1.0f;
    return m;
  }
  // The gather along the neighbourhood's largest velocity (pixel x, y of the view).
  Vec3 gather(int x, int y, Vec3 cx, Vec2 vn) const {
    const Vec2 vx = radiusAt(x, y);
    const float sx = std::max(lengthOf(vx), 0.5f), zx = Z.at(x + ox, y + oy)[0];
    float weight = 1.0f / sx;
    Vec3 sum = cx * weight;
    // Per-pixel jitter in [-0.5, 0.5] (a hash: deterministic, no pattern).
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u;
    h = (h ^ (h >> 13)) * 0x5bd1e995u;
    const float j = float(h >> 8) / float(1 << 24) - 0.5f;
    for (int i = 0; i < S; ++i) {
      if (i == (S - 1) / 2) continue;
      const float t = -1.0f + 2.0f * (float(i) + j + 1.0f) / float(S + 1);
      const int yx = std::clamp(int(std::lround(float(x) + vn.x * t)), 0, W - 1);
      const int yy = std::clamp(int(std::lround(float(y) + vn.y * t)), 0, H - 1);
      const float dist = std::sqrt(float((yx - x) * (yx - x) + (yy - y) * (yy - y)));
      const Vec2 vy = radiusAt(yx, yy);
      const float sy = lengthOf(vy), zy = Z.at(yx + ox, yy + oy)[0];
      const float f = softFront(zy, zx, softZ), b = softFront(zx, zy, softZ);
      const float a =
          f * cone(dist, sy) + b * cone(dist, sx) + cylinder(dist, sy) * cylinder(dist, sx) * 2.0f;
      weight += a;
      sum = sum + C.rgb(yx + ox, yy + oy) * a;
    }
    return sum * (1.0f / weight);
  }
};

}  // namespace

std::vector<CounterDesc> PostfxMotionBlurPass::counters() const {
  return {
      {PostfxMotionBlurCounters::maskedTilesPercent, "percentage of tiles the blur mask covers"},
  };
}

void PostfxMotionBlurPass::execute(FrameContext& ctx) {
  const Buffer& C = ctx.input(*this, Slots::hdr);
  const Buffer& V = ctx.input(*this, Slots::velocity);
  const Buffer& Z = ctx.input(*this, Slots::viewDepth);
  Buffer& out = ctx.output(*this, Slots::mbPostfx);
  Buffer& maskOut = ctx.output(*this, Slots::mbMask);
  const PostfxMotionBlurSettings& s = settings();
  const int K = s.tileSize, S = s.samples | 1;
  const float softZ = s.softZ, threshold = s.maskThreshold;
  const bool edgesOnly = s.mask == PostfxMotionBlurSettings::Mask::Edges;
  size_t masked = 0, pixels = 0;
  for (const View& view : ctx.views) {
    const int ox = view.x, oy = view.y;
    ViewBlur vb{C, V, Z, view.width(), view.height(), ox, oy, K, S, softZ, threshold, edgesOnly};
    vb.tiles();
    vb.neighbours();
    parallelTiles(vb.W, vb.H, [&](int x0, int y0, int x1, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          maskOut.at(x + ox, y + oy)[0] = vb.maskAt(x, y);
          const Vec2 vn = vb.neighborMax[size_t(y / K) * vb.TX + size_t(x / K)];
          const Vec3 cx = C.rgb(x + ox, y + oy);
          out.setRgb(x + ox, y + oy, lengthOf(vn) <= 0.5f ? cx : vb.gather(x, y, cx, vn));
        }
    });
    for (float m : vb.tileMask) masked += m > 0;
    pixels += vb.tileMask.size();
  }
  ctx.report(*this, PostfxMotionBlurCounters::maskedTilesPercent,
             pixels ? 100.0 * double(masked) / double(pixels) : 0.0);
}

}  // namespace tandem
