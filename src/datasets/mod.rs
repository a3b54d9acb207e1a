//! The datasets of the paper's benchmark (Sußner & Greiner 2009, Sec. 8, Table 1 and the
//! caption of Fig. 15), generated deterministically by name, plus a scaling series.
//!
//! `random` makes the seeded point sets (bit-for-bit the same on every machine), `imr` the
//! letters PSLG, `pslg` the small PSLG examples beside them (holes, a 5° wedge, a slit,
//! nested boundaries, short segments beside long ones), reachable by name like the datasets.
//! Provenance and seeds are listed in `datasets/README.md`.

mod imr;
mod pslg;
mod random;

use crate::error::{Error, Result};
use crate::geom::Hexagon;
use crate::mesh::Pslg;

pub use pslg::{pslg_example, pslg_examples, PslgExample, PSLG_EXAMPLES, SHORT_PIECES, WEDGE_DEG};
pub use random::LINE_END;

/// The datasets of Table 1, small enough to commit and to mesh in a test.
pub const SMALL: &[&str] = &[
    "close-pair",
    "line-100",
    "plane-100",
    "plane-1k",
    "plane-2k",
    "imr",
];

/// Larger uniform point sets for scaling measurements, generated on demand, not committed.
pub const SCALING: &[&str] = &["plane-10k", "plane-100k", "plane-1m"];

/// The scaling datasets every report meshes (with plane-1k and plane-2k of [`SMALL`], the
/// points of its scaling plot); `report --scaling` adds the rest of [`SCALING`].
pub const SCALING_IN_REPORT: &[&str] = &["plane-10k", "plane-100k"];

#[derive(Clone, Copy)]
enum Kind {
    ClosePair,
    Line(usize),
    Plane(usize),
    Imr,
}

struct Spec {
    name: &'static str,
    kind: Kind,
    /// The seed of the canonical dataset; `None` for the ones that are not random.
    seed: Option<u64>,
    description: &'static str,
}

/// Every dataset: SMALL then SCALING, in that order. The seeds are fixed forever: changing one
/// changes a committed dataset and its hash.
const CATALOGUE: &[Spec] = &[
    Spec {
        name: "close-pair",
        kind: Kind::ClosePair,
        seed: None,
        description: "two points 0.02 apart, (-0.01, 0) and (0.01, 0), in the regular hexagon of \
                      circumradius 1 at the origin (not fitted); Table 1 row 1",
    },
    Spec {
        name: "line-100",
        kind: Kind::Line(100),
        seed: Some(1),
        description: "100 distinct points t*(1, 0.37), t uniform in [0, 1), pcg64 seed 1; \
                      Table 1 row 2",
    },
    Spec {
        name: "plane-100",
        kind: Kind::Plane(100),
        seed: Some(2),
        description: "100 distinct points uniform in the unit square, pcg64 seed 2; Table 1 row 3",
    },
    Spec {
        name: "plane-1k",
        kind: Kind::Plane(1_000),
        seed: Some(3),
        description: "1000 distinct points uniform in the unit square, pcg64 seed 3; Table 1 row 5",
    },
    Spec {
        name: "plane-2k",
        kind: Kind::Plane(2_000),
        seed: Some(4),
        description: "2000 distinct points uniform in the unit square, pcg64 seed 4; Table 1 row 6",
    },
    Spec {
        name: "imr",
        kind: Kind::Imr,
        seed: None,
        description: "the letters I, M, R as closed outlines, detail rising from I to R (R: arc \
                      bowl and a hole); this project's drawing; Table 1 row 4",
    },
    Spec {
        name: "plane-10k",
        kind: Kind::Plane(10_000),
        seed: Some(5),
        description:
            "10^4 distinct points uniform in the unit square, pcg64 seed 5; scaling series",
    },
    Spec {
        name: "plane-100k",
        kind: Kind::Plane(100_000),
        seed: Some(6),
        description:
            "10^5 distinct points uniform in the unit square, pcg64 seed 6; scaling series",
    },
    Spec {
        name: "plane-1m",
        kind: Kind::Plane(1_000_000),
        seed: Some(7),
        description:
            "10^6 distinct points uniform in the unit square, pcg64 seed 7; scaling series",
    },
];

/// Every dataset name, SMALL then SCALING.
pub fn names() -> Vec<&'static str> {
    CATALOGUE.iter().map(|s| s.name).collect()
}

/// The dataset or PSLG example called `name`. Unknown names give `Error::Usage` listing the
/// known ones.
pub fn by_name(name: &str) -> Result<Pslg> {
    if let Some(example) = pslg_example(name) {
        return Ok(example.pslg);
    }
    let spec = spec(name)?;
    match (spec.kind, spec.seed) {
        (Kind::ClosePair, _) => Ok(close_pair()),
        (Kind::Imr, _) => Ok(imr::letters()),
        (kind, Some(seed)) => Ok(generate(kind, seed)),
        // A random family without a seed would be a catalogue error; say so rather than panic.
        (_, None) => Err(Error::Usage(format!(
            "dataset '{name}' is random but has no seed in the catalogue"
        ))),
    }
}

/// A member of a random family (`line-100`, `plane-*`) drawn with another seed, for counts
/// averaged over seeds. `random_with_seed(name, default_seed(name))` equals `by_name(name)`.
/// For one seed, a smaller plane set is a prefix of a larger one.
pub fn random_with_seed(name: &str, seed: u64) -> Result<Pslg> {
    if PSLG_EXAMPLES.contains(&name) {
        return Err(not_random(name));
    }
    let spec = spec(name)?;
    match spec.kind {
        Kind::Line(_) | Kind::Plane(_) => Ok(generate(spec.kind, seed)),
        Kind::ClosePair | Kind::Imr => Err(not_random(name)),
    }
}

fn not_random(name: &str) -> Error {
    Error::Usage(format!(
        "dataset '{name}' is not random; the random ones are {}",
        random_names().join(", ")
    ))
}

/// The seed of the canonical dataset `name`; `None` for unknown names and the datasets that
/// are not random.
pub fn default_seed(name: &str) -> Option<u64> {
    CATALOGUE.iter().find(|s| s.name == name)?.seed
}

/// One line of provenance for `name` (for a PSLG example, what it tests); for an unknown
/// name, a line saying so.
pub fn describe(name: &str) -> &'static str {
    if let Some(example) = pslg_example(name) {
        return example.tests;
    }
    CATALOGUE
        .iter()
        .find(|s| s.name == name)
        .map_or("not a hexmesh dataset", |s| s.description)
}

/// The file `name` is written to: `<name>.poly` when it has segments, `<name>.node` when it
/// is a point set.
pub fn file_name(name: &str) -> Result<String> {
    if PSLG_EXAMPLES.contains(&name) {
        return Ok(format!("{name}.poly"));
    }
    let spec = spec(name)?;
    Ok(match spec.kind {
        Kind::Imr => format!("{name}.poly"),
        _ => format!("{name}.node"),
    })
}

fn spec(name: &str) -> Result<&'static Spec> {
    CATALOGUE.iter().find(|s| s.name == name).ok_or_else(|| {
        Error::Usage(format!(
            "unknown dataset '{name}'; the datasets are {}, and the PSLG examples {}",
            names().join(", "),
            PSLG_EXAMPLES.join(", ")
        ))
    })
}

fn random_names() -> Vec<&'static str> {
    CATALOGUE
        .iter()
        .filter(|s| matches!(s.kind, Kind::Line(_) | Kind::Plane(_)))
        .map(|s| s.name)
        .collect()
}

fn generate(kind: Kind, seed: u64) -> Pslg {
    match kind {
        Kind::Line(n) => Pslg::from_points(random::on_line(n, seed)),
        Kind::Plane(n) => Pslg::from_points(random::in_unit_square(n, seed)),
        Kind::ClosePair => close_pair(),
        Kind::Imr => imr::letters(),
    }
}

/// The paper's "popular benchmark": two points 0.02 apart "located within a hexagon with unit
/// radius", which Fig. 15's caption says is not adapted to the points.
fn close_pair() -> Pslg {
    Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_catalogue_lists_small_then_scaling() {
        let expected: Vec<&str> = SMALL.iter().chain(SCALING).copied().collect();
        assert_eq!(names(), expected);
    }

    #[test]
    fn an_unknown_name_is_a_usage_error_listing_the_names() {
        match by_name("plane-3k") {
            Err(Error::Usage(m)) => {
                assert!(m.contains("plane-3k"), "{m}");
                for name in names().into_iter().chain(PSLG_EXAMPLES.iter().copied()) {
                    assert!(m.contains(name), "{m} lacks {name}");
                }
            }
            other => panic!("expected a usage error, got {other:?}"),
        }
        assert_eq!(describe("plane-3k"), "not a hexmesh dataset");
        assert!(file_name("plane-3k").is_err());
    }

    #[test]
    fn only_the_random_families_take_a_seed() {
        assert!(matches!(random_with_seed("imr", 1), Err(Error::Usage(_))));
        assert!(matches!(
            random_with_seed("close-pair", 1),
            Err(Error::Usage(_))
        ));
        assert_eq!(default_seed("imr"), None);
        assert_eq!(default_seed("close-pair"), None);
        for name in ["line-100", "plane-100", "plane-1k", "plane-2k"] {
            assert!(default_seed(name).is_some(), "{name}");
        }
    }

    #[test]
    fn canonical_seeds_are_pairwise_different() {
        let mut seeds: Vec<u64> = CATALOGUE.iter().filter_map(|s| s.seed).collect();
        let n = seeds.len();
        seeds.sort_unstable();
        seeds.dedup();
        assert_eq!(seeds.len(), n);
    }

    #[test]
    fn the_seeded_variant_with_the_default_seed_is_the_canonical_dataset() {
        for name in ["line-100", "plane-100", "plane-1k"] {
            let seed = default_seed(name).unwrap_or_default();
            assert_eq!(
                random_with_seed(name, seed).ok(),
                by_name(name).ok(),
                "{name}"
            );
        }
        assert_ne!(
            random_with_seed("plane-100", 100).ok(),
            by_name("plane-100").ok()
        );
    }

    #[test]
    fn only_imr_and_the_pslg_examples_are_written_as_poly_files() {
        assert_eq!(file_name("imr").ok().as_deref(), Some("imr.poly"));
        for name in PSLG_EXAMPLES {
            assert_eq!(file_name(name).ok(), Some(format!("{name}.poly")));
        }
        assert_eq!(
            file_name("close-pair").ok().as_deref(),
            Some("close-pair.node")
        );
        assert_eq!(file_name("plane-1m").ok().as_deref(), Some("plane-1m.node"));
    }

    #[test]
    fn every_dataset_and_example_has_a_description_and_resolves_by_name() {
        for name in PSLG_EXAMPLES {
            assert_eq!(
                by_name(name).ok(),
                pslg_example(name).map(|e| e.pslg),
                "{name}"
            );
            assert!(matches!(random_with_seed(name, 1), Err(Error::Usage(_))));
            assert_eq!(default_seed(name), None);
        }
        for name in names().into_iter().chain(PSLG_EXAMPLES.iter().copied()) {
            assert_ne!(describe(name), "not a hexmesh dataset", "{name}");
        }
    }
}
