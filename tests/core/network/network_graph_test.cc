// SPDX-License-Identifier: AGPL-3.0-or-later
// Reading networks and building their graph: curves between junctions,
// welding, dangling curves, and refusals that name what is wrong.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

#include "dot/network.h"
#include "dot/network_samples.h"
#include "dot/validate.h"

namespace dot {
namespace {

Status Build(const std::string& obj, NetworkGraph* g, double weld = 0) {
  std::istringstream in(obj);
  CurveNetwork net;
  const Status s = ReadNetworkObj(in, &net);
  if (!s.ok()) return s;
  return BuildNetworkGraph(net, g, {}, weld);
}

TEST(NetworkIoTest, ReadsObjPolylinesAndEdges) {
  std::istringstream in(
      "# two curves\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "l 1 2 3\nl 3/7 -1\nl 4 1\n");
  CurveNetwork net;
  ASSERT_TRUE(ReadNetworkObj(in, &net).ok());
  EXPECT_EQ(net.vertices.size(), 4u);
  ASSERT_EQ(net.polylines.size(), 3u);
  EXPECT_EQ(net.polylines[1], (std::vector<int32_t>{2, 3}));
}

TEST(NetworkIoTest, RefusesWhatIsNotANetwork) {
  CurveNetwork net;
  std::istringstream mesh("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Status s = ReadNetworkObj(mesh, &net);
  EXPECT_NE(s.message.find("line 4"), std::string::npos) << s.message;
  std::istringstream bad_index("v 0 0 0\nv 1 0 0\nl 1 3\n");
  s = ReadNetworkObj(bad_index, &net);
  EXPECT_NE(s.message.find("'3'"), std::string::npos) << s.message;
  std::istringstream normals("v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1 2\n");
  s = ReadNetworkObj(normals, &net);
  EXPECT_NE(s.message.find("'vn'"), std::string::npos) << s.message;
  std::istringstream nothing("v 0 0 0\n");
  EXPECT_FALSE(ReadNetworkObj(nothing, &net).ok());
}

TEST(NetworkIoTest, TextBlocksMeetAtEqualPoints) {
  // A triangle drawn as three strokes, each a block; the ends coincide.
  std::istringstream in("0 0 0\n1 0 0\n\n1 0 0\n0.5 1 0\n\n0.5 1 0\n0 0 0\n");
  CurveNetwork net;
  ASSERT_TRUE(ReadNetworkText(in, &net).ok());
  EXPECT_EQ(net.polylines.size(), 3u);
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(net, &g).ok());
  EXPECT_EQ(g.vertices.size(), 3u);
  EXPECT_EQ(g.merged_vertices, 3);
  EXPECT_TRUE(g.dangling.empty());
}

TEST(NetworkIoTest, ObjRoundTrip) {
  const CurveNetwork net = CubeNetwork(3);
  std::stringstream io;
  ASSERT_TRUE(WriteNetworkObj(io, net).ok());
  CurveNetwork back;
  ASSERT_TRUE(ReadNetworkObj(io, &back).ok());
  EXPECT_EQ(back.polylines, net.polylines);
  ASSERT_EQ(back.vertices.size(), net.vertices.size());
  for (size_t i = 0; i < net.vertices.size(); ++i) {
    EXPECT_TRUE(back.vertices[i] == net.vertices[i]);
  }
}

TEST(NetworkGraphTest, SplitsPolylinesIntoCurvesAtJunctions) {
  // A square with a diagonal, drawn as one long polyline and one edge.
  NetworkGraph g;
  ASSERT_TRUE(Build("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                    "l 1 2 3 4 1\nl 1 3\n",
                    &g)
                  .ok());
  ASSERT_EQ(g.curves.size(), 3u);  // 1-2-3, 3-4-1, 1-3
  for (const NetworkCurve& c : g.curves) {
    const int32_t a = c.vertices.front(), b = c.vertices.back();
    EXPECT_TRUE((a == 0 && b == 2) || (a == 2 && b == 0));
  }
  EXPECT_EQ(g.curves[0].vertices, (std::vector<int32_t>{0, 1, 2}));
}

TEST(NetworkGraphTest, SetsDanglingCurvesApart) {
  // A triangle with a tail: the tail bounds nothing.
  NetworkGraph g;
  ASSERT_TRUE(Build("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 -1 0\nv -2 -1 0\n"
                    "l 1 2 3 1\nl 1 4 5\n",
                    &g)
                  .ok());
  ASSERT_EQ(g.dangling.size(), 1u);
  EXPECT_EQ(g.curves[g.dangling[0]].vertices.size(), 3u);
}

TEST(NetworkGraphTest, NamesDuplicateAndCrossingCurves) {
  NetworkGraph g;
  Status s = Build("v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\nl 3 2\n", &g);
  EXPECT_NE(s.message.find("duplicate"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("polylines 0 and 1"), std::string::npos);
  s = Build("v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 3 4\n", &g);
  EXPECT_NE(s.message.find("cross"), std::string::npos) << s.message;
  // Touching: an end on another curve's edge without sharing a vertex.
  s = Build("v 0 0 0\nv 2 0 0\nv 1 0 0\nv 1 1 0\nl 1 2\nl 3 4\n", &g);
  EXPECT_NE(s.message.find("cross"), std::string::npos) << s.message;
  // Overlapping along a line from a shared vertex.
  s = Build("v 0 0 0\nv 2 0 0\nv 1 0 0\nl 1 2\nl 1 3\n", &g);
  EXPECT_NE(s.message.find("cross"), std::string::npos) << s.message;
  s = Build("v 0 0 0\nv 0 0 0\nl 1 2\n", &g);
  EXPECT_NE(s.message.find("same place"), std::string::npos) << s.message;
  s = Build("v 0 0 0\nv nan 0 0\nl 1 2\n", &g);
  EXPECT_FALSE(s.ok());
}

// The cube's 12 edges as strokes of their own, each end off the corner by
// its own amount, at most 0.009 (as a sketch draws them): with a weld
// distance of 0.02 the ends meet at 8 junctions, each corner welded into
// the first stroke end that reaches it, and the box closes; without, every
// stroke dangles.
CurveNetwork CubeStrokes() {
  const CurveNetwork cube = CubeNetwork(4);
  CurveNetwork strokes;
  int jitter = 0;
  for (const auto& line : cube.polylines) {
    std::vector<int32_t> ids;
    for (size_t k = 0; k < line.size(); ++k) {
      Vec3 p = cube.vertices[line[k]];
      if (k == 0 || k + 1 == line.size()) {
        const double d = 0.0001 * ++jitter;  // 0.0001 .. 0.0024
        p = p + Vec3{d, -2 * d, 3 * d};
      }
      ids.push_back(static_cast<int32_t>(strokes.vertices.size()));
      strokes.vertices.push_back(p);
    }
    strokes.polylines.push_back(ids);
  }
  return strokes;
}

TEST(NetworkGraphTest, WeldsStrokeEndsWithinTheWeldDistance) {
  const CurveNetwork strokes = CubeStrokes();
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(strokes, &g).ok());
  EXPECT_EQ(g.dangling.size(), 12u);  // nothing meets
  ASSERT_TRUE(BuildNetworkGraph(strokes, &g, {}, 0.02).ok());
  EXPECT_TRUE(g.dangling.empty());
  EXPECT_EQ(g.curves.size(), 12u);
  EXPECT_EQ(g.merged_vertices, 24 - 8);
  for (size_t i = 0; i < strokes.vertices.size(); ++i) {
    // Each welded point names the first of its group, at its place.
    const int32_t v = g.vertex_of_input[i];
    ASSERT_GE(v, 0);
    EXPECT_LE(g.input_of_vertex[v], static_cast<int32_t>(i));
    EXPECT_LE(Distance(g.vertices[v], strokes.vertices[i]), 0.02);
  }
  SurfaceOptions o;
  o.weld_distance = 0.02;
  const SurfaceResult r = SurfaceNetwork(strokes, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_TRUE(r.report.closed);
  EXPECT_EQ(r.report.surfaced, 6);
  EXPECT_EQ(r.report.merged_vertices, 16);
  EXPECT_EQ(CountIntersectingPairs(r.mesh.vertices, r.mesh.triangles), 0);
}

TEST(NetworkGraphTest, WeldDropsEdgesItShrinksToAPointAndRefusesBadDistances) {
  // A triangle drawn as one stroke that overshoots its first corner by
  // 0.001, onto its first edge (a touch, refused), and a stroke 0.002 long
  // beside its second corner. Welded, the triangle closes at its first
  // point and the short stroke shrinks into the corner: its edge is gone.
  NetworkGraph g;
  std::istringstream in(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.001 0 0\nv 1.001 0.001 0\n"
      "v 1.002 0 0.001\nl 1 2 3 4\nl 5 6\n");
  CurveNetwork net;
  ASSERT_TRUE(ReadNetworkObj(in, &net).ok());
  const Status touch = BuildNetworkGraph(net, &g);
  EXPECT_NE(touch.message.find("cross"), std::string::npos) << touch.message;
  ASSERT_TRUE(BuildNetworkGraph(net, &g, {}, 0.01).ok());
  ASSERT_EQ(g.curves.size(), 1u);
  EXPECT_TRUE(g.curves[0].closed());
  EXPECT_EQ(g.curves[0].vertices.size(), 4u);  // 0, 1, 2 and 0 again
  EXPECT_EQ(g.welded_edges, 1);                // the short stroke
  for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    const Status s = BuildNetworkGraph(net, &g, {}, bad);
    EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
    EXPECT_NE(s.message.find("weld distance"), std::string::npos) << s.message;
    SurfaceOptions o;
    o.weld_distance = bad;
    EXPECT_NE(CheckSurfaceOptions(o).message.find("weld distance"),
              std::string::npos);
  }
  // Cells too many to index: refused, naming the vertex.
  const Status s = BuildNetworkGraph(net, &g, {}, 1e-300);
  EXPECT_NE(s.message.find("too small for vertex 1"), std::string::npos)
      << s.message;
}

// Only stroke ends move: a stroke sampled every 0.001 keeps every point
// under a weld distance of 0.01; a stroke whose end stops 0.004 short of
// another's inner point meets it there (a junction splits that stroke);
// ends 0.008 apart in a chain (A-B, B-C; A-C is 0.016) all meet.
TEST(NetworkGraphTest, WeldJoinsStrokeEndsOnlyAndTransitively) {
  CurveNetwork net;
  auto stroke = [&](std::vector<Vec3> points) {
    std::vector<int32_t> ids;
    for (const Vec3& p : points) {
      ids.push_back(static_cast<int32_t>(net.vertices.size()));
      net.vertices.push_back(p);
    }
    net.polylines.push_back(ids);
  };
  std::vector<Vec3> fine;
  for (int k = 0; k <= 1000; ++k) fine.push_back({0.001 * k, 0, 0});
  stroke(fine);                             // 0 .. 1000, on y = 0
  stroke({{0.5, 1, 0}, {0.5, 0.004, 0}});   // 1001, 1002: a T
  stroke({{1.008, 0, 0}, {1.5, 0.5, 0}});   // 1003 ..
  stroke({{1.016, 0, 0}, {1.5, -0.5, 0}});  // 1005 ..
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(net, &g, {}, 0.01).ok());
  EXPECT_EQ(g.welded_edges, 0);
  EXPECT_EQ(g.merged_vertices, 3);  // the T's foot, and the chain's two
  // The T's foot is welded into the fine stroke's nearest point, x = 0.5,
  // which becomes a junction (the points beside it, also within 0.01, stay).
  EXPECT_EQ(g.vertex_of_input[1002], g.vertex_of_input[500]);
  // The chain: the fine stroke's end (x = 1) and both others' ends.
  EXPECT_EQ(g.vertex_of_input[1003], g.vertex_of_input[1000]);
  EXPECT_EQ(g.vertex_of_input[1005], g.vertex_of_input[1000]);
  // Every inner point of the fine stroke is still a vertex of its own.
  for (int k = 1; k < 1000; ++k) {
    EXPECT_EQ(g.input_of_vertex[g.vertex_of_input[k]], k);
  }
  // Curves: the fine stroke split at the T (two), the T, the chain's two.
  EXPECT_EQ(g.curves.size(), 5u);
}

// Ends that already meet are not free: polylines of one edge each (OBJ's
// 'l a b', a wire mesh's chains) share every inner point, and a junction
// shared by index or by coordinates joins its curves. Only the one end
// no other polyline lists is welded.
TEST(NetworkGraphTest, WeldLeavesEndsThatAlreadyMeet) {
  CurveNetwork net;
  for (int k = 0; k <= 10; ++k) net.vertices.push_back({0.001 * k, 0, 0});
  for (int k = 0; k < 10; ++k) net.polylines.push_back({k, k + 1});
  // A star at vertex 10: two more strokes from it, one by index and one
  // from a copy of its point, each sampled every 0.001.
  auto stroke = [&](Vec3 from, Vec3 step, bool copy_first) {
    std::vector<int32_t> ids;
    if (!copy_first) ids.push_back(10);
    for (int k = copy_first ? 0 : 1; k <= 10; ++k) {
      ids.push_back(static_cast<int32_t>(net.vertices.size()));
      net.vertices.push_back(from + static_cast<double>(k) * step);
    }
    net.polylines.push_back(ids);
  };
  stroke({0.01, 0, 0}, {0, 0.001, 0}, false);  // 11 .. 20
  stroke({0.01, 0, 0}, {0, -0.001, 0}, true);  // 21 (at vertex 10) .. 31
  // A stroke whose end (32) stops 0.003 short of vertex 5.
  net.vertices.push_back({0.005, 0.003, 0});
  net.vertices.push_back({0.005, 1, 0});
  net.polylines.push_back({32, 33});
  NetworkGraph g;
  const Status s = BuildNetworkGraph(net, &g, {}, 0.005);
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(g.welded_edges, 0);
  EXPECT_EQ(g.merged_vertices, 2);  // the copy of vertex 10, and 32
  EXPECT_EQ(g.vertex_of_input[21], g.vertex_of_input[10]);
  EXPECT_EQ(g.vertex_of_input[32], g.vertex_of_input[5]);
  for (int v = 0; v <= 31; ++v) {
    if (v == 21) continue;
    EXPECT_EQ(g.input_of_vertex[g.vertex_of_input[v]], v) << v;
  }
  // The line split at the T (two), the star's two strokes, the T.
  EXPECT_EQ(g.curves.size(), 5u);
}

// A repeated point (an edge of zero length) is no edge to the weld: a T's
// foot whose last point is drawn twice is still a free end, and a stroke
// with a point drawn twice still keeps its points apart.
TEST(NetworkGraphTest, WeldIgnoresRepeatedPoints) {
  NetworkGraph g;
  Status s = Build(
      "v 0 0 0\nv .5 0 0\nv 1 0 0\nv .5 .0005 0\nv .5 .0005 0\n"
      "v .5 1 0\nl 1 2 3\nl 4 5 6\n",
      &g, 0.001);
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(g.vertex_of_input[3], g.vertex_of_input[1]);  // the T's foot
  EXPECT_EQ(g.vertex_of_input[4], g.vertex_of_input[1]);
  EXPECT_EQ(g.welded_edges, 1);  // the repeated point's edge
  EXPECT_EQ(g.curves.size(), 3u);
  s = Build(
      "v 0 0 0\nv .0004 0 0\nv .0004 0 0\nv .0008 0 0\nv 1 0 0\n"
      "l 1 2 3 4 5\n",
      &g, 0.001);
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(g.merged_vertices, 1);  // the copy only
  EXPECT_EQ(g.welded_edges, 1);
  ASSERT_EQ(g.curves.size(), 1u);
  EXPECT_EQ(g.curves[0].vertices.size(), 4u);
}

// A free end next to a junction: welded to the junction's neighbour its
// edge would double theirs, and welded near it, it would close a small
// loop. A stroke that curls through its second point, and one that
// overshoots an exact junction by 0.001, are left as drawn (the overshoot
// dangles).
TEST(NetworkGraphTest, WeldLeavesStubsBesideTheirJunction) {
  NetworkGraph g;
  Status s = Build(
      "v 0 0 0\nv .001 0 0\nv .002 .001 0\nv .001 .002 0\nv 1 0 0\n"
      "l 1 2 3 4 2 5\n",
      &g, 0.01);
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(g.merged_vertices, 0);
  CurveNetwork net;
  for (int k = -3; k <= 3; ++k) net.vertices.push_back({0.001 * k, 0, 0});
  net.polylines.push_back({0, 1, 2, 3, 4, 5, 6});  // through (0, 0, 0): 3
  net.vertices.push_back({0, -1, 0});              // 7
  net.vertices.push_back({0, 0, 0});               // 8, a copy of 3
  net.vertices.push_back({0, 0.001, 0});           // 9, past it
  net.polylines.push_back({7, 8, 9});
  s = BuildNetworkGraph(net, &g, {}, 0.005);
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(g.merged_vertices, 1);  // the copy only
  for (int v : {0, 1, 2, 4, 5, 6, 9}) {
    EXPECT_EQ(g.input_of_vertex[g.vertex_of_input[v]], v) << v;
  }
}

// A large network stops at a cancel or a passed deadline: the weld, the
// edges and the crossing check poll them (a million points took seconds
// past a client's deadline when only the crossing check did).
TEST(NetworkGraphTest, StopsWhenCancelledOrPastItsDeadline) {
  CurveNetwork net;
  constexpr int kPoints = 200000;
  for (int k = 0; k < kPoints; ++k) {
    const double t = 0.001 * k;
    net.vertices.push_back({std::cos(t), std::sin(t), 1e-5 * k});
  }
  for (int k = 0; k + 1 < kPoints; ++k) net.polylines.push_back({k, k + 1});
  NetworkGraph g;
  for (double weld : {0.0, 1e-4}) {
    SCOPED_TRACE(weld);
    std::atomic<bool> cancel{true};
    Control cancelled;
    cancelled.cancel = &cancel;
    EXPECT_EQ(BuildNetworkGraph(net, &g, cancelled, weld).code,
              StatusCode::kCancelled);
    Control expired;
    expired.deadline = std::chrono::steady_clock::now();
    const Status late = BuildNetworkGraph(net, &g, expired, weld);
    EXPECT_EQ(late.code, StatusCode::kDeadlineExceeded);
    // At the first step, not at the last.
    EXPECT_NE(late.message.find("weld"), std::string::npos) << late.message;
    // Unstopped, it is one open curve (nothing to weld: every end but two
    // is shared).
    ASSERT_TRUE(BuildNetworkGraph(net, &g, {}, weld).ok());
    EXPECT_EQ(g.merged_vertices, 0);
    EXPECT_EQ(g.curves.size(), 1u);
  }
}

}  // namespace
}  // namespace dot
