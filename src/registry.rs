//! Meshers by name: the list the CLI and the harness loop over. A mesher that does not work
//! yet is not listed.

use crate::error::{Error, Result};
use crate::mesher::Mesher;

/// Every registered mesher, in report order.
pub fn meshers() -> Vec<Box<dyn Mesher>> {
    vec![
        Box::new(crate::hex::extended::Hex),
        Box::new(crate::hex::HexSimple),
        #[cfg(feature = "cgal")]
        Box::new(crate::reference::cgal::Cgal),
        #[cfg(feature = "cgal")]
        Box::new(crate::reference::cgal::CgalConforming),
        Box::new(crate::reference::TriangleMesher),
        Box::new(crate::reference::SpadeMesher),
        Box::new(crate::rhomb::Rhomb),
        Box::new(crate::refine::Saalfeld::default()),
        Box::new(crate::refine::Lsb::default()),
    ]
}

/// The names of the registered meshers, in report order.
pub fn mesher_names() -> Vec<&'static str> {
    meshers().iter().map(|m| m.name()).collect()
}

/// The mesher called `name`.
pub fn mesher(name: &str) -> Result<Box<dyn Mesher>> {
    meshers()
        .into_iter()
        .find(|m| m.name() == name)
        .ok_or_else(|| Error::UnknownMesher {
            name: name.to_string(),
            known: mesher_names().iter().map(|s| s.to_string()).collect(),
        })
}
