#include "passes/heuristic/shadow_tile.h"

#include <algorithm>

#include "core/cycle_clock.h"
#include "passes/heuristic/ranked_tiles.h"
#include "scene/scene.h"
#include "shading/shade_batch.h"

namespace tandem {

Vec3 classShares(const uint8_t* classes, size_t lights, size_t stride, int j, int only) {
  Vec3 c(0.0f);
  float reached = 0;
  for (size_t i = 0; i < lights; ++i) {
    if (only >= 0 && i != size_t(only)) continue;
    const auto k = ShadowClass(classes[stride * i + size_t(j)]);
    if (k == ShadowClass::Culled) continue;
    reached += 1;
    c.x += k == ShadowClass::Traced ? 1.0f : 0.0f;
    c.y += k == ShadowClass::Lit ? 1.0f : 0.0f;
    c.z += k == ShadowClass::Shadowed ? 1.0f : 0.0f;
  }
  return reached > 0 ? c / reached : c;
}

namespace {

constexpr int W = ShadeBatch::kMax;
using F = ShadeBatch;

// One batch of up to 16 lanes: their shadow term S, light by light.
class ShadowBatch {
 public:
  ShadowBatch(const ShadowTile& t, EffectTally* tally, ShadowCounts& counts)
      : t_(t),
        tally_(tally),
        counts_(counts),
        lights_(t.scene.lights.size()),
        share_(lights_ * W),
        terms_(kLightTerms * lights_ * W),
        blocked_(3 * lights_ * W),
        classes_(t.classes ? lights_ * W : 0) {}

  ShadeBatch& batch() { return b_; }
  void push(int x, int y) {
    xs_[b_.count] = x;
    ys_[b_.count++] = y;
    if (b_.count == W) flush();
  }
  // A whole batch read at once (GBufferReader::readSpan) from the W pixels (x .., y), the box
  // around their positions with it: the same batch push() would have made of them.
  void pushSpan(int x, int y, const Bounds3& lanes) {
    for (int k = 0; k < W; ++k) xs_[k] = x + k, ys_[k] = y;
    b_.count = W;
    flush(&lanes);
  }

  void flush(const Bounds3* lanes = nullptr) {
    const int n = b_.count;
    if (n == 0) return;
    const uint64_t c0 = t_.timed ? cycleNow() : 0;
    // Only the lights that may reach a lane are weighed; the others are culled unseen.
    cullLights(b_, t_.shading, reached_, lanes);
    lightContributions(b_, t_.shading, share_.data(), W, terms_.data());
    Vec3 unshadowed[W];
    if (t_.shadedRadiance)
      for (int k = 0; k < n; ++k) unshadowed[k] = b_.result(k);
    counts_.culled += uint64_t(n) * (lights_ - reached_.size());
    if (t_.classes) std::fill(classes_.begin(), classes_.end(), uint8_t(ShadowClass::Culled));
    float floor[W];
    Vec3 pos[W], geo[W];
    int self[W], rays[W] = {};
    for (int k = 0; k < n; ++k) {
      floor[k] = t_.settings.shadowCull * luminance(b_.result(k));
      pos[k] = {b_.f[F::PX][k], b_.f[F::PY][k], b_.f[F::PZ][k]};
      geo[k] = t_.geoNormal.rgb(xs_[k], ys_[k]);
      self[k] = int(t_.ids.at(xs_[k], ys_[k])[0]);
    }
    if (t_.maps && t_.settings.shadows == ShadowMode::Maps) {
      // The maps' lookups read positions and normals as structure of arrays, the same for
      // every light.
      for (int k = 0; k < n; ++k) {
        soa_[0][k] = pos[k].x, soa_[1][k] = pos[k].y, soa_[2][k] = pos[k].z;
        soa_[3][k] = geo[k].x, soa_[4][k] = geo[k].y, soa_[5][k] = geo[k].z;
      }
    }
    blockedLights_.clear();
    for (const uint32_t i : reached_)
      if (light(i, n, floor, pos, geo, self, rays)) blockedLights_.push_back(i);
    if (!blockedLights_.empty()) {
      b_.lights = blockedLights_.data();
      b_.lightCount = blockedLights_.size();
      // From the terms the culling evaluated: no light is evaluated twice.
      shadeFromTerms(b_, t_.shading, terms_.data(), blocked_.data(), W);
    }
    const uint64_t ticks = t_.timed ? cycleNow() - c0 : 0;
    for (int k = 0; k < n; ++k) {
      const Vec3 s =
          blockedLights_.empty() ? Vec3(1.0f) : shadowFromBlocked(b_, k, t_.shading.ambient);
      float* out = t_.shadow.at(xs_[k], ys_[k]);
      const Vec3 v = t_.shadedRadiance ? unshadowed[k] - (Vec3(1.0f) - s) : s;
      out[t_.shadowChannel] = v.x, out[t_.shadowChannel + 1] = v.y, out[t_.shadowChannel + 2] = v.z;
      if (t_.coverChannel >= 0) out[t_.coverChannel] = 1.0f;
      if (t_.classes)
        t_.classes->setRgb(xs_[k], ys_[k],
                           classShares(classes_.data(), lights_, W, k, t_.classLight));
      if (!tally_) continue;
      EffectTally& e = tally_[size_t(self[k])];
      e.pixels[kShadow] += 1;
      e.rays[kShadow] += uint64_t(rays[k]);
      e.ticks[kShadow] += ticks / uint64_t(n);
    }
    counts_.surfaces += uint64_t(n);
    b_.count = 0;
  }

 private:
  // Light i for lanes [0, n): classes, rays for the undecided, the blocked fraction per channel
  // into blocked_; true when it blocks anything in any lane.
  bool light(size_t i, int n, const float* floor, const Vec3* pos, const Vec3* geo, const int* self,
             int* rays) {
    bool asked[W];
    ShadowClass c[W];
    const bool casts = t_.scene.lights[i].castsShadows;
    int askedLanes = 0;
    for (int k = 0; k < n; ++k) {
      const float sh = share_[i * W + size_t(k)];
      asked[k] = casts && sh > 0.0f && sh >= floor[k];
      c[k] = asked[k] ? ShadowClass::Traced : ShadowClass::Culled;
      askedLanes += asked[k] ? 1 : 0;
    }
    // Every lane culled (classes_ holds Culled already): nothing to classify, trace or shade.
    if (askedLanes == 0) {
      counts_.culled += uint64_t(n);
      return false;
    }
    const ShadowMode mode = t_.maps ? t_.settings.shadows : ShadowMode::Rays;
    if (mode == ShadowMode::Maps) return mapsLight(i, n, asked);
    if (mode == ShadowMode::Classified)
      for (int k0 = 0; k0 < n; k0 += 8)
        t_.maps->classify(i, std::min(8, n - k0), pos + k0, geo + k0, self + k0, asked + k0,
                          c + k0);
    Vec3 vis[W];
    Ray r[8];
    bool active[8] = {};
    int lane[8], m = 0;
    auto trace = [&] {
      Vec3 tr[8];
      t_.rt->transmittance8(r, active, tr, t_.settings.texturedShadows);
      for (int j = 0; j < m; ++j) vis[lane[j]] = tr[j];
      std::fill(active, active + 8, false);
      m = 0;
    };
    for (int k = 0; k < n; ++k) {
      vis[k] = Vec3(c[k] == ShadowClass::Shadowed ? 0.0f : 1.0f);
      if (c[k] == ShadowClass::Traced) {
        SurfaceSample s;
        s.position = pos[k];
        s.geoNormal = geo[k];
        r[m] = shadowRayTowards(s, sampleLight(t_.shading.lights[i], pos[k]), 0.0f);
        active[m] = true;
        lane[m++] = k;
        ++rays[k];
        if (m == 8) trace();
      }
      counts_.culled += c[k] == ShadowClass::Culled;
      counts_.lit += c[k] == ShadowClass::Lit;
      counts_.shadowed += c[k] == ShadowClass::Shadowed;
      counts_.traced += c[k] == ShadowClass::Traced;
      if (t_.classes) classes_[i * W + size_t(k)] = uint8_t(c[k]);
    }
    if (m > 0) trace();
    bool any = false;
    for (int k = 0; k < n; ++k)
      for (int ch = 0; ch < 3; ++ch) {
        const float b = 1.0f - vis[k][ch];
        blocked_[(3 * i + size_t(ch)) * W + size_t(k)] = b;
        any |= b != 0.0f;
      }
    return any;
  }

  // Light i with the maps deciding every asked lane: the lit fraction of each, 16 lanes a lookup
  // (the SIMD kernel), grey.
  bool mapsLight(size_t i, int n, const bool* asked) {
    float use[W] = {}, lit[W];
    for (int k = 0; k < n; ++k) {
      use[k] = asked[k] ? 1.0f : 0.0f;
      lit[k] = 1.0f;
    }
    t_.maps->visibilityBatch(i, soa_[0], soa_[1], soa_[2], soa_[3], soa_[4], soa_[5], use, n, lit);
    bool any = false;
    float* blocked = &blocked_[3 * i * W];
    for (int k = 0; k < n; ++k) {
      const ShadowClass c = !asked[k]       ? ShadowClass::Culled
                            : lit[k] > 0.5f ? ShadowClass::Lit
                                            : ShadowClass::Shadowed;
      counts_.culled += c == ShadowClass::Culled;
      counts_.lit += c == ShadowClass::Lit;
      counts_.shadowed += c == ShadowClass::Shadowed;
      if (t_.classes) classes_[i * W + size_t(k)] = uint8_t(c);
      const float b = asked[k] ? 1.0f - lit[k] : 0.0f;
      blocked[k] = blocked[W + size_t(k)] = blocked[2 * W + size_t(k)] = b;
      any |= b != 0.0f;
    }
    return any;
  }

  const ShadowTile& t_;
  EffectTally* tally_;
  ShadowCounts& counts_;
  size_t lights_;
  ShadeBatch b_;
  int xs_[W], ys_[W];
  alignas(64) float soa_[6][W];  // positions and geometric normals (Maps mode)
  std::vector<float> share_, terms_, blocked_;
  std::vector<uint8_t> classes_;
  std::vector<uint32_t> reached_, blockedLights_;
};

}  // namespace

void classifiedShadowTile(const ShadowTile& t, const View& v, int x0, int y0, int x1, int y1,
                          int64_t rank, EffectTally* tally, ShadowCounts& counts) {
  ShadowBatch batch(t, tally, counts);
  const bool perspective = v.camera.desc.projection == Projection::Perspective;
  const Vec3 eye = perspective ? v.camera.eye : -v.camera.forward;  // readSpan's eye directions
  auto wanted = [&](int x, int y) {
    return !t.mask || (t.mask->at(x, y)[kShadow] > 0.5f) != t.unselected;
  };
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      // W pixels of a row that all want their shadow, with no batch begun: read in one go
      // (falls through to the pixels one by one where one shows the sky).
      if (batch.batch().count == 0 && rank < 0 && x + W <= x1) {
        bool all = true;
        for (int k = 0; k < W && all; ++k) all = wanted(x + k, y);
        Bounds3 lanes;
        if (all && t.g.readSpan(x, y, W, batch.batch(), perspective, eye, lanes)) {
          batch.pushSpan(x, y, lanes);
          x += W - 1;
          continue;
        }
      }
      if (!wanted(x, y)) continue;
      if (rank >= 0 && nodeRank(t.order, t.ids.at(x, y)[0], kShadow) != uint32_t(rank)) continue;
      ShadeBatch& b = batch.batch();
      const int l = b.count;
      if (!t.g.read(x, y, b, l)) continue;
      // The eye direction as deferred shading takes it.
      const Vec3 p{b.f[F::PX][l], b.f[F::PY][l], b.f[F::PZ][l]};
      const Vec3 wo = perspective ? normalize(v.camera.eye - p) : -v.camera.forward;
      b.f[F::WX][l] = wo.x, b.f[F::WY][l] = wo.y, b.f[F::WZ][l] = wo.z;
      batch.push(x, y);
    }
  batch.flush();
}

}  // namespace tandem
