//! What a mesher promises, as checkable bounds: each mesher gives its own
//! (`Mesher::promise`); the constructors here are the shapes those promises take.
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

/// The criteria of `hex` (paper 000 Sec. 6), one value that its rules, its self-check, its
/// PSLG path, its promise ([`HexCriteria::bounds`]) and the checks all read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HexCriteria {
    /// Smallest angle: atan(5/(3√3)) in degrees (Fig. 10: 43.9°).
    pub min_angle: f64,
    /// Largest angle, degrees.
    pub max_angle: f64,
    /// The paper's "aspect ratio" bound, which is Verdict's radius ratio R/(2r) of the
    /// 43.9°/46.1°/90° triangle (1.2078697), rounded up as the paper states it (Sec. 6.2).
    pub max_radius_ratio: f64,
    /// Shortest edge over d_min: √7/(12√3) (Sec. 6.3).
    pub min_edge_over_dmin: f64,
    /// How far beyond each angle's placement allowance the mesher's own self-check lets an
    /// angle lie before it repairs the configuration: below the 1e-6° floor of the checks'
    /// allowance (`quality::rounding`), so the self-check is the stricter of the two.
    pub self_check_slack: f64,
}

/// `hex`'s criteria.
pub const HEX: HexCriteria = HexCriteria {
    min_angle: 43.897_886_248_013_98,
    max_angle: 90.0,
    max_radius_ratio: 1.20787,
    min_edge_over_dmin: 0.127_293_769_304_328_9,
    self_check_slack: 1e-7,
};

// The self-check is the stricter of the two: its slack lies below the checks' allowance floor.
const _: () = assert!(HEX.self_check_slack < super::rounding::ANGLE_FLOOR_DEG);

impl HexCriteria {
    /// What a `hex` mesh is checked against: the angles, radius ratio, shortest edge and the
    /// Delaunay property, on a PSLG away from the segments (Sec. 7); there, the triangles
    /// touching a segment keep [`NEAR_SEGMENT_ANGLES`] but at whole sharp input corners, and
    /// the mesh is constrained Delaunay (ours, beyond the paper: `hex::pslg::band`).
    pub fn bounds(&self) -> Bounds {
        Bounds {
            max_radius_ratio: Some(self.max_radius_ratio),
            min_edge_over_dmin: Some(self.min_edge_over_dmin),
            delaunay: true,
            near_segment_angles: Some(NEAR_SEGMENT_ANGLES),
            constrained_delaunay: true,
            ..Bounds::angles("hex", self.min_angle, self.max_angle)
        }
    }

    /// The cheap test that every angle of a triangle lies clearly inside the self-check's
    /// bounds [α − slack, 90° + slack].
    pub(crate) fn angle_filter(&self) -> super::rounding::AngleWindow {
        super::rounding::AngleWindow::new(self.min_angle, self.max_angle, self.self_check_slack)
    }
}

/// The angles `hex` keeps in the triangles touching a segment, degrees: Triangle's `-q30`
/// smallest angle and the largest angle it leaves (180° − 2·30°).
pub const NEAR_SEGMENT_ANGLES: (f64, f64) = (30.0, 120.0);

/// The descent ratio `lsb` promises (paper 003, Sec. 4): every angle at least half the
/// smallest angle of the initial triangle it descends from.
pub const LSB_ADAPTIVE_RATIO: f64 = 0.5;

/// The ratio Theorem 3.4 gives the family T(A, B, C) of a triangle (uniform modified
/// refinement).
pub const LSB_FAMILY_RATIO: f64 = 2.0 / 3.0;

/// The bounds that are not a mesher's promise, by name, for `Bounds::named`, error messages
/// and `--help`; a mesher's name gives its promise (`registry::bounds`).
pub const GENERIC_BOUNDS: &[&str] = &["valid", "delaunay", "min-angle=DEG"];

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
    /// On inputs with segments, the shape bounds (angles, radius ratio, edge, Delaunay) are
    /// checked on the triangles that do not touch a segment (paper Sec. 7).
    pub interior_only_on_segments: bool,
    /// An angle below `min_angle` passes where it is an input corner sharper than
    /// `min_angle` taken whole: at an input point, both of its edges along input segments
    /// from there (paper 001's exception; a split corner does not pass).
    pub whole_sharp_corners: bool,
    /// On inputs with segments, the angles of the triangles touching a segment, which
    /// `interior_only_on_segments` leaves out of the shape bounds: every one in [lo, hi]
    /// degrees, but an angle at an input corner sharper than lo taken whole.
    pub near_segment_angles: Option<(f64, f64)>,
    /// On inputs with segments, the constrained Delaunay property over the whole mesh: every
    /// edge that fails the exact empty-circle test lies on an input segment.
    pub constrained_delaunay: bool,
    /// Largest allowed triangle area everywhere (the maximum area the mesher was asked for).
    pub max_area: Option<f64>,
    /// Longest allowed edge everywhere (the maximum edge length the mesher was asked for).
    pub max_edge: Option<f64>,
    /// Every triangle's area is at most the area limit of the input region it lies in
    /// ([`crate::Region::area_limit`], regions located by [`crate::quality::triangle_regions`]).
    pub region_area_limits: bool,
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
            interior_only_on_segments: false,
            whole_sharp_corners: false,
            near_segment_angles: None,
            constrained_delaunay: false,
            max_area: None,
            max_edge: None,
            region_area_limits: false,
        }
    }

    /// These bounds and the area limits a mesher with size control keeps: `max_area`
    /// everywhere and each input region's own limit.
    pub fn with_area_limits(self, max_area: Option<f64>) -> Bounds {
        Bounds {
            max_area,
            region_area_limits: true,
            ..self
        }
    }

    /// These bounds and the size limits of a mesher that keeps every one it is given:
    /// `max_area` and each input region's own limit (`with_area_limits`) and `max_edge`.
    pub fn with_size_limits(self, max_area: Option<f64>, max_edge: Option<f64>) -> Bounds {
        Bounds {
            max_edge,
            ..self.with_area_limits(max_area)
        }
    }

    /// Angles in [lo, hi] degrees on top of validity; on a PSLG checked away from the
    /// segments.
    pub fn angles(name: &str, lo: f64, hi: f64) -> Bounds {
        Bounds {
            min_angle: Some(lo),
            max_angle: Some(hi),
            interior_only_on_segments: true,
            ..Bounds::validity(name)
        }
    }

    /// Validity and the exact Delaunay property: a conforming Delaunay mesher's promise.
    pub fn conforming_delaunay(name: &str) -> Bounds {
        Bounds {
            delaunay: true,
            ..Bounds::validity(name)
        }
    }

    /// Validity and every triangle's smallest angle at least `ratio` times that of the
    /// initial triangle it lies in (`quality::descent`): longest-side bisection's promise.
    pub fn descent(name: &str, ratio: f64) -> Bounds {
        Bounds {
            min_angle_over_ancestor: Some(ratio),
            ..Bounds::validity(name)
        }
    }

    /// The bounds that are no mesher's promise: `valid` (validity alone), `delaunay` (the
    /// empty-circle test alone) or `min-angle=DEG` (validity and a smallest angle, but at
    /// input corners sharper than it taken whole, which no mesh can improve). A
    /// mesher's name is looked up by `registry::bounds`.
    pub fn named(name: &str) -> Result<Bounds> {
        match name {
            "valid" => Ok(Bounds::validity(name)),
            "delaunay" => Ok(Bounds {
                delaunay: true,
                conforming: false,
                ..Bounds::validity(name)
            }),
            _ => match name.strip_prefix("min-angle=") {
                Some(deg) => {
                    let value: f64 = deg.trim().parse().map_err(|_| {
                        Error::Usage(format!(
                            "bounds '{name}': '{deg}' is not a number of degrees"
                        ))
                    })?;
                    Ok(Bounds {
                        whole_sharp_corners: true,
                        ..Bounds::validity(name).with_min_angle(value)?
                    })
                }
                None => Err(Error::Usage(format!(
                    "unknown bounds '{name}'; valid names: {}",
                    GENERIC_BOUNDS.join(", ")
                ))),
            },
        }
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
    fn hex_criteria_match_their_formulas() {
        let alpha = (5.0 / (3.0 * 3f64.sqrt())).atan().to_degrees();
        assert_eq!(HEX.min_angle.to_bits(), alpha.to_bits(), "{alpha}");
        let edge = 7f64.sqrt() / (12.0 * 3f64.sqrt());
        assert!((HEX.min_edge_over_dmin - edge).abs() < 1e-15, "{edge}");
        // Right triangle with legs 5 and 3√3: R/(2r) = c / (2(a + b − c)).
        let (a, b) = (5.0, 3.0 * 3f64.sqrt());
        let c = (a * a + b * b).sqrt();
        let rr = c / (2.0 * (a + b - c));
        assert!(
            rr <= HEX.max_radius_ratio && HEX.max_radius_ratio - rr < 1e-6,
            "{rr}"
        );
    }

    #[test]
    fn the_hex_promise_is_its_criteria() {
        let hex = HEX.bounds();
        assert_eq!(hex.min_angle, Some(HEX.min_angle));
        assert_eq!(hex.max_angle, Some(90.0));
        assert_eq!(hex.max_radius_ratio, Some(HEX.max_radius_ratio));
        assert!(hex.delaunay && hex.conforming);
        assert!(hex.interior_only_on_segments);
        assert_eq!(hex.near_segment_angles, Some((30.0, 120.0)));
        assert!(hex.constrained_delaunay);
    }

    #[test]
    fn min_angle_parses_and_rejects_nonsense() {
        assert_eq!(
            Bounds::named("min-angle=33.5").expect("33.5").min_angle,
            Some(33.5)
        );
        assert!(matches!(
            Bounds::named("min-angle=abc"),
            Err(Error::Usage(_))
        ));
        assert!(matches!(
            Bounds::named("min-angle=75"),
            Err(Error::Usage(_))
        ));
        assert!(matches!(
            Bounds::named("min-angle=NaN"),
            Err(Error::Usage(_))
        ));
    }

    #[test]
    fn an_unknown_name_lists_the_generic_ones() {
        match Bounds::named("hexx") {
            Err(Error::Usage(msg)) => {
                assert!(
                    msg.contains("hexx")
                        && msg.contains("delaunay")
                        && msg.contains("min-angle=DEG"),
                    "{msg}"
                )
            }
            other => panic!("expected a usage error, got {other:?}"),
        }
    }
}
