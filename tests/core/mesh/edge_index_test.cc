// SPDX-License-Identifier: AGPL-3.0-or-later
// The edge index groups every triangle side by undirected edge, in (edge,
// triangle, side) order, with each use's direction; checked against a
// std::map built the obvious way.
#include "mesh/edge_index.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <map>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "fixtures/meshes.h"

namespace dot {
namespace {

// (triangle, side, from, to) of one use.
using Use = std::tuple<int32_t, int, int32_t, int32_t>;
using Grouped = std::map<std::pair<int32_t, int32_t>, std::vector<Use>>;

Grouped ByMap(const std::vector<Triangle>& triangles) {
  Grouped g;
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      g[std::minmax(a, b)].emplace_back(static_cast<int32_t>(t), k, a, b);
    }
  }
  return g;  // uses in (triangle, side) order, as generated
}

Grouped ByIndex(const EdgeIndex& index) {
  Grouped g;
  ForEachEdge(index, [&](const EdgeUses& edge) {
    auto& uses = g[{edge.lo(), edge.hi()}];
    EXPECT_TRUE(uses.empty())
        << "edge " << edge.lo() << "-" << edge.hi() << " visited twice";
    for (const EdgeUse& u : edge) {
      EXPECT_EQ(u.lo(), edge.lo());
      EXPECT_EQ(u.hi(), edge.hi());
      uses.emplace_back(u.triangle, u.side, u.from(), u.to());
    }
  });
  return g;
}

TEST(EdgeIndexTest, TwoTrianglesSharingAnEdge) {
  // 0-1-2 and 2-1-3 share edge 1-2, in opposite directions.
  const EdgeIndex index = BuildEdgeIndex({{0, 1, 2}, {2, 1, 3}});
  ASSERT_EQ(index.uses.size(), 6u);
  std::vector<std::pair<int32_t, int32_t>> edges;
  std::vector<size_t> sizes;
  ForEachEdge(index, [&](const EdgeUses& edge) {
    edges.emplace_back(edge.lo(), edge.hi());
    sizes.push_back(edge.size());
    if (edge.size() == 2) {
      EXPECT_EQ(edge[0].triangle, 0);
      EXPECT_EQ(edge[0].side, 1);
      EXPECT_EQ(edge[0].from(), 1);
      EXPECT_EQ(edge[0].to(), 2);
      EXPECT_TRUE(edge[0].forward);
      EXPECT_EQ(edge[1].triangle, 1);
      EXPECT_EQ(edge[1].side, 0);
      EXPECT_EQ(edge[1].from(), 2);
      EXPECT_EQ(edge[1].to(), 1);
      EXPECT_FALSE(edge[1].forward);
    }
  });
  const std::vector<std::pair<int32_t, int32_t>> expected = {
      {0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}};
  EXPECT_EQ(edges, expected);
  EXPECT_EQ(sizes, (std::vector<size_t>{1, 1, 2, 1, 1}));
  EXPECT_TRUE(HasEdge(index, 2, 1));
  EXPECT_TRUE(HasEdge(index, 3, 1));
  EXPECT_FALSE(HasEdge(index, 0, 3));
  EXPECT_FALSE(HasEdge(index, 4, 5));
}

TEST(EdgeIndexTest, MatchesAMapOnRandomTriangleSoups) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 200; ++trial) {
    // Few vertices, many triangles: shared, non-manifold and degenerate
    // (repeated-vertex) sides all occur, and long per-vertex lists too.
    const int vertices = 3 + trial % 12;
    const int count = 1 + trial % 60;
    std::vector<Triangle> triangles;
    for (int t = 0; t < count; ++t) {
      triangles.push_back({static_cast<int32_t>(rng() % vertices),
                           static_cast<int32_t>(rng() % vertices),
                           static_cast<int32_t>(rng() % vertices)});
    }
    const EdgeIndex index = BuildEdgeIndex(triangles);
    const Grouped expected = ByMap(triangles);
    EXPECT_EQ(ByIndex(index), expected) << "trial " << trial;
    for (int32_t a = 0; a < vertices + 1; ++a) {
      for (int32_t b = 0; b < vertices + 1; ++b) {
        EXPECT_EQ(HasEdge(index, a, b), expected.count(std::minmax(a, b)) > 0)
            << a << "-" << b;
      }
    }
  }
}

TEST(EdgeIndexTest, ClosedTorusHasEveryEdgeTwiceInOppositeDirections) {
  const MeshData torus = testing::BumpyTorus(30, 20);
  const EdgeIndex index = BuildEdgeIndex(torus.triangles);
  size_t edges = 0;
  ForEachEdge(index, [&](const EdgeUses& edge) {
    ++edges;
    ASSERT_EQ(edge.size(), 2u);
    EXPECT_EQ(edge[0].from(), edge[1].to());
    EXPECT_LT(edge[0].triangle, edge[1].triangle);
  });
  EXPECT_EQ(2 * edges, 3 * torus.triangles.size());
}

TEST(EdgeIndexTest, EmptyInput) {
  const EdgeIndex index = BuildEdgeIndex({});
  EXPECT_TRUE(index.uses.empty());
  int calls = 0;
  ForEachEdge(index, [&](const EdgeUses&) { ++calls; });
  EXPECT_EQ(calls, 0);
  EXPECT_FALSE(HasEdge(index, 0, 1));
}

// Whole meshes: the index stops with its ticker (before, building it took
// ~0.6 s on 10 M faces with no way to stop), and an unbounded ticker gives
// the plain index.
TEST(EdgeIndexTest, StopsWhenItsTickerSaysSoAndMatchesThePlainIndexOtherwise) {
  const MeshData torus = testing::BumpyTorus(200, 100);
  std::atomic<bool> cancel{true};
  Control cancelled;
  cancelled.cancel = &cancel;
  RunTicker stop(cancelled, "indexing");
  EdgeIndex index;
  EXPECT_FALSE(BuildEdgeIndex(torus.triangles, stop, &index));
  EXPECT_EQ(stop.status().code, StatusCode::kCancelled);

  Control expired;
  expired.deadline = std::chrono::steady_clock::now();
  RunTicker late(expired, "indexing");
  EXPECT_FALSE(BuildEdgeIndex(torus.triangles, late, &index));
  EXPECT_EQ(late.status().code, StatusCode::kDeadlineExceeded);
  EXPECT_NE(late.status().message.find("indexing"), std::string::npos);

  const Control unbounded;
  RunTicker go(unbounded, "indexing");
  ASSERT_TRUE(BuildEdgeIndex(torus.triangles, go, &index));
  const EdgeIndex plain = BuildEdgeIndex(torus.triangles);
  ASSERT_EQ(index.uses.size(), plain.uses.size());
  for (size_t k = 0; k < plain.uses.size(); ++k) {
    EXPECT_EQ(index.uses[k].key, plain.uses[k].key);
    EXPECT_EQ(index.uses[k].triangle, plain.uses[k].triangle);
    EXPECT_EQ(index.uses[k].side, plain.uses[k].side);
  }
}

TEST(EdgeIndexTest, ForEachEdgeStopsWhenItsFunctionReturnsFalse) {
  const MeshData torus = testing::BumpyTorus(10, 5);
  int seen = 0;
  ForEachEdge(BuildEdgeIndex(torus.triangles),
              [&](const EdgeUses&) { return ++seen < 7; });
  EXPECT_EQ(seen, 7);
}

}  // namespace
}  // namespace dot
