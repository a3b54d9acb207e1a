// CGAL 5.5's 2D meshers behind plain data (CGAL manual, "2D Conforming Triangulations and
// Meshes" by L. Rineau: Delaunay_mesher_2 and Triangulation_conformer_2 and their step API).
// The refinement loops are driven one inserted point at a time so that a step, vertex and time
// budget can stop them: CGAL guarantees termination only for b <= 0.125 (20.7 degrees).
//
// Compiled without NDEBUG/CGAL_NDEBUG on purpose: CGAL's preconditions then throw
// CGAL::Precondition_exception on input they cannot handle instead of running into undefined
// behaviour, and the bridge turns the exception into a Rust error. Measured cost (opt-level 2,
// 100,000 random points in their bounding hexagon, 30 degrees, 866,156 triangles, plus the
// conforming triangulation of the same; user time over three runs on a busy 2-core machine):
// 3.4-4.1 s with the preconditions, 3.8-3.9 s with -DCGAL_NDEBUG, so no cost above the noise.

#include "hexmesh/cpp/cgal_shim.h"
#include "hexmesh/src/reference/cgal/mod.rs.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_conformer_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/version.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace hexmesh {
namespace cgal {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Crossing constraints would need constructed intersection points; this tag makes CGAL throw
// instead, so that a crossing input is an error rather than a silently different domain.
using Itag = CGAL::No_constraint_intersection_requiring_constructions_tag;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, Itag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Mesher = CGAL::Delaunay_mesher_2<CDT, Criteria>;
using Conformer = CGAL::Triangulation_conformer_2<CDT>;
using Point = CDT::Point;
using Vertex_handle = CDT::Vertex_handle;
using Face_handle = CDT::Face_handle;
using Clock = std::chrono::steady_clock;

std::vector<Point> read_points(rust::Slice<const double> coords, const char *what) {
  if (coords.size() % 2 != 0) {
    std::ostringstream msg;
    msg << what << ": " << coords.size() << " coordinates is not a whole number of points";
    throw std::invalid_argument(msg.str());
  }
  std::vector<Point> points;
  points.reserve(coords.size() / 2);
  for (std::size_t i = 0; i < coords.size(); i += 2) {
    // A NaN reaching the exact fallback of the kernel aborts inside GMP, so refuse it here.
    if (!std::isfinite(coords[i]) || !std::isfinite(coords[i + 1])) {
      std::ostringstream msg;
      msg << what << " " << i / 2 << " has a non-finite coordinate";
      throw std::invalid_argument(msg.str());
    }
    points.emplace_back(coords[i], coords[i + 1]);
  }
  return points;
}

// Inserts the points as a range (spatially sorted, each insertion starting from the previous
// vertex's face), then the constraints between the returned vertex handles. Returns the handle
// of every input point, in input order.
std::vector<Vertex_handle> build_domain(CDT &cdt, const std::vector<Point> &points,
                                        rust::Slice<const std::uint32_t> segments) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Pmap = CGAL::Pointer_property_map<Point>::const_type;
  using Sort_traits = CGAL::Spatial_sort_traits_adapter_2<K, Pmap>;
  CGAL::spatial_sort(order.begin(), order.end(), Sort_traits(CGAL::make_property_map(points)));

  std::vector<Vertex_handle> handles(points.size());
  std::unordered_map<const void *, std::size_t> index_of;
  Face_handle hint;
  for (std::size_t i : order) {
    const std::size_t before = cdt.number_of_vertices();
    Vertex_handle v = cdt.insert(points[i], hint);
    if (cdt.number_of_vertices() == before) {
      const std::size_t other = index_of.at(&*v);
      std::ostringstream msg;
      msg << "points " << std::min(i, other) << " and " << std::max(i, other)
          << " are duplicates";
      throw std::invalid_argument(msg.str());
    }
    index_of.emplace(&*v, i);
    handles[i] = v;
    hint = v->face();
  }

  if (segments.size() % 2 != 0) {
    throw std::invalid_argument("segments: an odd number of vertex indices");
  }
  for (std::size_t s = 0; s < segments.size(); s += 2) {
    const std::uint32_t a = segments[s], b = segments[s + 1];
    if (a >= handles.size() || b >= handles.size()) {
      std::ostringstream msg;
      msg << "segment " << s / 2 << " names vertex " << std::max(a, b) << ", but there are only "
          << handles.size() << " points";
      throw std::invalid_argument(msg.str());
    }
    if (a == b) {
      std::ostringstream msg;
      msg << "segment " << s / 2 << " joins a vertex to itself";
      throw std::invalid_argument(msg.str());
    }
    cdt.insert_constraint(handles[a], handles[b]);
  }
  return handles;
}

// The budget from Rust, with the clock started when the bridged call began.
class Budget {
public:
  Budget(const Limits &limits, Clock::time_point start) : limits_(limits), start_(start) {}

  // False while refinement may go on; otherwise true, with the budget that ran out in
  // `stopped_by` (the codes of `CgalMesh::stopped_by`). Called once per step.
  bool exhausted(std::uint64_t steps, std::size_t vertices, std::uint8_t &stopped_by) const {
    const bool by_steps = steps >= limits_.max_steps;
    const bool by_vertices = !by_steps && vertices >= limits_.max_vertices;
    const bool by_time = !by_steps && !by_vertices &&
                         limits_.max_seconds < std::numeric_limits<double>::infinity() &&
                         std::chrono::duration<double>(Clock::now() - start_).count() >=
                             limits_.max_seconds;
    if (!by_steps && !by_vertices && !by_time) return false;
    stopped_by = by_steps ? 1 : by_vertices ? 2 : 3;
    return true;
  }

private:
  const Limits &limits_;
  Clock::time_point start_;
};

// Vertices: every input point first, in input order (so they are found by index and are
// bit-exact: CGAL stores inserted points unchanged), then the Steiner points that the returned
// faces use, in face order. Faces of a CDT are counter-clockwise.
template <typename InDomain>
CgalMesh extract(const CDT &cdt, const std::vector<Vertex_handle> &inputs, InDomain in_domain,
                 std::uint64_t steps, std::uint8_t stopped_by) {
  CgalMesh out;
  std::unordered_map<const void *, std::uint32_t> id;
  auto add_vertex = [&](Vertex_handle v) {
    auto [it, fresh] = id.emplace(&*v, static_cast<std::uint32_t>(id.size()));
    if (fresh) {
      out.vertices.push_back(v->point().x());
      out.vertices.push_back(v->point().y());
    }
    return it->second;
  };
  for (Vertex_handle v : inputs) add_vertex(v);
  if (cdt.dimension() == 2) {
    for (Face_handle f : cdt.finite_face_handles()) {
      if (!in_domain(f)) continue;
      for (int k = 0; k < 3; ++k) out.triangles.push_back(add_vertex(f->vertex(k)));
    }
  }
  if (id.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("more than 2^32 vertices");
  }
  out.steps = steps;
  out.stopped_by = stopped_by;
  return out;
}

// Nesting levels as in CGAL's polygon_triangulation example: the infinite face's region is
// level 0, and each constraint crossed from a region of level k leads to level k + 1. Faces of
// odd level are in the domain. Breadth-first over the border queue keeps the levels minimal.
void mark_nesting_parity(CDT &cdt) {
  std::unordered_map<const void *, int> level;
  std::deque<CDT::Edge> border;
  auto flood = [&](Face_handle start, int lvl) {
    if (level.count(&*start)) return;
    std::deque<Face_handle> queue{start};
    level.emplace(&*start, lvl);
    while (!queue.empty()) {
      Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        Face_handle n = f->neighbor(i);
        if (level.count(&*n)) continue;
        if (cdt.is_constrained(CDT::Edge(f, i))) {
          border.emplace_back(f, i);
        } else {
          level.emplace(&*n, lvl);
          queue.push_back(n);
        }
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    CDT::Edge e = border.front();
    border.pop_front();
    Face_handle n = e.first->neighbor(e.second);
    flood(n, level.at(&*e.first) + 1);
  }
  for (Face_handle f : cdt.all_face_handles()) f->set_in_domain(level.at(&*f) % 2 == 1);
}

// Removes from the domain the region around each seed, bounded by constraints (the meaning of
// hole seeds in Triangle's .poly files and in CGAL's mesher seeds).
void remove_seed_regions(CDT &cdt, const std::vector<Point> &seeds) {
  for (const Point &p : seeds) {
    Face_handle start = cdt.locate(p);
    if (start == Face_handle() || cdt.is_infinite(start) || !start->is_in_domain()) continue;
    std::deque<Face_handle> queue{start};
    start->set_in_domain(false);
    while (!queue.empty()) {
      Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        Face_handle n = f->neighbor(i);
        if (!cdt.is_constrained(CDT::Edge(f, i)) && n->is_in_domain()) {
          n->set_in_domain(false);
          queue.push_back(n);
        }
      }
    }
  }
}

} // namespace

rust::String version() { return rust::String(CGAL_VERSION_STR); }

CgalMesh mesh_delaunay(rust::Slice<const double> points, rust::Slice<const std::uint32_t> segments,
                       rust::Slice<const double> holes, double shape_bound, double size_bound,
                       const Limits &limits) {
  const Clock::time_point start = Clock::now();
  // b = sin^2 of the smallest angle; b >= 3/4 would ask for better than equilateral.
  if (!(shape_bound >= 0.0 && shape_bound < 0.75)) {
    throw std::invalid_argument("shape bound b = sin^2(min angle) must be in [0, 0.75)");
  }
  if (!(size_bound >= 0.0) || !std::isfinite(size_bound)) {
    throw std::invalid_argument("size bound must be a finite edge length >= 0 (0: none)");
  }
  const std::vector<Point> input = read_points(points, "point");
  const std::vector<Point> seeds = read_points(holes, "hole");
  CDT cdt;
  const std::vector<Vertex_handle> handles = build_domain(cdt, input, segments);
  if (cdt.dimension() < 2) {
    return extract(cdt, handles, [](Face_handle) { return false; }, 0, 0);
  }

  Mesher mesher(cdt, Criteria(shape_bound, size_bound));
  mesher.set_seeds(seeds.begin(), seeds.end(), false);
  mesher.init();
  const Budget budget(limits, start);
  std::uint64_t steps = 0;
  std::uint8_t stop = 0;
  while (!mesher.is_refinement_done()) {
    if (budget.exhausted(steps, cdt.number_of_vertices(), stop)) break;
    // Each successful call inserts one Steiner point (an edge midpoint or a circumcentre).
    if (!mesher.step_by_step_refine_mesh()) break;
    ++steps;
  }
  return extract(cdt, handles, [](Face_handle f) { return f->is_in_domain(); }, steps, stop);
}

CgalMesh mesh_conforming(rust::Slice<const double> points,
                         rust::Slice<const std::uint32_t> segments,
                         rust::Slice<const double> holes, const Limits &limits) {
  const Clock::time_point start = Clock::now();
  const std::vector<Point> input = read_points(points, "point");
  const std::vector<Point> seeds = read_points(holes, "hole");
  CDT cdt;
  const std::vector<Vertex_handle> handles = build_domain(cdt, input, segments);
  if (cdt.dimension() < 2) {
    return extract(cdt, handles, [](Face_handle) { return false; }, 0, 0);
  }

  // make_conforming_Delaunay_2(cdt) is Conformer::make_conforming_Delaunay(); the same
  // conformer stepped one split at a time can be stopped by the budget.
  Conformer conformer(cdt);
  conformer.init_Delaunay();
  const Budget budget(limits, start);
  std::uint64_t steps = 0;
  std::uint8_t stop = 0;
  while (!conformer.is_conforming_done()) {
    if (budget.exhausted(steps, cdt.number_of_vertices(), stop)) break;
    if (!conformer.step_by_step_conforming_Delaunay()) break;
    ++steps;
  }
  mark_nesting_parity(cdt);
  remove_seed_regions(cdt, seeds);
  return extract(cdt, handles, [](Face_handle f) { return f->is_in_domain(); }, steps, stop);
}

} // namespace cgal
} // namespace hexmesh
