// SPDX-License-Identifier: AGPL-3.0-or-later
// Plain 3D vector and the few operations the library needs on it.
#ifndef DOT_GEOMETRY_H_
#define DOT_GEOMETRY_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace dot {

inline constexpr double kPi = 3.14159265358979323846;

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline bool operator==(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline double Dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double Norm(const Vec3& a) { return std::sqrt(Dot(a, a)); }
inline double Distance(const Vec3& a, const Vec3& b) { return Norm(a - b); }
// Unit vector along `a`, or the zero vector when `a` is zero.
// Divided by its largest component first, so that vectors of any finite
// size (a cross product at coordinates of 1e150) neither overflow nor
// underflow.
inline Vec3 Normalized(const Vec3& a) {
  const double m =
      std::max(std::max(std::abs(a.x), std::abs(a.y)), std::abs(a.z));
  if (!(m > 0) || !std::isfinite(m)) return Vec3{};
  const Vec3 b{a.x / m, a.y / m, a.z / m};
  return (1.0 / Norm(b)) * b;
}
inline bool IsFinite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// A triangle as three vertex indices. Orientation is the index order.
using Triangle = std::array<int32_t, 3>;

}  // namespace dot

#endif  // DOT_GEOMETRY_H_
