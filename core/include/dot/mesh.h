// SPDX-License-Identifier: AGPL-3.0-or-later
// The plain data the readers fill and the algorithms take: a polygon with
// optional boundary normals, a triangle mesh, and a polygon soup (faces of
// any corner count, as files hold them).
#ifndef DOT_MESH_H_
#define DOT_MESH_H_

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "dot/geometry.h"

namespace dot {

struct PolygonData {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;  // empty or one per vertex
  // Several loops (Problem::loop_sizes): their sizes; empty: one loop.
  std::vector<int32_t> loop_sizes = {};
};

struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

// One face of a FaceList: its corners, valid until the list changes.
class FaceView {
 public:
  FaceView(const int32_t* first, const int32_t* last)
      : first_(first), last_(last) {}
  size_t size() const { return static_cast<size_t>(last_ - first_); }
  bool empty() const { return first_ == last_; }
  int32_t operator[](size_t k) const { return first_[k]; }
  int32_t front() const { return *first_; }
  int32_t back() const { return last_[-1]; }
  const int32_t* begin() const { return first_; }
  const int32_t* end() const { return last_; }
  bool operator==(const std::vector<int32_t>& o) const {
    return size() == o.size() && std::equal(first_, last_, o.begin());
  }

 private:
  const int32_t* first_;
  const int32_t* last_;
};

// Faces of any corner count in two flat arrays (compressed rows): face f's
// corners are a run of indices() (offsets mark where each starts). About 20
// bytes a triangle, where a vector per face took about 75: a scan's faces fit.
// Read like a vector of faces (size, [], iteration), built by push_back.
class FaceList {
 public:
  FaceList() = default;
  FaceList(std::initializer_list<std::initializer_list<int32_t>> faces) {
    for (const auto& f : faces) push_back(f);
  }
  size_t size() const { return offsets_.size() - 1; }
  bool empty() const { return size() == 0; }
  FaceView operator[](size_t f) const {
    return {indices_.data() + offsets_[f], indices_.data() + offsets_[f + 1]};
  }
  FaceView back() const { return (*this)[size() - 1]; }
  template <class It>
  void Add(It first, It last) {
    indices_.insert(indices_.end(), first, last);
    offsets_.push_back(static_cast<int64_t>(indices_.size()));
  }
  void push_back(const std::vector<int32_t>& corners) {
    Add(corners.begin(), corners.end());
  }
  void push_back(std::initializer_list<int32_t> corners) {
    Add(corners.begin(), corners.end());
  }
  void push_back(const Triangle& t) { Add(t.begin(), t.end()); }
  void push_back(FaceView f) { Add(f.begin(), f.end()); }
  void reserve(size_t faces, size_t corners = 0) {
    offsets_.reserve(faces + 1);
    indices_.reserve(corners > 0 ? corners : 3 * faces);
  }
  void clear() {
    indices_.clear();
    offsets_.assign(1, 0);
  }
  size_t corners() const { return indices_.size(); }
  const std::vector<int32_t>& indices() const { return indices_; }

  class Iterator {
   public:
    Iterator(const FaceList* list, size_t f) : list_(list), f_(f) {}
    FaceView operator*() const { return (*list_)[f_]; }
    Iterator& operator++() {
      ++f_;
      return *this;
    }
    bool operator!=(const Iterator& o) const { return f_ != o.f_; }

   private:
    const FaceList* list_;
    size_t f_;
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size()}; }

  bool operator==(const FaceList& o) const {
    return indices_ == o.indices_ && offsets_ == o.offsets_;
  }

 private:
  std::vector<int32_t> indices_;
  std::vector<int64_t> offsets_ = {0};
};

// Data a file carries besides positions: normals, colours, texture
// coordinates, or any other numbers, `dims` floats an entry. An entry per
// vertex (`indices` empty: entry v is vertex v's), or indexed per face
// corner as OBJ does (`indices[c]` is the entry of corner c, in the order of
// FaceList::indices()): a seam is a vertex whose corners name entries of
// different values. Names the readers give: "normal" (3), "color" (RGB or
// RGBA in [0, 1]), "uv" (2); a PLY vertex property of another name keeps it.
struct AttributeChannel {
  std::string name;
  int dims = 0;
  std::vector<float> values;     // dims per entry
  std::vector<int32_t> indices;  // per face corner, or empty: per vertex

  bool per_corner() const { return !indices.empty(); }
  size_t entries() const { return dims > 0 ? values.size() / dims : 0; }
  const float* entry(size_t e) const { return values.data() + e * dims; }
};

struct PolygonSoup {
  std::vector<Vec3> vertices;
  FaceList faces;
  std::vector<AttributeChannel> attributes;  // none unless the file had them
};

// `mesh` as a soup of its triangles (what FillSoup and the wire take).
inline PolygonSoup ToSoup(const MeshData& mesh) {
  PolygonSoup soup{mesh.vertices, {}, {}};
  soup.faces.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) soup.faces.push_back(t);
  return soup;
}

}  // namespace dot

#endif  // DOT_MESH_H_
