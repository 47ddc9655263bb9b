// SPDX-License-Identifier: AGPL-3.0-or-later
#include "mesh/face_tree.h"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <iterator>
#include <numeric>

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_3 ToPoint(const Vec3& p) { return {p.x, p.y, p.z}; }

// Face id -> its triangle, or a point of it, read from the mesh on demand:
// the tree holds ids only (ExternalPropertyMaps: the maps are stored once).
K::Triangle_3 Read(const MeshData& m, int32_t f, K::Triangle_3*) {
  const Triangle& t = m.triangles[f];
  return {ToPoint(m.vertices[t[0]]), ToPoint(m.vertices[t[1]]),
          ToPoint(m.vertices[t[2]])};
}
K::Point_3 Read(const MeshData& m, int32_t f, K::Point_3*) {
  return ToPoint(m.vertices[m.triangles[f][0]]);
}
template <class Value>
struct FaceMap {
  using key_type = int32_t;
  using value_type = Value;
  using reference = Value;
  using category = boost::readable_property_map_tag;
  const MeshData* mesh = nullptr;
  friend Value get(const FaceMap& m, key_type f) {
    return Read(*m.mesh, f, static_cast<Value*>(nullptr));
  }
};
using TriangleMap = FaceMap<K::Triangle_3>;
using CornerMap = FaceMap<K::Point_3>;

using Primitive = CGAL::AABB_primitive<int32_t, TriangleMap, CornerMap,
                                       CGAL::Tag_true, CGAL::Tag_false>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

}  // namespace

void Box3::Add(const Vec3& p) {
  lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
}

bool Box3::Meets(const Box3& o) const {
  return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y &&
         lo.z <= o.hi.z && o.lo.z <= hi.z;
}

struct FaceTree::Tree : CgalTree {
  using CgalTree::CgalTree;
};

FaceTree::FaceTree(const MeshData& mesh) {
  std::vector<int32_t> ids(mesh.triangles.size());
  std::iota(ids.begin(), ids.end(), 0);
  tree_ = std::make_unique<Tree>(ids.begin(), ids.end(), TriangleMap{&mesh},
                                 CornerMap{&mesh});
  tree_->build();  // now, not lazily on the first (concurrent) query
}

FaceTree::~FaceTree() = default;

void FaceTree::FacesMeeting(const Box3& box,
                            std::vector<int32_t>* faces) const {
  if (tree_->empty() || box.lo.x > box.hi.x) return;
  const size_t first = faces->size();
  const CGAL::Bbox_3 query(box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y,
                           box.hi.z);
  tree_->all_intersected_primitives(query, std::back_inserter(*faces));
  std::sort(faces->begin() + static_cast<std::ptrdiff_t>(first), faces->end());
}

}  // namespace dot
