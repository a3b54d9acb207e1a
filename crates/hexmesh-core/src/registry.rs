//! The library's meshers by name: the list the harness extends with the reference meshers.
//! A mesher that does not work yet is not listed.

use crate::error::{Error, Result};
use crate::mesher::{Mesher, Params};
use crate::quality::{Bounds, GENERIC_BOUNDS};

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

/// The bounds called `name`: the promise of the library's mesher or variant of that name
/// under default parameters, or one of `GENERIC_BOUNDS` (`valid`, `delaunay`,
/// `min-angle=DEG`).
pub fn bounds(name: &str) -> Result<Bounds> {
    bounds_among(name, meshers().into_iter().chain(variants()).collect())
}

/// The bounds called `name`, a mesher's among `candidates` (its promise under default
/// parameters) or a generic one; an unknown name is a usage error listing every valid one.
/// The harness looks up its own list, references included, with it.
pub fn bounds_among(name: &str, candidates: Vec<Box<dyn Mesher>>) -> Result<Bounds> {
    if let Some(m) = candidates.iter().find(|m| m.name() == name) {
        return Ok(m.promise(&Params::default()));
    }
    Bounds::named(name).map_err(|e| match e {
        Error::Usage(_) if !name.starts_with("min-angle=") => {
            let names: Vec<&str> = candidates.iter().map(|m| m.name()).collect();
            Error::Usage(format!(
                "unknown bounds '{name}'; valid names: {}, {}",
                names.join(", "),
                GENERIC_BOUNDS.join(", ")
            ))
        }
        other => other,
    })
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

    #[test]
    fn a_mesher_name_gives_its_promise_and_generic_names_their_bounds() {
        use crate::quality::HEX;
        let hex = bounds("hex").expect("hex");
        // With no limit asked for: the criteria, and the regions' area limits (`hex::size`).
        assert_eq!(hex, HEX.bounds().with_size_limits(None, None));
        let simple = bounds("hex-simple").expect("hex-simple");
        assert_eq!(
            (simple.min_angle, simple.max_angle),
            (Some(30.0), Some(120.0))
        );
        assert!(!simple.delaunay);
        let rhomb = bounds("rhomb").expect("rhomb");
        assert_eq!((rhomb.min_angle, rhomb.max_angle), (Some(30.0), Some(90.0)));
        for name in ["saalfeld", "saalfeld-sec5"] {
            let b = bounds(name).expect(name);
            assert!(
                b.delaunay && b.conforming && b.min_angle.is_none(),
                "{name}"
            );
            assert_eq!(b.name, name);
        }
        for name in ["lsb", "lsb-plain"] {
            let b = bounds(name).expect(name);
            assert_eq!(b.min_angle_over_ancestor, Some(0.5));
            assert!(b.conforming && !b.delaunay);
        }
        assert_eq!(
            bounds("min-angle=33.5").expect("33.5").min_angle,
            Some(33.5)
        );
        assert!(bounds("delaunay").expect("delaunay").delaunay);
    }

    #[test]
    fn an_unknown_bounds_name_lists_meshers_and_generic_names() {
        match bounds("hexx") {
            Err(Error::Usage(msg)) => assert!(
                msg.contains("hexx")
                    && msg.contains("hex-simple")
                    && msg.contains("lsb-plain")
                    && msg.contains("min-angle=DEG"),
                "{msg}"
            ),
            other => panic!("expected a usage error, got {other:?}"),
        }
        // A malformed angle keeps its own message.
        match bounds("min-angle=abc") {
            Err(Error::Usage(msg)) => assert!(msg.contains("not a number"), "{msg}"),
            other => panic!("expected a usage error, got {other:?}"),
        }
    }
}
