// SPDX-License-Identifier: AGPL-3.0-or-later
// Cycles of networks with known patches: a cube, a genus-3 polygon mesh's
// face edges, and the rims of patches cut from a real mesh (each found
// cycle must be a cut patch's rim).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "dot/io.h"
#include "dot/network.h"
#include "dot/network_samples.h"
#include "fixtures/cut_mesh.h"

namespace dot {
namespace {

std::set<int32_t> CurvesOf(const NetworkCycle& c) {
  std::set<int32_t> out;
  for (const auto& loop : c.loops) {
    for (const CurveUse& u : loop) out.insert(u.curve);
  }
  return out;
}

// Every curve bounds two cycles, run once each way.
void ExpectEachCurveTwiceOppositely(const NetworkGraph& g,
                                    const std::vector<NetworkCycle>& cycles) {
  std::vector<int> forward(g.curves.size(), 0), backward(g.curves.size(), 0);
  for (const NetworkCycle& c : cycles) {
    for (const CurveUse& u : c.loops[0])
      ++(u.reversed ? backward : forward)[u.curve];
  }
  for (size_t c = 0; c < g.curves.size(); ++c) {
    EXPECT_EQ(forward[c], 1) << "curve " << c;
    EXPECT_EQ(backward[c], 1) << "curve " << c;
  }
}

TEST(NetworkCyclesTest, CubeHasSixSquares) {
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(CubeNetwork(4), &g).ok());
  std::vector<NetworkCycle> cycles;
  ASSERT_TRUE(FindNetworkCycles(g, &cycles).ok());
  ASSERT_EQ(cycles.size(), 6u);
  for (const NetworkCycle& c : cycles) {
    ASSERT_EQ(c.loops.size(), 1u);
    EXPECT_EQ(c.loops[0].size(), 4u);
    // The four corners of a square face share a coordinate.
    const std::vector<int32_t> vs = LoopVertices(g, c.loops[0]);
    int shared_axes = 0;
    for (int axis = 0; axis < 3; ++axis) {
      bool same = true;
      for (int32_t v : vs) {
        const Vec3& p = g.vertices[v];
        const Vec3& q = g.vertices[vs[0]];
        const double a[3] = {p.x, p.y, p.z}, b[3] = {q.x, q.y, q.z};
        same = same && a[axis] == b[axis];
      }
      shared_axes += same;
    }
    EXPECT_EQ(shared_axes, 1);
  }
  ExpectEachCurveTwiceOppositely(g, cycles);
}

// Cuts `mesh_name` into patches and finds the cycles of their rims:
// how many patches, and how many found cycles are a patch's rim.
struct RimsFound {
  int patches = 0, cycles = 0, rims = 0;
};
RimsFound FindCutRims(const std::string& mesh_name, int patches, uint64_t seed,
                      int keep_every = 1) {
  RimsFound out;
  const CutNetwork cut = testing::CutMesh(mesh_name, patches, keep_every, seed);
  // Graph ids are the network's: a cut uses every vertex it lists, once.
  NetworkGraph g;
  EXPECT_TRUE(BuildNetworkGraph(cut.network, &g).ok());
  std::vector<NetworkCycle> cycles;
  EXPECT_TRUE(FindNetworkCycles(g, &cycles).ok());
  std::vector<std::vector<int32_t>> found;
  for (const NetworkCycle& c : cycles) {
    found.emplace_back();
    for (int32_t curve : CurvesOf(c)) {
      const auto& vs = g.curves[curve].vertices;
      found.back().insert(found.back().end(), vs.begin(), vs.end());
    }
  }
  out.patches = cut.patches;
  out.cycles = static_cast<int>(cycles.size());
  out.rims = CountRimsFound(cut, found);
  return out;
}

// The cut knows its answer: a rim per patch, every curve on two of them.
TEST(NetworkCyclesTest, CutRimsAreThePatchBoundaries) {
  const CutNetwork cut = testing::CutMesh("homer.off", 25, 3, 1);
  ASSERT_EQ(cut.rims.size(), static_cast<size_t>(cut.patches));
  for (const auto& line : cut.network.polylines) {
    int on = 0;
    for (const auto& rim : cut.rims) {
      on += std::all_of(line.begin(), line.end(), [&](int32_t v) {
        return std::binary_search(rim.begin(), rim.end(), v);
      });
    }
    EXPECT_EQ(on, 2);
  }
  EXPECT_EQ(CountRimsFound(cut, cut.rims), cut.patches);
  EXPECT_EQ(CountRimsFound(cut, {cut.network.polylines[0]}), 0);
}

// Homer (genus 0): every cycle is a rim, at every density.
TEST(NetworkCyclesTest, CutMeshRimsAreFound) {
  for (int patches : {25, 100, 200}) {
    SCOPED_TRACE(patches);
    const RimsFound found = FindCutRims("homer.off", patches, 1);
    EXPECT_EQ(found.cycles, found.patches);
    EXPECT_EQ(found.rims, found.patches);
  }
}

// The elephant mesh has genus 3 (Euler characteristic -4): the rotation
// system finds a genus-3 embedding, also with every third rim vertex
// (fewer, longer curves: the votes and face counts alone found 190 of 202,
// the faces' cost the rest).
TEST(NetworkCyclesTest, GenusThreeCutRimsAreFound) {
  for (uint64_t seed : {1, 2}) {
    const RimsFound found = FindCutRims("elephant.off", 200, seed);
    EXPECT_EQ(found.rims, found.patches);
  }
  const RimsFound sparse = FindCutRims("elephant.off", 200, 1, 3);
  EXPECT_EQ(sparse.rims, sparse.patches);
}

// Coarse cuts, where a few normals carried along long, bent curves vote
// for the wrong sign: the faces' DOT cost finds every rim (the votes and
// face counts alone: 56 of 59 and 27 of 30).
TEST(NetworkCyclesTest, CoarseCutRimsAreFoundByWhatTheirFacesCost) {
  const RimsFound elephant = FindCutRims("elephant.off", 40, 1);
  EXPECT_EQ(elephant.patches, 59);
  EXPECT_EQ(elephant.rims, elephant.patches);
  const RimsFound armadillo = FindCutRims("armadillo.off", 12, 1);
  EXPECT_EQ(armadillo.patches, 30);
  EXPECT_EQ(armadillo.rims, armadillo.patches);
  // The votes keep the cost in check: a flip may overrule one vote more
  // than it wins (none: 136 of 147 here; two: 140).
  const RimsFound sparse = FindCutRims("elephant.off", 140, 1, 3);
  EXPECT_EQ(sparse.patches, 147);
  EXPECT_GE(sparse.rims, 141);
}

// Two rims and a seam: the caps, and the tube's face, which runs the seam
// one way and back (a cycle SurfaceNetwork cuts in two).
TEST(NetworkCyclesTest, SeamFaceIsACycle) {
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(CylinderNetwork(16, true), &g).ok());
  ASSERT_EQ(g.curves.size(), 3u);
  std::vector<NetworkCycle> cycles;
  std::vector<std::string> notes;
  ASSERT_TRUE(FindNetworkCycles(g, &cycles, &notes).ok());
  EXPECT_TRUE(notes.empty());
  ASSERT_EQ(cycles.size(), 3u);
  int tubes = 0;
  for (const NetworkCycle& c : cycles) {
    std::map<int32_t, int> runs;
    for (const CurveUse& u : c.loops[0]) runs[u.curve] += u.reversed ? -1 : 1;
    if (c.loops[0].size() == 4) {
      ++tubes;
      EXPECT_EQ(runs.size(), 3u);
      for (const auto& [curve, net] : runs) {
        if (curve == 2) {
          EXPECT_EQ(net, 0);  // the seam, once each way
        }
      }
    }
  }
  EXPECT_EQ(tubes, 1);
}

// Adds a closed circle of n points around `centre` in the plane z =
// centre.z; `clockwise` runs it the other way round.
void AddCircle(CurveNetwork* net, Vec3 centre, double radius, int n,
               bool clockwise) {
  std::vector<int32_t> line;
  for (int k = 0; k < n; ++k) {
    const double a = (clockwise ? -2 : 2) * M_PI * k / n;
    line.push_back(static_cast<int32_t>(net->vertices.size()));
    net->vertices.push_back(
        centre + Vec3{radius * std::cos(a), radius * std::sin(a), 0});
  }
  line.push_back(line.front());
  net->polylines.push_back(std::move(line));
}

// Signed area of a loop seen from +z (positive: counter-clockwise).
double AreaAlongZ(const NetworkGraph& g, const std::vector<CurveUse>& loop) {
  const std::vector<int32_t> vs = LoopVertices(g, loop);
  double twice = 0;
  for (size_t k = 0; k < vs.size(); ++k) {
    const Vec3& p = g.vertices[vs[k]];
    const Vec3& q = g.vertices[vs[(k + 1) % vs.size()]];
    twice += p.x * q.y - q.x * p.y;
  }
  return twice / 2;
}

// Three concentric circles in one plane, drawn either way round, and a
// fourth above them: each of the three is an island of the next one out
// (its loop run against that face's), and keeps a patch of its own facing
// the same way; the one above is in no face (it is farther from the plane
// than a quarter of the radius around it). With kHole the middle circle is
// a hole of the outer face, and the inner one, in that hole, a disk of its
// own; kOff pairs nothing.
TEST(NetworkCyclesTest, LoneLoopsInAFaceAreItsIslands) {
  CurveNetwork net;
  AddCircle(&net, {0, 0, 0}, 1.0, 40, false);
  AddCircle(&net, {0, 0, 0}, 0.6, 30, true);
  AddCircle(&net, {0.05, 0, 0}, 0.3, 20, false);
  AddCircle(&net, {0, 0, 0.5}, 0.2, 12, false);
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(net, &g).ok());
  ASSERT_EQ(g.curves.size(), 4u);
  for (NetworkIslands mode :
       {NetworkIslands::kInset, NetworkIslands::kHole, NetworkIslands::kOff}) {
    SCOPED_TRACE(std::string(NetworkIslandsName(mode)));
    std::vector<NetworkCycle> cycles;
    std::vector<std::string> notes;
    ASSERT_TRUE(FindNetworkCycles(g, &cycles, &notes, {}, {mode, false}).ok());
    std::map<int32_t, const NetworkCycle*> by_outer;
    for (const NetworkCycle& c : cycles) by_outer[c.loops[0][0].curve] = &c;
    if (mode == NetworkIslands::kOff) {
      EXPECT_EQ(cycles.size(), 4u);
      for (const NetworkCycle& c : cycles) EXPECT_EQ(c.loops.size(), 1u);
      EXPECT_TRUE(notes.empty());
      continue;
    }
    const bool hole = mode == NetworkIslands::kHole;
    EXPECT_EQ(notes.size(), hole ? 1u : 2u);
    ASSERT_EQ(cycles.size(), hole ? 3u : 4u);
    const NetworkCycle& outer = *by_outer.at(0);
    ASSERT_EQ(outer.loops.size(), 2u);
    EXPECT_EQ(outer.loops[1][0].curve, 1);
    EXPECT_LT(AreaAlongZ(g, outer.loops[0]) * AreaAlongZ(g, outer.loops[1]), 0);
    ASSERT_EQ(by_outer.count(3), 1u);
    EXPECT_EQ(by_outer.at(3)->loops.size(), 1u);  // above: no island
    if (hole) {
      // The middle circle is a hole; the inner one, inside it, is on no
      // surface: a disk of its own.
      EXPECT_EQ(by_outer.count(1), 0u);
      ASSERT_EQ(by_outer.count(2), 1u);
      EXPECT_EQ(by_outer.at(2)->loops.size(), 1u);
      continue;
    }
    const NetworkCycle& middle = *by_outer.at(1);
    ASSERT_EQ(middle.loops.size(), 2u);
    EXPECT_EQ(middle.loops[1][0].curve, 2);
    const double facing = AreaAlongZ(g, outer.loops[0]);
    EXPECT_GT(AreaAlongZ(g, middle.loops[0]) * facing, 0);
    EXPECT_LT(AreaAlongZ(g, middle.loops[1]) * facing, 0);
    const NetworkCycle& inner = *by_outer.at(2);
    ASSERT_EQ(inner.loops.size(), 1u);
    EXPECT_GT(AreaAlongZ(g, inner.loops[0]) * facing, 0);
  }
}

// A thin slab (1 x 1 x 0.1) with a circle on its lid: the lid holds it,
// not the bottom (as large, and it holds it too seen along z), far from the
// origin as well. A circle standing upright above the lid, and one flat
// but above it by more than its radius, are in no face.
TEST(NetworkCyclesTest, IslandHostIsTheNearestFaceThatHoldsIt) {
  for (double offset : {0.0, 1e8}) {
    SCOPED_TRACE(offset);
    CurveNetwork net = CubeNetwork(2);
    for (Vec3& p : net.vertices) p.z *= 0.1;
    AddCircle(&net, {0.5, 0.5, 0.1}, 0.3, 24, false);
    AddCircle(&net, {0.3, 0.3, 0.23}, 0.1, 12, false);  // 0.13 above: > 0.1
    const auto upright = static_cast<int32_t>(net.polylines.size());
    AddCircle(&net, {0, 0, 0}, 0.1, 12, false);
    for (int32_t v : net.polylines[upright]) {
      Vec3& p = net.vertices[v];
      p = {0.7 + p.x, 0.7, 0.3 + p.y};
    }
    for (Vec3& p : net.vertices) p = p + Vec3{offset, offset, offset};
    NetworkGraph g;
    ASSERT_TRUE(BuildNetworkGraph(net, &g).ok());
    std::vector<NetworkCycle> cycles;
    ASSERT_TRUE(FindNetworkCycles(g, &cycles).ok());
    ASSERT_EQ(cycles.size(), 9u);  // 6 faces, 3 circles
    int hosts = 0;
    for (const NetworkCycle& c : cycles) {
      if (c.loops.size() == 1) continue;
      ++hosts;
      ASSERT_EQ(c.loops.size(), 2u);
      EXPECT_EQ(g.curves[c.loops[1][0].curve].vertices.size(), 25u);
      for (int32_t v : LoopVertices(g, c.loops[0])) {
        EXPECT_EQ(g.vertices[v].z, 0.1 + offset);  // the lid
      }
    }
    EXPECT_EQ(hosts, 1);
  }
}

// A square of 400 points (its edges looked up by bands) around a 10 x 10
// grid of circles: each is an island of it; circles just over its rim, or
// outside it, are not.
TEST(NetworkCyclesTest, ManyIslandsInALongLoop) {
  CurveNetwork net;
  std::vector<int32_t> square;
  for (int k = 0; k < 400; ++k) {
    const double t = (k % 100) / 100.0 * 10;
    const Vec3 corner[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
    const Vec3 along[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    square.push_back(static_cast<int32_t>(net.vertices.size()));
    net.vertices.push_back(corner[k / 100] + t * along[k / 100]);
  }
  square.push_back(square.front());
  net.polylines.push_back(square);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      AddCircle(&net, {0.5 + i, 0.5 + j, 0}, 0.3, 16, (i + j) % 2 == 1);
    }
  }
  AddCircle(&net, {10, 5, 0.02}, 0.3, 16, false);    // over the rim
  AddCircle(&net, {5, -0.2, 0.02}, 0.3, 16, false);  // over the rim
  AddCircle(&net, {12, 5, 0}, 0.3, 16, false);       // outside
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(net, &g).ok());
  std::vector<NetworkCycle> cycles;
  ASSERT_TRUE(FindNetworkCycles(g, &cycles).ok());
  ASSERT_EQ(cycles.size(), 104u);
  ASSERT_EQ(cycles[0].loops.size(), 101u);
  for (size_t k = 1; k < cycles[0].loops.size(); ++k) {
    EXPECT_LT(
        AreaAlongZ(g, cycles[0].loops[0]) * AreaAlongZ(g, cycles[0].loops[k]),
        0);
  }
}

TEST(NetworkCyclesTest, UserCyclesByCornersOrEveryVertex) {
  const CurveNetwork net = CubeNetwork(2);  // corners 0..7, midpoints 8..19
  NetworkGraph g;
  ASSERT_TRUE(BuildNetworkGraph(net, &g).ok());
  std::vector<NetworkCycle> cycles;
  // The z = 0 face by its corners, and the y = 0 face by every vertex,
  // each running the edge they share (0-1) its own way.
  ASSERT_TRUE(CyclesFromVertices(
                  g, {{{0, 1, 3, 2}}, {{0, 10, 4, 16, 5, 12, 1, 8}}}, &cycles)
                  .ok());
  ASSERT_EQ(cycles.size(), 2u);
  EXPECT_EQ(cycles[0].loops[0].size(), 4u);
  EXPECT_EQ(cycles[1].loops[0].size(), 4u);
  Status s = CyclesFromVertices(g, {{{0, 7, 3}}}, &cycles);
  EXPECT_NE(s.message.find("no curve joins vertices 0 and 7"),
            std::string::npos)
      << s.message;
  s = CyclesFromVertices(g, {{{0, 1, 99}}}, &cycles);
  EXPECT_NE(s.message.find("vertex 99 is not"), std::string::npos) << s.message;
  // Both faces running the edge 0-1 the same way: not one surface.
  s = CyclesFromVertices(g, {{{0, 1, 3, 2}}, {{0, 1, 5, 4}}}, &cycles);
  EXPECT_NE(s.message.find("the same way"), std::string::npos) << s.message;
  s = CyclesFromVertices(g, {{{0, 1, 3, 2}}, {{1, 3, 2, 0}}}, &cycles);
  EXPECT_NE(s.message.find("repeats cycle 0"), std::string::npos) << s.message;
  // A loop with no junction, listed by three of its vertices.
  NetworkGraph rim;
  ASSERT_TRUE(BuildNetworkGraph(CylinderNetwork(20, false), &rim).ok());
  ASSERT_TRUE(CyclesFromVertices(rim, {{{5, 10, 15}}}, &cycles).ok())
      << s.message;
  EXPECT_EQ(LoopVertices(rim, cycles[0].loops[0]).size(), 20u);
}

}  // namespace
}  // namespace dot
