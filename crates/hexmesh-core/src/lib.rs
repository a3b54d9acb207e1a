//! 2D triangle meshes with guaranteed quality, and the checks of those guarantees.
//!
//! The meshers, each with the promise its paper proves, kept on every input up to f64
//! rounding (see [`quality::rounding`]):
//!
//! | name | method | promise |
//! | --- | --- | --- |
//! | `hex` | hexagonal Delaunay refinement (Sußner & Greiner 2009) | angles 43.9°–90°, radius ratio ≤ 1.20787, Delaunay, shortest edge ≥ 0.127·d_min |
//! | `hex-simple` | its simple refinement | angles 30°–120° |
//! | `rhomb` | rhomboidal quad-tree (Neugebauer & Diekmann) | angles 30°–90° |
//! | `saalfeld` | Delaunay edge refinement (Saalfeld) | conforming Delaunay |
//! | `lsb` | modified longest-side bisection | each angle ≥ half its initial triangle's smallest |
//!
//! On point sets the mesh covers a bounding hexagon (given, or fitted around the points); on a
//! planar straight-line graph ([`Pslg`]) it covers the domain the segments bound.
//!
//! # Meshing points
//!
//! [`mesh()`] meshes a point set with `hex`. Points may be `[f64; 2]`, `glam::DVec2` or anything
//! else that converts into `[f64; 2]`:
//!
//! ```
//! use glam::DVec2;
//!
//! let points = (0..10).map(|i| DVec2::new((i as f64 * 0.7).sin(), (i as f64 * 1.3).cos()));
//! let mesh = hexmesh_core::mesh(points)?;
//! let hex = hexmesh_core::bounds("hex")?;
//! assert!(hexmesh_core::quality::verdict(&mesh, None, Some(&hex)).passed());
//! # Ok::<(), hexmesh_core::Error>(())
//! ```
//!
//! # Meshing a domain, with any mesher
//!
//! [`mesh_domain`] takes a [`Pslg`] (points, segments, holes) and [`Options`]: the mesher and
//! its [`Params`]. The [`MeshRun`] says whether the mesh is complete or why a budget stopped
//! it:
//!
//! ```
//! use hexmesh_core::{mesh_domain, Method, Options, Pslg};
//!
//! // A unit square with a square hole.
//! let square = |lo: f64, hi: f64| vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]];
//! let mut points = square(0.0, 1.0);
//! points.extend(square(0.4, 0.6));
//! let ring = |b: u32| (0..4).map(move |k| [b + k, b + (k + 1) % 4]);
//! let domain = Pslg {
//!     points,
//!     segments: ring(0).chain(ring(4)).collect(),
//!     holes: vec![[0.5, 0.5]],
//!     ..Pslg::default()
//! };
//! let run = mesh_domain(&domain, &Options::new(Method::Saalfeld))?;
//! assert!(run.complete && run.stop_reason.is_none());
//! assert!((run.mesh.area() - 0.96).abs() < 1e-12);
//! # Ok::<(), hexmesh_core::Error>(())
//! ```
//!
//! Every mesher is also reachable by name ([`mesher()`]) behind the [`Mesher`] trait; the
//! [`Bounds`] its meshes are checked against go to [`quality::verdict()`].
//!
//! # Files
//!
//! [`io`] reads Triangle's .node/.poly files and writes .node/.ele, VTK, Gmsh .msh and SVG;
//! [`io::read_any_mesh`] reads a triangle mesh from Gmsh .msh, VTK .vtk/.vtu or .node/.ele.
//!
//! # Layers
//!
//! [`geom`] (exact predicates, the lattice arithmetic) → [`mod@mesh`] (input and output types) →
//! [`quality`] (metrics, validation, the rounding allowance, verdicts) → the meshers (their
//! machinery in [`internals`]: `hex`, `rhomb`, `refine`) → [`registry`] and the functions
//! above.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod enclosed;
pub mod error;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod mesher;
pub mod progress;
pub mod quality;
pub mod registry;
mod shuffle;
#[cfg(test)]
mod xorshift;

pub mod internals;
use internals::{hex, refine, rhomb};

/// The library examples of the READMEs, compiled and run as doctests (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;

pub use error::{Error, InputError, Result, Unenclosed};
pub use geom::{Hexagon, Point};
pub use hex::extended::Hex;
pub use hex::HexSimple;
pub use mesh::{Labels, Pslg, Region, TriMesh};
pub use mesher::{Budget, MeshRun, Mesher, Params, StopReason};
pub use progress::Progress;
pub use quality::Bounds;
pub use refine::{Lsb, Saalfeld};
pub use registry::{bounds, mesher, meshers};
pub use rhomb::Rhomb;

/// Meshes a point set with `hex`: every angle in [43.9°, 90°], radius ratio at most 1.20787,
/// Delaunay, every edge at least 0.127 times the closest pair's distance (each up to its
/// rounding allowance, [`quality::rounding`]). The mesh covers the points' fitted bounding
/// hexagon; the input points are its first vertices, in order.
///
/// Errors name the problem: no points, a non-finite coordinate, a duplicate point, or two
/// points too close together for f64 at their coordinates ([`InputError`]).
pub fn mesh<P: Into<[f64; 2]>>(points: impl IntoIterator<Item = P>) -> Result<TriMesh> {
    let input = Pslg::from_points(points.into_iter().map(Into::into).collect());
    let run = mesh_domain(&input, &Options::default())?;
    Ok(run.mesh)
}

/// Which of the library's meshers [`mesh_domain`] runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// The hexagonal Delaunay mesher (Sußner & Greiner, Sec. 5).
    #[default]
    Hex,
    /// Its simple refinement (Sec. 4.3).
    HexSimple,
    /// The rhomboidal quad-tree (Neugebauer & Diekmann): point sets and polygonal domains.
    Rhomb,
    /// Saalfeld's Delaunay edge refinement (conforming Delaunay).
    Saalfeld,
    /// Modified longest-side bisection.
    Lsb,
}

impl Method {
    /// The mesher behind this method.
    pub fn mesher(self) -> Box<dyn Mesher> {
        match self {
            Method::Hex => Box::new(Hex),
            Method::HexSimple => Box::new(HexSimple),
            Method::Rhomb => Box::new(Rhomb),
            Method::Saalfeld => Box::new(Saalfeld::default()),
            Method::Lsb => Box::new(Lsb::default()),
        }
    }
}

/// What [`mesh_domain`] is asked for: the mesher and its parameters.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Options {
    /// The mesher.
    pub method: Method,
    /// Its parameters (budgets, the largest rounding allowance, an area bound).
    pub params: Params,
}

impl Options {
    /// `method` with default parameters.
    pub fn new(method: Method) -> Options {
        Options {
            method,
            params: Params::default(),
        }
    }

    /// These options with `params`.
    pub fn with_params(mut self, params: Params) -> Options {
        self.params = params;
        self
    }
}

/// Checks `input` ([`Pslg::check`]) and meshes it with the chosen mesher. A budget that runs
/// out is not an error: the mesh so far comes back with `complete == false` and the reason.
pub fn mesh_domain(input: &Pslg, options: &Options) -> Result<MeshRun> {
    input.check().map_err(Error::input)?;
    options.method.mesher().mesh(input, &options.params)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_keeps_the_points_first_and_in_order() {
        let points = [[0.0, 0.0], [1.0, 0.25], [0.5, 0.75]];
        let mesh = mesh(points).expect("meshes");
        assert_eq!(&mesh.vertices[..3], &points[..]);
    }

    #[test]
    fn mesh_names_a_duplicate_point() {
        match mesh([[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]]) {
            Err(Error::Input {
                problem: InputError::Duplicate { .. },
                ..
            }) => {}
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn every_method_is_a_registered_mesher() {
        for m in [
            Method::Hex,
            Method::HexSimple,
            Method::Rhomb,
            Method::Saalfeld,
            Method::Lsb,
        ] {
            assert!(registry::mesher(m.mesher().name()).is_ok());
        }
    }
}
