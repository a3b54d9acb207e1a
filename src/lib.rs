//! hexmesh: the hexagonal Delaunay mesher of Sußner & Greiner (IMR 2009) and the other
//! meshers of the papers in `shared/papers`, plus a harness that checks every mesh against
//! what its mesher promises and compares meshers side by side.
//!
//! Data flow: [`Pslg`] → [`Mesher::mesh`] → [`MeshRun`] (a [`TriMesh`]) → `quality` → `report`.

pub mod cli;
pub mod datasets;
pub mod error;
pub mod geom;
pub mod hex;
pub mod io;
pub mod isolate;
pub mod maxangle;
pub mod mesh;
pub mod mesher;
pub mod quality;
pub mod reference;
pub mod refine;
pub mod registry;
pub mod report;
pub mod rhomb;

pub use error::{Error, InputError, Result};
pub use geom::{Hexagon, Point};
pub use mesh::{Pslg, TriMesh};
pub use mesher::{Budget, MeshRun, Mesher, Params};
pub use registry::{mesher, mesher_names, meshers};
