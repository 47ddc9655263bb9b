// SPDX-License-Identifier: AGPL-3.0-or-later
#include "request_flags.h"

#include <CLI/CLI.hpp>

namespace dot::client {

void AddWeightFlags(CLI::App* cmd, MetricWeights* weights,
                    const std::string& group,
                    const std::array<std::string, kMetricCount>& help) {
  for (Metric m : kAllMetrics) {
    std::string flag(MetricName(m));  // squared_dihedral -> --squared-dihedral
    std::replace(flag.begin(), flag.end(), '_', '-');
    cmd->add_option("--" + flag, (*weights)[m], help[static_cast<int>(m)])
        ->group(group);
  }
}

void AddRequestFlags(CLI::App* cmd, RequestFlags* f) {
  AddWeightFlags(
      cmd, &f->weights, "Metric weights (default: --area 1)",
      {"weight of triangle area (minimal surfaces)",
       "weight of triangle perimeter",
       "weight of deviation from the boundary normals (needs normals in the "
       "input)",
       "weight of triangle shape (0 equilateral, 1 flat)",
       "weight of the bending angle between triangles",
       "weight of the squared bending angle (fair surfaces); negative "
       "maximizes twisting"});
  cmd->add_option("--space", f->space,
                  "search space: auto (Delaunay, then all triangles for small "
                  "polygons), delaunay (never self-intersects), all (GK, may "
                  "self-intersect), delaunay_first (every triangle, Delaunay "
                  "ones first: large polygons with no Delaunay "
                  "triangulation; may self-intersect)")
      ->check(CLI::IsMember({"auto", "delaunay", "all", "delaunay_first"}))
      ->capture_default_str()
      ->group("Options");
  cmd->add_option("--delaunay", f->delaunay,
                  "3D Delaunay backend: cgal or tetgen (default: the "
                  "server's, cgal with --local)")
      ->check(CLI::IsMember({"cgal", "tetgen"}))
      ->group("Options");
  cmd->add_flag("--no-cache", f->no_cache,
                "do not use the server's search-space cache")
      ->group("Options");
  cmd->add_flag("--protect-edges", f->protect_edges,
                "split non-Delaunay polygon edges so more polygons succeed")
      ->group("Options");
  cmd->add_flag("--keep-loop-directions", f->keep_loop_directions,
                "two loops: keep the second loop's direction (by default the "
                "solver may reverse it; three or more loops always keep "
                "theirs)")
      ->group("Options");
  cmd->add_flag("--validate", f->validate,
                "count self-intersecting triangle pairs of the result")
      ->group("Options");
  cmd->add_option("--time-budget-ms", f->time_budget_ms,
                  "compute time allowed per polygon (0: the server's limit)")
      ->group("Options");
}

v1::Options RequestFlags::ToOptions() const {
  v1::Options o;
  o.set_search_space(space == "delaunay" ? v1::SEARCH_SPACE_DELAUNAY
                     : space == "all"    ? v1::SEARCH_SPACE_ALL
                     : space == "delaunay_first"
                         ? v1::SEARCH_SPACE_DELAUNAY_FIRST
                         : v1::SEARCH_SPACE_AUTO);
  o.set_delaunay_backend(delaunay == "cgal"     ? v1::DELAUNAY_BACKEND_CGAL
                         : delaunay == "tetgen" ? v1::DELAUNAY_BACKEND_TETGEN
                                                : v1::DELAUNAY_BACKEND_DEFAULT);
  o.set_no_cache(no_cache);
  o.set_protect_edges(protect_edges);
  o.set_validate_output(validate);
  o.set_keep_loop_directions(keep_loop_directions);
  o.set_time_budget_ms(time_budget_ms);
  o.set_omit_input_vertices(omit_input_vertices);
  return o;
}

void AddConnectionFlags(CLI::App* app, ConnectionFlags* f) {
  app->add_option("-s,--server", f->server,
                  "server address host:port, or dns:///name:port to balance "
                  "over every address of a headless service")
      ->envname("DOT_SERVER")
      ->capture_default_str()
      ->group("Connection");
  app->add_option("--tls-ca", f->tls_ca, "PEM CA bundle: connect with TLS")
      ->envname("DOT_TLS_CA")
      ->group("Connection");
  app->add_option("--tls-cert", f->tls_cert,
                  "PEM client certificate (mutual TLS)")
      ->envname("DOT_TLS_CERT")
      ->group("Connection");
  app->add_option("--tls-key", f->tls_key, "PEM client key (mutual TLS)")
      ->envname("DOT_TLS_KEY")
      ->group("Connection");
  app->add_option("--tls-server-name", f->tls_server_name,
                  "name to expect in the server certificate")
      ->group("Connection");
  app->add_option("--timeout", f->timeout_s, "deadline of each call, seconds")
      ->capture_default_str()
      ->group("Connection");
}

}  // namespace dot::client
