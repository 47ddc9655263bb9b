// SPDX-License-Identifier: AGPL-3.0-or-later
// FillSoup with keep_polygons: the filled mesh comes back shaped as it was
// sent (quads stay quads) with every attribute channel carried, and new
// corners interpolated from the hole's rim, seams kept.
#include "fill/soup_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

// n x n unit quads at z = bump(x, y) without the quads [lo, hi)^2.
PolygonSoup QuadGridWithHole(int n, int lo, int hi, double bump = 0.05) {
  PolygonSoup soup;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double x = i, y = j;
      soup.vertices.push_back({x, y, bump * std::sin(x) * std::cos(y)});
    }
  }
  auto id = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i >= lo && i < hi && j >= lo && j < hi) continue;
      soup.faces.push_back(
          {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return soup;
}

// The soup's faces as triangles (fans), for the checks on the whole mesh.
std::vector<Triangle> Fans(const PolygonSoup& soup) {
  std::vector<Triangle> out;
  for (FaceView f : soup.faces) {
    for (size_t k = 1; k + 1 < f.size(); ++k)
      out.push_back({f[0], f[k], f[k + 1]});
  }
  return out;
}

// Entry of channel `ch` at corner c (face corner order) of vertex v.
const float* At(const AttributeChannel& ch, size_t c, int32_t v) {
  return ch.entry(ch.per_corner() ? ch.indices[c] : v);
}

FillOptions Keeping() {
  FillOptions o;
  o.keep_polygons = true;
  return o;
}

TEST(SoupOutputTest, QuadsTheFillDidNotTouchStayQuads) {
  const PolygonSoup sent = QuadGridWithHole(8, 3, 5);
  const size_t quads = sent.faces.size();
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_EQ(r.fill.report.filled, 1);
  EXPECT_TRUE(r.fill.mesh.triangles.empty());  // moved into the soup
  size_t kept = 0;
  for (FaceView f : r.soup.faces) kept += f.size() == 4;
  const int split = static_cast<int>(r.fill.report.holes[0].split_faces.size());
  EXPECT_EQ(kept + split, quads);
  // Input vertices first, unchanged; the whole is closed at the hole and
  // valid: the faces as triangles make one valid disk.
  for (size_t v = 0; v < sent.vertices.size(); ++v) {
    EXPECT_EQ(r.soup.vertices[v].x, sent.vertices[v].x);
    EXPECT_EQ(r.soup.vertices[v].z, sent.vertices[v].z);
  }
  std::vector<int32_t> rim;
  for (int j = 0; j <= 8; ++j) rim.push_back(j);  // any: not checked here
  const MeshReport m = ValidateMesh(r.soup.vertices, {}, Fans(r.soup), true);
  EXPECT_TRUE(m.indices_in_range);
  EXPECT_EQ(m.intersecting_pairs, 0);
  EXPECT_EQ(m.misoriented_edges, 0);
  EXPECT_EQ(m.non_manifold_edges, 0);
  EXPECT_EQ(m.degenerate_triangles, 0);
}

TEST(SoupOutputTest, ADryRunGivesTheSoupBackAsSent) {
  PolygonSoup sent = QuadGridWithHole(6, 2, 4);
  FillOptions o = Keeping();
  o.dry_run = true;
  const SoupFillResult r = FillSoup(sent, o);
  ASSERT_TRUE(r.fill.status.ok());
  EXPECT_EQ(r.soup.faces, sent.faces);
  EXPECT_EQ(r.soup.vertices.size(), sent.vertices.size());
}

TEST(SoupOutputTest, VertexAttributesAreCarriedAndNewOnesBlendFromTheRim) {
  PolygonSoup sent = QuadGridWithHole(10, 3, 7);
  AttributeChannel color{"color", 3, {}, {}}, height{"height", 1, {}, {}};
  for (const Vec3& p : sent.vertices) {
    color.values.insert(color.values.end(), {0.2f, 0.5f, 0.9f});
    height.values.push_back(static_cast<float>(p.x + 2 * p.y));
  }
  sent.attributes = {color, height};
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_GT(r.fill.report.added_vertices, 0);  // refinement added some
  ASSERT_TRUE(CheckAttributes(r.soup).ok()) << CheckAttributes(r.soup).message;
  ASSERT_EQ(r.soup.attributes.size(), 2u);
  const AttributeChannel& c = r.soup.attributes[0];
  const AttributeChannel& h = r.soup.attributes[1];
  EXPECT_FALSE(c.per_corner());  // no seam: one entry per vertex
  EXPECT_FALSE(h.per_corner());
  for (size_t v = 0; v < r.soup.vertices.size(); ++v) {
    // A constant stays exactly constant.
    EXPECT_EQ(c.entry(v)[0], 0.2f);
    EXPECT_EQ(c.entry(v)[2], 0.9f);
    if (v < sent.vertices.size()) {
      EXPECT_EQ(h.entry(v)[0], height.values[v]);  // kept as sent
    } else {
      // Harmonic: within the rim's range (x, y in [3, 7]: 9..21), and
      // close to the linear field it was sampled from.
      const Vec3& p = r.soup.vertices[v];
      EXPECT_GE(h.entry(v)[0], 9.0f - 1e-4f);
      EXPECT_LE(h.entry(v)[0], 21.0f + 1e-4f);
      EXPECT_NEAR(h.entry(v)[0], p.x + 2 * p.y, 1.5) << "vertex " << v;
    }
  }
}

// A planar UV map of a flat patch stays planar: mean-value weights
// reproduce a linear field exactly (uniform weights were off by 0.04).
TEST(SoupOutputTest, AFlatPatchKeepsALinearFieldExactly) {
  PolygonSoup sent = QuadGridWithHole(10, 3, 7, /*bump=*/0);
  AttributeChannel uv{"uv", 2, {}, {}};
  for (const Vec3& p : sent.vertices) {
    uv.values.insert(uv.values.end(), {float(p.x / 10), float(p.y / 10)});
  }
  sent.attributes = {uv};
  FillOptions o = Keeping();
  o.selection.skip_longest = true;
  const SoupFillResult r = FillSoup(sent, o);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_GT(r.fill.report.added_vertices, 0);
  const AttributeChannel& out = r.soup.attributes.at(0);
  for (size_t v = sent.vertices.size(); v < r.soup.vertices.size(); ++v) {
    EXPECT_NEAR(out.entry(v)[0], r.soup.vertices[v].x / 10, 1e-5) << v;
    EXPECT_NEAR(out.entry(v)[1], r.soup.vertices[v].y / 10, 1e-5) << v;
  }
}

TEST(SoupOutputTest, NormalsStayUnitAndFollowTheSurface) {
  const MeshData sphere = testing::SphereWithCapCut(16, 24, 0.6);
  PolygonSoup sent = ToSoup(sphere);
  AttributeChannel normal{"normal", 3, {}, {}};
  for (const Vec3& p : sphere.vertices) {
    normal.values.insert(normal.values.end(),
                         {float(p.x), float(p.y), float(p.z)});
  }
  sent.attributes = {normal};
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_GT(r.fill.report.added_vertices, 0);
  const AttributeChannel& n = r.soup.attributes.at(0);
  // The oracle: each new vertex's area-weighted normal, from the faces of
  // the output.
  std::vector<Vec3> geometric(r.soup.vertices.size(), Vec3{0, 0, 0});
  for (const Triangle& t : Fans(r.soup)) {
    const std::vector<Vec3>& p = r.soup.vertices;
    const Vec3 c = Cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    for (int32_t v : t) geometric[v] = geometric[v] + c;
  }
  for (size_t v = sphere.vertices.size(); v < r.soup.vertices.size(); ++v) {
    const float* e = n.entry(v);
    const Vec3 value{e[0], e[1], e[2]};
    EXPECT_NEAR(std::sqrt(Dot(value, value)), 1.0, 1e-5);
    // They follow the new surface, outward as the sphere's were.
    EXPECT_GT(Dot(value, Normalized(geometric[v])), 0.9999) << "vertex " << v;
    EXPECT_GT(e[0], 0.5) << "vertex " << v;
  }
}

// UVs per corner in two charts: faces right of x = 5 use u + 10. The seam
// runs along x = 5 through the hole; no face may straddle the charts.
TEST(SoupOutputTest, ASeamThroughTheHoleRunsOnThroughThePatch) {
  PolygonSoup sent = QuadGridWithHole(10, 3, 7);
  AttributeChannel uv{"uv", 2, {}, {}};
  for (FaceView f : sent.faces) {
    double cx = 0;
    for (int32_t v : f) cx += sent.vertices[v].x / f.size();
    for (int32_t v : f) {
      uv.indices.push_back(static_cast<int32_t>(uv.entries()));
      const Vec3& p = sent.vertices[v];
      uv.values.push_back(static_cast<float>(p.x + (cx > 5 ? 10 : 0)));
      uv.values.push_back(static_cast<float>(p.y));
    }
  }
  sent.attributes = {uv};
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_TRUE(CheckAttributes(r.soup).ok()) << CheckAttributes(r.soup).message;
  const AttributeChannel& out = r.soup.attributes.at(0);
  ASSERT_TRUE(out.per_corner());  // the seam is still there
  size_t c = 0, left = 0, right = 0;
  for (size_t f = 0; f < r.soup.faces.size(); ++f) {
    const FaceView face = r.soup.faces[f];
    float lo = 1e9f, hi = -1e9f;
    for (size_t k = 0; k < face.size(); ++k, ++c) {
      const float u = At(out, c, face[k])[0];
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
    EXPECT_LT(hi - lo, 4.0f) << "face " << f << " straddles the seam";
    if (f >= sent.faces.size()) (lo >= 10 ? right : left) += 1;
  }
  EXPECT_GT(left, 0u);  // the patch is cut by the seam
  EXPECT_GT(right, 0u);
}

// Edge protection splits faces at the rim: their pieces' new corners are
// interpolated inside the face, so a linear field stays exact on every
// corner (at the triangulate stage no other vertex is new).
TEST(SoupOutputTest, PiecesOfASplitFaceInterpolateInsideIt) {
  PolygonSoup sent;
  ASSERT_TRUE(
      ReadPolygonSoupFile(testing::MeshPath("mech-holes-shark.off"), &sent)
          .ok());
  auto field = [](const Vec3& p) { return p.x + 2 * p.y + 3 * p.z; };
  AttributeChannel linear{"linear", 1, {}, {}};
  for (const Vec3& p : sent.vertices) {
    linear.values.push_back(static_cast<float>(field(p)));
  }
  sent.attributes = {linear};
  FillOptions o = Keeping();
  o.stage = FillStage::kTriangulate;
  const SoupFillResult r = FillSoup(sent, o);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  int inserted = 0;
  for (const HoleReport& h : r.fill.report.holes)
    inserted += h.boundary_inserted;
  ASSERT_GT(inserted, 0) << "the shark's hole needs edge protection";
  const AttributeChannel& out = r.soup.attributes.at(0);
  size_t c = 0;
  for (FaceView f : r.soup.faces) {
    for (int32_t v : f) {
      const double want = field(r.soup.vertices[v]);
      EXPECT_NEAR(At(out, c, v)[0], want, 1e-4 * (1 + std::abs(want)))
          << "corner " << c << " of vertex " << v;
      ++c;
    }
  }
}

TEST(SoupOutputTest, AttributesThatDoNotFitTheSoupAreRefusedByName) {
  PolygonSoup sent = QuadGridWithHole(4, 1, 2);
  sent.attributes = {{"uv", 2, {0.5f, 0.5f}, {}}};
  SoupFillResult r = FillSoup(sent, Keeping());
  EXPECT_EQ(r.fill.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(r.fill.status.message.find("attribute 'uv' has 1 entries for 25"),
            std::string::npos)
      << r.fill.status.message;
  sent.attributes = {{"uv", 2, {0.5f, 0.5f}, std::vector<int32_t>(60, 3)}};
  r = FillSoup(sent, Keeping());
  EXPECT_NE(r.fill.status.message.find("corner"), std::string::npos)
      << r.fill.status.message;
}

// A polygon of hundreds of corners keeps each corner's own value (its
// corners are found in a sorted copy, not by a scan per triangle corner).
TEST(SoupOutputTest, ALargePolygonKeepsEveryCornersValue) {
  const int n = 600;
  PolygonSoup sent;
  std::vector<int32_t> ring;
  AttributeChannel uv{"uv", 2, {}, {}};
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    sent.vertices.push_back({std::cos(a), std::sin(a), 0});
    ring.push_back(i);
    uv.values.insert(uv.values.end(), {static_cast<float>(i), 0.5f});
    uv.indices.push_back(n - 1 - i);  // entries in reverse: order matters
  }
  sent.faces.push_back(ring);
  sent.attributes = {uv};
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_EQ(r.soup.faces.size(), 1u);
  EXPECT_EQ(r.soup.faces[0].size(), static_cast<size_t>(n));
  const AttributeChannel& got = r.soup.attributes[0];
  for (size_t c = 0; c < static_cast<size_t>(n); ++c) {
    const int32_t v = r.soup.faces[0][c];
    EXPECT_EQ(At(got, c, v)[0], static_cast<float>(n - 1 - v)) << c;
  }
}

// Entries no corner names any more (a face repair dropped) are not
// answered: a per-corner channel never has more entries than corners.
TEST(SoupOutputTest, EntriesOfDroppedFacesAreNotAnswered) {
  PolygonSoup sent = QuadGridWithHole(6, 2, 4);
  sent.faces.push_back(sent.faces[0]);  // a duplicate repair drops
  AttributeChannel uv{"uv", 2, {}, {}};
  for (FaceView f : sent.faces) {
    const bool right = sent.vertices[f[0]].x >= 3;  // a seam: per corner
    for (int32_t v : f) {
      uv.indices.push_back(static_cast<int32_t>(uv.entries()));
      uv.values.insert(uv.values.end(),
                       {static_cast<float>(sent.vertices[v].x + right),
                        static_cast<float>(sent.vertices[v].y)});
    }
  }
  sent.attributes = {uv};
  const SoupFillResult r = FillSoup(sent, Keeping());
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_GT(r.repair.duplicate_faces, 0);
  ASSERT_EQ(r.notes.size(), 1u);  // the copy's own values are not kept
  EXPECT_NE(r.notes[0].find("duplicate triangles were dropped"),
            std::string::npos);
  const AttributeChannel& ch = r.soup.attributes[0];
  ASSERT_TRUE(ch.per_corner());
  EXPECT_LE(ch.entries(), r.soup.faces.corners());
  std::vector<bool> named(ch.entries(), false);
  for (int32_t e : ch.indices) named[e] = true;
  EXPECT_EQ(std::count(named.begin(), named.end(), false), 0);
}

// Without keep_polygons the answer is the fill's triangles, in order, and
// the channels ride on them.
TEST(SoupOutputTest, WithoutKeepPolygonsTheTrianglesCarryTheAttributes) {
  PolygonSoup sent = QuadGridWithHole(6, 2, 4);
  sent.attributes = {{"height", 1, {}, {}}};
  for (const Vec3& p : sent.vertices)
    sent.attributes[0].values.push_back(static_cast<float>(p.x + 2 * p.y));
  const SoupFillResult r = FillSoup(sent);
  ASSERT_TRUE(r.fill.status.ok());
  EXPECT_TRUE(r.notes.empty());
  EXPECT_TRUE(r.fill.mesh.triangles.empty());  // moved into the soup
  ASSERT_TRUE(CheckAttributes(r.soup).ok());
  const int64_t triangles = r.input_faces + r.fill.report.added_faces;
  ASSERT_EQ(static_cast<int64_t>(r.soup.faces.size()), triangles);
  for (FaceView f : r.soup.faces) EXPECT_EQ(f.size(), 3u);
  const AttributeChannel& h = r.soup.attributes[0];
  for (size_t v = 0; v < sent.vertices.size(); ++v) {
    EXPECT_EQ(h.entry(v)[0], sent.attributes[0].values[v]);
  }
}

// The patches answer gives each channel at every corner of a patch's faces
// and replacements: the values the whole filled mesh has there.
TEST(SoupOutputTest, PatchesGiveTheFilledMeshsCornerValues) {
  PolygonSoup sent = QuadGridWithHole(8, 3, 5);
  AttributeChannel uv{"uv", 2, {}, {}};  // per corner, a seam along x = 4
  for (FaceView f : sent.faces) {
    const bool right = sent.vertices[f[0]].x >= 4;
    for (int32_t v : f) {
      uv.indices.push_back(static_cast<int32_t>(uv.entries()));
      const Vec3& p = sent.vertices[v];
      uv.values.insert(uv.values.end(), {static_cast<float>(p.x / 8 + right),
                                         static_cast<float>(p.y / 8)});
    }
  }
  sent.attributes = {uv};
  const auto n = static_cast<int64_t>(sent.vertices.size());
  const SoupFillResult r = FillSoup(sent);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  ASSERT_EQ(r.fill.report.filled, 1);
  const std::vector<SentPatch> patches = PatchesAsSent(r, n);
  ASSERT_EQ(patches.size(), 1u);
  const SentPatch& p = patches[0];
  ASSERT_EQ(p.attributes.size(), 1u);
  EXPECT_EQ(p.attributes[0].name, "uv");
  ASSERT_EQ(p.attributes[0].faces.size(), 6 * p.faces.size());
  size_t pieces = 0;
  for (const auto& t : p.replacements) pieces += t.size();
  ASSERT_EQ(p.attributes[0].replaced.size(), 6 * pieces);
  // The patch's faces are the soup's last triangles, in order.
  const AttributeChannel& ch = r.soup.attributes[0];
  const size_t first = r.soup.faces.size() - p.faces.size();
  for (size_t k = 0; k < p.faces.size(); ++k) {
    for (size_t c = 0; c < 3; ++c) {
      const float* want =
          At(ch, 3 * (first + k) + c, r.soup.faces[first + k][c]);
      EXPECT_EQ(p.attributes[0].faces[6 * k + 2 * c], want[0]);
      EXPECT_EQ(p.attributes[0].faces[6 * k + 2 * c + 1], want[1]);
    }
  }
  // Replacement pieces lie in the quad they replace: their u is on that
  // quad's side of the seam, their v within the grid.
  size_t at = 0;
  for (size_t q = 0; q < p.replaced_faces.size(); ++q) {
    const bool right = sent.vertices[sent.faces[p.replaced_faces[q]][0]].x >= 4;
    for (size_t t = 0; t < 3 * p.replacements[q].size(); ++t, at += 2) {
      const float u = p.attributes[0].replaced[at];
      EXPECT_GE(u, right ? 1.0f : 0.0f);
      EXPECT_LE(u, right ? 2.0f : 1.0f);
    }
  }
}

}  // namespace
}  // namespace dot
