//! Reference meshers behind the `Mesher` trait (DESIGN.md "Data flow"): each meshes the
//! domain the paper's Sec. 8 comparison uses — the bounding hexagon's corners and edges plus
//! the input points for a point set (`Pslg::reference_domain`), the segments' region minus the
//! seeded holes for a PSLG — and is asked for the minimum angle of the run.
//!
//! - `cgal`, `cgal-conforming`: CGAL's 2D Delaunay mesher through `cxx` (feature `cgal`).
//! - `spade`: spade's constrained Delaunay refinement (Ruppert/Chew style).
//! - `triangle`: Shewchuk's Triangle through the `tritet` crate.

#[cfg(feature = "cgal")]
pub mod cgal;
pub mod spade;
pub mod triangle;

pub use self::spade::SpadeMesher;
pub use self::triangle::TriangleMesher;

use crate::error::{Error, Result};
use crate::mesher::Params;

/// Refuses requests no reference mesher can honour: a minimum angle outside [0°, 60°) (no
/// triangle has all angles above 60°) or a maximum area that is not a positive finite number.
pub(crate) fn check_params(mesher: &str, params: &Params) -> Result<()> {
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
    Ok(())
}
