// SPDX-License-Identifier: AGPL-3.0-or-later
// The faces of a mesh in a bounding-box tree, built once so that "which
// faces come near this patch" costs a query, not a scan of every face:
// per-hole work then does not grow with the mesh. A linear BVH: faces
// sorted along a Morton curve of their centroids, leaves of kLeafFaces
// consecutive faces, float boxes (rounded outward) in a complete binary
// tree kept in one array: about 8 bytes a face, where CGAL's AABB_tree
// (used before) took about 60; a scan of millions of faces fills memory.
#ifndef DOT_CORE_MESH_FACE_TREE_H_
#define DOT_CORE_MESH_FACE_TREE_H_

#include <cstdint>
#include <limits>
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

  // Appends to `faces`, in increasing order, every face whose bounding box
  // meets `box` (a superset of the faces that meet it: none is missed).
  // Safe from many threads at once.
  void FacesMeeting(const Box3& box, std::vector<int32_t>* faces) const;

 private:
  static constexpr size_t kLeafFaces = 16;
  struct FloatBox {
    static constexpr float kInf = std::numeric_limits<float>::infinity();
    float lo[3] = {kInf, kInf, kInf};  // empty
    float hi[3] = {-kInf, -kInf, -kInf};
    void Add(const FloatBox& o);
    bool Meets(const Box3& b) const;
  };
  const MeshData* mesh_;
  std::vector<int32_t> order_;   // face ids along the curve
  std::vector<FloatBox> nodes_;  // node i: children 2i+1, 2i+2
  size_t leaves_ = 0;            // the last `leaves_` nodes
};

}  // namespace dot

#endif  // DOT_CORE_MESH_FACE_TREE_H_
