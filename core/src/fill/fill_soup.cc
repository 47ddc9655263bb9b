// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/fill_soup.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <utility>

#include "fill/soup_output.h"

namespace dot {

SoupFillResult FillSoup(PolygonSoup soup, const FillOptions& options,
                        const Control& control,
                        const FillProgressFn& on_progress) {
  SoupFillResult out;
  out.fill.status = CheckFillOptions(options);
  if (!out.fill.status.ok()) return out;
  FillOptions fill_options = options;
  for (int32_t& v : fill_options.selection.through_vertices) {
    if (v < 0 || static_cast<size_t>(v) >= soup.vertices.size()) {
      out.fill.status =
          InvalidArgument("loops_through: vertex " + std::to_string(v) +
                          " is not a vertex of the mesh (it has " +
                          std::to_string(soup.vertices.size()) + ")");
      return out;
    }
  }
  out.fill.status = CheckAttributes(soup);
  if (!out.fill.status.ok()) return out;
  // What keep_polygons needs of the soup once it is repaired; the rest of
  // it is released by the repair.
  FaceList faces_as_sent;
  std::vector<AttributeChannel> channels = std::move(soup.attributes);
  soup.attributes = {};
  // A soup of plain triangles has nothing to keep: its answer stays
  // fill.mesh, without a second copy of a scan.
  bool polygons = false;
  for (FaceView f : soup.faces) polygons = polygons || f.size() > 3;
  if (options.dry_run) channels.clear();  // nothing is answered
  const bool keep = !channels.empty() || (options.keep_polygons && polygons);
  if (!channels.empty()) faces_as_sent = soup.faces;
  if (on_progress) on_progress(FillPhase::kRepair, 0, 0);
  MeshData mesh;
  out.fill.status =
      options.repair
          ? RepairMesh(std::move(soup), control, &mesh, &out.repair)
          : TriangulateSoup(soup, control, &mesh, &out.repair.face_origin);
  soup = {};  // the repaired mesh replaces it
  if (!out.fill.status.ok()) return out;
  if (!out.repair.vertex_map.empty()) {
    HoleSelection& sel = fill_options.selection;
    sel.through_names = sel.through_vertices;  // refusals name the sent ids
    for (int32_t& v : sel.through_vertices) v = out.repair.vertex_map[v];
  }
  out.input_vertices = static_cast<int64_t>(mesh.vertices.size());
  out.input_faces = static_cast<int64_t>(mesh.triangles.size());
  SoupTrace trace;
  if (!channels.empty()) {
    if (out.repair.duplicate_faces > 0) {
      // A dropped copy's own values (another UV chart) are not carried.
      out.notes.push_back(
          std::to_string(out.repair.duplicate_faces) +
          " duplicate triangles were dropped by the repair; attributes "
          "come from the copy kept, not from the dropped ones");
    }
    trace = TraceSoup(faces_as_sent, std::move(channels), out.repair, mesh);
    faces_as_sent = {};
  }
  out.fill = FillHoles(std::move(mesh), fill_options, control, on_progress);
  if (keep && !out.fill.mesh.triangles.empty()) {
    out.soup = SoupOfFill(&out.fill, out.repair.face_origin, out.input_faces,
                          std::move(trace), options.keep_polygons, &out.notes);
  }
  return out;
}

std::vector<SentPatch> PatchesAsSent(const SoupFillResult& r,
                                     int64_t soup_vertices) {
  // The filled triangles: fill.mesh's, or the soup's one by one when the
  // channels were carried (same order, see SoupFillResult::soup).
  const bool in_soup = r.fill.mesh.triangles.empty() && !r.soup.faces.empty();
  auto triangle = [&](size_t t) -> Triangle {
    if (!in_soup) return r.fill.mesh.triangles[t];
    const FaceView f = r.soup.faces[t];
    return {f[0], f[1], f[2]};
  };
  // Repaired vertex -> its first copy in the soup.
  const auto repaired = static_cast<int32_t>(r.input_vertices);
  std::vector<int32_t> sent_id;
  if (!r.repair.vertex_map.empty()) {
    sent_id.assign(repaired, -1);
    for (size_t i = r.repair.vertex_map.size(); i-- > 0;) {
      sent_id[r.repair.vertex_map[i]] = static_cast<int32_t>(i);
    }
  }
  auto as_sent = [&](Triangle t) {
    for (int32_t& v : t) {
      v = v >= repaired     ? static_cast<int32_t>(soup_vertices + v - repaired)
          : sent_id.empty() ? v
                            : sent_id[v];
    }
    return t;
  };
  // Where each hole's triangles are in the result (see Merge in
  // fill_holes.cc): a split face's first piece in its place, its other
  // pieces, then the patch. Split repaired faces -> their pieces' places;
  // soup faces that change, and the last patch (in merge order) that splits
  // one of their triangles: a polygon two holes split is replaced once, by
  // the later patch, whose replacement may use the earlier patch's vertices
  // but not the reverse.
  std::unordered_map<int32_t, std::vector<size_t>> pieces_of;
  std::unordered_map<int32_t, std::vector<size_t>> replacement;
  std::unordered_map<int32_t, size_t> replaced_by;
  std::vector<size_t> first_face(r.fill.patches.size());
  size_t cursor = static_cast<size_t>(r.input_faces);
  for (size_t p = 0; p < r.fill.patches.size(); ++p) {
    const FilledHole& h = r.fill.patches[p];
    for (size_t k = 0; k < h.patch.split_faces.size(); ++k) {
      const int32_t f = h.patch.split_faces[k];
      std::vector<size_t>& at = pieces_of[f];
      at = {static_cast<size_t>(f)};
      for (size_t i = 1; i < h.patch.pieces[k].size(); ++i)
        at.push_back(cursor++);
      replacement[r.repair.face_origin[f]];
      replaced_by[r.repair.face_origin[f]] = p;
    }
    first_face[p] = cursor;
    cursor += h.patch.faces.size();
  }
  // Not laid out as Merge lays it, or regrouped (keep_polygons): no
  // triangle can be named.
  if (cursor != (in_soup ? r.soup.faces.size() : r.fill.mesh.triangles.size()))
    return {};
  if (!replacement.empty()) {
    for (int32_t f = 0; f < static_cast<int32_t>(r.input_faces); ++f) {
      auto it = replacement.find(r.repair.face_origin[f]);
      if (it == replacement.end()) continue;
      auto split = pieces_of.find(f);
      if (split == pieces_of.end()) {
        it->second.push_back(static_cast<size_t>(f));
      } else {
        it->second.insert(it->second.end(), split->second.begin(),
                          split->second.end());
      }
    }
  }
  // A channel's values at triangle t's corners.
  const std::vector<AttributeChannel> none;
  const std::vector<AttributeChannel>& channels =
      in_soup ? r.soup.attributes : none;
  auto add_values = [&](const AttributeChannel& ch, size_t t,
                        std::vector<float>* out) {
    for (size_t k = 0; k < 3; ++k) {
      const size_t e = ch.per_corner()
                           ? static_cast<size_t>(ch.indices[3 * t + k])
                           : static_cast<size_t>(triangle(t)[k]);
      out->insert(out->end(), ch.entry(e), ch.entry(e) + ch.dims);
    }
  };
  std::vector<SentPatch> out;
  for (size_t index = 0; index < r.fill.patches.size(); ++index) {
    const FilledHole& h = r.fill.patches[index];
    SentPatch& p = out.emplace_back();
    p.hole = h.hole;
    p.first_vertex =
        static_cast<int32_t>(soup_vertices + h.first_vertex - repaired);
    p.new_vertices = h.patch.new_vertices;
    std::vector<size_t> triangles;  // of the faces, then the replacements
    for (size_t k = 0; k < h.patch.faces.size(); ++k) {
      triangles.push_back(first_face[index] + k);
      p.faces.push_back(as_sent(h.patch.faces[k]));
    }
    for (int32_t f : h.patch.split_faces) {
      const int32_t sent = r.repair.face_origin[f];
      if (replaced_by[sent] != index ||
          std::find(p.replaced_faces.begin(), p.replaced_faces.end(), sent) !=
              p.replaced_faces.end()) {
        continue;  // a later patch replaces it; two triangles of one polygon
      }
      p.replaced_faces.push_back(sent);
      std::vector<Triangle>& pieces = p.replacements.emplace_back();
      for (size_t t : replacement[sent]) {
        pieces.push_back(as_sent(triangle(t)));
        triangles.push_back(t);
      }
    }
    for (const AttributeChannel& ch : channels) {
      PatchChannel& c = p.attributes.emplace_back();
      c.name = ch.name;
      c.dims = ch.dims;
      for (size_t i = 0; i < triangles.size(); ++i) {
        add_values(ch, triangles[i],
                   i < p.faces.size() ? &c.faces : &c.replaced);
      }
    }
  }
  return out;
}

}  // namespace dot
