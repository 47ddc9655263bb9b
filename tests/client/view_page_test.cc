// SPDX-License-Identifier: AGPL-3.0-or-later
// The viewer page's data: which faces are whose patch, and a page no name
// can break out of. (The page itself runs in Chromium: viewer_test.cjs.)
#include "view_page.h"

#include <gtest/gtest.h>

#include <map>

#include "fill_call.h"

namespace dot::client {
namespace {

PolygonSoup ReadMesh(const std::string& name) {
  PolygonSoup soup;
  const Status s = ReadPolygonSoupFile(DOT_MESH_DIR "/" + name, &soup);
  EXPECT_TRUE(s.ok()) << s.message;
  return soup;
}

// Each filled hole owns exactly its patch's faces (lion: no face split),
// and every face of the input is its own.
TEST(PatchOwnersTest, EachFilledHoleOwnsItsPatchFaces) {
  const PolygonSoup lion = ReadMesh("lion.off");
  v1::FillOptions options;
  options.set_max_hole_edges(40);  // hole 2 (115 edges) stays open
  const FillOutcome o = FillLocal("lion", options, lion);
  ASSERT_TRUE(o.status.ok()) << o.status.error_message();
  ASSERT_FALSE(o.as_sent);
  const PolygonSoup after = ToSoup(o.mesh);
  const std::vector<int32_t> owner = PatchOwners(lion, after, o.report);
  ASSERT_EQ(owner.size(), after.faces.size());
  std::map<int32_t, uint32_t> faces;
  for (int32_t h : owner) ++faces[h];
  EXPECT_EQ(faces[-1], lion.faces.size());
  int filled = 0;
  for (const v1::HoleReport& h : o.report.holes()) {
    ASSERT_TRUE(h.split_faces().empty());
    if (h.status() != v1::HOLE_STATUS_FILLED) {
      EXPECT_EQ(faces.count(h.id()), 0u) << "hole " << h.id();
      continue;
    }
    ++filled;
    EXPECT_EQ(faces[h.id()], h.patch_triangles()) << "hole " << h.id();
  }
  EXPECT_EQ(filled, 4);
}

// A polygon triangulated again is the same face; without filled holes
// nothing is a patch.
TEST(PatchOwnersTest, PolygonsTriangulatedAgainAreNotPatches) {
  const PolygonSoup quads{
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}},
      {{0, 1, 2, 3}, {1, 4, 5, 2}},
      {}};
  const PolygonSoup triangles{
      quads.vertices, {{0, 1, 3}, {1, 2, 3}, {1, 4, 2}, {4, 5, 2}}, {}};
  v1::FillReport report;
  v1::HoleReport* h = report.add_holes();
  h->set_status(v1::HOLE_STATUS_FILLED);
  for (double c : {0.5, 0.5, 0.0}) h->add_centroid(c);
  EXPECT_EQ(PatchOwners(quads, triangles, report), std::vector<int32_t>(4, -1));
  // A triangle across the two quads is new, and the only hole's.
  const PolygonSoup crossing{quads.vertices, {{0, 4, 5}}, {}};
  EXPECT_EQ(PatchOwners(quads, crossing, report), std::vector<int32_t>{0});
  EXPECT_EQ(PatchOwners(quads, crossing, v1::FillReport()),
            std::vector<int32_t>{-1});
}

// Names go into the page as data: a title or a reason that reads like
// markup cannot close the script element or add an element.
TEST(RenderViewPageTest, NamesCannotBreakOutOfThePage) {
  if (!ViewerBuilt()) GTEST_SKIP() << "built without the viewer";
  const PolygonSoup mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, {}};
  const std::string evil = "</script><img src=x onerror=alert(1)>";
  v1::FillReport report;
  report.add_holes()->set_reason(evil);
  ViewPage page;
  page.title = evil;
  page.summary = evil;
  page.after = &mesh;
  page.report = &report;
  std::string html;
  ASSERT_TRUE(RenderViewPage(page, &html).ok());
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_NE(html.find("\\u003c/script>\\u003cimg"), std::string::npos);
  EXPECT_NE(html.find("<title>&lt;/script&gt;&lt;img"), std::string::npos);
  // Every placeholder was filled; the template's text is there once.
  EXPECT_EQ(html.find("@DOT_"), std::string::npos);
  EXPECT_EQ(html.find("<script id=\"dot-data\""),
            html.rfind("<script id=\"dot-data\""));
}

TEST(RenderViewPageTest, AnEmptyMeshIsAnError) {
  const PolygonSoup empty;
  ViewPage page;
  page.after = &empty;
  std::string html;
  const Status s = RenderViewPage(page, &html);
  EXPECT_FALSE(s.ok());
  EXPECT_FALSE(s.message.empty());
}

}  // namespace
}  // namespace dot::client
