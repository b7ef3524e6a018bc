// The foveated sample distribution of Peres 2022 §4.2, computed once per configuration (and again
// only when the gaze moves): three concentric layers around the gaze point of one eye's viewport.
//   inner  (radius r0):   every pixel, spp_inner samples;
//   middle (r0 ... r1):   a pixel is listed with a probability that falls linearly with its
//                         distance from 1 at r0 to p at r1, spp_middle samples;
//   outer  (beyond r1):   a constant probability (outer_p; default p), spp_outer samples.
// Layer areas follow Table 2: a layer of radius r holds round(area of the disc ∩ viewport) pixels
// (π r² when the disc lies inside), the pixels nearest the gaze (ties broken by pixel order), so
// the thesis' radii give its areas exactly. The same map serves both eyes (the thesis' one
// buffer). Output: the coordinate buffer (a contiguous list of the listed pixels of one eye with
// their sample counts), the binary mask and the layer of every pixel.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace tandem {

struct FoveationDesc {
  float r0 = 144, r1 = 288;  // layer radii in pixels (the thesis' FHD values)
  float p = 0.5f;            // middle ring's probability at r1 (falls linearly from 1 at r0)
  float outerP = -1.0f;      // outer layer's constant probability; < 0: p (see docs/design.md)
  int spp[3] = {4, 3, 2};    // samples per listed pixel: inner, middle, outer
  Vec2 gaze{0.5f, 0.5f};     // gaze point, fraction of the eye's viewport (0,0 top left)
  uint64_t seed = 0;
  // The selection toss turned by rotation x the golden ratio (mod 1): 0 is the thesis' map; a
  // distribution that rotates each frame takes the frame's number, so a pixel listed with
  // probability q is listed on a share q of the frames, evenly spread over them.
  uint32_t rotation = 0;
  bool full = false;  // Base: no foveation, every pixel listed with spp[0] samples
  float outerProbability() const { return outerP < 0 ? p : outerP; }
  // Throws InputError naming `where` and the field for r1 < r0, p or outer_p outside [0,1],
  // spp outside [1, 1024].
  void validate(const std::string& where) const;
  bool operator==(const FoveationDesc& o) const;
};

struct FoveationLayerStats {
  float radius = 0;    // outer radius in pixels (0: the viewport's edge)
  int64_t area = 0;    // pixels of the layer
  int64_t listed = 0;  // pixels listed for sampling
  int spp = 0;         // samples per listed pixel
  int64_t samples() const { return listed * spp; }
  int64_t tableSamples() const { return area * spp; }  // Table 2's "samples": area x spp
};

struct FoveationMap {
  int width = 0, height = 0;     // one eye
  std::vector<uint8_t> layer;    // per pixel: 0 inner, 1 middle, 2 outer
  std::vector<uint16_t> spp;     // per pixel: samples, 0 = not listed (the binary mask is spp > 0)
  std::vector<uint32_t> coords;  // listed pixels, y * width + x, in row order
  FoveationLayerStats layers[3];
  int64_t totalSamples() const;
};

// Area in pixels of the disc (centre c, radius r) inside [0,w] x [0,h].
double discAreaInRect(Vec2 c, double r, int w, int h);

FoveationMap computeFoveation(int width, int height, const FoveationDesc& desc);

// The selection of `m` (computed for a desc equal to `desc` but for its rotation) tossed again
// for desc.rotation: the layers kept, the listed pixels, their counts and coordinates renewed.
// The same map computeFoveation gives for `desc`, without ranking the pixels again.
void reselectFoveation(FoveationMap& m, const FoveationDesc& desc);

}  // namespace tandem
