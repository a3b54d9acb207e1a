//! Reference meshers behind the `Mesher` trait, like our own (input `Pslg`, output a
//! `MeshRun` the harness checks with `quality`): each meshes the
//! domain the paper's Sec. 8 comparison uses — the bounding hexagon's corners and edges plus
//! the input points for a point set (`Pslg::reference_domain`), the segments' region minus the
//! seeded holes for a PSLG — and is asked for the minimum angle of the run.
//!
//! - `cgal`, `cgal-conforming`: CGAL's 2D Delaunay mesher through `cxx` (feature `cgal`).
//! - `spade`: spade's constrained Delaunay refinement (Ruppert/Chew style).
//! - `triangle`: Shewchuk's Triangle, its `triangulate()` called directly (the C code compiled
//!   by the `tritet` crate), with the input's regions and the user's switches.
//! - `gmsh`: Gmsh's Frontal-Delaunay 2D mesher, Debian's `gmsh` program run on a `.geo`
//!   script of the domain; no angle bound (its promise is validity).

#[cfg(feature = "cgal")]
pub mod cgal;
pub mod gmsh;
pub mod spade;
pub mod triangle;

pub use self::gmsh::GmshMesher;
pub use self::spade::SpadeMesher;
pub use self::triangle::TriangleMesher;

use crate::error::{Error, InputError, Result};
use crate::mesh::Pslg;
use crate::mesher::Params;
use crate::quality::Bounds;

/// A quality reference's promise: a valid mesh whose every angle is at least the minimum
/// angle it was asked for, or its `default` one when none was (spade's 30°, Triangle's bare
/// `q` 20°, CGAL's b = 0.125, 20.7°), but at input corners sharper than that, which it takes
/// whole (Delaunay refinement cannot split a sharp input angle into better ones).
fn asked_angle(name: &str, params: &Params, default: f64) -> Bounds {
    Bounds {
        min_angle: Some(params.min_angle.unwrap_or(default)),
        whole_sharp_corners: true,
        ..Bounds::validity(name)
    }
}

/// The lengths CGAL's and Triangle's refinement can measure, as a power of ten. Their quality
/// tests multiply squared lengths (fourth powers of lengths), which f64 holds only between
/// about 1e-77 and 1e77; beyond 1e±75 both were seen to return meshes far below the requested
/// angle as complete (CGAL at 1e-80 and 1e80 with 6.6° for 30°, Triangle at 1e-100 with 2.3°
/// for 25°; cgal-conforming made zero-area triangles at 1e-160), or to stop with Triangle's
/// "Ran out of precision". 1e70 leaves room for the refinement's smaller edges.
pub const SCALE_LIMIT: f64 = 1e70;

/// Refuses a domain whose coordinates exceed [`SCALE_LIMIT`] or whose closest points are
/// nearer than its inverse: such a mesh would come back wrong, not fail.
pub(crate) fn check_scale(mesher: &str, domain: &Pslg) -> Result<()> {
    let largest = domain
        .points
        .iter()
        .flat_map(|p| [p[0].abs(), p[1].abs()])
        .fold(0.0, f64::max);
    let range = |detail: String| Err(Error::input(InputError::Range { detail }));
    if largest > SCALE_LIMIT {
        return range(format!(
            "coordinates as large as {largest:e} are beyond what {mesher} can measure \
             (its quality tests need fourth powers of lengths, up to {SCALE_LIMIT:e}): scale the input"
        ));
    }
    if let Some(c) = crate::quality::closest_pair(&domain.points) {
        if c.distance < 1.0 / SCALE_LIMIT {
            return range(format!(
                "points {:e} apart are closer than {mesher} can measure (its quality tests \
                 need fourth powers of lengths, down to {:e}): scale the input",
                c.distance,
                1.0 / SCALE_LIMIT
            ));
        }
    }
    Ok(())
}

/// Refuses what a reference mesher without options of its own cannot honour: such options
/// (`Params::switches`, which only `triangle` takes) and the requests `check_request` refuses.
pub(crate) fn check_params(mesher: &str, params: &Params) -> Result<()> {
    params.refuse_switches(mesher)?;
    check_request(mesher, params)
}

/// Refuses requests no reference mesher can honour: a minimum angle outside [0°, 60°) (no
/// triangle has all angles above 60°) or a maximum area or edge length that is not a positive
/// finite number.
pub(crate) fn check_request(mesher: &str, params: &Params) -> Result<()> {
    if let Some(a) = params.min_angle {
        if !(a.is_finite() && (0.0..60.0).contains(&a)) {
            return Err(Error::mesher(
                mesher,
                format!("minimum angle {a}° is not in [0°, 60°)"),
            ));
        }
    }
    if let Some(a) = params.max_area {
        if !(a.is_finite() && a > 0.0) {
            return Err(Error::mesher(
                mesher,
                format!("maximum area {a} is not a positive finite number"),
            ));
        }
    }
    if let Some(l) = params.max_edge {
        if !(l.is_finite() && l > 0.0) {
            return Err(Error::mesher(
                mesher,
                format!("maximum edge length {l} is not a positive finite number"),
            ));
        }
    }
    Ok(())
}
