//! What each mesher promises, as checkable bounds, one set per mesher name.
//! The hex bounds are Sußner & Greiner 2009: angles in [α, 90°] with tan α = 5/(3√3)
//! (Sec. 6.1, Fig. 10), radius ratio ≤ 1.20787 (Sec. 6.2), shortest edge ≥ √7/(12√3)·d_min
//! (Sec. 6.3), Delaunay (Sec. 6.4); on PSLG inputs they hold away from the segments (Sec. 7).
//! Simple refinement gives [30°, 120°] (Sec. 4); Neugebauer–Diekmann's rhomboidal mesher
//! [30°, 90°]. Saalfeld's conforming Delaunay triangulation (paper 002) promises the exact
//! Delaunay property and conformity; longest-side bisection (paper 003) every angle at least
//! half the smallest angle of the initial triangle it descends from (`quality::descent`).

use crate::error::{Error, Result};

/// The floor of every angle's rounding allowance, in degrees (`quality::rounding`, where the
/// verdict adds what rounding of a triangle's corners explains): the slack of checks that
/// compare a summary figure with a bound (`maxangle`'s protocol, the PSLG report).
pub const ANGLE_SLACK_DEG: f64 = super::rounding::ANGLE_FLOOR_DEG;

/// The hex minimum angle atan(5/(3√3)) in degrees (paper Fig. 10: 43.9°).
pub const HEX_MIN_ANGLE_DEG: f64 = 43.897_886_248_013_98;

/// The paper's "aspect ratio" bound, which is Verdict's radius ratio R/(2r) of the
/// 43.9°/46.1°/90° triangle (1.2078697), rounded up as the paper states it.
pub const HEX_MAX_RADIUS_RATIO: f64 = 1.20787;

/// Shortest edge over d_min for hex: √7/(12√3) (paper Sec. 6.3).
pub const HEX_MIN_EDGE_OVER_DMIN: f64 = 0.127_293_769_304_328_9;

/// The descent ratio `lsb` promises (paper 003, Sec. 4): every angle at least half the
/// smallest angle of the initial triangle it descends from.
pub const LSB_ADAPTIVE_RATIO: f64 = 0.5;

/// The ratio Theorem 3.4 gives the family T(A, B, C) of a triangle (uniform modified
/// refinement).
pub const LSB_FAMILY_RATIO: f64 = 2.0 / 3.0;

/// The bound sets `Bounds::parse` knows, for error messages and `--help`.
pub const BOUND_NAMES: &[&str] = &[
    "hex",
    "hex-simple",
    "rhomb",
    "cgal",
    "cgal-conforming",
    "triangle",
    "spade",
    "saalfeld",
    "saalfeld-sec5",
    "lsb",
    "lsb-plain",
    "valid",
    "delaunay",
    "min-angle=DEG",
];

/// Bounds a mesh is checked against, on top of validity. `None` means not checked.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Bounds {
    /// The name the bounds were parsed from.
    pub name: String,
    /// Smallest allowed angle, degrees.
    pub min_angle: Option<f64>,
    /// Largest allowed angle, degrees.
    pub max_angle: Option<f64>,
    /// Largest allowed radius ratio R/(2r).
    pub max_radius_ratio: Option<f64>,
    /// Smallest allowed shortest-edge / d_min.
    pub min_edge_over_dmin: Option<f64>,
    /// Smallest allowed ratio of a triangle's smallest angle to the smallest angle of the
    /// triangle of the initial triangulation it lies in (`quality::descent`; needs the input).
    pub min_angle_over_ancestor: Option<f64>,
    /// Every interior edge passes the exact empty-circle test.
    pub delaunay: bool,
    /// Every input segment is a chain of mesh edges.
    pub conforming: bool,
    /// The mesh of a point set is one disc (applies only to inputs without segments).
    pub single_component: bool,
    /// On inputs with segments, the shape bounds (angles, radius ratio, edge, Delaunay) are
    /// checked on the triangles that do not touch a segment (paper Sec. 7).
    pub interior_only_on_segments: bool,
}

impl Bounds {
    /// Validity alone: every mesher's mesh must be valid, conform to the input segments and
    /// be one disc on a point set.
    pub fn validity(name: &str) -> Bounds {
        Bounds {
            name: name.to_string(),
            min_angle: None,
            max_angle: None,
            max_radius_ratio: None,
            min_edge_over_dmin: None,
            min_angle_over_ancestor: None,
            delaunay: false,
            conforming: true,
            single_component: true,
            interior_only_on_segments: false,
        }
    }

    /// The bounds called `name`: a mesher name (its promises), `valid`, `delaunay` (the
    /// empty-circle test alone) or `min-angle=DEG`.
    pub fn parse(name: &str) -> Result<Bounds> {
        let angles = |lo: f64, hi: f64| {
            let mut b = Bounds::validity(name);
            b.min_angle = Some(lo);
            b.max_angle = Some(hi);
            b.interior_only_on_segments = true;
            b
        };
        let bounds = match name {
            "hex" => Bounds {
                max_radius_ratio: Some(HEX_MAX_RADIUS_RATIO),
                min_edge_over_dmin: Some(HEX_MIN_EDGE_OVER_DMIN),
                delaunay: true,
                ..angles(HEX_MIN_ANGLE_DEG, 90.0)
            },
            "hex-simple" => angles(30.0, 120.0),
            "rhomb" => Bounds {
                interior_only_on_segments: false,
                ..angles(30.0, 90.0)
            },
            "cgal-conforming" | "saalfeld" | "saalfeld-sec5" => Bounds {
                delaunay: true,
                ..Bounds::validity(name)
            },
            // Paper 003: plain bisection and the adaptive refinement with rule 4.1 keep half
            // the smallest angle of the initial triangle (Sec. 4); 2/3 needs every quaternary
            // split completed, which only uniform refinement does (Theorem 3.4).
            "lsb" | "lsb-plain" => Bounds {
                min_angle_over_ancestor: Some(LSB_ADAPTIVE_RATIO),
                ..Bounds::validity(name)
            },
            "cgal" | "triangle" | "spade" | "valid" => Bounds::validity(name),
            "delaunay" => Bounds {
                delaunay: true,
                conforming: false,
                single_component: false,
                ..Bounds::validity(name)
            },
            _ => match name.strip_prefix("min-angle=") {
                Some(deg) => {
                    let value: f64 = deg.trim().parse().map_err(|_| {
                        Error::Usage(format!(
                            "bounds '{name}': '{deg}' is not a number of degrees"
                        ))
                    })?;
                    Bounds::validity(name).with_min_angle(value)?
                }
                None => {
                    return Err(Error::Usage(format!(
                        "unknown bounds '{name}'; valid names: {}",
                        BOUND_NAMES.join(", ")
                    )))
                }
            },
        };
        Ok(bounds)
    }

    /// These bounds with a minimum angle (degrees), e.g. the angle a reference mesher was
    /// asked for. The angle must lie in [0°, 60°], the range a triangle's smallest angle has.
    pub fn with_min_angle(mut self, degrees: f64) -> Result<Bounds> {
        if !(0.0..=60.0).contains(&degrees) {
            return Err(Error::Usage(format!(
                "a minimum angle must lie between 0 and 60 degrees, not {degrees}"
            )));
        }
        self.min_angle = Some(degrees);
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_constants_match_their_formulas() {
        let alpha = (5.0 / (3.0 * 3f64.sqrt())).atan().to_degrees();
        assert!((HEX_MIN_ANGLE_DEG - alpha).abs() < 1e-12, "{alpha}");
        let edge = 7f64.sqrt() / (12.0 * 3f64.sqrt());
        assert!((HEX_MIN_EDGE_OVER_DMIN - edge).abs() < 1e-15, "{edge}");
        // Right triangle with legs 5 and 3√3: R/(2r) = c / (2(a + b − c)).
        let (a, b) = (5.0, 3.0 * 3f64.sqrt());
        let c = (a * a + b * b).sqrt();
        let rr = c / (2.0 * (a + b - c));
        assert!(
            rr <= HEX_MAX_RADIUS_RATIO && HEX_MAX_RADIUS_RATIO - rr < 1e-6,
            "{rr}"
        );
    }

    #[test]
    fn mesher_names_parse_to_their_promises() {
        let hex = Bounds::parse("hex").expect("hex");
        assert_eq!(hex.min_angle, Some(HEX_MIN_ANGLE_DEG));
        assert_eq!(hex.max_angle, Some(90.0));
        assert!(hex.delaunay && hex.conforming && hex.single_component);
        let simple = Bounds::parse("hex-simple").expect("hex-simple");
        assert_eq!(
            (simple.min_angle, simple.max_angle),
            (Some(30.0), Some(120.0))
        );
        assert!(!simple.delaunay);
        let rhomb = Bounds::parse("rhomb").expect("rhomb");
        assert_eq!((rhomb.min_angle, rhomb.max_angle), (Some(30.0), Some(90.0)));
        assert!(Bounds::parse("saalfeld").expect("saalfeld").delaunay);
        assert!(Bounds::parse("cgal-conforming").expect("cgal-c").delaunay);
        let cgal = Bounds::parse("cgal").expect("cgal");
        assert!(!cgal.delaunay && cgal.min_angle.is_none());
        for lsb in ["lsb", "lsb-plain"] {
            let b = Bounds::parse(lsb).expect("lsb");
            assert_eq!(b.min_angle_over_ancestor, Some(0.5));
            assert!(b.conforming && !b.delaunay);
        }
        assert!(cgal.min_angle_over_ancestor.is_none());
    }

    #[test]
    fn min_angle_parses_and_rejects_nonsense() {
        assert_eq!(
            Bounds::parse("min-angle=33.5").expect("33.5").min_angle,
            Some(33.5)
        );
        assert!(matches!(
            Bounds::parse("min-angle=abc"),
            Err(Error::Usage(_))
        ));
        assert!(matches!(
            Bounds::parse("min-angle=75"),
            Err(Error::Usage(_))
        ));
        assert!(matches!(
            Bounds::parse("min-angle=NaN"),
            Err(Error::Usage(_))
        ));
    }

    #[test]
    fn an_unknown_name_lists_the_valid_ones() {
        match Bounds::parse("hexx") {
            Err(Error::Usage(msg)) => {
                assert!(
                    msg.contains("hexx")
                        && msg.contains("hex-simple")
                        && msg.contains("min-angle=DEG"),
                    "{msg}"
                )
            }
            other => panic!("expected a usage error, got {other:?}"),
        }
    }
}
