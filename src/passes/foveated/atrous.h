// Edge-avoiding À-Trous wavelet filtering (Dammertz et al. 2010), non-homogeneous as in Peres 2022
// §4.4: a 5x5 kernel from the cubic B-spline (1/16, 1/4, 3/8, 1/4, 1/16) taps pixels `step` apart;
// each tap is weighted by colour, normal and position edge-stopping weights (eq. 4.1)
//   w = exp(-|c_j - c_u|² / (σ_c² L̄² 2^-k)) · exp(-|n_j - n_u|² / σ_n²) · exp(-|x_j - x_u|² / (σ_x
//   z_u)²)
// times the binary mask b(j) (eq. 4.2): a pixel that was not sampled is never read. L̄ is the mean
// luminance of the sampled pixels (σ_c is relative, so exposure does not matter) and k the
// iteration's index within its region (σ_c halves each iteration, as Dammertz's c_phi); z_u is
// the centre's distance to its eye (σ_x is relative). Taps outside the centre's view (off screen,
// or in the other eye's half of the dual image) are skipped. Regions are filtered one after
// another, each with its own level count L and decreasing step widths 2^(L-1) ... 1 (Qi et al.
// 2012; Algorithm 1). A pixel whose taps all have zero weight keeps its value.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tandem {

struct AtrousWeights {
  float sigmaColor = 16.0f;     // relative to the sampled pixels' mean luminance
  float sigmaNormal = 0.3f;     // unit-normal difference
  float sigmaPosition = 0.05f;  // relative to the centre's distance from the eye
  // Beyond Dammertz: the colour term scaled by the centre's own noise instead (SVGF-like,
  // Schied et al. 2017): exp(-|c_j - c_u|² / (6 σ_v² var_u)), var_u the variance of the centre's
  // estimate, carried through the levels as the weighted mean's (Σ w² var_j / (Σ w)²).
  bool varianceGuided = false;
  float sigmaVariance = 4.0f;
};

// The frame in planes: colour (filtered in place), guides and per-pixel flags.
struct AtrousImage {
  int width = 0, height = 0;
  std::vector<float> c[3], n[3], x[3];
  std::vector<float> positionScale;  // 1 / (σ_x z_u)² per pixel (filled by prepare())
  std::vector<float> sampled;        // b: 1 where the pixel was sampled, 0 where not
  std::vector<float> known;          // 1 where the pixel holds an estimate (sampled or filtered)
  std::vector<float> var;            // variance of the pixel's estimate's luminance (known ones)
  std::vector<float> colorScale;     // per level: the centre's 1 / (colour σ)², 0 if not known
  // Variance-guided weights only: the colour the weights compare (before a pixel's first level
  // the mean of its 3 x 3 same-surface sampled neighbours, then its filtered estimate) and that
  // guide's variance.
  std::vector<float> g[3], gvar;
  std::vector<float> scratch;  // one level's sums (atrousLevel), kept to avoid reallocation
  void resize(int w, int h);
  size_t index(int px, int py) const { return size_t(py) * size_t(width) + size_t(px); }
};

// A run of pixels [x0, x1) of row y, inside the view rectangle [vx0, vx1) x [vy0, vy1).
struct AtrousSpan {
  int y, x0, x1;
  int vx0, vy0, vx1, vy1;
};

struct AtrousRegion {
  std::vector<AtrousSpan> spans;
  int levels = 0;
};

// One level over a region: every pixel of its spans filtered with taps `step` apart, from the
// values before the level. `iteration` is the level's index within the region (for σ_c).
void atrousLevel(AtrousImage& img, const AtrousRegion& region, int step, int iteration,
                 float meanLuminance, const AtrousWeights& w);

// Algorithm 1: the regions in order, each with step widths 2^(levels-1) ... 1, the colour σ
// relative to `meanLuminance` (L̄). Returns the (region index, step width) of every level run, in
// order.
std::vector<std::pair<int, int>> nonHomogeneousAtrous(AtrousImage& img,
                                                      const std::vector<AtrousRegion>& regions,
                                                      const AtrousWeights& w, float meanLuminance);

// The luminance of pixel i's colour planes, in double (sums over millions of pixels).
inline double planeLuminance(const AtrousImage& img, size_t i) {
  return 0.2126 * img.c[0][i] + 0.7152 * img.c[1][i] + 0.0722 * img.c[2][i];
}

// Mean luminance of the sampled pixels (at least a small positive floor).
float sampledMeanLuminance(const AtrousImage& img);

}  // namespace tandem
