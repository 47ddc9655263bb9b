// SPDX-License-Identifier: AGPL-3.0-or-later
#include "fill/soup_output.h"

#include <algorithm>
#include <array>
#include <unordered_map>
#include <utility>

#include "fill/attribute_entries.h"
#include "fill/patch_attributes.h"
#include "mesh/edge_index.h"

namespace dot {
namespace {

// Barycentric coordinates of p in triangle abc (of its projection onto the
// triangle's plane), clamped into the triangle.
std::array<double, 3> Barycentric(const Vec3& a, const Vec3& b, const Vec3& c,
                                  const Vec3& p) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = Dot(v0, v0), d01 = Dot(v0, v1), d11 = Dot(v1, v1);
  const double d20 = Dot(v2, v0), d21 = Dot(v2, v1);
  const double denom = d00 * d11 - d01 * d01;
  if (!(std::abs(denom) > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double v = (d11 * d20 - d01 * d21) / denom;
  const double w = (d00 * d21 - d01 * d20) / denom;
  std::array<double, 3> l = {std::max(0.0, 1 - v - w), std::max(0.0, v),
                             std::max(0.0, w)};
  const double sum = l[0] + l[1] + l[2];
  for (double& x : l) x /= sum;
  return l;
}

// The corners of the result's triangles, channel by channel: the trace's
// for the input triangles, then the split pieces and the patches.
bool CarryThroughFill(const FillResult& fill, int64_t input_faces,
                      SoupTrace* trace, CornerEntries* corners) {
  const std::vector<Triangle>& tris = fill.mesh.triangles;
  const std::vector<Vec3>& points = fill.mesh.vertices;
  const size_t nc = trace->channels.size();
  corners->assign(nc, {});
  if (nc == 0) return true;
  for (size_t c = 0; c < nc; ++c) {
    (*corners)[c] = std::move(trace->channels[c].indices);
    (*corners)[c].resize(3 * tris.size(), kNoEntry);
  }
  // Where each hole's faces are in the result (see Merge in fill_holes.cc):
  // its split faces in place, their other pieces, then its patch.
  std::vector<std::pair<size_t, size_t>> patches;  // first face, count
  size_t cursor = static_cast<size_t>(input_faces);
  for (const FilledHole& h : fill.patches) {
    for (size_t k = 0; k < h.patch.split_faces.size(); ++k) {
      const int32_t f = h.patch.split_faces[k];
      const Triangle& orig = trace->triangles[f];
      const auto& pieces = h.patch.pieces[k];
      // The split face's own entries, before its first piece takes its place.
      std::vector<std::array<int32_t, 3>> own(nc);
      for (size_t c = 0; c < nc; ++c) {
        const std::vector<int32_t>& e = (*corners)[c];
        own[c] = {e[3 * f], e[3 * f + 1], e[3 * f + 2]};
      }
      for (size_t p = 0; p < pieces.size(); ++p) {
        const size_t at = p == 0 ? static_cast<size_t>(f) : cursor++;
        if (at >= tris.size() || tris[at] != pieces[p]) return false;
        for (size_t c = 0; c < nc; ++c) {
          AttributeChannel* ch = &trace->channels[c];
          std::vector<int32_t>& e = (*corners)[c];
          const auto [e0, e1, e2] = own[c];
          for (int j = 0; j < 3; ++j) {
            const int32_t v = pieces[p][j];
            int32_t entry = v == orig[0]   ? e0
                            : v == orig[1] ? e1
                            : v == orig[2] ? e2
                                           : kNoEntry;
            if (entry == kNoEntry) {
              const auto l = Barycentric(points[orig[0]], points[orig[1]],
                                         points[orig[2]], points[v]);
              entry = AddEntry(
                  ch, Blend(*ch, {{e0, l[0]}, {e1, l[1]}, {e2, l[2]}}));
            }
            e[3 * at + j] = entry;
          }
        }
      }
    }
    patches.push_back({cursor, h.patch.faces.size()});
    cursor += h.patch.faces.size();
  }
  if (cursor != tris.size()) return false;
  InterpolatePatches(points, tris, patches, &trace->channels, corners);
  // A patch with no face across its rim (the mesh's orientation disagrees
  // with it, as with repair off) has nothing to blend from: its corners get
  // the channel's mean, so that no corner is left without an entry.
  for (size_t c = 0; c < nc; ++c) {
    AttributeChannel* ch = &trace->channels[c];
    int32_t fallback = kNoEntry;
    for (int32_t& e : (*corners)[c]) {
      if (e != kNoEntry) continue;
      if (fallback == kNoEntry) {
        const size_t n = ch->entries();
        std::vector<std::pair<int32_t, double>> w;
        for (size_t k = 0; k < n; ++k) w.push_back({int32_t(k), 1.0 / n});
        fallback = AddEntry(
            ch, n > 0 ? Blend(*ch, w) : std::vector<double>(ch->dims, 0.0));
      }
      e = fallback;
    }
  }
  return true;
}

// The polygon a group of triangles was cut from, from the sides they do
// not share, or empty when they do not make one simple polygon. Each
// corner comes with the triangle corner (3t + k) it takes its entries from.
std::vector<std::pair<int32_t, size_t>> Regroup(
    const std::vector<Triangle>& tris, const int32_t* group, size_t size) {
  std::unordered_map<int32_t, std::pair<int32_t, size_t>> next;  // a -> b
  std::unordered_map<uint64_t, int> uses;
  for (size_t i = 0; i < size; ++i) {
    const Triangle& t = tris[group[i]];
    for (int k = 0; k < 3; ++k) ++uses[UndirectedEdgeKey(t[k], t[(k + 1) % 3])];
  }
  for (size_t i = 0; i < size; ++i) {
    const Triangle& t = tris[group[i]];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      if (uses[UndirectedEdgeKey(a, b)] != 1) continue;
      if (!next.emplace(a, std::make_pair(b, 3 * size_t(group[i]) + k))
               .second) {
        return {};  // a vertex twice on the border
      }
    }
  }
  if (next.size() != size + 2) return {};
  std::vector<std::pair<int32_t, size_t>> polygon;
  int32_t v = tris[group[0]][0];
  if (!next.count(v)) return {};
  for (size_t i = 0; i < next.size(); ++i) {
    const auto& [to, corner] = next.at(v);
    polygon.push_back({v, corner});
    v = to;
    if (!next.count(v)) return {};
  }
  if (v != polygon.front().first) return {};
  return polygon;
}

// A channel per vertex where every vertex's corners agree in value (the
// shape most formats and tools take); left per corner otherwise.
void PerVertexWhereSeamless(size_t vertices, const FaceList& faces,
                            const std::vector<int32_t>* sent_vertex,
                            AttributeChannel* ch) {
  std::vector<int32_t> of(vertices, kNoEntry);
  if (sent_vertex != nullptr) {  // a vertex on no face keeps its own entry
    std::copy(sent_vertex->begin(), sent_vertex->end(), of.begin());
  }
  std::vector<bool> seen(vertices, false);
  const std::vector<int32_t>& corner_vertex = faces.indices();
  for (size_t c = 0; c < corner_vertex.size(); ++c) {
    int32_t& e = of[corner_vertex[c]];
    if (!seen[corner_vertex[c]]) {
      seen[corner_vertex[c]] = true;
      e = ch->indices[c];
    } else if (!SameEntry(*ch, e, ch->indices[c])) {
      return;
    }
  }
  std::vector<float> values;
  values.reserve(vertices * ch->dims);
  for (size_t v = 0; v < vertices; ++v) {
    if (of[v] == kNoEntry) {
      values.insert(values.end(), ch->dims, 0.0f);  // on no face
    } else {
      values.insert(values.end(), ch->entry(of[v]),
                    ch->entry(of[v]) + ch->dims);
    }
  }
  ch->values = std::move(values);
  ch->indices = {};
}

// Entries no corner names (a dropped face's, a split face's own) left
// out, so that an answer has no more entries than corners.
void DropUnusedEntries(AttributeChannel* ch) {
  std::vector<int32_t> renumbered(ch->entries(), kNoEntry);
  for (int32_t e : ch->indices) renumbered[e] = 0;
  int32_t kept = 0;
  for (size_t e = 0; e < renumbered.size(); ++e) {
    if (renumbered[e] == kNoEntry) continue;
    std::copy(ch->entry(e), ch->entry(e) + ch->dims,
              ch->values.begin() + static_cast<int64_t>(kept) * ch->dims);
    renumbered[e] = kept++;
  }
  ch->values.resize(static_cast<size_t>(kept) * ch->dims);
  ch->values.shrink_to_fit();
  for (int32_t& e : ch->indices) e = renumbered[e];
}

}  // namespace

SoupTrace TraceSoup(const FaceList& faces,
                    std::vector<AttributeChannel> channels,
                    const RepairReport& repair, const MeshData& repaired) {
  SoupTrace trace;
  trace.triangles = repaired.triangles;
  trace.sent_vertex.assign(repaired.vertices.size(), kNoEntry);
  for (size_t v = repair.vertex_map.empty() ? repaired.vertices.size()
                                            : repair.vertex_map.size();
       v-- > 0;) {
    trace.sent_vertex[repair.vertex_map.empty() ? v : repair.vertex_map[v]] =
        static_cast<int32_t>(v);
  }
  const int32_t* first = faces.indices().data();
  auto mapped = [&](int32_t v) {
    return repair.vertex_map.empty() ? v : repair.vertex_map[v];
  };
  // The sent corner of each repaired triangle corner: the first corner of
  // its face at that vertex (the face's last when none is, which repair
  // does not make). Large polygons are searched in a sorted copy of their
  // corners, so a client's 1,000-gon costs k log k, not k^2.
  constexpr size_t kScanned = 8;  // faces this small are scanned
  std::vector<std::pair<int32_t, int32_t>> sorted;  // (vertex, corner)
  for (FaceView f : faces) {
    if (f.size() <= kScanned) continue;
    if (sorted.empty()) sorted.resize(faces.corners());
    const auto at = static_cast<size_t>(f.begin() - first);
    for (size_t c = 0; c < f.size(); ++c)
      sorted[at + c] = {mapped(f[c]), static_cast<int32_t>(c)};
    std::sort(sorted.begin() + at, sorted.begin() + at + f.size());
  }
  std::vector<int64_t> corner(3 * repaired.triangles.size());
  for (size_t t = 0; t < repaired.triangles.size(); ++t) {
    const FaceView face = faces[repair.face_origin[t]];
    const auto at = static_cast<size_t>(face.begin() - first);
    for (int k = 0; k < 3; ++k) {
      const int32_t v = repaired.triangles[t][k];
      size_t c = face.size() - 1;
      if (face.size() <= kScanned) {
        for (size_t i = 0; i < face.size(); ++i) {
          if (mapped(face[i]) == v) {
            c = i;
            break;
          }
        }
      } else {
        const auto begin = sorted.begin() + at, end = begin + face.size();
        const auto it = std::lower_bound(begin, end, std::make_pair(v, 0));
        if (it != end && it->first == v) c = static_cast<size_t>(it->second);
      }
      corner[3 * t + k] = static_cast<int64_t>(at + c);
    }
  }
  sorted = {};
  for (AttributeChannel& ch : channels) {
    std::vector<int32_t> entries(corner.size());
    for (size_t i = 0; i < corner.size(); ++i) {
      entries[i] = ch.per_corner() ? ch.indices[corner[i]] : first[corner[i]];
    }
    trace.per_vertex.push_back(!ch.per_corner());
    ch.indices = std::move(entries);
    trace.channels.push_back(std::move(ch));
  }
  return trace;
}

PolygonSoup SoupOfFill(FillResult* fill,
                       const std::vector<int32_t>& face_origin,
                       int64_t input_faces, SoupTrace trace, bool regroup,
                       std::vector<std::string>* notes) {
  CornerEntries corners;
  if (!CarryThroughFill(*fill, input_faces, &trace, &corners)) {
    for (const AttributeChannel& ch : trace.channels) {
      notes->push_back("attribute '" + ch.name +
                       "' could not be carried: the filled mesh is not laid "
                       "out as the fill promised");
    }
    trace.channels.clear();
    corners.clear();
  }
  std::vector<Triangle> tris = std::move(fill->mesh.triangles);
  fill->mesh.triangles = {};
  PolygonSoup out;
  out.vertices = std::move(fill->mesh.vertices);
  fill->mesh.vertices = {};
  // Triangles grouped by the input face they come from (counting sort);
  // a group with a split face is given as its triangles.
  const auto n_in = regroup ? static_cast<size_t>(input_faces) : size_t{0};
  int32_t origins = 0;
  for (size_t t = 0; t < n_in; ++t)
    origins = std::max(origins, face_origin[t] + 1);
  std::vector<int32_t> start(origins + 1, 0);
  for (size_t t = 0; t < n_in; ++t) ++start[face_origin[t] + 1];
  for (int32_t o = 0; o < origins; ++o) start[o + 1] += start[o];
  std::vector<int32_t> group(n_in), fill_at(start.begin(), start.end() - 1);
  for (size_t t = 0; t < n_in; ++t) {
    group[fill_at[face_origin[t]]++] = static_cast<int32_t>(t);
  }
  std::vector<bool> split(n_in, false);
  for (const FilledHole& h : fill->patches) {
    for (int32_t f : h.patch.split_faces) {
      if (static_cast<size_t>(f) < n_in) split[f] = true;
    }
  }
  std::vector<std::vector<int32_t>> out_entries(trace.channels.size());
  std::vector<int32_t> ids;
  auto emit = [&](const std::vector<std::pair<int32_t, size_t>>& polygon) {
    ids.clear();
    for (const auto& [v, corner] : polygon) {
      ids.push_back(v);
      for (size_t c = 0; c < out_entries.size(); ++c) {
        out_entries[c].push_back(corners[c][corner]);
      }
    }
    out.faces.push_back(ids);
  };
  auto emit_triangle = [&](size_t t) {
    emit({{tris[t][0], 3 * t},
          {tris[t][1], 3 * t + 1},
          {tris[t][2], 3 * t + 2}});
  };
  out.faces.reserve(tris.size());
  for (size_t t = 0; t < n_in; ++t) {
    const int32_t o = face_origin[t];
    const int32_t* g = group.data() + start[o];
    const auto size = static_cast<size_t>(start[o + 1] - start[o]);
    if (size == 1) {
      emit_triangle(t);
      continue;
    }
    if (static_cast<size_t>(g[0]) != t) {
      if (std::any_of(g, g + size, [&](int32_t f) { return split[f]; }))
        emit_triangle(t);
      continue;  // emitted with its group's first triangle
    }
    std::vector<std::pair<int32_t, size_t>> polygon;
    if (std::none_of(g, g + size, [&](int32_t f) { return split[f]; })) {
      polygon = Regroup(tris, g, size);
    }
    if (polygon.empty()) {
      emit_triangle(t);
      if (std::none_of(g, g + size, [&](int32_t f) { return split[f]; })) {
        for (size_t i = 1; i < size; ++i) emit_triangle(g[i]);
      }
    } else {
      emit(polygon);
    }
  }
  for (size_t t = n_in; t < tris.size(); ++t) emit_triangle(t);
  for (size_t c = 0; c < trace.channels.size(); ++c) {
    AttributeChannel& ch =
        out.attributes.emplace_back(std::move(trace.channels[c]));
    ch.indices = std::move(out_entries[c]);
    PerVertexWhereSeamless(out.vertices.size(), out.faces,
                           trace.per_vertex[c] ? &trace.sent_vertex : nullptr,
                           &ch);
    if (ch.per_corner()) DropUnusedEntries(&ch);
  }
  return out;
}

}  // namespace dot
