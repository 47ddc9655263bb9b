// SPDX-License-Identifier: AGPL-3.0-or-later
// The faces of a mesh in a bounding-box tree (CGAL's AABB_tree), built once
// so that "which faces come near this patch" costs a query, not a scan of
// every face: per-hole work then does not grow with the mesh.
#ifndef DOT_CORE_MESH_FACE_TREE_H_
#define DOT_CORE_MESH_FACE_TREE_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "dot/mesh.h"

namespace dot {

// Axis-aligned box of some points.
struct Box3 {
  Vec3 lo{1e308, 1e308, 1e308};
  Vec3 hi{-1e308, -1e308, -1e308};
  void Add(const Vec3& p);
  bool Meets(const Box3& o) const;
};

class FaceTree {
 public:
  // Over `mesh`'s faces; `mesh` must outlive the tree and not change.
  explicit FaceTree(const MeshData& mesh);
  ~FaceTree();
  FaceTree(const FaceTree&) = delete;
  FaceTree& operator=(const FaceTree&) = delete;

  // Appends to `faces`, in increasing order, every face that meets `box`
  // (exact predicates: none is missed). Safe from many threads at once.
  void FacesMeeting(const Box3& box, std::vector<int32_t>* faces) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace dot

#endif  // DOT_CORE_MESH_FACE_TREE_H_
