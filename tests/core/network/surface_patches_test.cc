// SPDX-License-Identifier: AGPL-3.0-or-later
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dot/network.h"
#include "network/surface_steps.h"

namespace dot {
namespace {

// A patch's reason says how its latest solve went: a re-solve that needs
// no bending-alone fallback takes the earlier solve's note out, and keeps
// every other note in its place.
TEST(TriangulatePatchTest, SolveWithoutBendingAloneTakesItsNoteOut) {
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::string note = kBendingAloneNote;
  struct Case {
    std::string before, after;
  };
  for (const Case& c : {Case{note, ""}, Case{"kept; " + note, "kept"},
                        Case{note + "; later", "later"},
                        Case{"kept; " + note + "; later", "kept; later"},
                        Case{"kept", "kept"}}) {
    SCOPED_TRACE(c.before);
    PatchReport report;
    report.reason = c.before;
    PatchMesh patch;
    ASSERT_TRUE(TriangulatePatch(square, {{0, 1, 2, 3}}, {}, {},
                                 SurfaceOptions{}, Control{}, &patch, &report)
                    .ok());
    EXPECT_EQ(patch.faces.size(), 2u);
    EXPECT_EQ(report.reason, c.after);
  }
}

}  // namespace
}  // namespace dot
