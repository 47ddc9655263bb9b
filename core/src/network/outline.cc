// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/outline.h"

#include <algorithm>
#include <cmath>

namespace dot {

namespace {

// The bands [lo, hi] that v values from v_lo to v_hi meet, clamped.
std::pair<size_t, size_t> BandsOf(const Outline& o, double v_lo, double v_hi) {
  const double last = static_cast<double>(o.bands.size() - 1);
  auto band = [&](double v) {
    return static_cast<size_t>(
        std::clamp(std::floor((v - o.band_v0) / o.band_height), 0.0, last));
  };
  return {band(v_lo), band(v_hi)};
}

// Calls f(k) for each edge k whose v span may meet [v_lo, v_hi] (an edge
// may come twice); false as soon as f returns false.
template <typename F>
bool ForEdgesNear(const Outline& o, double v_lo, double v_hi, const F& f) {
  if (o.bands.empty()) {
    for (size_t k = 0; k < o.x.size(); ++k) {
      if (!f(k)) return false;
    }
    return true;
  }
  const auto [lo, hi] = BandsOf(o, v_lo, v_hi);
  for (size_t b = lo; b <= hi; ++b) {
    for (int32_t k : o.bands[b]) {
      if (!f(static_cast<size_t>(k))) return false;
    }
  }
  return true;
}

}  // namespace

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
  if (n >= 64) {
    const auto [y0, y1] = std::minmax_element(o.y.begin(), o.y.end());
    const size_t count = n / 4;
    o.band_v0 = *y0;
    o.band_height = (*y1 - *y0) / static_cast<double>(count);
    if (o.band_height > 0) {
      o.bands.resize(count);
      for (size_t k = 0; k < n; ++k) {
        const size_t m = (k + 1) % n;
        const auto [lo, hi] =
            BandsOf(o, std::min(o.y[k], o.y[m]), std::max(o.y[k], o.y[m]));
        for (size_t b = lo; b <= hi; ++b) {
          o.bands[b].push_back(static_cast<int32_t>(k));
        }
      }
    }
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
  return !ForEdgesNear(o, std::min(py, qy), std::max(py, qy), [&](size_t k) {
    const size_t m = (k + 1) % n;
    const double a = side(px, py, qx, qy, o.x[k], o.y[k]);
    const double b = side(px, py, qx, qy, o.x[m], o.y[m]);
    if ((a > 0 && b > 0) || (a < 0 && b < 0) || (a == 0 && b == 0)) {
      return true;
    }
    const double c = side(o.x[k], o.y[k], o.x[m], o.y[m], px, py);
    const double d = side(o.x[k], o.y[k], o.x[m], o.y[m], qx, qy);
    return !((c < 0 && d > 0) || (c > 0 && d < 0));  // false: they cross
  });
}

bool Inside(const Outline& o, const Vec3& p) {
  if (!(o.area > 0) || p.x < o.lo.x || p.x > o.hi.x || p.y < o.lo.y ||
      p.y > o.hi.y || p.z < o.lo.z || p.z > o.hi.z) {
    return false;
  }
  const Vec3 d = p - o.centre;
  if (std::abs(Dot(d, o.normal)) > o.reach) return false;
  const double px = Dot(d, o.u), py = Dot(d, o.v);
  // Each edge counts once: an edge listed in one band only (a point
  // meets one band).
  int winding = 0;
  const size_t n = o.x.size();
  ForEdgesNear(o, py, py, [&](size_t k) {
    const size_t m = (k + 1) % n;
    const double side =
        (o.x[m] - o.x[k]) * (py - o.y[k]) - (px - o.x[k]) * (o.y[m] - o.y[k]);
    if (o.y[k] <= py) {
      if (o.y[m] > py && side > 0) ++winding;
    } else if (o.y[m] <= py && side < 0) {
      --winding;
    }
    return true;
  });
  return winding != 0;
}

}  // namespace dot
