//! The hexagonal Delaunay mesher of Sußner & Greiner, "Hexagonal Delaunay Triangulation"
//! (IMR 2009, paper 000): an adaptive hexagon subdivision of the bounding hexagon (Sec. 3),
//! refined around the input points (Sec. 4.1), whose dual is the mesh (Sec. 4.2).
//!
//! `hex-simple` is the simple refinement: every angle in [30°, 120°] (Sec. 4.3).
//!
//! - `key`: integer keys of hexagons, their children, parents and neighbours (Sec. 3.1).
//! - `lattice`: exact positions of the keys, the bounding-hexagon test.
//! - `keyset`, `keylines`, `fxhash`: containers of lattice keys (ours, not the paper's).
//! - `parallel`: long lists split over the machine's threads (ours, not the paper's).
//! - `subdivision`: split, join, balancing, point location (Sec. 3).
//! - `refine`: refinement rules 1–5 on a work list (Sec. 4.1).
//! - `size`: the maximum area and edge length, kept by subdividing further (ours).
//! - `blossom`: local coarsening into blossoms (Sec. 5.3).
//! - `dual`: the dual triangle mesh (Sec. 4.2).
//! - `pslg`: planar straight-line graphs: segments, holes, the domain (Sec. 7).
//! - `picture`: SVG of the hexagons with the dual over them (Figs. 3, 4, 7).

pub mod blossom;
pub mod classify;
pub mod dual;
pub mod extended;
pub mod fxhash;
pub mod incremental;
pub mod key;
pub mod keylines;
pub mod keyset;
pub mod lattice;
pub mod mc3;
pub(crate) mod parallel;
pub mod picture;
pub mod pslg;
pub mod refine;
pub mod region;
pub mod size;
pub mod subdivision;

use std::time::Instant;

use crate::error::{Error, InputError, Result};
use crate::geom::{Hexagon, Point};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params, StopReason};
use crate::quality::rounding;
use crate::quality::Bounds;

pub use dual::Placement;
pub use incremental::IncrementalHex;
pub use lattice::{Key, Lattice};
pub use picture::{write_hexagons_svg, write_hierarchy_svg};
pub use refine::{insert_points, InsertError};
pub use subdivision::{Cell, Hierarchy, Stop};

/// The simple hexagonal mesher (Sec. 4): angles in [30°, 120°].
#[derive(Debug, Clone, Copy, Default)]
pub struct HexSimple;

impl Mesher for HexSimple {
    fn name(&self) -> &'static str {
        "hex-simple"
    }

    fn version(&self) -> String {
        format!("hexmesh {}", env!("CARGO_PKG_VERSION"))
    }

    fn settings(&self, params: &Params) -> String {
        let mut s = String::from("simple refinement (Sec. 4), angles 30-120 deg");
        size_settings(&mut s, params);
        s
    }

    fn supports_segments(&self) -> bool {
        false
    }

    fn promise(&self, params: &Params) -> Bounds {
        Bounds::angles(self.name(), SIMPLE_ANGLES.0, SIMPLE_ANGLES.1)
            .with_size_limits(params.max_area, params.max_edge)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        params.refuse_switches(self.name())?;
        let start = Instant::now();
        let mut h = new_hierarchy(input, params, "hex-simple")?;
        let progress = params.progress.as_ref();
        crate::progress::phase(progress, "simple refinement");
        let stop = run_simple(&mut h)?;
        let placement = if stop.is_none() {
            Placement::Relocated
        } else {
            Placement::Plain
        };
        crate::progress::phase(progress, "dual");
        let mesh = dual::extract(&h, placement);
        if let Some(t) = dual::first_inverted_over(&mesh, h.threads()) {
            return Err(Error::mesher(
                self.name(),
                format!("internal error: dual triangle {t} is not counter-clockwise"),
            ));
        }
        if stop.is_none() {
            check_rounded_angles(&mesh, &input.points, params.max_rounding_deg(), h.threads())?;
            size::check(&mesh, size::limits(input, params)?, self.name(), |_| true)?;
        }
        Ok(MeshRun {
            mesh,
            complete: stop.is_none(),
            stop_reason: stop,
            steps: h.steps,
            elapsed: start.elapsed(),
        })
    }
}

/// Appends to a hex mesher's settings the size limits it keeps (`size`; a region's area limit
/// is kept too, the smallest one everywhere), and that the minimum angle asked for is not
/// used (the bounds are fixed).
pub(crate) fn size_settings(s: &mut String, params: &Params) {
    if let Some(a) = params.max_area {
        s.push_str(&format!("; max_area {a}"));
    }
    if let Some(l) = params.max_edge {
        s.push_str(&format!("; max_edge {l}"));
    }
    if params.min_angle.is_some() {
        s.push_str("; min_angle not used (fixed bounds)");
    }
}

/// The root of the hex meshers' hierarchy for a point set: the given hexagon, or the fitted
/// one (`Pslg::bounding_hexagon`) turned onto the principal axis of elongated points
/// (`Hexagon::aligned`, `geom::principal_turn`). The turn is these meshers' own: it has the
/// same inscribed circle and area, but a line of points along a lattice direction ends at
/// two edge midpoints, 1e-9 inside the edges, where the references' boundary segments would
/// force them into needless refinement; they mesh the flat-topped hexagon (`reference_domain`).
pub fn root_hexagon(input: &Pslg) -> Hexagon {
    input
        .hexagon
        .unwrap_or_else(|| Hexagon::aligned(&input.points))
}

/// The unrefined hierarchy of a point set, for the mesher called `mesher`: refuses segments,
/// invalid input, a degenerate bounding hexagon, and points not strictly inside it.
pub(crate) fn new_hierarchy(input: &Pslg, params: &Params, mesher: &str) -> Result<Hierarchy> {
    if input.has_segments() {
        return Err(Error::mesher(
            mesher,
            "input segments are not supported; give a point set",
        ));
    }
    input.validate_input()?;
    let root = root_hexagon(input);
    if !(root.circumradius > 0.0 && root.circumradius.is_finite()) {
        return Err(Error::mesher(
            mesher,
            "the bounding hexagon has no positive finite radius",
        ));
    }
    if let Some(i) = input
        .points
        .iter()
        .position(|&p| !root.contains_strictly(p))
    {
        return Err(Error::input(InputError::OutsideHexagon {
            index: i,
            point: input.points[i],
            fitted: input.hexagon.is_none(),
        }));
    }
    let lattice = Lattice::new(root);
    let level = size::level(
        lattice.r0,
        size::limits(input, params)?,
        size::Factors::of(mesher),
        mesher,
    )?;
    let mut h = Hierarchy::new(lattice, input.points.clone(), params.budget);
    h.set_max_rounding(params.max_rounding_deg());
    // `Hierarchy::new` takes every thread the machine has; only a count given changes it.
    if let Some(threads) = params.threads {
        h.set_threads(threads.get());
    }
    h.set_size_level(level);
    Ok(h)
}

/// Runs the simple refinement on a point set and returns the final hierarchy, with the reason
/// it stopped early when a budget ran out. Errors: segments (not supported), points outside
/// the bounding hexagon, points too close together for f64 (`InputError::Range`).
pub fn mesh_with_hierarchy(
    input: &Pslg,
    params: &Params,
) -> Result<(Hierarchy, Option<StopReason>)> {
    let mut h = new_hierarchy(input, params, "hex-simple")?;
    let stop = run_simple(&mut h)?;
    Ok((h, stop))
}

/// Runs the simple refinement, then the subdivisions of the size limits (`size::refine`):
/// `None` when it finished, the reason when a budget stopped it.
fn run_simple(h: &mut Hierarchy) -> Result<Option<StopReason>> {
    match refine::refine_simple(h).and_then(|()| size::refine(h)) {
        Ok(()) => Ok(None),
        Err(Stop::Budget(why)) => Ok(Some(why)),
        Err(Stop::Precision(problem)) => Err(Error::input(problem)),
    }
}

/// The angle bounds of the simple refinement, degrees (Sec. 4.3).
const SIMPLE_ANGLES: (f64, f64) = (30.0, 120.0);

/// The mesh of `hex-simple` against [30°, 120°] (`quality::rounding::check_angles_over`,
/// over `threads` threads: the same verdict for every count).
fn check_rounded_angles(
    mesh: &TriMesh,
    points: &[Point],
    max_rounding: f64,
    threads: usize,
) -> Result<()> {
    rounding::check_angles_over(
        mesh,
        points,
        SIMPLE_ANGLES,
        max_rounding,
        "hex-simple",
        threads,
    )
}

/// The error of a failed insertion into a finished mesh of the mesher `mesher`.
pub(crate) fn insert_error(mesher: &str, e: InsertError) -> Error {
    match e {
        InsertError::NonFinite { point } => Error::mesher(
            mesher,
            format!("added point ({}, {}) is not finite", point[0], point[1]),
        ),
        InsertError::Outside { point } => Error::mesher(
            mesher,
            format!(
                "added point ({}, {}) does not lie strictly inside the bounding hexagon",
                point[0], point[1]
            ),
        ),
        InsertError::Duplicate { point, existing } => Error::mesher(
            mesher,
            format!(
                "added point ({}, {}) duplicates point {existing}",
                point[0], point[1]
            ),
        ),
        InsertError::Stopped(stop) => stop_error(mesher, stop),
    }
}

/// The error of a refinement stopped by a budget or by the precision limit.
pub(crate) fn stop_error(mesher: &str, stop: Stop) -> Error {
    match stop {
        Stop::Budget(why) => Error::mesher(mesher, format!("stopped: {why}")),
        Stop::Precision(problem) => Error::input(problem),
    }
}

/// A finished `hex-simple` mesh that accepts further points and refines only around them
/// (paper 000 Sec. 1 and 9). The bounding hexagon stays the one of the first input, so added
/// points must lie strictly inside it.
#[derive(Debug, Clone)]
pub struct IncrementalHexSimple {
    hierarchy: Hierarchy,
}

impl IncrementalHexSimple {
    /// Meshes `input` (a point set) to completion; a budget that stops the first meshing is an
    /// error here, since a partial hierarchy cannot take more points.
    pub fn new(input: &Pslg, params: &Params) -> Result<IncrementalHexSimple> {
        let (hierarchy, stop) = mesh_with_hierarchy(input, params)?;
        match stop {
            None => Ok(IncrementalHexSimple { hierarchy }),
            Some(why) => Err(Error::mesher("hex-simple", format!("stopped: {why}"))),
        }
    }

    /// Adds points and refines locally. Returns the vertex indices they got in `mesh()`.
    pub fn insert(&mut self, points: &[Point]) -> Result<Vec<u32>> {
        insert_points(&mut self.hierarchy, points).map_err(|e| insert_error("hex-simple", e))
    }

    /// The current mesh: input point i (first the initial points, then the added ones in
    /// order) is vertex i.
    pub fn mesh(&self) -> TriMesh {
        dual::extract(&self.hierarchy, Placement::Relocated)
    }

    /// The subdivision as it stands after the last insertion.
    pub fn hierarchy(&self) -> &Hierarchy {
        &self.hierarchy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_simple_reports_its_two_phases_and_meshes_the_same_bytes() {
        let points = (0..300)
            .map(|i| {
                let i = f64::from(i);
                [(i * 0.618_034).fract(), (i * 0.414_214).fract()]
            })
            .collect();
        let input = Pslg::from_points(points);
        let phases = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
        let progress = {
            let phases = std::sync::Arc::clone(&phases);
            crate::progress::Progress::new(move |e| phases.lock().unwrap().push(e.phase))
        };
        let observed = HexSimple
            .mesh(&input, &Params::default().with_progress(progress))
            .expect("meshes");
        let unobserved = HexSimple.mesh(&input, &Params::default()).expect("meshes");
        assert_eq!(*phases.lock().unwrap(), ["simple refinement", "dual"]);
        let bits = |m: &TriMesh| {
            let v = m.vertices.iter().flat_map(|p| p.map(f64::to_bits));
            (v.collect::<Vec<u64>>(), m.triangles.clone())
        };
        assert_eq!(bits(&observed.mesh), bits(&unobserved.mesh));
    }

    /// A right triangle at `offset` whose angle at the third corner is 30° less `short`
    /// degrees.
    fn thin(offset: f64, short: f64) -> TriMesh {
        let tan = (30.0f64 - short).to_radians().tan();
        TriMesh {
            vertices: vec![
                [offset, offset],
                [offset + 1.0, offset],
                [offset + 1.0, offset + tan],
            ],
            triangles: vec![[0, 1, 2]],
        }
    }

    #[test]
    fn the_rounding_check_refuses_a_mesh_that_uses_more_than_the_largest_rounding() {
        // 30° − 1e-3° at 1e12, where the allowance (about 2e-2°) explains it but the mesh
        // would use more than 1e-4°: refused, naming the input points beside it.
        let mesh = thin(1e12, 1e-3);
        let points = [mesh.vertices[0], mesh.vertices[1]];
        match check_rounded_angles(&mesh, &points, 1e-4, 1) {
            Err(Error::Input {
                problem:
                    crate::error::InputError::Rounding {
                        first: 0,
                        second: 1,
                        needed,
                        allowed,
                        ..
                    },
                ..
            }) => assert!(needed > 9e-4 && allowed == 1e-4, "{needed}"),
            other => panic!("expected a rounding refusal, got {other:?}"),
        }
        // Allowed 0.01°, the same mesh passes.
        assert!(check_rounded_angles(&mesh, &points, 0.01, 1).is_ok());
    }

    #[test]
    fn an_angle_beyond_its_allowance_is_a_defect_not_a_refusal() {
        // 30° − 1e-5° at coordinates near 1: rounding explains about 1e-6°.
        let mesh = thin(0.0, 1e-5);
        let points = [mesh.vertices[0], mesh.vertices[1]];
        assert!(matches!(
            check_rounded_angles(&mesh, &points, 0.01, 1),
            Err(Error::Mesher { .. })
        ));
        assert!(check_rounded_angles(&thin(0.0, 0.0), &points, 0.01, 1).is_ok());
    }
}
