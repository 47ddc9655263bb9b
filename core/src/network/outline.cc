// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/outline.h"

#include <algorithm>
#include <cmath>

namespace dot {

Outline MakeOutline(const NetworkGraph& g, std::vector<int32_t> vertices,
                    double reach_fraction) {
  Outline o;
  o.vertices = std::move(vertices);
  const size_t n = o.vertices.size();
  if (n == 0) return o;
  // From the first vertex: far from the origin, p x q would cancel.
  const Vec3 origin = g.vertices[o.vertices[0]];
  for (size_t k = 0; k < n; ++k) {
    const Vec3& p = g.vertices[o.vertices[k]];
    const Vec3& q = g.vertices[o.vertices[(k + 1) % n]];
    o.vector_area = o.vector_area + 0.5 * Cross(p - origin, q - origin);
    o.centre = o.centre + (1.0 / static_cast<double>(n)) * p;
  }
  o.area = Norm(o.vector_area);
  if (!(o.area > 0)) return o;
  o.radius = std::sqrt(o.area / M_PI);
  o.normal = (1.0 / o.area) * o.vector_area;
  // Any unit vector across the normal, and the third of the frame.
  const Vec3 axis = std::abs(o.normal.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  o.u = Normalized(Cross(o.normal, axis));
  o.v = Cross(o.normal, o.u);
  o.lo = o.hi = g.vertices[o.vertices[0]];
  for (int32_t id : o.vertices) {
    const Vec3& p = g.vertices[id];
    const Vec3 d = p - o.centre;
    o.off_plane = std::max(o.off_plane, std::abs(Dot(d, o.normal)));
    o.x.push_back(Dot(d, o.u));
    o.y.push_back(Dot(d, o.v));
    o.lo = {std::min(o.lo.x, p.x), std::min(o.lo.y, p.y),
            std::min(o.lo.z, p.z)};
    o.hi = {std::max(o.hi.x, p.x), std::max(o.hi.y, p.y),
            std::max(o.hi.z, p.z)};
  }
  o.reach = o.off_plane + reach_fraction * o.radius;
  const Vec3 grow{o.reach, o.reach, o.reach};
  o.lo = o.lo - grow;
  o.hi = o.hi + grow;
  return o;
}

bool CrossesOutline(const Outline& o, const Vec3& p, const Vec3& q) {
  const double px = Dot(p - o.centre, o.u), py = Dot(p - o.centre, o.v);
  const double qx = Dot(q - o.centre, o.u), qy = Dot(q - o.centre, o.v);
  auto side = [](double ax, double ay, double bx, double by, double cx,
                 double cy) {
    return (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
  };
  const size_t n = o.x.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t m = (k + 1) % n;
    const double a = side(px, py, qx, qy, o.x[k], o.y[k]);
    const double b = side(px, py, qx, qy, o.x[m], o.y[m]);
    if ((a > 0 && b > 0) || (a < 0 && b < 0) || (a == 0 && b == 0)) continue;
    const double c = side(o.x[k], o.y[k], o.x[m], o.y[m], px, py);
    const double d = side(o.x[k], o.y[k], o.x[m], o.y[m], qx, qy);
    if ((c < 0 && d > 0) || (c > 0 && d < 0)) return true;
  }
  return false;
}

bool Inside(const Outline& o, const Vec3& p) {
  if (!(o.area > 0) || p.x < o.lo.x || p.x > o.hi.x || p.y < o.lo.y ||
      p.y > o.hi.y || p.z < o.lo.z || p.z > o.hi.z) {
    return false;
  }
  const Vec3 d = p - o.centre;
  if (std::abs(Dot(d, o.normal)) > o.reach) return false;
  const double px = Dot(d, o.u), py = Dot(d, o.v);
  int winding = 0;
  const size_t n = o.x.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t m = (k + 1) % n;
    const double side =
        (o.x[m] - o.x[k]) * (py - o.y[k]) - (px - o.x[k]) * (o.y[m] - o.y[k]);
    if (o.y[k] <= py) {
      if (o.y[m] > py && side > 0) ++winding;
    } else if (o.y[m] <= py && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

}  // namespace dot
