// SPDX-License-Identifier: AGPL-3.0-or-later
#include "view_page.h"

#include <absl/strings/escaping.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "cli/json_envelope.h"
#include "viewer_assets.h"

namespace dot::client {
namespace {

struct CoordHash {
  size_t operator()(const Vec3& p) const {
    size_t h = 0;
    for (double c : {p.x, p.y, p.z}) {
      uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      h = h * 0x9e3779b97f4a7c15ULL ^ (bits + (h >> 7));
    }
    return h;
  }
};

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return uint64_t{a} << 32 | b;
}

// A soup with its vertices welded by coordinates (files such as STL
// repeat every corner), its polygons in welded ids.
struct Welded {
  std::vector<Vec3> points;
  std::vector<uint32_t> of;  // soup vertex -> welded id
};

Welded Weld(const PolygonSoup& soup) {
  Welded w;
  std::unordered_map<Vec3, uint32_t, CoordHash> ids;
  ids.reserve(soup.vertices.size());
  w.of.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) {
    const auto [it, added] =
        ids.emplace(p, static_cast<uint32_t>(w.points.size()));
    if (added) w.points.push_back(p);
    w.of.push_back(it->second);
  }
  return w;
}

// Union-find over faces, for the patches (connected new faces).
struct Components {
  std::vector<uint32_t> parent;
  explicit Components(size_t n) : parent(n) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  uint32_t Find(uint32_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  }
  void Join(uint32_t a, uint32_t b) { parent[Find(a)] = Find(b); }
};

// Where each hole's patch should be: its loop's centroid, under the id of
// the hole whose patch fills it (an island's rim).
struct Anchor {
  Vec3 at;
  int32_t hole;
};

// Every hole of the report (`filled_only`: those filled), under the id of
// the hole whose patch fills it (`by_patch`: an island under its rim).
std::vector<Anchor> Anchors(const v1::FillReport& report, bool filled_only,
                            bool by_patch) {
  std::vector<Anchor> anchors;
  for (const v1::HoleReport& h : report.holes()) {
    if ((filled_only && h.status() != v1::HOLE_STATUS_FILLED) ||
        h.centroid_size() != 3) {
      continue;
    }
    anchors.push_back({{h.centroid(0), h.centroid(1), h.centroid(2)},
                       by_patch && h.has_joined_to() ? h.joined_to() : h.id()});
  }
  return anchors;
}

// The hole whose anchor is nearest `at`, or -1 without anchors.
int32_t NearestHole(const std::vector<Anchor>& anchors, const Vec3& at) {
  double best = std::numeric_limits<double>::infinity();
  int32_t hole = -1;
  for (const Anchor& a : anchors) {
    const double d = Distance(at, a.at);
    if (d < best) {
      best = d;
      hole = a.hole;
    }
  }
  return hole;
}

// A mesh's open edges (of one polygon), as its faces run them, in loops
// (edges joined by their vertices): each loop's hole (nearest centroid;
// -1 without a report) and the side its rim faces, so the page can show
// one hole's rim and look into it.
struct OpenLoop {
  int32_t hole = -1;
  Vec3 normal{0, 0, 0};
  std::vector<uint32_t> edges;  // pairs of welded ids
};

std::vector<OpenLoop> OpenLoops(const PolygonSoup& soup, const Welded& w,
                                const v1::FillReport* report) {
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> once;
  std::unordered_map<uint64_t, uint32_t> uses;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const FaceView face = soup.faces[f];
    const size_t n = face.size();
    for (size_t k = 0; k < n; ++k) {
      const uint32_t a = w.of[face[k]], b = w.of[face[(k + 1) % n]];
      const uint64_t key = EdgeKey(a, b);
      if (++uses[key] == 1) once[key] = {a, b};
    }
  }
  std::vector<uint64_t> keys;  // sorted: deterministic pages
  for (const auto& [key, count] : uses) {
    if (count == 1) keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end());
  Components parts(w.points.size());
  for (uint64_t key : keys) {
    parts.Join(static_cast<uint32_t>(key >> 32),
               static_cast<uint32_t>(key & 0xffffffffu));
  }
  std::unordered_map<uint32_t, size_t> loop_of;
  std::vector<OpenLoop> loops;
  std::vector<Vec3> sums;
  std::vector<double> lengths;
  for (uint64_t key : keys) {
    const auto [a, b] = once[key];
    const auto [it, added] = loop_of.emplace(parts.Find(a), loops.size());
    if (added) {
      loops.emplace_back();
      sums.push_back({0, 0, 0});
      lengths.push_back(0);
    }
    OpenLoop& loop = loops[it->second];
    loop.edges.insert(loop.edges.end(), {a, b});
    const Vec3 &p = w.points[a], &q = w.points[b];
    const double len = Distance(p, q);
    sums[it->second] = sums[it->second] + (len / 2) * (p + q);
    lengths[it->second] += len;
    // Newell's normal, taken against the faces' direction: a hole's rim
    // runs the other way round from the surface around it.
    loop.normal = loop.normal - Cross(p, q);
  }
  if (report != nullptr) {
    const std::vector<Anchor> anchors = Anchors(*report, false, false);
    for (size_t i = 0; i < loops.size(); ++i) {
      if (lengths[i] > 0) {
        loops[i].hole = NearestHole(anchors, (1 / lengths[i]) * sums[i]);
      }
    }
  }
  return loops;
}

// The file's colours (a "color" channel, per vertex or per corner, in
// [0, 1]) as RGB bytes per welded vertex (its first corner's where corners
// differ), or none.
std::vector<uint8_t> VertexColors(const PolygonSoup& soup, const Welded& w) {
  const AttributeChannel* color = nullptr;
  for (const AttributeChannel& ch : soup.attributes) {
    if (ch.name == "color" && ch.dims >= 3) color = &ch;
  }
  if (color == nullptr) return {};
  std::vector<uint8_t> rgb(3 * w.points.size(), 200);
  std::vector<bool> set(w.points.size(), false);
  auto byte = [](float x) {
    return static_cast<uint8_t>(std::lround(255 * std::clamp(x, 0.0f, 1.0f)));
  };
  size_t corner = 0;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    for (int32_t v : soup.faces[f]) {
      const size_t entry = color->per_corner()
                               ? static_cast<size_t>(color->indices[corner])
                               : static_cast<size_t>(v);
      ++corner;
      const uint32_t at = w.of[v];
      if (set[at] || entry >= color->entries()) continue;
      set[at] = true;
      for (int k = 0; k < 3; ++k)
        rgb[3 * at + k] = byte(color->entry(entry)[k]);
    }
  }
  return rgb;
}

// A mesh as the page takes it: float positions about `center` (of the
// vertices faces use; unused ones are left out), its faces as triangles
// (polygons triangulated as the fill reads them, a fan where that fails)
// ordered by owner, so each patch is one draw group, and its open edges.
Status MeshJson(const PolygonSoup& soup, const std::vector<int32_t>& owner,
                const v1::FillReport* report, const Vec3& center,
                std::string* json) {
  const Welded w = Weld(soup);
  MeshData triangulated;
  std::vector<int32_t> face_of;
  if (!TriangulateSoup(soup, Control{}, &triangulated, &face_of).ok()) {
    triangulated.triangles.clear();
    face_of.clear();
    for (size_t f = 0; f < soup.faces.size(); ++f) {
      const FaceView face = soup.faces[f];
      for (size_t k = 1; k + 1 < face.size(); ++k) {
        triangulated.triangles.push_back({face[0], face[k], face[k + 1]});
        face_of.push_back(static_cast<int32_t>(f));
      }
    }
  }
  const std::vector<uint8_t> rgb = VertexColors(soup, w);
  // Welded vertices the faces use, renumbered in order of first use.
  std::vector<uint32_t> index(w.points.size(), UINT32_MAX);
  std::vector<float> positions;
  std::vector<uint8_t> colors;
  auto use = [&](int32_t v) {
    uint32_t& id = index[w.of[v]];
    if (id == UINT32_MAX) {
      id = static_cast<uint32_t>(positions.size() / 3);
      const Vec3 d = w.points[w.of[v]] - center;
      positions.insert(positions.end(),
                       {static_cast<float>(d.x), static_cast<float>(d.y),
                        static_cast<float>(d.z)});
      if (!rgb.empty()) {
        colors.insert(colors.end(), rgb.begin() + 3 * w.of[v],
                      rgb.begin() + 3 * w.of[v] + 3);
      }
    }
    return id;
  };
  struct Tri {
    int32_t owner;
    std::array<uint32_t, 3> v;
  };
  std::vector<Tri> tris;
  tris.reserve(triangulated.triangles.size());
  for (size_t t = 0; t < triangulated.triangles.size(); ++t) {
    const Triangle& tri = triangulated.triangles[t];
    tris.push_back({owner.empty() ? -1 : owner[face_of[t]],
                    {use(tri[0]), use(tri[1]), use(tri[2])}});
  }
  for (size_t i = 0; i < positions.size(); ++i) {
    if (!std::isfinite(positions[i]) || std::fabs(positions[i]) > 1e30f) {
      return InvalidArgument(
          "vertex coordinates too large to show (beyond 1e30 from the "
          "mesh's centre)");
    }
  }
  std::stable_sort(tris.begin(), tris.end(), [](const Tri& a, const Tri& b) {
    return a.owner < b.owner;
  });
  std::vector<uint32_t> triangles;
  triangles.reserve(3 * tris.size());
  std::ostringstream groups;
  for (size_t i = 0; i < tris.size();) {
    size_t j = i;
    while (j < tris.size() && tris[j].owner == tris[i].owner) {
      triangles.insert(triangles.end(), tris[j].v.begin(), tris[j].v.end());
      ++j;
    }
    groups << (i ? "," : "") << "{\"start\":" << i << ",\"count\":" << j - i
           << ",\"hole\":" << tris[i].owner << "}";
    i = j;
  }
  // Edges of one polygon (a hole's rim, a border), loop by loop.
  std::vector<uint32_t> open;
  std::ostringstream open_groups;
  open_groups.precision(9);
  for (const OpenLoop& loop : OpenLoops(soup, w, report)) {
    const Vec3 n = Normalized(loop.normal);
    open_groups << (open.empty() ? "" : ",") << "{\"start\":" << open.size()
                << ",\"count\":" << loop.edges.size()
                << ",\"hole\":" << loop.hole << ",\"normal\":[" << n.x << ","
                << n.y << "," << n.z << "]}";
    for (uint32_t v : loop.edges) open.push_back(index[v]);
  }
  auto b64 = [](const auto& v) {
    return "\"" +
           absl::Base64Escape(
               absl::string_view(reinterpret_cast<const char*>(v.data()),
                                 v.size() * sizeof(v[0]))) +
           "\"";
  };
  *json =
      "{\"positions\":" + b64(positions) + ",\"triangles\":" + b64(triangles) +
      ",\"groups\":[" + groups.str() + "],\"open_edges\":" + b64(open) +
      ",\"open_groups\":[" + open_groups.str() +
      "],\"colors\":" + (colors.empty() ? std::string("null") : b64(colors)) +
      "}";
  return OkStatus();
}

// The centre of the box of the vertices faces use.
Vec3 UsedCenter(const PolygonSoup& soup) {
  bool any = false;
  Vec3 lo, hi;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    for (int32_t v : soup.faces[f]) {
      const Vec3& p = soup.vertices[v];
      if (!any) lo = hi = p;
      any = true;
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

std::vector<int32_t> PatchOwners(const PolygonSoup& before,
                                 const PolygonSoup& after,
                                 const v1::FillReport& report) {
  std::vector<int32_t> owner(after.faces.size(), -1);
  const std::vector<Anchor> anchors = Anchors(report, true, true);
  if (anchors.empty() || before.faces.empty()) return owner;
  // before: vertex (by coordinates) -> its faces.
  const Welded wb = Weld(before);
  std::unordered_map<Vec3, uint32_t, CoordHash> id_of;
  for (uint32_t v = 0; v < wb.points.size(); ++v) id_of[wb.points[v]] = v;
  std::vector<std::vector<uint32_t>> faces_at(wb.points.size());
  for (size_t f = 0; f < before.faces.size(); ++f) {
    for (int32_t v : before.faces[f]) {
      faces_at[wb.of[v]].push_back(static_cast<uint32_t>(f));
    }
  }
  auto in_face = [&](uint32_t f, uint32_t v) {
    for (int32_t c : before.faces[f]) {
      if (wb.of[c] == v) return true;
    }
    return false;
  };
  // A face of `after` is old when one face of `before` has all its corners.
  const Welded wa = Weld(after);
  std::vector<bool> fresh(after.faces.size(), false);
  std::vector<int64_t> old_id(wa.points.size(), -1);
  for (uint32_t v = 0; v < wa.points.size(); ++v) {
    const auto it = id_of.find(wa.points[v]);
    if (it != id_of.end()) old_id[v] = it->second;
  }
  for (size_t f = 0; f < after.faces.size(); ++f) {
    const FaceView face = after.faces[f];
    bool old = true;
    for (int32_t c : face) old = old && old_id[wa.of[c]] >= 0;
    if (old) {
      old = false;
      for (uint32_t g : faces_at[old_id[wa.of[face[0]]]]) {
        bool all = true;
        for (int32_t c : face) {
          all = all && in_face(g, static_cast<uint32_t>(old_id[wa.of[c]]));
        }
        if (all) {
          old = true;
          break;
        }
      }
    }
    fresh[f] = !old;
  }
  // Patches: new faces joined by their edges; each patch's rim (its edges
  // of one new face) gives its centroid, as the report measures a loop's.
  Components parts(after.faces.size());
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> edge_faces;
  for (size_t f = 0; f < after.faces.size(); ++f) {
    if (!fresh[f]) continue;
    const FaceView face = after.faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      const uint64_t key =
          EdgeKey(wa.of[face[k]], wa.of[face[(k + 1) % face.size()]]);
      const auto [it, added] =
          edge_faces.emplace(key, std::make_pair(static_cast<uint32_t>(f), 1u));
      if (!added) {
        parts.Join(static_cast<uint32_t>(f), it->second.first);
        ++it->second.second;
      }
    }
  }
  struct Rim {
    Vec3 sum{0, 0, 0};
    double length = 0;
  };
  std::unordered_map<uint32_t, Rim> rims;
  for (const auto& [key, use] : edge_faces) {
    if (use.second != 1) continue;
    const Vec3& a = wa.points[key >> 32];
    const Vec3& b = wa.points[key & 0xffffffffu];
    const double len = Distance(a, b);
    Rim& rim = rims[parts.Find(use.first)];
    rim.sum = rim.sum + (len / 2) * (a + b);
    rim.length += len;
  }
  std::unordered_map<uint32_t, int32_t> hole_of;
  for (const auto& [root, rim] : rims) {
    if (rim.length > 0) {
      hole_of[root] = NearestHole(anchors, (1 / rim.length) * rim.sum);
    }
  }
  for (size_t f = 0; f < after.faces.size(); ++f) {
    if (!fresh[f]) continue;
    const auto it = hole_of.find(parts.Find(static_cast<uint32_t>(f)));
    if (it != hole_of.end()) owner[f] = it->second;
  }
  return owner;
}

bool ViewerBuilt() { return !ViewerScript().empty(); }

Status RenderViewPage(const ViewPage& page, std::string* html) {
  if (!ViewerBuilt()) {
    return MakeStatus(
        StatusCode::kInternal,
        "this dotctl was built without the viewer (DOT_BUILD_VIEWER=OFF: npm "
        "was not found when it was built)");
  }
  if (page.after == nullptr || page.after->faces.empty()) {
    return InvalidArgument("the mesh has no faces to show");
  }
  // Centred on the result's box, so float positions keep their precision.
  const Vec3 center = UsedCenter(*page.after);
  std::vector<int32_t> owner;
  if (page.before != nullptr && page.report != nullptr) {
    owner = PatchOwners(*page.before, *page.after, *page.report);
  }
  std::string after, before = "null";
  Status s = MeshJson(*page.after, owner, page.report, center, &after);
  if (s.ok() && page.before != nullptr) {
    s = MeshJson(*page.before, {}, page.report, center, &before);
  }
  if (!s.ok()) return s;
  std::ostringstream data;
  data.precision(17);
  data << "{\"title\":" << JsonQuote(page.title)
       << ",\"summary\":" << JsonQuote(page.summary) << ",\"center\":["
       << center.x << "," << center.y << "," << center.z
       << "],\"after\":" << after << ",\"before\":" << before << ",\"report\":"
       << (page.report ? ProtoJson(*page.report) : std::string("null")) << "}";
  // '<' appears only inside JSON strings, where \u003c reads the same: no
  // name in the data can close the script element that holds it.
  std::string json;
  for (char c : data.str()) {
    if (c == '<') {
      json += "\\u003c";
    } else {
      json += c;
    }
  }
  std::string title;
  for (char c : page.title) {
    switch (c) {
      case '<':
        title += "&lt;";
        break;
      case '>':
        title += "&gt;";
        break;
      case '&':
        title += "&amp;";
        break;
      default:
        title += c;
    }
  }
  // The template's placeholders are replaced in one pass, so nothing
  // inserted is read again.
  const std::string_view tpl = ViewerPageTemplate();
  const std::pair<std::string_view, std::string_view> fills[] = {
      {"@DOT_TITLE@", title},
      {"@DOT_DATA@", json},
      {"@DOT_SCRIPT@", ViewerScript()}};
  html->clear();
  html->reserve(tpl.size() + json.size() + ViewerScript().size());
  size_t at = 0;
  while (at < tpl.size()) {
    size_t next = std::string_view::npos;
    const std::pair<std::string_view, std::string_view>* fill = nullptr;
    for (const auto& f : fills) {
      const size_t p = tpl.find(f.first, at);
      if (p < next) {
        next = p;
        fill = &f;
      }
    }
    if (fill == nullptr) {
      html->append(tpl.substr(at));
      break;
    }
    html->append(tpl.substr(at, next - at));
    html->append(fill->second);
    at = next + fill->first.size();
  }
  return OkStatus();
}

}  // namespace dot::client
