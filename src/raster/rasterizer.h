// Tile-binned, multithreaded software rasterizer (oneTBB) writing a visibility buffer.
//  - vertices to clip space once per frame; triangles set up and binned into 64x64 tiles in
//    parallel chunks (chunk order = submission order, so results never depend on threads);
//  - clipping against the near plane (and a guard band, so fixed-point never overflows);
//  - 8-bit sub-pixel fixed point with a consistent top-left fill rule: a pixel centre on an
//    edge shared by two triangles is drawn by exactly one of them;
//  - back-face culling unless the material is double-sided; alpha-mask discard;
//  - reversed-Z float depth (greater wins), perspective-correct because z/w is affine on screen.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/visibility_buffer.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

// Screen coordinates are fixed point with this many sub-pixel bits.
constexpr int kRasterSubBits = 8;

// True when the world box lies entirely outside one plane of the view frustum of `vp` (the real
// one, not the clipper's guard band): none of its triangles can cover a pixel.
// `planes`: the planes tested (bits: near, far, left, right, bottom, top), all by default.
bool boundsOutsideFrustum(const Mat4& vp, const Bounds3& b, unsigned planes = 0x3f);

struct RasterStats {
  size_t trianglesIn = 0, trianglesCulled = 0, trianglesClipped = 0, trianglesBinned = 0;
};

class Rasterizer {
 public:
  // Draws `fs` through `cam` (which may look through a lens point: Camera::make's `lens`). With
  // `tau` in [0, 1] moving objects are drawn where they are at that fraction of the shutter
  // (positionAt); tau < 0 draws them at the frame time.
  void render(const FrameScene& fs, const Camera& cam, VisibilityBuffer& out,
              RasterStats* stats = nullptr, float tau = -1.0f);

  // What else a draw may be asked for (shadow maps: static casters once, moving ones over them).
  struct Subset {
    const std::vector<uint8_t>* objects = nullptr;  // non-zero entries are drawn; null: all
    bool keep = false;  // draw over `out`'s contents (same size) instead of clearing it
    // Draw back faces of single-sided materials too (shadow maps: a wall seen from behind by
    // the light still blocks it, as it blocks a shadow ray).
    bool bothFaces = false;
  };
  void render(const FrameScene& fs, const Camera& cam, VisibilityBuffer& out, const Subset& subset,
              RasterStats* stats = nullptr, float tau = -1.0f);

  // Sparse samples for one pass of interleaved sampling: the screen is cut into cells of
  // cellW x cellH pixels; cell c (row-major) holds the samples ids[start[c] .. start[c + 1]),
  // sample id at pixel position pos[id] (fx, fy: the same in 8-bit fixed point).
  struct SampleSet {
    int cellW = 1, cellH = 1, cellsX = 0, cellsY = 0;
    const uint32_t* start = nullptr;
    const uint32_t* ids = nullptr;
    const Vec2* pos = nullptr;
    const int32_t *fx = nullptr, *fy = nullptr;
    // Optional: cells whose entry is 0 are neither cleared nor drawn (a masked pass); a bin
    // without an active cell skips its triangles.
    const uint8_t* cellActive = nullptr;
  };
  // Draws `fs` through `cam` into the entries of `out` (indexed by sample id) of the samples in
  // `set`, clearing them first and touching no other entry. Each triangle visits only the cells
  // its screen box at this (time, lens) touches: one sample per cell for interleaved tiles.
  void renderSamples(const FrameScene& fs, const Camera& cam, const SampleSet& set,
                     VisibilityBuffer& out, RasterStats* stats = nullptr, float tau = -1.0f) {
    renderSamples(fs, cam, set, out, Subset{}, stats, tau);
  }
  // The same for a subset of the objects; with subset.keep the samples are drawn over, not
  // cleared.
  void renderSamples(const FrameScene& fs, const Camera& cam, const SampleSet& set,
                     VisibilityBuffer& out, const Subset& subset, RasterStats* stats = nullptr,
                     float tau = -1.0f);

  struct SetupTriangle {
    int32_t x[3], y[3];  // fixed point, 8 sub-pixel bits, positive orientation
    float zRef, dzdx,
        dzdy;  // depth plane from unsnapped coordinates: z = zRef + dzdx*(px-xRef) + ...
    float xRef, yRef;
    uint32_t object, prim;
    int16_t tx0, ty0, tx1, ty1;  // tile range (inclusive)
    bool alphaMask;
  };

 private:
  // Steps 1-2: clip-space vertices, triangle setup, binning into binW x binH pixel bins (pixel
  // ranges by centre coverage, or every pixel touched with `anywhere`). Returns the chunk count.
  int prepare(const FrameScene& fs, const Camera& cam, const Subset& subset, float tau, int binW,
              int binH, bool anywhere, RasterStats* stats);
  // Step 1: the vertices of the objects that reach into the frustum, to clip space.
  void transformVertices(const FrameScene& fs, const Mat4& vp, int W, int H, const Subset& subset,
                         float tau);
  // Alpha-mask test of triangle t at pixel position (px, py).
  static bool alphaKeeps(const FrameScene& fs, const Camera& cam, const SetupTriangle& t, float px,
                         float py);

  std::vector<std::vector<Vec4>> clip_;  // per object, clip-space vertices
  std::vector<char> objectCulled_;       // per object: outside the frustum
  // What clip_[o] was computed for: skipped when neither the camera nor the geometry changed.
  struct ClipKey {
    Mat4 viewProj;
    uint64_t geometryVersion = ~0ull;
    float tau = -2.0f;
    int width = 0, height = 0;
  };
  // Per object, each vertex's outcode against the clip planes and, where it is inside them
  // all, its screen position: a vertex is shared by about six triangles, and a triangle inside
  // every plane (most of them) takes its three vertices from here instead of projecting them.
  struct ScreenVertex {
    unsigned outcode;
    int32_t x, y;     // fixed point
    float sx, sy, z;  // unsnapped screen position and depth
  };
  std::vector<std::vector<ScreenVertex>> screen_;
  std::vector<ClipKey> clipKeys_;
  // This frame's vertices to transform, in runs of at most kVertexRun of one object.
  struct VertexRun {
    uint32_t object, begin, end;
  };
  static constexpr size_t kVertexRun = 2048;
  std::vector<VertexRun> runs_;
  std::vector<std::vector<SetupTriangle>> chunkTris_;     // per chunk
  std::vector<std::vector<std::vector<uint32_t>>> bins_;  // [chunk][tile] -> triangle index
};

}  // namespace tandem
