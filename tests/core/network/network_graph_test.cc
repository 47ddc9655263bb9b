// SPDX-License-Identifier: AGPL-3.0-or-later
// Reading networks and building their graph: curves between junctions,
// welding, dangling curves, and refusals that name what is wrong.
#include <gtest/gtest.h>

#include <sstream>

#include "dot/network.h"
#include "dot/network_samples.h"

namespace dot {
namespace {

Status Build(const std::string& obj, NetworkGraph* g) {
  std::istringstream in(obj);
  CurveNetwork net;
  const Status s = ReadNetworkObj(in, &net);
  if (!s.ok()) return s;
  return BuildNetworkGraph(net, g);
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
  EXPECT_NE(s.message.find("polylines 1 and 2"), std::string::npos);
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

}  // namespace
}  // namespace dot
