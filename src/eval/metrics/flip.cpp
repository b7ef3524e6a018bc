#include "eval/metrics/flip.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/interrupt.h"
#include "core/math.h"
#include "core/parallel.h"

namespace tandem {

namespace {

// One channel image (planar) for filtering.
struct Plane {
  int w = 0, h = 0;
  std::vector<float> v;
  Plane(int w_, int h_) : w(w_), h(h_), v(size_t(w_) * size_t(h_), 0.0f) {}
  float& at(int x, int y) { return v[size_t(y) * size_t(w) + size_t(x)]; }
  float at(int x, int y) const { return v[size_t(y) * size_t(w) + size_t(x)]; }
};

// One direction of a separable convolution with replicated borders: (dx, dy) is (1, 0) for rows,
// (0, 1) for columns.
void convolve1d(const Plane& in, Plane& out, const std::vector<float>& kernel, int dx, int dy) {
  const int r = int(kernel.size() / 2);
  parallelRange(
      size_t(in.h),
      [&](size_t b, size_t e) {
        for (int y = int(b); y < int(e); ++y) {
          if (y % 16 == 0) pollInterrupt();  // a Python caller's Ctrl-C, within a wide kernel
          for (int x = 0; x < in.w; ++x) {
            float s = 0;
            for (int k = -r; k <= r; ++k)
              s += kernel[size_t(k + r)] *
                   in.at(std::clamp(x + k * dx, 0, in.w - 1), std::clamp(y + k * dy, 0, in.h - 1));
            out.at(x, y) = s;
          }
        }
      },
      16);
}

// Separable convolution with replicated borders: rows with kx, then columns with ky.
Plane convolve(const Plane& in, const std::vector<float>& kx, const std::vector<float>& ky) {
  Plane tmp(in.w, in.h), out(in.w, in.h);
  convolve1d(in, tmp, kx, 1, 0);
  convolve1d(tmp, out, ky, 0, 1);
  return out;
}

// D65 white point of XYZ.
const Vec3 kWhite{0.950428545f, 1.0f, 1.088900371f};

float srgbToLinear(float c) {
  return c > 0.04045f ? std::pow((c + 0.055f) / 1.055f, 2.4f) : c / 12.92f;
}

Vec3 linearToXyz(Vec3 c) {
  return {0.4123908f * c.x + 0.3575843f * c.y + 0.1804808f * c.z,
          0.2126390f * c.x + 0.7151687f * c.y + 0.0721923f * c.z,
          0.0193308f * c.x + 0.1191948f * c.y + 0.9505322f * c.z};
}

Vec3 xyzToLinear(Vec3 c) {
  return {3.241003275f * c.x - 1.537398934f * c.y - 0.498615861f * c.z,
          -0.969224334f * c.x + 1.875930071f * c.y + 0.041554224f * c.z,
          0.055639423f * c.x - 0.204011202f * c.y + 1.057148933f * c.z};
}

// YCxCz: the linear opponent space FLIP filters in (L*a*b* without the cube root).
Vec3 xyzToYcxcz(Vec3 c) {
  const Vec3 n{c.x / kWhite.x, c.y / kWhite.y, c.z / kWhite.z};
  return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}

Vec3 ycxczToXyz(Vec3 c) {
  const float y = (c.x + 16.0f) / 116.0f;
  return {(y + c.y / 500.0f) * kWhite.x, y * kWhite.y, (y - c.z / 200.0f) * kWhite.z};
}

// Hunt-adjusted L*a*b*: chroma scaled by 0.01 L, so dark colours differ less.
Vec3 linearToHuntLab(Vec3 rgb) {
  const Vec3 x = linearToXyz(rgb);
  auto f = [](float t) {
    const float d = 6.0f / 29.0f;
    return t > d * d * d ? std::cbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
  };
  const float fx = f(x.x / kWhite.x), fy = f(x.y / kWhite.y), fz = f(x.z / kWhite.z);
  const float L = 116.0f * fy - 16.0f;
  return {L, 0.01f * L * 500.0f * (fx - fy), 0.01f * L * 200.0f * (fy - fz)};
}

float hyab(Vec3 a, Vec3 b) {
  return std::abs(a.x - b.x) + std::sqrt((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// Contrast sensitivity of one opponent channel as a sum of two Gaussians,
// s(r) = a1 sqrt(pi/b1) exp(-pi^2 r^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2 / b2), r in degrees;
// each term is separable, so the 2D filter is applied as two separable passes, normalised so
// the whole 2D kernel sums to 1.
struct Csf {
  float a1, b1, a2, b2;
};
const Csf kCsfA{1.0f, 0.0047f, 0.0f, 1e-5f}, kCsfRG{1.0f, 0.0053f, 0.0f, 1e-5f},
    kCsfBY{34.1f, 0.04f, 13.5f, 0.025f};

Plane csfFilter(const Plane& in, const Csf& c, double ppd) {
  const double maxB = 0.04;  // the widest of all channels sets one support for all
  const int r = int(std::ceil(3.0 * std::sqrt(maxB / (2.0 * kPi * kPi)) * ppd));
  auto gauss = [&](float b) {
    std::vector<float> g(size_t(2 * r + 1));
    for (int i = -r; i <= r; ++i) {
      const double d = i / ppd;
      g[size_t(i + r)] = float(std::exp(-kPi * kPi * d * d / b));
    }
    return g;
  };
  const std::vector<float> g1 = gauss(c.b1), g2 = gauss(c.b2);
  double s1 = 0, s2 = 0;
  for (float v : g1) s1 += v;
  for (float v : g2) s2 += v;
  const double w1 = c.a1 * std::sqrt(kPi / c.b1), w2 = c.a2 * std::sqrt(kPi / c.b2);
  const double total = w1 * s1 * s1 + w2 * s2 * s2;
  Plane out = convolve(in, g1, g1);
  for (float& v : out.v) v *= float(w1 / total);
  if (w2 > 0) {
    Plane second = convolve(in, g2, g2);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += float(w2 / total) * second.v[i];
  }
  return out;
}

// Edge (first derivative) or point (second derivative) detector along x, Gaussian along y, with
// positive weights normalised to 1 and negative ones to -1 (of the 2D kernel, which for these
// separable kernels is the same as normalising the x factor and the Gaussian separately).
std::vector<float> featureKernel(double sd, int r, bool point) {
  std::vector<float> k(size_t(2 * r + 1));
  double pos = 0, neg = 0;
  for (int i = -r; i <= r; ++i) {
    const double g = std::exp(-double(i * i) / (2 * sd * sd));
    const double v = point ? (i * i / (sd * sd) - 1.0) * g : -i * g;
    k[size_t(i + r)] = float(v);
    (v > 0 ? pos : neg) += v;
  }
  for (float& v : k) v = v > 0 ? float(v / pos) : float(v / -neg);
  return k;
}

}  // namespace

double defaultPixelsPerDegree() {
  return 0.7 * 3840.0 / 0.7 * kPi / 180.0;
}

double flip(const Buffer& reference, const Buffer& test, Buffer* map, double ppd) {
  const int w = reference.width, h = reference.height;
  // Both images in YCxCz, as three planes each.
  auto toYcxcz = [&](const Buffer& img) {
    std::vector<Plane> p(3, Plane(w, h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (x == 0 && y % 64 == 0) pollInterrupt();  // a Python caller's Ctrl-C
        const Vec3 s = img.rgb(x, y);
        const Vec3 lin{srgbToLinear(std::clamp(s.x, 0.0f, 1.0f)),
                       srgbToLinear(std::clamp(s.y, 0.0f, 1.0f)),
                       srgbToLinear(std::clamp(s.z, 0.0f, 1.0f))};
        const Vec3 c = xyzToYcxcz(linearToXyz(lin));
        p[0].at(x, y) = c.x, p[1].at(x, y) = c.y, p[2].at(x, y) = c.z;
      }
    return p;
  };
  const std::vector<Plane> ref = toYcxcz(reference), tst = toYcxcz(test);

  // Colour pipeline.
  auto filtered = [&](const std::vector<Plane>& p) {
    return std::vector<Plane>{csfFilter(p[0], kCsfA, ppd), csfFilter(p[1], kCsfRG, ppd),
                              csfFilter(p[2], kCsfBY, ppd)};
  };
  const std::vector<Plane> fr = filtered(ref), ft = filtered(tst);
  const float qc = 0.7f, pc = 0.4f, pt = 0.95f;
  const float cmax = std::pow(hyab(linearToHuntLab({0, 1, 0}), linearToHuntLab({0, 0, 1})), qc);
  auto huntLab = [](const std::vector<Plane>& p, int x, int y) {
    Vec3 lin = xyzToLinear(ycxczToXyz({p[0].at(x, y), p[1].at(x, y), p[2].at(x, y)}));
    lin = vmin(vmax(lin, Vec3(0.0f)), Vec3(1.0f));  // back into the RGB cube
    return linearToHuntLab(lin);
  };

  // Feature pipeline on the normalised achromatic channel.
  const double sd = 0.5 * 0.082 * ppd;
  const int fr_ = int(std::ceil(3 * sd));
  std::vector<float> gy(size_t(2 * fr_ + 1));
  double gs = 0;
  for (int i = -fr_; i <= fr_; ++i)
    gs += gy[size_t(i + fr_)] = float(std::exp(-double(i * i) / (2 * sd * sd)));
  for (float& v : gy) v = float(v / gs);
  const std::vector<float> edge = featureKernel(sd, fr_, false),
                           point = featureKernel(sd, fr_, true);
  auto features = [&](const Plane& Y) {
    Plane n(w, h);
    for (size_t i = 0; i < n.v.size(); ++i) n.v[i] = (Y.v[i] + 16.0f) / 116.0f;
    return std::vector<Plane>{convolve(n, edge, gy), convolve(n, gy, edge), convolve(n, point, gy),
                              convolve(n, gy, point)};
  };
  const std::vector<Plane> er = features(ref[0]), et = features(tst[0]);

  if (map) *map = Buffer(w, h, 1);
  double sum = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x == 0 && y % 64 == 0) pollInterrupt();
      const float dE = std::pow(hyab(huntLab(fr, x, y), huntLab(ft, x, y)), qc);
      const float c = dE < pc * cmax ? pt / (pc * cmax) * dE
                                     : pt + (dE - pc * cmax) / (cmax - pc * cmax) * (1.0f - pt);
      auto mag = [&](const std::vector<Plane>& f, int k) {
        return std::hypot(f[size_t(k)].at(x, y), f[size_t(k) + 1].at(x, y));
      };
      const float df =
          std::max(std::abs(mag(er, 0) - mag(et, 0)), std::abs(mag(er, 2) - mag(et, 2)));
      const float f = std::pow(df / std::sqrt(2.0f), 0.5f);
      const float e = std::pow(std::min(c, 1.0f), 1.0f - f);
      if (map) map->at(x, y)[0] = e;
      sum += e;
    }
  return sum / double(std::max<size_t>(size_t(w) * size_t(h), 1));
}

Buffer flipColorMap(const Buffer& error) {
  // Control points of a perceptually ordered dark-to-bright ramp.
  static const Vec3 ramp[] = {{0.0f, 0.0f, 0.02f},   {0.23f, 0.06f, 0.44f}, {0.55f, 0.16f, 0.51f},
                              {0.87f, 0.29f, 0.38f}, {0.99f, 0.62f, 0.42f}, {0.99f, 0.99f, 0.75f}};
  const int n = int(std::size(ramp)) - 1;
  Buffer out(error.width, error.height, 3);
  for (int y = 0; y < error.height; ++y)
    for (int x = 0; x < error.width; ++x) {
      const float t = std::clamp(error.at(x, y)[0], 0.0f, 1.0f) * float(n);
      const int i = std::min(int(t), n - 1);
      out.setRgb(x, y, lerp(ramp[i], ramp[i + 1], t - float(i)));
    }
  return out;
}

}  // namespace tandem
