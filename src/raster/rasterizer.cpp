#include "raster/rasterizer.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "raster/raster_tile.h"
#include "shading/surface_resolve.h"

namespace tandem {

namespace {

constexpr int kSubBits = kRasterSubBits;
constexpr float kSubScale = float(1 << kSubBits);
constexpr int kBinSize = 64;        // pixels per tile side
constexpr float kGuardBand = 4.0f;  // clip x,y to +-4 w: coordinates stay far from overflow
constexpr int kChunks = 64;

struct ClipVert {
  Vec4 p;
};

// Round to 8-bit sub-pixel fixed point (std::lround is a libm call; this is one instruction).
inline int32_t toFixed(float v) {
  float f = v * kSubScale;
  return int32_t(f + (f >= 0 ? 0.5f : -0.5f));
}

// Signed distance to the clip planes used here: near, far, left, right, bottom, top (guard).
inline float planeDist(const Vec4& v, int plane) {
  switch (plane) {
    case 0:
      return v.w - v.z;  // near: z/w <= 1 in reversed-Z
    case 1:
      return v.z;  // far: z >= 0
    case 2:
      return v.x + kGuardBand * v.w;
    case 3:
      return kGuardBand * v.w - v.x;
    case 4:
      return v.y + kGuardBand * v.w;
    default:
      return kGuardBand * v.w - v.y;
  }
}

// Bit p set when the vertex lies outside plane p (NaN counts as outside).
inline unsigned outcode(const Vec4& v) {
  unsigned code = 0;
  for (int p = 0; p < 6; ++p)
    if (!(planeDist(v, p) >= 0)) code |= 1u << p;
  return code;
}

// Clip space to the screen: unsnapped position, 8-bit fixed point, depth z / w.
template <class ScreenVertex>
inline void project(const Vec4& v, int W, int H, ScreenVertex& out) {
  const float iw = 1.0f / v.w;
  out.sx = (v.x * iw * 0.5f + 0.5f) * W;
  out.sy = (0.5f - v.y * iw * 0.5f) * H;
  out.x = toFixed(out.sx);
  out.y = toFixed(out.sy);
  out.z = v.z * iw;
}

// Sutherland-Hodgman against the planes in `mask`; returns the vertex count (<= 9).
int clipPolygon(Vec4* poly, int n, unsigned mask) {
  Vec4 tmp[12];
  for (int plane = 0; plane < 6 && n > 0; ++plane) {
    if (!(mask & (1u << plane))) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const Vec4& a = poly[i];
      const Vec4& b = poly[(i + 1) % n];
      float da = planeDist(a, plane), db = planeDist(b, plane);
      if (da >= 0) tmp[m++] = a;
      if ((da >= 0) != (db >= 0)) {
        float t = da / (da - db);
        tmp[m++] = a + (b - a) * t;
      }
    }
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = tmp[i];
  }
  return n;
}

}  // namespace

bool boundsOutsideFrustum(const Mat4& vp, const Bounds3& b, unsigned planes) {
  if (!(b.lo.x <= b.hi.x)) return true;  // empty object
  unsigned andCode = planes;
  for (int k = 0; k < 8; ++k) {
    Vec3 p{k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
    Vec4 c = vp * Vec4(p, 1.0f);
    unsigned code = 0;
    if (!(c.w - c.z >= 0)) code |= 1;
    if (!(c.z >= 0)) code |= 2;
    if (!(c.x + c.w >= 0)) code |= 4;
    if (!(c.w - c.x >= 0)) code |= 8;
    if (!(c.y + c.w >= 0)) code |= 16;
    if (!(c.w - c.y >= 0)) code |= 32;
    andCode &= code;
  }
  return andCode != 0;
}

void Rasterizer::render(const FrameScene& fs, const Camera& cam, VisibilityBuffer& out,
                        RasterStats* stats, float tau) {
  render(fs, cam, out, Subset{}, stats, tau);
}

namespace {

// One piece of a triangle fan: its corners (a, b, c; positive orientation) in fixed point, its
// depth plane and the bins it touches. False when it covers no pixel centre (or is degenerate).
bool setUpPiece(const int32_t* X, const int32_t* Y, const float* Z, const float* SX,
                const float* SY, int a, int b, int c, int W, int H, int binW, int binH,
                bool anywhere, Rasterizer::SetupTriangle& st) {
  st.x[0] = X[a];
  st.x[1] = X[b];
  st.x[2] = X[c];
  st.y[0] = Y[a];
  st.y[1] = Y[b];
  st.y[2] = Y[c];
  // Depth is affine in screen space; derive its plane from the unsnapped positions (in
  // double) so that sub-pixel snapping of large clipped triangles does not tilt it.
  {
    double ux = SX[b] - SX[a], uy = SY[b] - SY[a], vx = SX[c] - SX[a], vy = SY[c] - SY[a];
    double uz = double(Z[b]) - Z[a], vz = double(Z[c]) - Z[a];
    double det = ux * vy - uy * vx;
    if (det == 0) return false;
    st.dzdx = float((uz * vy - vz * uy) / det);
    st.dzdy = float((vz * ux - uz * vx) / det);
    st.zRef = Z[a];
    st.xRef = SX[a];
    st.yRef = SY[a];
  }
  // Pixel range whose centres (px + 0.5) can be covered; with `anywhere`, every pixel
  // the triangle's box touches (samples may sit anywhere inside a pixel).
  int32_t minX = std::min({st.x[0], st.x[1], st.x[2]}),
          maxX = std::max({st.x[0], st.x[1], st.x[2]});
  int32_t minY = std::min({st.y[0], st.y[1], st.y[2]}),
          maxY = std::max({st.y[0], st.y[1], st.y[2]});
  const int32_t centre = anywhere ? 0 : 128, round = anywhere ? 0 : 255;
  int px0 = std::max(0, int((minX - centre + round) >> kSubBits));
  int px1 = std::min(W - 1, int((maxX - centre) >> kSubBits));
  int py0 = std::max(0, int((minY - centre + round) >> kSubBits));
  int py1 = std::min(H - 1, int((maxY - centre) >> kSubBits));
  if (px0 > px1 || py0 > py1) return false;  // covers no pixel centre
  st.tx0 = int16_t(px0 / binW);
  st.tx1 = int16_t(px1 / binW);
  st.ty0 = int16_t(py0 / binH);
  st.ty1 = int16_t(py1 / binH);
  return true;
}

}  // namespace

void Rasterizer::transformVertices(const FrameScene& fs, const Mat4& vp, int W, int H,
                                   const Subset& subset, float tau) {
  // 1. Vertices to clip space, for objects whose bounds reach into the view frustum, and only
  // when the camera or the geometry changed since they were last transformed.
  clip_.resize(fs.objects.size());
  screen_.resize(fs.objects.size());
  clipKeys_.resize(fs.objects.size());
  objectCulled_.assign(fs.objects.size(), 0);
  runs_.clear();
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const FrameObject& fo = fs.objects[o];
    const auto& pos = fo.positions;
    if ((subset.objects && !(*subset.objects)[o]) || boundsOutsideFrustum(vp, fo.bounds)) {
      objectCulled_[o] = 1;
      continue;
    }
    const bool atTau = tau >= 0.0f && !fo.stepPositions.empty();
    ClipKey& key = clipKeys_[o];
    auto& c = clip_[o];
    if (c.size() == pos.size() && key.geometryVersion == fs.geometryVersion &&
        key.tau == (atTau ? tau : -1.0f) && sameMatrix(key.viewProj, vp) && key.width == W &&
        key.height == H)
      continue;
    key = {vp, fs.geometryVersion, atTau ? tau : -1.0f, W, H};
    c.resize(pos.size());
    screen_[o].resize(pos.size());
    for (size_t b = 0; b < pos.size(); b += kVertexRun)
      runs_.push_back({uint32_t(o), uint32_t(b), uint32_t(std::min(pos.size(), b + kVertexRun))});
  }
  // Every object's vertices in one parallel loop: most objects are smaller than a worker's share.
  tbb::parallel_for(size_t(0), runs_.size(), [&](size_t r) {
    const VertexRun run = runs_[r];
    const FrameObject& fo = fs.objects[run.object];
    const bool atTau = tau >= 0.0f && !fo.stepPositions.empty();
    auto& c = clip_[run.object];
    auto& sv = screen_[run.object];
    for (size_t i = run.begin; i < run.end; ++i) {
      c[i] = vp * Vec4(atTau ? positionAt(fo, i, tau) : fo.positions[i], 1.0f);
      sv[i].outcode = outcode(c[i]);
      if (sv[i].outcode == 0) project(c[i], W, H, sv[i]);
    }
  });
}

int Rasterizer::prepare(const FrameScene& fs, const Camera& cam, const Subset& subset, float tau,
                        int binW, int binH, bool anywhere, RasterStats* stats) {
  const Scene& scene = *fs.scene;
  const int W = cam.width, H = cam.height;
  const int tilesX = (W + binW - 1) / binW, tilesY = (H + binH - 1) / binH;
  const int tileCount = tilesX * tilesY;
  const Mat4 vp = cam.viewProj;

  // 1. Vertices to clip space, for objects whose bounds reach into the view frustum, and only
  // when the camera or the geometry changed since they were last transformed.
  transformVertices(fs, vp, W, H, subset, tau);

  // Global triangle numbering: prefix sums over objects.
  std::vector<size_t> firstTri(fs.objects.size() + 1, 0);
  for (size_t o = 0; o < fs.objects.size(); ++o)
    firstTri[o + 1] = firstTri[o] + scene.meshes[scene.objects[o].mesh].triangleCount();
  const size_t totalTris = firstTri.back();

  // 2. Setup and binning in chunks of consecutive triangles.
  const int chunks = int(std::min<size_t>(kChunks, std::max<size_t>(1, totalTris / 256)));
  chunkTris_.resize(chunks);
  bins_.resize(chunks);
  std::atomic<size_t> culled{0}, clipped{0};
  tbb::parallel_for(0, chunks, [&](int ch) {
    auto& tris = chunkTris_[ch];
    auto& bins = bins_[ch];
    tris.clear();
    bins.resize(tileCount);
    for (auto& b : bins) b.clear();
    size_t t0 = totalTris * ch / chunks, t1 = totalTris * (ch + 1) / chunks;
    size_t o = std::upper_bound(firstTri.begin(), firstTri.end(), t0) - firstTri.begin() - 1;
    size_t localCulled = 0, localClipped = 0;
    for (size_t g = t0; g < t1; ++g) {
      while (g >= firstTri[o + 1]) ++o;
      if (objectCulled_[o]) {  // the whole object lies outside: skip to the next one
        const size_t next = std::min(firstTri[o + 1], t1);
        localCulled += next - g;
        g = next - 1;
        continue;
      }
      const Object& obj = scene.objects[o];
      const Material& mat = scene.materials[obj.material];
      const Mesh& mesh = scene.meshes[obj.mesh];
      const uint32_t prim = uint32_t(g - firstTri[o]);
      const uint32_t* idx = &mesh.indices[3 * size_t(prim)];
      const auto& sv = screen_[o];
      // Outcodes: trivially reject when all vertices lie outside one plane.
      const unsigned andCode = sv[idx[0]].outcode & sv[idx[1]].outcode & sv[idx[2]].outcode,
                     orCode = sv[idx[0]].outcode | sv[idx[1]].outcode | sv[idx[2]].outcode;
      if (andCode) {
        ++localCulled;
        continue;
      }
      // Fixed-point screen coordinates: the vertices' own when the triangle lies inside every
      // plane, else those of the clipped polygon.
      int n = 3;
      int32_t X[12], Y[12];
      float Z[12], SX[12], SY[12];
      if (orCode) {
        const auto& cv = clip_[o];
        Vec4 poly[12] = {cv[idx[0]], cv[idx[1]], cv[idx[2]]};
        n = clipPolygon(poly, 3, orCode);
        ++localClipped;
        if (n < 3) continue;
        for (int k = 0; k < n; ++k) {
          ScreenVertex p;
          project(poly[k], W, H, p);
          X[k] = p.x, Y[k] = p.y, Z[k] = p.z, SX[k] = p.sx, SY[k] = p.sy;
        }
      } else {
        for (int k = 0; k < 3; ++k) {
          const ScreenVertex& p = sv[idx[k]];
          X[k] = p.x, Y[k] = p.y, Z[k] = p.z, SX[k] = p.sx, SY[k] = p.sy;
        }
      }
      // Triangle fan over the clipped polygon; all pieces share the original's orientation.
      for (int k = 1; k + 1 < n; ++k) {
        int a = 0, b = k, c = k + 1;
        int64_t area = int64_t(X[b] - X[a]) * (Y[c] - Y[a]) - int64_t(Y[b] - Y[a]) * (X[c] - X[a]);
        if (area == 0) continue;
        // Counter-clockwise in the world is clockwise on a y-down screen: area < 0 is front.
        if (area > 0) {
          if (!mat.doubleSided && !subset.bothFaces) {
            ++localCulled;
            continue;
          }
        } else {
          std::swap(b, c);
        }
        SetupTriangle st;
        if (!setUpPiece(X, Y, Z, SX, SY, a, b, c, W, H, binW, binH, anywhere, st)) continue;
        st.object = uint32_t(o);
        st.prim = prim;
        st.alphaMask = mat.alphaMode == AlphaMode::Mask;
        uint32_t id = uint32_t(tris.size());
        tris.push_back(st);
        for (int ty = st.ty0; ty <= st.ty1; ++ty)
          for (int tx = st.tx0; tx <= st.tx1; ++tx) bins[ty * tilesX + tx].push_back(id);
      }
    }
    culled += localCulled;
    clipped += localClipped;
  });

  if (stats) {
    stats->trianglesIn = totalTris;
    stats->trianglesCulled = culled;
    stats->trianglesClipped = clipped;
    size_t binned = 0;
    for (int ch = 0; ch < chunks; ++ch) binned += chunkTris_[ch].size();
    stats->trianglesBinned = binned;
  }
  return chunks;
}

void Rasterizer::render(const FrameScene& fs, const Camera& cam, VisibilityBuffer& out,
                        const Subset& subset, RasterStats* stats, float tau) {
  const int W = cam.width, H = cam.height;
  TANDEM_ASSERT(!subset.keep || (out.width == W && out.height == H));
  out.resize(W, H);
  const int tilesX = (W + kBinSize - 1) / kBinSize, tilesY = (H + kBinSize - 1) / kBinSize;
  const int tileCount = tilesX * tilesY;
  const int chunks = prepare(fs, cam, subset, tau, kBinSize, kBinSize, false, stats);

  // 3. Rasterize each tile, chunks in submission order.
  tbb::parallel_for(0, tileCount, [&](int tile) {
    const int tx = tile % tilesX, ty = tile / tilesX;
    const int x0 = tx * kBinSize, y0 = ty * kBinSize;
    const int x1 = std::min(W, x0 + kBinSize) - 1, y1 = std::min(H, y0 + kBinSize) - 1;
    for (int y = y0; y <= y1 && !subset.keep; ++y) {
      size_t row = size_t(y) * W;
      std::fill(out.depth.begin() + row + x0, out.depth.begin() + row + x1 + 1, 0.0f);
      std::fill(out.object.begin() + row + x0, out.object.begin() + row + x1 + 1, kNoObject);
      std::fill(out.prim.begin() + row + x0, out.prim.begin() + row + x1 + 1, 0u);
    }
    // Chunks in submission order; inside one, the vector kernel draws every triangle but the
    // alpha-masked ones, which are drawn here, in their turn, texel by texel.
    const RasterTile target{
        out.depth.data(), out.object.data(), out.prim.data(), W, x0, y0, x1, y1};
    for (int ch = 0; ch < chunks; ++ch) {
      const auto& tris = chunkTris_[ch];
      const auto& ids = bins_[ch][tile];
      for (size_t k = 0; k < ids.size(); ++k) {
        k = rasterTileTriangles(target, tris.data(), ids.data(), k, ids.size());
        if (k == ids.size()) break;
        const SetupTriangle& t = tris[ids[k]];
        const TriangleBox b = triangleBox(t, x0, y0, x1, y1);
        if (b.empty()) continue;
        walkRows(b, [&](int py, const int64_t* e) {
          const size_t row = size_t(py) * W;
          walkRowPixels(t, b, b.px0, e, rowDepth(t, b, py), [&](int px, float z) {
            const size_t i = row + px;
            if (z > out.depth[i] && z <= 1.0f && alphaKeeps(fs, cam, t, px + 0.5f, py + 0.5f)) {
              out.depth[i] = z;
              out.object[i] = t.object;
              out.prim[i] = t.prim;
            }
          });
        });
      }
    }
  });
}

bool Rasterizer::alphaKeeps(const FrameScene& fs, const Camera& cam, const SetupTriangle& t,
                            float px, float py) {
  const Scene& scene = *fs.scene;
  Vec3 o, d;
  cam.generateRay(px, py, o, d);
  const Mesh& mesh = scene.meshes[scene.objects[t.object].mesh];
  const uint32_t* idx = &mesh.indices[3 * size_t(t.prim)];
  const auto& wp = fs.objects[t.object].positions;
  float tt, u, v;
  intersectTriangle(o, d, wp[idx[0]], wp[idx[1]], wp[idx[2]], tt, u, v);
  const Material& m = scene.materials[scene.objects[t.object].material];
  return surfaceAlpha(fs, int(t.object), int(t.prim), u, v) >= m.alphaCutoff;
}

void Rasterizer::renderSamples(const FrameScene& fs, const Camera& cam, const SampleSet& set,
                               VisibilityBuffer& out, const Subset& subset, RasterStats* stats,
                               float tau) {
  const int W = cam.width, H = cam.height;
  // Bins are whole numbers of cells near 64 pixels, so each cell (and sample) has one owner.
  const int binCellsX = std::max(1, kBinSize / set.cellW),
            binCellsY = std::max(1, kBinSize / set.cellH);
  const int binW = binCellsX * set.cellW, binH = binCellsY * set.cellH;
  const int tilesX = (W + binW - 1) / binW, tilesY = (H + binH - 1) / binH;
  const int chunks = prepare(fs, cam, subset, tau, binW, binH, true, stats);
  tbb::parallel_for(0, tilesX * tilesY, [&](int tile) {
    const int bx = tile % tilesX, by = tile / tilesX;
    const int cx0 = bx * binCellsX, cy0 = by * binCellsY;
    const int cx1 = std::min(set.cellsX, cx0 + binCellsX) - 1;
    const int cy1 = std::min(set.cellsY, cy0 + binCellsY) - 1;
    auto skipped = [&](size_t c) { return set.cellActive && !set.cellActive[c]; };
    bool anyActive = !set.cellActive;
    for (int cy = cy0; cy <= cy1 && !anyActive; ++cy)
      for (int cx = cx0; cx <= cx1 && !anyActive; ++cx)
        anyActive = !skipped(size_t(cy) * size_t(set.cellsX) + size_t(cx));
    if (!anyActive) return;
    for (int cy = cy0; cy <= cy1 && !subset.keep; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) {
        const size_t c = size_t(cy) * size_t(set.cellsX) + size_t(cx);
        if (skipped(c)) continue;
        for (uint32_t k = set.start[c]; k < set.start[c + 1]; ++k) {
          const uint32_t id = set.ids[k];
          out.depth[id] = 0.0f;
          out.object[id] = kNoObject;
          out.prim[id] = 0;
        }
      }
    for (int ch = 0; ch < chunks; ++ch) {
      const auto& tris = chunkTris_[ch];
      for (uint32_t ti : bins_[ch][tile]) {
        const SetupTriangle& t = tris[ti];
        const int32_t minX = std::min({t.x[0], t.x[1], t.x[2]}),
                      maxX = std::max({t.x[0], t.x[1], t.x[2]});
        const int32_t minY = std::min({t.y[0], t.y[1], t.y[2]}),
                      maxY = std::max({t.y[0], t.y[1], t.y[2]});
        // Cells the triangle's box touches, inside this bin.
        const int tx0 = std::max(cx0, int(minX >> kSubBits) / set.cellW);
        const int tx1 = std::min(cx1, int(maxX >> kSubBits) / set.cellW);
        const int ty0 = std::max(cy0, int(minY >> kSubBits) / set.cellH);
        const int ty1 = std::min(cy1, int(maxY >> kSubBits) / set.cellH);
        if (tx0 > tx1 || ty0 > ty1) continue;
        int64_t dx[3], dy[3], bias[3];
        for (int e = 0; e < 3; ++e) {
          const int a = e, b = (e + 1) % 3;
          dx[e] = int64_t(t.x[b]) - t.x[a];
          dy[e] = int64_t(t.y[b]) - t.y[a];
          bias[e] = (dy[e] < 0 || (dy[e] == 0 && dx[e] > 0)) ? 0 : -1;  // top-left rule
        }
        for (int cy = ty0; cy <= ty1; ++cy)
          for (int cx = tx0; cx <= tx1; ++cx) {
            const size_t c = size_t(cy) * size_t(set.cellsX) + size_t(cx);
            if (skipped(c)) continue;
            for (uint32_t k = set.start[c]; k < set.start[c + 1]; ++k) {
              const uint32_t id = set.ids[k];
              const int64_t sx = set.fx[id], sy = set.fy[id];
              bool inside = true;
              for (int e = 0; e < 3 && inside; ++e)
                inside = dx[e] * (sy - t.y[e]) - dy[e] * (sx - t.x[e]) + bias[e] >= 0;
              if (!inside) continue;
              const Vec2 p = set.pos[id];
              const float z = t.zRef + t.dzdx * (p.x - t.xRef) + t.dzdy * (p.y - t.yRef);
              if (!(z > out.depth[id] && z <= 1.0f)) continue;
              if (t.alphaMask && !alphaKeeps(fs, cam, t, p.x, p.y)) continue;
              out.depth[id] = z;
              out.object[id] = t.object;
              out.prim[id] = t.prim;
            }
          }
      }
    }
  });
}

}  // namespace tandem
