// SPDX-License-Identifier: AGPL-3.0-or-later
// The HTML page of a result (dotctl view, fill-holes --report): one file,
// three.js and the data inside, that any browser opens without a network.
// It shows the mesh with each filled hole's patch highlighted, its open
// edges, the holes of the report in a table that flies to each, and for a
// fill the mesh before it.
#ifndef DOT_CLIENT_VIEW_PAGE_H_
#define DOT_CLIENT_VIEW_PAGE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"

namespace dot::client {

struct ViewPage {
  std::string title;                       // the input's name
  std::string summary;                     // one line under it
  const PolygonSoup* after = nullptr;      // shown: the result (required)
  const PolygonSoup* before = nullptr;     // the mesh as read (a fill's input)
  const v1::FillReport* report = nullptr;  // its holes fill the table
};

// Which filled hole's patch each face of `after` is: -1 for a face of
// `before` (its corners, by coordinates, are corners of one face of
// `before`, so a polygon triangulated again counts as the same), else the
// id of the filled hole whose loop's centroid lies nearest the rim of the
// face's patch (connected new faces; islands count as their rim's hole).
// Without `before`, or without filled holes, every face is -1.
std::vector<int32_t> PatchOwners(const PolygonSoup& before,
                                 const PolygonSoup& after,
                                 const v1::FillReport& report);

// Whether this dotctl has the viewer's script (built with npm).
bool ViewerBuilt();

// The page as one string. Error: built without the viewer, or no mesh.
Status RenderViewPage(const ViewPage& page, std::string* html);

}  // namespace dot::client

#endif  // DOT_CLIENT_VIEW_PAGE_H_
