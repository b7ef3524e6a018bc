// Small vector and matrix types for Tandem. Trivially copyable, float, column vectors.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace tandem {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
inline float radians(float deg) {
  return deg * (kPi / 180.0f);
}
inline float degrees(float rad) {
  return rad * (180.0f / kPi);
}

struct Vec2 {
  float x = 0, y = 0;
  constexpr Vec2() = default;
  constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(float s) const { return {x * s, y * s}; }
  constexpr Vec2 operator*(Vec2 o) const { return {x * o.x, y * o.y}; }
};

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
  constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(Vec3 o) { return *this = *this + o; }
  Vec3& operator-=(Vec3 o) { return *this = *this - o; }
  Vec3& operator*=(float s) { return *this = *this * s; }
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};
inline constexpr Vec3 operator*(float s, Vec3 v) {
  return v * s;
}

struct Vec4 {
  float x = 0, y = 0, z = 0, w = 0;
  constexpr Vec4() = default;
  constexpr Vec4(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
  constexpr Vec4(Vec3 v, float w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
  constexpr Vec3 xyz() const { return {x, y, z}; }
  constexpr Vec4 operator+(Vec4 o) const { return {x + o.x, y + o.y, z + o.z, w + o.w}; }
  constexpr Vec4 operator-(Vec4 o) const { return {x - o.x, y - o.y, z - o.z, w - o.w}; }
  constexpr Vec4 operator*(float s) const { return {x * s, y * s, z * s, w * s}; }
  constexpr Vec4 operator*(Vec4 o) const { return {x * o.x, y * o.y, z * o.z, w * o.w}; }
};

// Three consecutive floats (a channel triple of a buffer pixel) as a vector.
inline constexpr Vec3 loadVec3(const float* p) {
  return {p[0], p[1], p[2]};
}
inline constexpr float dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
// The cube-map face a direction falls on: its major axis, +x -x +y -y +z -z = 0..5.
inline int cubeFace(Vec3 d) {
  const float ax = d.x < 0 ? -d.x : d.x, ay = d.y < 0 ? -d.y : d.y, az = d.z < 0 ? -d.z : d.z;
  return ax >= ay && ax >= az ? (d.x > 0 ? 0 : 1)
         : ay >= az           ? (d.y > 0 ? 2 : 3)
                              : (d.z > 0 ? 4 : 5);
}
inline constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 v) {
  return std::sqrt(dot(v, v));
}
inline Vec3 normalize(Vec3 v) {
  // The test on the squared length (the same outcome) does not wait for the square root.
  const float l2 = dot(v, v);
  return l2 > 0 ? v / std::sqrt(l2) : Vec3(0, 0, 0);
}
inline Vec3 vmin(Vec3 a, Vec3 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 vmax(Vec3 a, Vec3 b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline Vec3 lerp(Vec3 a, Vec3 b, float t) {
  return a + (b - a) * t;
}
inline float maxComponent(Vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}
inline bool isFinite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline float luminance(Vec3 c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// Row-major 4x4 matrix acting on column vectors: p' = M * p.
struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  static Mat4 identity() { return {}; }
  static Mat4 translate(Vec3 t);
  static Mat4 scale(Vec3 s);
  static Mat4 rotateX(float rad);
  static Mat4 rotateY(float rad);
  static Mat4 rotateZ(float rad);
  // Euler angles in degrees applied X, then Y, then Z (R = Rz * Ry * Rx).
  static Mat4 eulerXYZ(Vec3 deg);
  static Mat4 fromQuaternion(Vec4 q);                  // (x, y, z, w)
  static Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up);  // world -> view (view looks down -Z)

  Mat4 operator*(const Mat4& o) const;
  // Inline: these run per vertex and per pixel.
  Vec4 operator*(Vec4 v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z + m[0][3] * v.w,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z + m[1][3] * v.w,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z + m[2][3] * v.w,
            m[3][0] * v.x + m[3][1] * v.y + m[3][2] * v.z + m[3][3] * v.w};
  }
  Vec3 transformPoint(Vec3 p) const {
    Vec4 r = *this * Vec4(p, 1.0f);
    return r.w != 1.0f && r.w != 0.0f ? r.xyz() / r.w : r.xyz();
  }
  Vec3 transformVector(Vec3 v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat4 inverse() const;
  Mat4 transposed() const;
  // Matrix for normals: inverse transpose of the upper 3x3.
  Mat4 normalMatrix() const { return inverse().transposed(); }
};

// Bit-for-bit equality (a matrix recomputed from the same inputs compares equal).
inline bool sameMatrix(const Mat4& a, const Mat4& b) {
  return std::memcmp(&a, &b, sizeof(Mat4)) == 0;
}

struct Bounds3 {
  Vec3 lo{1e30f, 1e30f, 1e30f};
  Vec3 hi{-1e30f, -1e30f, -1e30f};
  void extend(Vec3 p) {
    lo = vmin(lo, p);
    hi = vmax(hi, p);
  }
  void extend(const Bounds3& b) {
    lo = vmin(lo, b.lo);
    hi = vmax(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  Vec3 extent() const { return hi - lo; }
};

// Orthonormal basis around n (Duff et al. 2017).
inline void orthonormalBasis(Vec3 n, Vec3& t, Vec3& b) {
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float bb = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x};
  b = {bb, sign + n.y * n.y * a, -n.y};
}

}  // namespace tandem
