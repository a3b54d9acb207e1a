//! The library's meshers by name: the list the harness extends with the reference meshers.
//! A mesher that does not work yet is not listed.

use crate::error::{Error, Result};
use crate::mesher::Mesher;

/// The library's meshers, in the order the harness reports them.
pub fn meshers() -> Vec<Box<dyn Mesher>> {
    vec![
        Box::new(crate::hex::extended::Hex),
        Box::new(crate::hex::HexSimple),
        Box::new(crate::rhomb::Rhomb),
        Box::new(crate::refine::Saalfeld::default()),
        Box::new(crate::refine::Lsb::default()),
    ]
}

/// Options of the library's meshers, reachable by name but not run by default: Saalfeld's
/// constructive refinement of Sec. 5 and plain longest-side bisection, the variants the
/// papers compare against.
pub fn variants() -> Vec<Box<dyn Mesher>> {
    vec![
        Box::new(crate::refine::Saalfeld {
            constructive: true,
            ..crate::refine::Saalfeld::default()
        }),
        Box::new(crate::refine::Lsb { plain: true }),
    ]
}

/// The library's mesher or variant called `name`.
pub fn mesher(name: &str) -> Result<Box<dyn Mesher>> {
    find(name, meshers().into_iter().chain(variants()).collect())
}

/// The mesher called `name` among `candidates`; otherwise an `UnknownMesher` error listing
/// their names in order. The harness looks up its own list, references included, with it.
pub fn find(name: &str, candidates: Vec<Box<dyn Mesher>>) -> Result<Box<dyn Mesher>> {
    let known = candidates.iter().map(|m| m.name().to_string()).collect();
    candidates
        .into_iter()
        .find(|m| m.name() == name)
        .ok_or_else(|| Error::UnknownMesher {
            name: name.to_string(),
            known,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mesher_and_variant_resolves_by_its_name() {
        for m in meshers().iter().chain(variants().iter()) {
            let found = mesher(m.name()).map(|f| f.name());
            assert_eq!(found.ok(), Some(m.name()));
        }
        assert!(matches!(
            mesher("triangle"),
            Err(Error::UnknownMesher { .. })
        ));
    }
}
