// SPDX-License-Identifier: AGPL-3.0-or-later
// The viewer's files, embedded at build time (client/viewer/CMakeLists.txt).
#ifndef DOT_CLIENT_VIEWER_VIEWER_ASSETS_H_
#define DOT_CLIENT_VIEWER_VIEWER_ASSETS_H_

#include <string_view>

namespace dot::client {

// src/page.html, with its @DOT_TITLE@, @DOT_DATA@ and @DOT_SCRIPT@.
std::string_view ViewerPageTemplate();
// three.js and src/viewer.js in one script; empty when dotctl was built
// without the viewer (DOT_BUILD_VIEWER=OFF: no npm).
std::string_view ViewerScript();

}  // namespace dot::client

#endif  // DOT_CLIENT_VIEWER_VIEWER_ASSETS_H_
