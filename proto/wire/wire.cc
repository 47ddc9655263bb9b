// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire.h"

#include <algorithm>

namespace dot::wire {
namespace {}  // namespace

MetricValues FromWire(const v1::MetricWeights& w) {
  MetricValues v;
  v[Metric::kArea] = w.area();
  v[Metric::kPerimeter] = w.perimeter();
  v[Metric::kNormalDeviation] = w.normal_deviation();
  v[Metric::kShape] = w.shape();
  v[Metric::kDihedral] = w.dihedral();
  v[Metric::kSquaredDihedral] = w.squared_dihedral();
  return v;
}

v1::MetricWeights ToWire(const MetricValues& v) {
  v1::MetricWeights w;
  w.set_area(v[Metric::kArea]);
  w.set_perimeter(v[Metric::kPerimeter]);
  w.set_normal_deviation(v[Metric::kNormalDeviation]);
  w.set_shape(v[Metric::kShape]);
  w.set_dihedral(v[Metric::kDihedral]);
  w.set_squared_dihedral(v[Metric::kSquaredDihedral]);
  return w;
}

SearchSpace FromWire(v1::SearchSpace s) {
  switch (s) {
    case v1::SEARCH_SPACE_DELAUNAY:
      return SearchSpace::kDelaunay;
    case v1::SEARCH_SPACE_ALL:
      return SearchSpace::kAll;
    case v1::SEARCH_SPACE_DELAUNAY_FIRST:
      return SearchSpace::kDelaunayFirst;
    default:
      return SearchSpace::kAuto;
  }
}

v1::Stage ToWire(Stage s) {
  switch (s) {
    case Stage::kValidate:
      return v1::STAGE_VALIDATE;
    case Stage::kDelaunay:
      return v1::STAGE_DELAUNAY;
    case Stage::kAdjacency:
      return v1::STAGE_ADJACENCY;
    case Stage::kDynamicProgram:
      return v1::STAGE_DYNAMIC_PROGRAM;
    case Stage::kTiling:
      return v1::STAGE_TILING;
  }
  return v1::STAGE_UNSPECIFIED;
}

Status ProblemFromRequest(const v1::TriangulateRequest& request,
                          Problem* problem, Options* options) {
  const auto& c = request.polygon().coordinates();
  if (c.size() % 3 != 0) {
    return InvalidArgument("polygon.coordinates has " +
                           std::to_string(c.size()) +
                           " values; expected 3 per vertex");
  }
  const auto& nm = request.polygon().normals();
  if (!nm.empty() && nm.size() != c.size()) {
    return InvalidArgument("polygon.normals has " + std::to_string(nm.size()) +
                           " values; expected none or " +
                           std::to_string(c.size()));
  }
  if (!v1::SearchSpace_IsValid(request.options().search_space())) {
    return InvalidArgument("options.search_space " +
                           std::to_string(request.options().search_space()) +
                           " is not a known search space");
  }
  const v1::DelaunayBackend backend = request.options().delaunay_backend();
  if (!v1::DelaunayBackend_IsValid(backend)) {
    return InvalidArgument("options.delaunay_backend " +
                           std::to_string(backend) + " is not a known backend");
  }
  problem->vertices.clear();
  problem->normals.clear();
  problem->vertices.reserve(c.size() / 3);
  for (int i = 0; i + 2 < c.size(); i += 3) {
    problem->vertices.push_back({c[i], c[i + 1], c[i + 2]});
  }
  for (int i = 0; i + 2 < nm.size(); i += 3) {
    problem->normals.push_back({nm[i], nm[i + 1], nm[i + 2]});
  }
  const auto& sizes = request.polygon().loop_sizes();
  problem->loop_sizes.clear();
  if (sizes.size() == 1 && sizes[0] != static_cast<uint32_t>(c.size() / 3)) {
    return InvalidArgument(
        "polygon.loop_sizes has one loop of " + std::to_string(sizes[0]) +
        " vertices, but there are " + std::to_string(c.size() / 3));
  }
  if (sizes.size() > 1) {
    for (uint32_t size : sizes) {
      if (size > static_cast<uint32_t>(c.size() / 3)) {
        return InvalidArgument("polygon.loop_sizes has a loop of " +
                               std::to_string(size) + " vertices, more than " +
                               std::to_string(c.size() / 3) + " in all");
      }
      problem->loop_sizes.push_back(static_cast<int32_t>(size));
    }
  }
  const auto& forbidden = request.polygon().forbidden_edges();
  if (forbidden.size() % 2 != 0) {
    return InvalidArgument("polygon.forbidden_edges has an odd count (" +
                           std::to_string(forbidden.size()) +
                           "): give pairs of vertex indices");
  }
  problem->forbidden_edges.clear();
  for (int i = 0; i + 1 < forbidden.size(); i += 2) {
    const uint32_t n = static_cast<uint32_t>(c.size() / 3);
    if (forbidden[i] >= n || forbidden[i + 1] >= n) {
      return InvalidArgument(
          "polygon.forbidden_edges pair " + std::to_string(i / 2) +
          " names vertex " +
          std::to_string(std::max(forbidden[i], forbidden[i + 1])) +
          "; the polygon has " + std::to_string(n));
    }
    problem->forbidden_edges.emplace_back(forbidden[i], forbidden[i + 1]);
  }
  problem->weights = FromWire(request.weights());
  options->reorient_loops = !request.options().keep_loop_directions();
  options->space = FromWire(request.options().search_space());
  options->protect_edges = request.options().protect_edges();
  if (backend != v1::DELAUNAY_BACKEND_DEFAULT) {
    options->delaunay = backend == v1::DELAUNAY_BACKEND_TETGEN
                            ? DelaunayBackend::kTetgen
                            : DelaunayBackend::kCgal;
  }
  options->validate_output = request.options().validate_output();
  return OkStatus();
}

v1::TriangulateRequest MakeRequest(const std::string& id,
                                   const PolygonData& polygon,
                                   const MetricWeights& weights,
                                   const v1::Options& options) {
  v1::TriangulateRequest r;
  r.set_id(id);
  auto* c = r.mutable_polygon()->mutable_coordinates();
  c->Reserve(static_cast<int>(3 * polygon.vertices.size()));
  for (const Vec3& p : polygon.vertices) {
    c->Add(p.x);
    c->Add(p.y);
    c->Add(p.z);
  }
  auto* nm = r.mutable_polygon()->mutable_normals();
  for (const Vec3& n : polygon.normals) {
    nm->Add(n.x);
    nm->Add(n.y);
    nm->Add(n.z);
  }
  for (int32_t size : polygon.loop_sizes) {
    r.mutable_polygon()->add_loop_sizes(static_cast<uint32_t>(size));
  }
  *r.mutable_weights() = ToWire(weights);
  *r.mutable_options() = options;
  return r;
}

void FillSummary(const Result& r, v1::Summary* s) {
  s->set_status(r.status.ok() ? v1::RESULT_STATUS_OK
                              : v1::RESULT_STATUS_NO_TRIANGULATION);
  s->set_message(r.status.message);
  s->set_vertex_count(static_cast<uint32_t>(r.vertices.size()));
  s->set_triangle_count(static_cast<uint32_t>(r.triangles.size()));
  s->set_inserted_count(static_cast<uint32_t>(r.inserted.size()));
  if (!r.inserted.empty() || !r.loop_sizes.empty()) {
    s->mutable_loop()->Add(r.polygon.begin(), r.polygon.end());
  }
  s->mutable_loop_sizes()->Add(r.loop_sizes.begin(), r.loop_sizes.end());
  s->mutable_reversed_loops()->Add(r.reversed_loops.begin(),
                                   r.reversed_loops.end());
  for (const auto& [a, b] : r.bridges) {
    s->add_bridges(a);
    s->add_bridges(b);
  }
  for (const auto& [a, b] : r.non_delaunay_edges) {
    s->add_non_delaunay_edges(a);
    s->add_non_delaunay_edges(b);
  }
  s->set_total_cost(r.total_cost);
  *s->mutable_metric_costs() = ToWire(r.metric_costs);
  s->set_search_space_used(std::string(SpaceUsedName(r.space_used)));
  s->set_solver(std::string(SolverName(r.solver)));
  s->set_planar(r.planar);
  s->set_intersecting_pairs(r.intersecting_pairs);
  s->set_delaunay_backend(r.space_used == SpaceUsed::kDelaunay3d
                              ? std::string(DelaunayBackendName(r.delaunay))
                              : "");
  s->set_cache_hit(r.stats.cache_hit);
  v1::Stats* st = s->mutable_stats();
  st->set_n(r.stats.n);
  st->set_tetrahedra(r.stats.tetrahedra);
  st->set_delaunay_triangles(r.stats.delaunay_triangles);
  st->set_search_triangles(r.stats.search_triangles);
  st->set_adjacency_entries(r.stats.adjacency_entries);
  st->set_dp_states(r.stats.dp_states);
  st->set_table_bytes(r.stats.table_bytes);
  st->set_validate_ms(r.stats.validate_ms);
  st->set_delaunay_ms(r.stats.delaunay_ms);
  st->set_adjacency_ms(r.stats.adjacency_ms);
  st->set_dp_ms(r.stats.dp_ms);
  st->set_tiling_ms(r.stats.tiling_ms);
  st->set_non_delaunay_triangles(r.stats.non_delaunay_triangles);
  st->set_total_ms(r.stats.total_ms);
}

// Packed doubles cost 8 bytes, packed uint32 indices at most 5.
MeshChunker::MeshChunker(const std::vector<Vec3>& vertices,
                         const std::vector<Triangle>& triangles,
                         size_t first_vertex, size_t max_bytes)
    : vertices_(&vertices),
      triangles_(&triangles),
      next_vertex_(first_vertex),
      vertices_per_chunk_(std::max<size_t>(1, max_bytes / 24)),
      triangles_per_chunk_(std::max<size_t>(1, max_bytes / 15)) {}

bool MeshChunker::Next(v1::MeshChunk* chunk) {
  chunk->Clear();
  const auto& vertices = *vertices_;
  const auto& triangles = *triangles_;
  if (next_vertex_ < vertices.size()) {
    const size_t v = next_vertex_;
    const size_t end = std::min(vertices.size(), v + vertices_per_chunk_);
    chunk->set_first_vertex(static_cast<uint32_t>(v));
    chunk->mutable_vertices()->Reserve(static_cast<int>(3 * (end - v)));
    for (size_t i = v; i < end; ++i) {
      chunk->add_vertices(vertices[i].x);
      chunk->add_vertices(vertices[i].y);
      chunk->add_vertices(vertices[i].z);
    }
    next_vertex_ = end;
    return true;
  }
  if (next_triangle_ < triangles.size()) {
    const size_t t = next_triangle_;
    const size_t end = std::min(triangles.size(), t + triangles_per_chunk_);
    chunk->set_first_vertex(static_cast<uint32_t>(vertices.size()));
    chunk->set_first_triangle(static_cast<uint32_t>(t));
    chunk->mutable_triangles()->Reserve(static_cast<int>(3 * (end - t)));
    for (size_t i = t; i < end; ++i) {
      for (int32_t v : triangles[i]) chunk->add_triangles(v);
    }
    next_triangle_ = end;
    return true;
  }
  return false;
}

Status MeshAssembler::Add(const v1::MeshChunk& chunk) {
  if (chunk.vertices_size() % 3 != 0 || chunk.triangles_size() % 3 != 0) {
    return InvalidArgument("mesh chunk with a partial vertex or triangle");
  }
  if (chunk.vertices_size() > 0) {
    if (!started_) {
      started_ = true;
      first_vertex_ = chunk.first_vertex();
    }
    if (chunk.first_vertex() != first_vertex_ + vertices_.size()) {
      return InvalidArgument("mesh chunk out of order: vertex " +
                             std::to_string(chunk.first_vertex()) + " after " +
                             std::to_string(first_vertex_ + vertices_.size()));
    }
    for (int i = 0; i < chunk.vertices_size(); i += 3) {
      vertices_.push_back(
          {chunk.vertices(i), chunk.vertices(i + 1), chunk.vertices(i + 2)});
    }
  }
  if (chunk.triangles_size() > 0) {
    if (chunk.first_triangle() != triangles_.size()) {
      return InvalidArgument("mesh chunk out of order: triangle " +
                             std::to_string(chunk.first_triangle()) +
                             " after " + std::to_string(triangles_.size()));
    }
    for (int i = 0; i < chunk.triangles_size(); i += 3) {
      triangles_.push_back({static_cast<int32_t>(chunk.triangles(i)),
                            static_cast<int32_t>(chunk.triangles(i + 1)),
                            static_cast<int32_t>(chunk.triangles(i + 2))});
    }
  }
  return OkStatus();
}

Status MeshAssembler::Finish(size_t vertex_count, size_t triangle_count,
                             const std::vector<Vec3>& input, MeshData* mesh) {
  mesh->vertices.clear();
  if (!started_) first_vertex_ = vertex_count;
  if (first_vertex_ > input.size()) {
    return InvalidArgument("mesh starts at vertex " +
                           std::to_string(first_vertex_) + " but only " +
                           std::to_string(input.size()) +
                           " input vertices are known");
  }
  mesh->vertices.assign(input.begin(), input.begin() + first_vertex_);
  mesh->vertices.insert(mesh->vertices.end(), vertices_.begin(),
                        vertices_.end());
  mesh->triangles = std::move(triangles_);
  if (mesh->vertices.size() != vertex_count ||
      mesh->triangles.size() != triangle_count) {
    return InvalidArgument(
        "incomplete mesh: " + std::to_string(mesh->vertices.size()) +
        " vertices and " + std::to_string(mesh->triangles.size()) +
        " triangles received, the server announced " +
        std::to_string(vertex_count) + " and " +
        std::to_string(triangle_count));
  }
  for (const Triangle& t : mesh->triangles) {
    for (int32_t v : t) {
      if (v < 0 || static_cast<size_t>(v) >= mesh->vertices.size()) {
        return InvalidArgument("mesh triangle refers to vertex " +
                               std::to_string(v));
      }
    }
  }
  return OkStatus();
}

grpc::StatusCode ToGrpcCode(StatusCode code) {
  switch (code) {
    case StatusCode::kOk:
      return grpc::StatusCode::OK;
    case StatusCode::kNoTriangulation:
      return grpc::StatusCode::OK;
    case StatusCode::kInvalidArgument:
      return grpc::StatusCode::INVALID_ARGUMENT;
    case StatusCode::kResourceExhausted:
      return grpc::StatusCode::RESOURCE_EXHAUSTED;
    case StatusCode::kCancelled:
      return grpc::StatusCode::CANCELLED;
    case StatusCode::kDeadlineExceeded:
      return grpc::StatusCode::DEADLINE_EXCEEDED;
    case StatusCode::kInternal:
      return grpc::StatusCode::INTERNAL;
  }
  return grpc::StatusCode::UNKNOWN;
}

grpc::Status ToGrpcStatus(const Status& s) {
  return {ToGrpcCode(s.code), s.message};
}

std::string_view GrpcCodeName(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK:
      return "OK";
    case grpc::StatusCode::CANCELLED:
      return "CANCELLED";
    case grpc::StatusCode::UNKNOWN:
      return "UNKNOWN";
    case grpc::StatusCode::INVALID_ARGUMENT:
      return "INVALID_ARGUMENT";
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return "DEADLINE_EXCEEDED";
    case grpc::StatusCode::NOT_FOUND:
      return "NOT_FOUND";
    case grpc::StatusCode::ALREADY_EXISTS:
      return "ALREADY_EXISTS";
    case grpc::StatusCode::PERMISSION_DENIED:
      return "PERMISSION_DENIED";
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return "RESOURCE_EXHAUSTED";
    case grpc::StatusCode::FAILED_PRECONDITION:
      return "FAILED_PRECONDITION";
    case grpc::StatusCode::ABORTED:
      return "ABORTED";
    case grpc::StatusCode::OUT_OF_RANGE:
      return "OUT_OF_RANGE";
    case grpc::StatusCode::UNIMPLEMENTED:
      return "UNIMPLEMENTED";
    case grpc::StatusCode::INTERNAL:
      return "INTERNAL";
    case grpc::StatusCode::UNAVAILABLE:
      return "UNAVAILABLE";
    case grpc::StatusCode::DATA_LOSS:
      return "DATA_LOSS";
    case grpc::StatusCode::UNAUTHENTICATED:
      return "UNAUTHENTICATED";
    default:
      return "UNKNOWN";
  }
}

}  // namespace dot::wire
