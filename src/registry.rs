//! Meshers by name: the list the CLI and the harness loop over. A mesher that does not work
//! yet is not listed.

use crate::error::Result;
use crate::mesher::Mesher;
use crate::quality::Bounds;

/// Every registered mesher, in report order: the library's (`hexmesh_core::meshers`) with
/// the references among them.
pub fn meshers() -> Vec<Box<dyn Mesher>> {
    let mut ours = hexmesh_core::meshers().into_iter();
    let mut take = |name: &str| {
        let m = ours.next().expect("the library's meshers");
        assert_eq!(m.name(), name, "the library's report order");
        m
    };
    let mut all: Vec<Box<dyn Mesher>> = vec![take("hex"), take("hex-simple")];
    #[cfg(feature = "cgal")]
    {
        all.push(Box::new(crate::reference::cgal::Cgal));
        all.push(Box::new(crate::reference::cgal::CgalConforming));
    }
    all.push(Box::new(crate::reference::TriangleMesher));
    all.push(Box::new(crate::reference::SpadeMesher));
    all.push(Box::new(crate::reference::GmshMesher));
    all.extend([take("rhomb"), take("saalfeld"), take("lsb")]);
    all
}

/// Options of registered meshers, reachable by name (`hexmesh mesh --mesher NAME`,
/// `report --meshers NAME`) but not run by default: the library's variants.
pub fn variants() -> Vec<Box<dyn Mesher>> {
    hexmesh_core::registry::variants()
}

/// The names of the registered meshers, in report order.
pub fn mesher_names() -> Vec<&'static str> {
    meshers().iter().map(|m| m.name()).collect()
}

/// The mesher or variant called `name`.
pub fn mesher(name: &str) -> Result<Box<dyn Mesher>> {
    hexmesh_core::registry::find(name, meshers().into_iter().chain(variants()).collect())
}

/// The bounds `verify --bounds NAME` checks: a registered mesher's or variant's promise under
/// default parameters (a reference: its default minimum angle), or a generic name (`valid`,
/// `delaunay`, `min-angle=DEG`).
pub fn bounds(name: &str) -> Result<Bounds> {
    hexmesh_core::registry::bounds_among(name, meshers().into_iter().chain(variants()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn variants_resolve_by_name_but_are_not_in_the_default_list() {
        for v in ["saalfeld-sec5", "lsb-plain"] {
            assert_eq!(mesher(v).expect(v).name(), v);
            assert!(!mesher_names().contains(&v), "{v} is run by default");
        }
        match mesher("no-such") {
            Err(Error::UnknownMesher { known, .. }) => {
                assert!(known.iter().any(|k| k == "saalfeld-sec5"), "{known:?}")
            }
            other => panic!("{:?}", other.map(|m| m.name())),
        }
    }
}
