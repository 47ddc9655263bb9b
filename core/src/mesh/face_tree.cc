// SPDX-License-Identifier: AGPL-3.0-or-later
#include "mesh/face_tree.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dot {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kFloatMax = std::numeric_limits<float>::max();

// The float at or just below / above a (finite) double: a float box that
// contains the double one, so that no face is missed.
float Down(double x) {
  if (x > kFloatMax) return std::numeric_limits<float>::max();
  if (x < -kFloatMax) return -kInf;
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) <= x ? f : std::nextafter(f, -kInf);
}
float Up(double x) {
  if (x > kFloatMax) return kInf;
  if (x < -kFloatMax) return -std::numeric_limits<float>::max();
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : std::nextafter(f, kInf);
}

// Spreads the low 21 bits of x to every third bit (for a Morton code).
uint64_t Spread(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffff;
  x = (x | x << 16) & 0x1f0000ff0000ff;
  x = (x | x << 8) & 0x100f00f00f00f00f;
  x = (x | x << 4) & 0x10c30c30c30c30c3;
  x = (x | x << 2) & 0x1249249249249249;
  return x;
}

Box3 FaceBox(const MeshData& mesh, int32_t f) {
  Box3 b;
  for (int32_t v : mesh.triangles[f]) b.Add(mesh.vertices[v]);
  return b;
}

}  // namespace

void Box3::Add(const Vec3& p) {
  lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
}

bool Box3::Meets(const Box3& o) const {
  return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y &&
         lo.z <= o.hi.z && o.lo.z <= hi.z;
}

void FaceTree::FloatBox::Add(const FloatBox& o) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(lo[k], o.lo[k]);
    hi[k] = std::max(hi[k], o.hi[k]);
  }
}

bool FaceTree::FloatBox::Meets(const Box3& b) const {
  return lo[0] <= b.hi.x && b.lo.x <= hi[0] && lo[1] <= b.hi.y &&
         b.lo.y <= hi[1] && lo[2] <= b.hi.z && b.lo.z <= hi[2];
}

FaceTree::FaceTree(const MeshData& mesh) : mesh_(&mesh) {
  const size_t n = mesh.triangles.size();
  if (n == 0) return;
  Box3 all;
  for (const Vec3& p : mesh.vertices) all.Add(p);
  // Faces in the order of their centroids along a Morton curve: faces
  // near each other in space are near each other in `order_`.
  std::vector<std::pair<uint64_t, int32_t>> keyed(n);
  const Vec3 size = all.hi - all.lo;
  const double extent = std::max({size.x, size.y, size.z, 1e-300});
  const double scale = double{(1 << 21) - 1} / extent;
  tbb::parallel_for(size_t{0}, n, [&](size_t f) {
    const Triangle& t = mesh.triangles[f];
    const Vec3 c = (1.0 / 3) * (mesh.vertices[t[0]] + mesh.vertices[t[1]] +
                                mesh.vertices[t[2]]);
    auto cell = [&](double x, double lo) {
      const double d = (x - lo) * scale;  // NaN when the extent overflows
      return d >= 1 ? static_cast<uint64_t>(std::min(d, double{(1 << 21) - 1}))
                    : uint64_t{0};
    };
    keyed[f] = {Spread(cell(c.x, all.lo.x)) | Spread(cell(c.y, all.lo.y)) << 1 |
                    Spread(cell(c.z, all.lo.z)) << 2,
                static_cast<int32_t>(f)};
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[i] = keyed[i].second;
  keyed = {};
  // A complete binary tree over the leaves, in an array: node i has
  // children 2i+1 and 2i+2; the last `leaves_` nodes are the leaves.
  const size_t leaves_used = (n + kLeafFaces - 1) / kLeafFaces;
  leaves_ = 1;
  while (leaves_ < leaves_used) leaves_ *= 2;
  nodes_.assign(2 * leaves_ - 1, FloatBox{});
  const size_t first_leaf = leaves_ - 1;
  tbb::parallel_for(size_t{0}, leaves_used, [&](size_t leaf) {
    FloatBox& box = nodes_[first_leaf + leaf];
    const size_t end = std::min(n, (leaf + 1) * kLeafFaces);
    for (size_t i = leaf * kLeafFaces; i < end; ++i) {
      const Box3 b = FaceBox(mesh, order_[i]);
      box.Add({{Down(b.lo.x), Down(b.lo.y), Down(b.lo.z)},
               {Up(b.hi.x), Up(b.hi.y), Up(b.hi.z)}});
    }
  });
  for (size_t i = first_leaf; i-- > 0;) {
    nodes_[i] = nodes_[2 * i + 1];
    nodes_[i].Add(nodes_[2 * i + 2]);
  }
}

void FaceTree::FacesMeeting(const Box3& box,
                            std::vector<int32_t>* faces) const {
  if (nodes_.empty() || box.lo.x > box.hi.x) return;
  const size_t first = faces->size();
  const size_t first_leaf = leaves_ - 1;
  size_t stack[64];
  size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const size_t node = stack[--top];
    if (!nodes_[node].Meets(box)) continue;
    if (node < first_leaf) {
      stack[top++] = 2 * node + 1;
      stack[top++] = 2 * node + 2;
      continue;
    }
    const size_t leaf = node - first_leaf;
    const size_t end = std::min(order_.size(), (leaf + 1) * kLeafFaces);
    for (size_t i = leaf * kLeafFaces; i < end; ++i) {
      if (FaceBox(*mesh_, order_[i]).Meets(box)) faces->push_back(order_[i]);
    }
  }
  std::sort(faces->begin() + static_cast<std::ptrdiff_t>(first), faces->end());
}

}  // namespace dot
