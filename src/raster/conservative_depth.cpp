#include "raster/conservative_depth.h"

#include <algorithm>
#include <cmath>

#include "raster/visibility_buffer.h"

namespace tandem {

namespace {

struct Projector {
  const Camera& cam;
  bool perspective;
  float nearPlane, farPlane;
  float viewZ(Vec3 p) const { return dot(p - cam.desc.position, cam.forward); }
  // Texel coordinates and reversed-Z depth of a point in front of the near plane.
  Vec3 project(Vec3 p) const {
    const Mat4& m = cam.viewProj;
    const float w =
        perspective ? m.m[3][0] * p.x + m.m[3][1] * p.y + m.m[3][2] * p.z + m.m[3][3] : 1.0f;
    const float x = (m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3]) / w;
    const float y = (m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3]) / w;
    const float z = viewZ(p);
    const float d = perspective ? nearPlane / z : (farPlane - z) / (farPlane - nearPlane);
    return {(x * 0.5f + 0.5f) * float(cam.width), (0.5f - y * 0.5f) * float(cam.height), d};
  }
};

// One projected triangle into the map: every texel its area touches gets the nearest depth the
// triangle's plane reaches over that texel (never nearer than its nearest vertex).
void drawTriangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t object,
                  ConservativeDepth& out) {
  const float lo = std::min({a.x, b.x, c.x}), hi = std::max({a.x, b.x, c.x});
  const float bot = std::min({a.y, b.y, c.y}), top = std::max({a.y, b.y, c.y});
  if (!(hi >= 0 && top >= 0 && lo < float(out.width) && bot < float(out.height))) return;
  // Clamped as floats first: a corner projected far off the map (beyond an int) stays in range.
  const int x0 = int(std::max(std::floor(lo), 0.0f)),
            x1 = int(std::min(std::floor(hi), float(out.width - 1)));
  const int y0 = int(std::max(std::floor(bot), 0.0f)),
            y1 = int(std::min(std::floor(top), float(out.height - 1)));
  const float dMax = std::max({a.z, b.z, c.z});
  const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  // Edge functions E = A x + B y + C, >= 0 inside; a texel overlaps the half-plane when its
  // most inside corner does: E(centre) + (|A| + |B|) / 2 >= 0.
  const Vec3* v[3] = {&a, &b, &c};
  float ea[3], eb[3], ec[3];
  const float sign = area >= 0 ? 1.0f : -1.0f;
  for (int e = 0; e < 3; ++e) {
    const Vec3 &p = *v[e], &q = *v[(e + 1) % 3];
    ea[e] = sign * (p.y - q.y);
    eb[e] = sign * (q.x - p.x);
    ec[e] = sign * (p.x * q.y - p.y * q.x);
  }
  const bool flat = std::abs(area) < 1e-6f;  // seen edge-on: a segment, covered where it passes
  float pa = 0, pb = 0, pc = dMax;           // depth plane d = pa x + pb y + pc
  if (!flat) {
    pa = ((b.z - a.z) * (c.y - a.y) - (c.z - a.z) * (b.y - a.y)) / area;
    pb = ((c.z - a.z) * (b.x - a.x) - (b.z - a.z) * (c.x - a.x)) / area;
    pc = a.z - pa * a.x - pb * a.y;
  }
  const float reach = 0.5f * (std::abs(pa) + std::abs(pb));
  int longest = 0;
  for (int e = 1; e < 3; ++e)
    if (ea[e] * ea[e] + eb[e] * eb[e] > ea[longest] * ea[longest] + eb[longest] * eb[longest])
      longest = e;
  for (int y = y0; y <= y1; ++y) {
    const float cy = float(y) + 0.5f;
    for (int x = x0; x <= x1; ++x) {
      const float cx = float(x) + 0.5f;
      bool touches = true;
      if (flat) {
        const int e = longest;
        const float slack = 0.5f * (std::abs(ea[e]) + std::abs(eb[e])) * 1.001f + 1e-6f;
        touches = std::abs(ea[e] * cx + eb[e] * cy + ec[e]) <= slack;
      } else {
        for (int e = 0; e < 3 && touches; ++e) {
          const float slack = 0.5f * (std::abs(ea[e]) + std::abs(eb[e])) * 1.001f + 1e-6f;
          touches = ea[e] * cx + eb[e] * cy + ec[e] + slack >= 0;
        }
      }
      if (!touches) continue;
      const float d = flat ? dMax : std::min(dMax, pa * cx + pb * cy + pc + reach);
      ConservativeDepth::Texel& t = out.texels[size_t(y) * size_t(out.width) + size_t(x)];
      if (d > t.depth) t = {d, object};
    }
  }
}

// Clips a world-space triangle to the front of the near plane (perspective) and draws it.
void drawWorldTriangle(const Projector& pr, const Vec3& a, const Vec3& b, const Vec3& c,
                       uint32_t object, ConservativeDepth& out) {
  if (!pr.perspective) {
    drawTriangle(pr.project(a), pr.project(b), pr.project(c), object, out);
    return;
  }
  const Vec3 in[3] = {a, b, c};
  float z[3];
  int front = 0;
  for (int k = 0; k < 3; ++k) front += (z[k] = pr.viewZ(in[k]) - pr.nearPlane) > 0 ? 1 : 0;
  if (front == 0) return;
  if (front == 3) {
    drawTriangle(pr.project(a), pr.project(b), pr.project(c), object, out);
    return;
  }
  Vec3 poly[4];
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    if (z[k] > 0) poly[n++] = in[k];
    if ((z[k] > 0) != (z[j] > 0)) {
      const float t = z[k] / (z[k] - z[j]);
      // Just in front of the plane, so the projection stays finite.
      poly[n++] = in[k] + (in[j] - in[k]) * std::clamp(t, 0.0f, 1.0f) +
                  pr.cam.forward * (1e-4f * pr.nearPlane);
    }
  }
  Vec3 s[4];
  for (int k = 0; k < n; ++k) s[k] = pr.project(poly[k]);
  for (int k = 1; k + 1 < n; ++k) drawTriangle(s[0], s[k], s[k + 1], object, out);
}

}  // namespace

std::array<std::array<Vec3, 3>, 12> boxTriangles(const Bounds3& b) {
  Vec3 v[8];
  for (int k = 0; k < 8; ++k)
    v[k] = {k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
  static const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  std::array<std::array<Vec3, 3>, 12> out;
  for (int f = 0; f < 6; ++f) {
    out[size_t(2 * f)] = {v[faces[f][0]], v[faces[f][1]], v[faces[f][2]]};
    out[size_t(2 * f + 1)] = {v[faces[f][0]], v[faces[f][2]], v[faces[f][3]]};
  }
  return out;
}

void drawConservativeDepth(const FrameScene& fs, const Camera& cam,
                           const std::vector<uint8_t>* objects, bool keep, bool sweep,
                           ConservativeDepth& out) {
  const size_t n = size_t(cam.width) * size_t(cam.height);
  if (!keep || out.width != cam.width || out.height != cam.height) {
    out.width = cam.width;
    out.height = cam.height;
    out.texels.assign(n, {0.0f, kNoObject});
  }
  const Projector pr{cam, cam.desc.projection == Projection::Perspective, cam.desc.nearPlane,
                     cam.desc.farPlane};
  const Scene& scene = *fs.scene;
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    if (objects && !(*objects)[o]) continue;
    const FrameObject& fo = fs.objects[o];
    if (sweep && !fo.stepPositions.empty()) {
      for (const auto& t : boxTriangles(fo.bounds))
        drawWorldTriangle(pr, t[0], t[1], t[2], uint32_t(o), out);
      continue;
    }
    const std::vector<uint32_t>& idx = scene.meshes[size_t(scene.objects[o].mesh)].indices;
    for (size_t t = 0; t + 2 < idx.size(); t += 3)
      drawWorldTriangle(pr, fo.positions[idx[t]], fo.positions[idx[t + 1]],
                        fo.positions[idx[t + 2]], uint32_t(o), out);
  }
}

}  // namespace tandem
