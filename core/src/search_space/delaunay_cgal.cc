// SPDX-License-Identifier: AGPL-3.0-or-later
// The CGAL Delaunay backend. Points are inserted in spatial-sort order (what
// CGAL's range insert does) but by our own loop, so cancel and deadline are
// honoured inside the tetrahedralization too. Large inputs are inserted by
// several threads as CGAL's parallel range insert does (a lock grid over the
// bounding box; a thread retries a point whose conflict zone another thread
// holds), in batches between which the calling thread polls and reports
// progress.
#include "search_space/delaunay_cgal.h"

// The cells and vertices of a sequential tetrahedralization live in a
// BlockArena (huge pages, freed all at once): CGAL's containers allocate
// through CGAL_ALLOCATOR, which here gives ArenaAllocator to the types
// wrapped in InArena below and std::allocator, CGAL's default, to every
// other type, so no CGAL type changes for the rest of the program.
#include <memory>
#include <type_traits>

#include "util/block_arena.h"
namespace dot {
namespace {
template <typename T>
struct UsesBlockArena : std::false_type {};
template <typename T>
using CgalAllocator = std::conditional_t<UsesBlockArena<T>::value,
                                         ArenaAllocator<T>, std::allocator<T>>;
static_assert(std::is_same_v<CgalAllocator<int>, std::allocator<int>>);
}  // namespace
}  // namespace dot
#ifdef CGAL_ALLOCATOR
#error "a CGAL header came first: CGAL_ALLOCATOR must be defined before any"
#endif
#define CGAL_ALLOCATOR(T) ::dot::CgalAllocator<T>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <new>
#include <string>
#include <utility>

#include "util/run_control.h"

namespace dot {
namespace {

// A vertex or cell base whose objects CGAL allocates in the BlockArena.
template <typename Base>
struct InArena : Base {
  using Base::Base;
  template <typename Tds>
  struct Rebind_TDS {
    using Other = InArena<typename Base::template Rebind_TDS<Tds>::Other>;
  };
};

template <typename Base>
struct UsesBlockArena<InArena<Base>> : std::true_type {};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int32_t, Kernel>;
using SequentialDelaunay = CGAL::Delaunay_triangulation_3<
    Kernel,
    CGAL::Triangulation_data_structure_3<
        InArena<VertexBase>, InArena<CGAL::Triangulation_ds_cell_base_3<>>>>;
using ParallelDelaunay = CGAL::Delaunay_triangulation_3<
    Kernel, CGAL::Triangulation_data_structure_3<
                VertexBase, CGAL::Delaunay_triangulation_cell_base_3<Kernel>,
                CGAL::Parallel_tag>>;
using IndexedPoint = std::pair<Kernel::Point_3, int32_t>;

// Points inserted by the calling thread alone before threads join: they
// need a 3D triangulation to lock regions of, and CGAL does the same.
constexpr size_t kSequentialPoints = 500;
// Parallel batches grow from the first to the largest size: polls between
// batches stay frequent while the triangulation is small.
constexpr size_t kFirstBatch = 1000;
constexpr size_t kLargestBatch = 32000;
// Workers check for cancel and deadline themselves every this many points.
constexpr size_t kWorkerPollStride = 64;

// The memory a tetrahedralization of `cells` cells stands for: its own
// cells, the faces read off it (two per cell), and the smallest tables a
// solve over those faces needs. Past the budget the insertion stops: on
// cospherical input (the moment curve) the cells grow as n^2 and would
// take gigabytes before any table is allocated.
template <typename Delaunay>
struct CellBudget {
  int64_t budget_bytes;
  int64_t Bytes(int64_t cells) const {
    const int64_t structure =
        cells * static_cast<int64_t>(sizeof(typename Delaunay::Cell) +
                                     2 * sizeof(Triangle));
    return std::max(structure, EstimateTableBytes(2 * cells, false));
  }
  bool Exceeded(const Delaunay& dt) const {
    return Bytes(static_cast<int64_t>(dt.number_of_cells())) > budget_bytes;
  }
  Status Refusal(const Delaunay& dt, size_t inserted, size_t total) const {
    const int64_t cells = static_cast<int64_t>(dt.number_of_cells());
    return MakeStatus(
        StatusCode::kResourceExhausted,
        "the Delaunay tetrahedralization outgrew the memory budget: " +
            std::to_string(cells) + " cells after " + std::to_string(inserted) +
            " of " + std::to_string(total) + " points need about " +
            std::to_string(Bytes(cells) >> 20) +
            " MiB with their faces and tables, which exceeds the budget of " +
            std::to_string(budget_bytes >> 20) + " MiB");
  }
};

std::vector<IndexedPoint> SpatiallySorted(const std::vector<Vec3>& points) {
  std::vector<IndexedPoint> sorted;
  sorted.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    sorted.emplace_back(Kernel::Point_3(p.x, p.y, p.z),
                        static_cast<int32_t>(i));
  }
  using Traits = CGAL::Spatial_sort_traits_adapter_3<
      Kernel, CGAL::First_of_pair_property_map<IndexedPoint>>;
  CGAL::spatial_sort(sorted.begin(), sorted.end(), Traits());
  return sorted;
}

// Inserts sorted[*next, ...) on this thread until `enough` says stop (or
// the points run out), polling every 64 points: one insertion can cost
// thousands of new cells on cospherical input. `last` is the vertex of the
// last point inserted.
template <typename Delaunay, typename Enough>
Status InsertOnThisThread(const std::vector<IndexedPoint>& sorted,
                          Enough enough, const CellBudget<Delaunay>& budget,
                          RunTicker* ticker, size_t* next,
                          typename Delaunay::Vertex_handle* last,
                          Delaunay* dt) {
  const double count = static_cast<double>(sorted.size());
  typename Delaunay::Cell_handle hint;
  for (size_t& k = *next; k < sorted.size() && !enough(k); ++k) {
    if (k % 64 == 0) {
      if (!ticker->Poll(static_cast<double>(k) / count)) {
        return ticker->status();
      }
      if (budget.Exceeded(*dt)) return budget.Refusal(*dt, k, sorted.size());
    }
    *last = dt->insert(sorted[k].first, hint);
    (*last)->info() = sorted[k].second;
    hint = (*last)->cell();
  }
  return OkStatus();
}

// Inserts sorted[first, last) on the arena's threads. A worker that finds
// the run stopped (cancel, deadline) leaves its remaining points and sets
// `abandoned`.
void InsertBatch(
    const std::vector<IndexedPoint>& sorted, size_t first, size_t last,
    const Control& control, const CellBudget<ParallelDelaunay>& budget,
    tbb::enumerable_thread_specific<ParallelDelaunay::Vertex_handle>* hints,
    std::atomic<bool>* abandoned, ParallelDelaunay* dt) {
  tbb::parallel_for(
      tbb::blocked_range<size_t>(first, last),
      [&](const tbb::blocked_range<size_t>& range) {
        ParallelDelaunay::Vertex_handle& hint = hints->local();
        for (size_t k = range.begin(); k != range.end(); ++k) {
          if ((k - range.begin()) % kWorkerPollStride == 0 &&
              (abandoned->load() || StopRequested(control) ||
               budget.Exceeded(*dt))) {
            abandoned->store(true);
            return;
          }
          const Kernel::Point_3& p = sorted[k].first;
          // CGAL's parallel insertion protocol: lock the hint and the
          // point's grid cell, insert if the conflict zone could be locked
          // too, release everything, retry otherwise.
          for (bool inserted = false; !inserted;) {
            if (dt->try_lock_vertex(hint) && dt->try_lock_point(p)) {
              const ParallelDelaunay::Vertex_handle v =
                  dt->insert(p, hint, &inserted);
              if (inserted) {
                v->info() = sorted[k].second;
                hint = v;
              }
            }
            dt->unlock_all_elements();
          }
        }
      });
}

Status ParallelInsert(const std::vector<IndexedPoint>& sorted, int threads,
                      const Control& control,
                      const CellBudget<ParallelDelaunay>& budget,
                      RunTicker* ticker, ParallelDelaunay* dt) {
  // Alone first, until the triangulation is 3D and has some size.
  size_t next = 0;
  ParallelDelaunay::Vertex_handle last_vertex;
  Status s = InsertOnThisThread(
      sorted,
      [dt](size_t k) { return k >= kSequentialPoints && dt->dimension() == 3; },
      budget, ticker, &next, &last_vertex, dt);
  if (!s.ok() || next == sorted.size()) return s;
  tbb::enumerable_thread_specific<ParallelDelaunay::Vertex_handle> hints(
      last_vertex);
  std::atomic<bool> abandoned{false};
  tbb::task_arena arena(threads);
  const double count = static_cast<double>(sorted.size());
  for (size_t batch = kFirstBatch; next < sorted.size();
       batch = std::min(2 * batch, kLargestBatch)) {
    if (!ticker->Poll(static_cast<double>(next) / count)) {
      return ticker->status();
    }
    const size_t last = std::min(sorted.size(), next + batch);
    arena.execute([&] {
      InsertBatch(sorted, next, last, control, budget, &hints, &abandoned, dt);
    });
    if (abandoned.load() && budget.Exceeded(*dt)) {
      return budget.Refusal(*dt, last, sorted.size());
    }
    if (abandoned.load()) {
      // The stop a worker saw persists, unless the caller withdrew a
      // cancel: points are missing either way, so the run ends.
      return ticker->Poll()
                 ? MakeStatus(StatusCode::kCancelled, "cancelled by the caller")
                 : ticker->status();
    }
    next = last;
  }
  return OkStatus();
}

template <typename Delaunay>
Status CheckComplete(size_t point_count, const Delaunay& dt) {
  if (dt.number_of_vertices() != point_count) {
    return InvalidArgument(
        std::to_string(point_count - dt.number_of_vertices()) +
        " vertices coincide with others");
  }
  if (dt.dimension() < 3) {
    return InvalidArgument("the polygon's vertices are coplanar");
  }
  return OkStatus();
}

template <typename Delaunay>
Status ReadFaces(const Delaunay& dt, RunTicker* ticker,
                 std::vector<Triangle>* faces, int64_t* tetrahedra) {
  *tetrahedra = static_cast<int64_t>(dt.number_of_finite_cells());
  faces->clear();
  faces->reserve(2 * dt.number_of_cells());
  int64_t work = 0;
  for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
    if (!ticker->Advance(work, 1)) return ticker->status();
    const typename Delaunay::Cell_handle c = f->first;
    const int i = f->second;
    Triangle t = {c->vertex((i + 1) & 3)->info(),
                  c->vertex((i + 2) & 3)->info(),
                  c->vertex((i + 3) & 3)->info()};
    std::sort(t.begin(), t.end());
    faces->push_back(t);
  }
  return OkStatus();
}

// Threads for `points` points: 1 below the threshold or when asked for.
int ThreadsFor(size_t points, const Options& options) {
  if (static_cast<int64_t>(points) < options.parallel_delaunay_min_points) {
    return 1;
  }
  return options.delaunay_threads > 0 ? options.delaunay_threads
                                      : tbb::info::default_concurrency();
}

Status Faces(const std::vector<Vec3>& points, const Options& options,
             const Control& control, std::vector<Triangle>* faces,
             int64_t* tetrahedra) {
  const std::vector<IndexedPoint> sorted = SpatiallySorted(points);
  RunTicker ticker(control, Stage::kDelaunay);
  const int threads = ThreadsFor(points.size(), options);
  if (threads <= 1) {
    BlockArena arena;  // outlives dt, whose cells it holds; dt is never
                       // copied or moved out of this scope
    SequentialDelaunay dt;
    size_t next = 0;
    SequentialDelaunay::Vertex_handle last;
    Status s = InsertOnThisThread(
        sorted, [](size_t) { return false; },
        CellBudget<SequentialDelaunay>{options.memory_budget_bytes}, &ticker,
        &next, &last, &dt);
    if (s.ok()) s = CheckComplete(points.size(), dt);
    if (s.ok()) s = ReadFaces(dt, &ticker, faces, tetrahedra);
    return s;
  }
  CGAL::Bbox_3 box;
  for (const IndexedPoint& p : sorted) box += p.first.bbox();
  ParallelDelaunay::Lock_data_structure locks(box, 50);
  ParallelDelaunay dt(&locks);
  Status s = ParallelInsert(
      sorted, threads, control,
      CellBudget<ParallelDelaunay>{options.memory_budget_bytes}, &ticker, &dt);
  if (s.ok()) s = CheckComplete(points.size(), dt);
  if (s.ok()) s = ReadFaces(dt, &ticker, faces, tetrahedra);
  return s;
}

}  // namespace

Status CgalDelaunayFaces(const std::vector<Vec3>& points,
                         const Options& options, const Control& control,
                         std::vector<Triangle>* faces, int64_t* tetrahedra) {
  try {
    return Faces(points, options, control, faces, tetrahedra);
  } catch (const std::bad_alloc&) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "CGAL's Delaunay tetrahedralization ran out of memory "
                      "on " +
                          std::to_string(points.size()) + " points");
  }
}

int AffineDimension(const std::vector<Vec3>& points) {
  auto point = [&](size_t i) {
    return Kernel::Point_3(points[i].x, points[i].y, points[i].z);
  };
  size_t i = 1;
  while (i < points.size() && point(i) == point(0)) ++i;
  if (i == points.size()) return 0;
  const size_t second = i;
  while (i < points.size() &&
         CGAL::collinear(point(0), point(second), point(i))) {
    ++i;
  }
  if (i == points.size()) return 1;
  const size_t third = i;
  while (i < points.size() &&
         CGAL::coplanar(point(0), point(second), point(third), point(i))) {
    ++i;
  }
  return i == points.size() ? 2 : 3;
}

}  // namespace dot
