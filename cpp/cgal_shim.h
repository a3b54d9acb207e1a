// The C++ side of the CGAL bridge (src/reference/cgal/mod.rs): free functions over plain data.
// No CGAL type appears here, so only cgal_shim.cc pays for CGAL's headers (one translation unit).
#pragma once

#include <cstdint>
#include <exception>

#include "rust/cxx.h"

namespace hexmesh {
namespace cgal {

// Shared structs, defined by the cxx bridge.
struct Limits;
struct CgalMesh;

// CGAL_VERSION_STR of the headers this was compiled against.
rust::String version();

// CGAL's Delaunay mesher (Delaunay_mesher_2 with Delaunay_mesh_size_criteria_2(shape_bound,
// size_bound)), run step by step under `limits`. Points are x0,y0,x1,y1,...; segments are
// index pairs; holes are seed points whose regions are not meshed.
CgalMesh mesh_delaunay(rust::Slice<const double> points, rust::Slice<const std::uint32_t> segments,
                       rust::Slice<const double> holes, double shape_bound, double size_bound,
                       const Limits &limits);

// CGAL's conforming Delaunay triangulation (Triangulation_conformer_2, the algorithm of
// make_conforming_Delaunay_2), run step by step under `limits`; the domain is marked by
// nesting-level parity of the constraint loops, minus the regions of the hole seeds.
CgalMesh mesh_conforming(rust::Slice<const double> points,
                         rust::Slice<const std::uint32_t> segments,
                         rust::Slice<const double> holes, const Limits &limits);

} // namespace cgal
} // namespace hexmesh

// Every bridged function returns Result on the Rust side; this catches what CGAL throws
// (Failure_exception and its subclasses, Intersection_of_constraints_exception, std::bad_alloc)
// and anything not derived from std::exception, so no exception unwinds into Rust.
namespace rust {
namespace behavior {
template <typename Try, typename Fail>
static void trycatch(Try &&func, Fail &&fail) noexcept try {
  func();
} catch (const std::exception &e) {
  fail(e.what());
} catch (...) {
  fail("unknown C++ exception");
}
} // namespace behavior
} // namespace rust
