//! CGAL 5.5's 2D meshers through a `cxx` bridge (C++ side: `cpp/cgal_shim.cc`): `cgal` is
//! `Delaunay_mesher_2` with `Delaunay_mesh_size_criteria_2(b, S)`, `cgal-conforming` is the
//! conforming Delaunay triangulation of `make_conforming_Delaunay_2` (CGAL manual, "2D
//! Conforming Triangulations and Meshes"). CGAL's shape bound is b = sin²θ for a smallest angle
//! θ (termination guaranteed up to b = 0.125, θ = 20.7°) and its size bound S is an edge length.
//!
//! Only plain data crosses the bridge: flat coordinates, index pairs and one result struct.
//! Every bridged function returns `Result`, so a C++ exception (CGAL's precondition failures
//! included: the shim is compiled with them on) becomes `Error::Mesher`.

use std::borrow::Cow;
use std::time::{Duration, Instant};

use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{Budget, MeshRun, Mesher, Params, StopReason};
use crate::quality::Bounds;

#[cxx::bridge(namespace = "hexmesh::cgal")]
pub mod ffi {
    /// Refinement budget; `u64::MAX` and `f64::INFINITY` mean no limit.
    #[derive(Debug, Clone, Copy, PartialEq)]
    struct Limits {
        /// Inserted Steiner points.
        max_steps: u64,
        /// Vertices of the whole triangulation, in and out of the domain.
        max_vertices: u64,
        /// Wall-clock seconds since the call began, insertion of the input included.
        max_seconds: f64,
    }

    /// A mesh as flat arrays: `vertices` x0,y0,x1,y1,... with the input points first in input
    /// order, `triangles` three counter-clockwise vertex indices each.
    #[derive(Debug, Clone, PartialEq)]
    struct CgalMesh {
        vertices: Vec<f64>,
        triangles: Vec<u32>,
        /// Steiner points inserted.
        steps: u64,
        /// The budget that stopped the refinement: 0 none (complete), 1 steps, 2 vertices,
        /// 3 time.
        stopped_by: u8,
    }

    unsafe extern "C++" {
        include!("hexmesh/cpp/cgal_shim.h");

        /// CGAL's version string (`CGAL_VERSION_STR`).
        fn version() -> Result<String>;

        /// `Delaunay_mesher_2` with shape bound b = sin²θ and edge-length bound S (0: none),
        /// hole seeds as the mesher's seeds; returns the faces in the domain.
        fn mesh_delaunay(
            points: &[f64],
            segments: &[u32],
            holes: &[f64],
            shape_bound: f64,
            size_bound: f64,
            limits: &Limits,
        ) -> Result<CgalMesh>;

        /// Conforming Delaunay triangulation; the domain is the odd nesting levels of the
        /// constraint loops minus the regions of the hole seeds.
        fn mesh_conforming(
            points: &[f64],
            segments: &[u32],
            holes: &[f64],
            limits: &Limits,
        ) -> Result<CgalMesh>;
    }
}

/// CGAL's default shape bound, b = 0.125 (θ ≈ 20.7°): the largest with guaranteed termination.
pub const DEFAULT_SHAPE_BOUND: f64 = 0.125;

/// The minimum angle of `DEFAULT_SHAPE_BOUND`, degrees: b = sin²θ.
fn default_min_angle() -> f64 {
    DEFAULT_SHAPE_BOUND.sqrt().asin().to_degrees()
}

/// CGAL's version string, e.g. "5.5.1".
pub fn cgal_version() -> String {
    ffi::version().unwrap_or_else(|e| format!("unknown ({})", e.what()))
}

/// CGAL's shape bound for a smallest angle of `degrees`: b = sin²θ (in 5.5.1 a face is bad
/// when the squared sine of its smallest angle is below b).
pub fn shape_bound(degrees: f64) -> f64 {
    degrees.to_radians().sin().powi(2)
}

/// CGAL's size bound for a maximum triangle area `area`: the edge length of the equilateral
/// triangle of that area, S = sqrt(4A/√3). Every triangle whose longest edge is at most S has
/// area at most A, since the equilateral one has the largest area for a given longest edge.
pub fn size_bound(area: f64) -> f64 {
    (4.0 * area / 3f64.sqrt()).sqrt()
}

/// The budget as the bridge's plain struct.
pub fn limits(budget: &Budget) -> ffi::Limits {
    ffi::Limits {
        max_steps: budget.max_steps.unwrap_or(u64::MAX),
        max_vertices: budget
            .max_vertices
            .map_or(u64::MAX, |v| u64::try_from(v).unwrap_or(u64::MAX)),
        max_seconds: budget.max_time.map_or(f64::INFINITY, |t| t.as_secs_f64()),
    }
}

/// The domain CGAL meshes: a PSLG as given; a point set in its bounding hexagon
/// (`Pslg::reference_domain`, corners appended after the input points). Without enclosing
/// constraints CGAL's refinement would insert circumcentres outside the convex hull and need
/// not stop.
fn domain(input: &Pslg) -> Cow<'_, Pslg> {
    if input.has_segments() {
        Cow::Borrowed(input)
    } else {
        Cow::Owned(input.reference_domain())
    }
}

/// A domain (see `domain`) as the bridge's flat arrays: coordinates, segment index pairs,
/// hole coordinates.
fn flatten(input: &Pslg) -> (Vec<f64>, Vec<u32>, Vec<f64>) {
    let points = input.points.iter().flatten().copied().collect();
    let segments = input.segments.iter().flatten().copied().collect();
    let holes = input.holes.iter().flatten().copied().collect();
    (points, segments, holes)
}

/// Turns the bridge's result into a `MeshRun`, or its exception into `Error::Mesher`.
fn finish(
    mesher: &str,
    result: std::result::Result<ffi::CgalMesh, cxx::Exception>,
    elapsed: Duration,
    budget: &Budget,
) -> Result<MeshRun> {
    let out = result.map_err(|e| Error::mesher(mesher, format!("CGAL: {}", e.what())))?;
    let mesh = TriMesh {
        vertices: out.vertices.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        triangles: out
            .triangles
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    };
    let unlimited = || Error::mesher(mesher, "CGAL stopped by a budget that was not set");
    let stop_reason = match out.stopped_by {
        0 => None,
        1 => Some(StopReason::Steps(budget.max_steps.ok_or_else(unlimited)?)),
        2 => Some(StopReason::Vertices(
            budget.max_vertices.ok_or_else(unlimited)?,
        )),
        3 => Some(StopReason::Time(budget.max_time.ok_or_else(unlimited)?)),
        code => {
            return Err(Error::mesher(
                mesher,
                format!("CGAL returned stop code {code}"),
            ))
        }
    };
    Ok(MeshRun {
        mesh,
        complete: stop_reason.is_none(),
        stop_reason,
        steps: out.steps,
        elapsed,
    })
}

/// `cgal`: CGAL's Delaunay mesher (Delaunay refinement with Gabriel-conforming segments).
#[derive(Debug, Clone, Copy, Default)]
pub struct Cgal;

impl Cgal {
    /// CGAL's (b, S) for `params`: b = sin²θ (default 0.125), S = sqrt(4A/√3) for a maximum
    /// area A, or the maximum edge length L, the smaller of the two (0: none). S bounds every
    /// triangle's longest edge.
    pub fn criteria(&self, params: &Params) -> Result<(f64, f64)> {
        let b = match params.min_angle {
            None => DEFAULT_SHAPE_BOUND,
            Some(deg) if deg.is_finite() && (0.0..60.0).contains(&deg) => shape_bound(deg),
            Some(deg) => {
                return Err(Error::mesher(
                    self.name(),
                    format!("minimum angle {deg}° is outside [0°, 60°)"),
                ))
            }
        };
        let area = match params.max_area {
            None => None,
            Some(a) if a.is_finite() && a > 0.0 => Some(size_bound(a)),
            Some(a) => {
                return Err(Error::mesher(
                    self.name(),
                    format!("maximum area {a} is not a positive finite number"),
                ))
            }
        };
        let edge = match params.max_edge {
            None => None,
            Some(l) if l.is_finite() && l > 0.0 => Some(l),
            Some(l) => {
                return Err(Error::mesher(
                    self.name(),
                    format!("maximum edge length {l} is not a positive finite number"),
                ))
            }
        };
        let s = area.into_iter().chain(edge).reduce(f64::min).unwrap_or(0.0);
        Ok((b, s))
    }
}

impl Mesher for Cgal {
    fn name(&self) -> &'static str {
        "cgal"
    }

    fn version(&self) -> String {
        format!("CGAL {}", cgal_version())
    }

    fn settings(&self, params: &Params) -> String {
        let (b, s) = match self.criteria(params) {
            Ok(c) => c,
            Err(e) => return format!("invalid: {e}"),
        };
        let angle = match params.min_angle {
            Some(deg) => format!("b = sin²({deg}°) = {b}"),
            None => format!("b = {b} (CGAL default, θ = 20.7°)"),
        };
        let size = match (params.max_area, params.max_edge) {
            (Some(a), None) => format!(
                "S = {s} (edge length of the equilateral triangle of area A = {a}: sqrt(4A/√3))"
            ),
            (Some(a), Some(l)) => {
                format!("S = {s} (the smaller of the maximum edge {l} and sqrt(4A/√3) for A = {a})")
            }
            (None, Some(l)) => format!("S = {s} (the maximum edge {l})"),
            (None, None) => "S = 0 (no size bound)".to_string(),
        };
        format!(
            "Delaunay_mesh_size_criteria_2({angle}; {size}); point sets meshed in their \
             bounding hexagon; CGAL preconditions on"
        )
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        // The size bound S keeps every edge at most S long, so every area at most √3/4·S².
        super::asked_angle(self.name(), params, default_min_angle())
            .with_size_limits(params.max_area, params.max_edge)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        // Every mesher checks its input (`Pslg::check`): segments that enclose no region,
        // and a segment or point outside the region, are refused here as by ours.
        input.validate_input()?;
        params.refuse_switches(self.name())?;
        // The regions' area limits are kept with the smallest of them everywhere.
        let params = &Params {
            max_area: input.smallest_area_limit(params.max_area),
            ..params.clone()
        };
        let (b, s) = self.criteria(params)?;
        let domain = domain(input);
        crate::reference::check_scale(self.name(), &domain)?;
        let start = Instant::now();
        let (points, segments, holes) = flatten(&domain);
        let result = ffi::mesh_delaunay(&points, &segments, &holes, b, s, &limits(&params.budget));
        finish(self.name(), result, start.elapsed(), &params.budget)
    }
}

/// `cgal-conforming`: CGAL's conforming Delaunay triangulation of the domain (segments split
/// until every edge is Delaunay), without angle or size refinement.
#[derive(Debug, Clone, Copy, Default)]
pub struct CgalConforming;

impl Mesher for CgalConforming {
    fn name(&self) -> &'static str {
        "cgal-conforming"
    }

    fn version(&self) -> String {
        format!("CGAL {}", cgal_version())
    }

    fn settings(&self, params: &Params) -> String {
        let mut s = String::from(
            "make_conforming_Delaunay_2 (no angle or size refinement); domain: odd nesting \
             levels of the segment loops minus hole regions, point sets in their bounding \
             hexagon; CGAL preconditions on",
        );
        if params.min_angle.is_some() || params.max_area.is_some() {
            s.push_str("; min angle and max area ignored");
        }
        s
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, _: &Params) -> Bounds {
        Bounds::conforming_delaunay(self.name())
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        // Every mesher checks its input (`Pslg::check`): segments that enclose no region,
        // and a segment or point outside the region, are refused here as by ours.
        input.validate_input()?;
        hexmesh_core::mesher::refuse_area_limits(self.name(), input)?;
        params.refuse_switches(self.name())?;
        params.refuse_max_edge(
            self.name(),
            "make_conforming_Delaunay_2 has no size criterion (cgal's Delaunay_mesh_size_criteria_2 has)",
        )?;
        let domain = domain(input);
        crate::reference::check_scale(self.name(), &domain)?;
        let start = Instant::now();
        let (points, segments, holes) = flatten(&domain);
        let result = ffi::mesh_conforming(&points, &segments, &holes, &limits(&params.budget));
        finish(self.name(), result, start.elapsed(), &params.budget)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_bound_of_the_default_angle_is_cgal_default() {
        // CGAL documents b = 0.125 as 20.7°: asin(sqrt(0.125)) = 20.705°.
        let deg = default_min_angle();
        assert!((deg - 20.705).abs() < 1e-3, "{deg}");
        assert!((shape_bound(30.0) - 0.25).abs() < 1e-15);
    }

    #[test]
    fn size_bound_is_the_edge_of_the_equilateral_triangle_of_that_area() {
        let s = size_bound(0.5);
        let area = 3f64.sqrt() / 4.0 * s * s;
        assert!((area - 0.5).abs() < 1e-15, "{area}");
    }

    #[test]
    fn bad_angles_and_areas_are_refused_before_cgal_runs() {
        for p in [
            Params::default().with_min_angle(60.0),
            Params::default().with_min_angle(f64::NAN),
            Params::default().with_max_area(0.0),
            Params::default().with_max_area(f64::INFINITY),
        ] {
            assert!(
                matches!(Cgal.criteria(&p), Err(Error::Mesher { .. })),
                "{p:?}"
            );
        }
    }

    #[test]
    fn version_is_cgal_5() {
        assert!(cgal_version().starts_with("5."), "{}", cgal_version());
    }
}
