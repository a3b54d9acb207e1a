//! The `triangle` reference mesher: Shewchuk's Triangle 1.6 (constrained Delaunay
//! refinement, Shewchuk 2002 "Delaunay refinement algorithms for triangular mesh
//! generation"), its C code compiled into the binary by tritet 3.4.0 and called directly
//! through `triangulate()` (`ffi`), so that the harness chooses the whole switch string.
//!
//! The switch string (`triangle_switches`, shown by `settings`) is the fixed part the harness
//! needs, then what `Params` asks for, then the user's switches (`Params::switches`, the
//! CLI's `--triangle-switches`) as given:
//! - `pzAQ`: `p` PSLG, `z` zero-based numbering, `A` regional attributes, `Q` quiet; no `j`,
//!   so the input vertices come back first, in input order, with their exact bits; no `c`
//!   (unless the user adds it), so triangles outside the segments' region are eaten, as are
//!   seeded holes;
//! - a bare `a`: every region of the input (`Pslg::labels.regions`) goes to Triangle's
//!   regionlist with its area bound (`max_area`, or the attribute without one, as Triangle
//!   reads a .poly file; ≤ 0 means no bound), and Triangle applies it natively;
//! - `a<A>` for `--max-area`: Triangle keeps a fixed bound and the regional ones apart and
//!   splits a triangle above either, so both apply (the smaller one wins in a region);
//! - `q<θ>` for `--min-angle`, or a bare `q` (Triangle's 20°) when neither it nor the user's
//!   switches give a `q`: the harness always asks for quality;
//! - numbers are written as Rust's shortest round-trip decimals (no exponent: Triangle's
//!   reader takes digits and dots only), so Triangle's `strtod` reads the very f64 asked for.
//!
//! The user's switches are read by `switches::parse`, which refuses those that would break the
//! harness (`j`, `r`, output-shaping and unknown ones; see there). A `q` or an `a<A>` in them
//! together with `--min-angle` or `--max-area` is a usage error: neither silently wins.
//!
//! Triangle calls `exit()` (`triexit`) instead of returning on: an input of fewer than three
//! points or all-identical points, a zero fixed area, running out of memory, "Ran out of
//! precision" while splitting segments (tiny features), and internal errors; it may also not
//! terminate for angles above about 34°. `Pslg::check` plus the checks here rule out the input
//! errors; the rest can still end or hang the process, which is why the harness isolates it.
//! `Budget` is not enforced in-process; run through `isolate::run_isolated` to bound the time.
//! Triangle keeps global predicate state, so calls are serialized with a process-wide mutex.

mod ffi;
pub mod switches;

use std::sync::Mutex;
use std::time::Instant;

use super::check_request;
use crate::error::{Error, Result};
use crate::mesh::Pslg;
use crate::mesher::{MeshRun, Mesher, Params};
use crate::quality::Bounds;

pub use self::switches::Switches;

const NAME: &str = "triangle";

/// Triangle's default minimum angle for a bare `q` switch.
pub const DEFAULT_MIN_ANGLE: f64 = 20.0;

static TRIANGLE_LOCK: Mutex<()> = Mutex::new(());

/// Shewchuk's Triangle as a `Mesher`.
#[derive(Debug, Clone, Copy, Default)]
pub struct TriangleMesher;

/// The user's switches of `params`, read and checked against `--min-angle`/`--max-area`.
pub fn user_switches(params: &Params) -> Result<Option<Switches>> {
    let Some(given) = params.switches.as_deref() else {
        return Ok(None);
    };
    let user = switches::parse(given)?;
    let clash = |switch: &str, option: &str| {
        Err(Error::Usage(format!(
            "--triangle-switches \"{given}\" has {switch} and {option} asks for the same: give one"
        )))
    };
    if user.min_angle.is_some() && params.min_angle.is_some() {
        return clash("a q switch", "--min-angle");
    }
    if user.max_area.is_some() && params.max_area.is_some() {
        return clash("an a switch with a number", "--max-area");
    }
    Ok(Some(user))
}

/// The exact switch string sent to Triangle's `triangulate()` for `params` (module comment).
/// Errors for requests no reference honours and for refused or clashing user switches.
pub fn triangle_switches(params: &Params) -> Result<String> {
    check_request(NAME, params)?;
    params.refuse_max_edge(
        NAME,
        "Triangle bounds areas (a) and angles (q), not edge lengths; ask for --max-area instead",
    )?;
    let user = user_switches(params)?;
    let mut s = String::from("pzAQa");
    if let Some(area) = params.max_area {
        s.push_str(&format!("a{area}"));
    }
    match params.min_angle {
        Some(angle) => s.push_str(&format!("q{angle}")),
        None if user.as_ref().is_some_and(|u| u.min_angle.is_some()) => {}
        None => s.push('q'),
    }
    if let Some(u) = &user {
        s.push_str(&u.text);
    }
    // Rust writes an f64 in at most a few hundred digits, far below Triangle's buffer.
    debug_assert!(s.len() < switches::NUMBER_BUFFER);
    Ok(s)
}

/// The minimum angle a call with `params` asks for: `--min-angle`, else the user's `q`, else
/// the bare `q`'s 20°; none when the user's switches let Triangle stop short of it (`S`, `Y`).
fn asked_angle(params: &Params) -> Option<f64> {
    let user = user_switches(params).ok().flatten();
    if user.as_ref().is_some_and(Switches::may_miss_the_angle) {
        return None;
    }
    Some(
        params
            .min_angle
            .or(user.and_then(|u| u.min_angle))
            .unwrap_or(DEFAULT_MIN_ANGLE),
    )
}

/// Refuses what Triangle would `exit()` on or overflow with, before it sees the domain.
fn check_domain(domain: &Pslg) -> Result<()> {
    super::check_scale(NAME, domain)?;
    if domain.points.len() < 3 {
        return Err(Error::mesher(NAME, "Triangle needs at least three points"));
    }
    if domain.segments.len() < 3 {
        return Err(Error::mesher(
            NAME,
            "a PSLG needs at least three segments to bound a region",
        ));
    }
    // Triangle computes buffer sizes in `int` bytes (points × 2 × 8 and the like),
    // which overflows beyond 2^31 / 16 items (a region takes 4 × 8 bytes).
    let limit = i32::MAX as usize / 16;
    let regions = domain.labels.regions.len();
    if domain.points.len() > limit
        || domain.segments.len() > limit
        || domain.holes.len() > limit
        || regions > limit / 2
    {
        return Err(Error::mesher(
            NAME,
            format!("input too large for Triangle's int sizes (at most {limit} points)"),
        ));
    }
    if let Some((k, r)) = domain.labels.regions.iter().enumerate().find(|(_, r)| {
        ![r.point[0], r.point[1], r.attribute]
            .iter()
            .chain(&r.max_area)
            .all(|v| v.is_finite())
    }) {
        return Err(Error::mesher(
            NAME,
            format!("region {k} has a non-finite value: {r:?}"),
        ));
    }
    Ok(())
}

impl Mesher for TriangleMesher {
    fn name(&self) -> &'static str {
        NAME
    }

    fn version(&self) -> String {
        "Triangle 1.6 (compiled by tritet 3.4.0), triangulate() called directly".to_string()
    }

    fn settings(&self, params: &Params) -> String {
        let budget = if params.budget == Default::default() {
            ""
        } else {
            "; budget not enforced in-process, bounded by isolation's timeout"
        };
        match triangle_switches(params) {
            Ok(s) => {
                let bare_q = params.min_angle.is_none()
                    && !user_switches(params)
                        .is_ok_and(|u| u.is_some_and(|u| u.min_angle.is_some()));
                let q = if bare_q { " (bare q = 20°)" } else { "" };
                format!("triangulate(\"{s}\"){q}{budget}")
            }
            Err(e) => format!("invalid: {e}"),
        }
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        // Without S or Y (where Triangle may stop short), it keeps the angle and the area
        // limits: --max-area everywhere and each region's own.
        match asked_angle(params) {
            Some(angle) => super::asked_angle(
                NAME,
                &Params::default().with_min_angle(angle),
                DEFAULT_MIN_ANGLE,
            )
            .with_area_limits(params.max_area),
            None => Bounds::validity(NAME),
        }
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        // Triangle exits the process on inputs it rejects: check everything first.
        input.validate_input()?;
        let switches = triangle_switches(params)?;
        let domain = input.reference_domain();
        check_domain(&domain)?;
        let regions: Vec<[f64; 4]> = domain
            .labels
            .regions
            .iter()
            .map(|r| {
                let area = r.max_area.unwrap_or(r.attribute);
                [r.point[0], r.point[1], r.attribute, area]
            })
            .collect();
        let call = ffi::Input {
            switches: &switches,
            points: &domain.points,
            segments: &domain.segments,
            holes: &domain.holes,
            regions: &regions,
        };
        let start = Instant::now();
        let mesh = {
            // A poisoned lock only means another call panicked; Triangle's state is reset
            // at the start of every call, so it is safe to go on.
            let _guard = TRIANGLE_LOCK.lock().unwrap_or_else(|p| p.into_inner());
            ffi::run(&call).map_err(|e| Error::mesher(NAME, format!("Triangle: {e}")))?
        };
        let elapsed = start.elapsed();
        let vertices = &mesh.vertices;
        let n = vertices.len();
        if n < domain.points.len() {
            return Err(Error::mesher(
                NAME,
                format!(
                    "Triangle returned {n} points for {} input points",
                    domain.points.len()
                ),
            ));
        }
        if let Some(i) = (0..domain.points.len()).find(|&i| {
            vertices[i][0].to_bits() != domain.points[i][0].to_bits()
                || vertices[i][1].to_bits() != domain.points[i][1].to_bits()
        }) {
            return Err(Error::mesher(
                NAME,
                format!("Triangle moved input point {} (numbered from 1)", i + 1),
            ));
        }
        Ok(MeshRun {
            steps: (n - domain.points.len()) as u64,
            mesh,
            complete: true,
            stop_reason: None,
            elapsed,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Labels, Region};

    #[test]
    fn switches_are_the_fixed_part_the_request_and_the_users_in_that_order() {
        let p = Params::default().with_min_angle(30.0).with_max_area(0.5);
        assert_eq!(triangle_switches(&p).unwrap(), "pzAQaa0.5q30");
        assert_eq!(triangle_switches(&Params::default()).unwrap(), "pzAQaq");
        let user = Params::default().with_switches("-q25D");
        assert_eq!(triangle_switches(&user).unwrap(), "pzAQaq25D");
        let both = Params::default()
            .with_min_angle(28.5)
            .with_switches("Ya0.25");
        assert_eq!(triangle_switches(&both).unwrap(), "pzAQaq28.5Ya0.25");
    }

    #[test]
    fn numbers_are_sent_as_shortest_round_trip_decimals() {
        // No exponent: Triangle's reader takes digits and dots only.
        let p = Params::default().with_max_area(1e-20).with_min_angle(0.0);
        assert_eq!(
            triangle_switches(&p).unwrap(),
            "pzAQaa0.00000000000000000001q0"
        );
        let third = Params::default().with_max_area(1.0 / 3.0);
        let s = triangle_switches(&third).unwrap();
        let digits = &s["pzAQaa".len()..s.len() - 1];
        assert_eq!(
            digits.parse::<f64>().unwrap().to_bits(),
            (1.0f64 / 3.0).to_bits()
        );
    }

    #[test]
    fn a_user_q_or_a_beside_the_options_is_a_usage_error() {
        let angle = Params::default().with_min_angle(30.0).with_switches("q25");
        let area = Params::default().with_max_area(0.5).with_switches("a0.1");
        for p in [angle, area] {
            assert!(
                matches!(triangle_switches(&p), Err(Error::Usage(_))),
                "{p:?}"
            );
        }
        // A bare `a` (regional bounds) beside --max-area is no clash.
        let bare = Params::default().with_max_area(0.5).with_switches("a");
        assert_eq!(triangle_switches(&bare).unwrap(), "pzAQaa0.5qa");
    }

    #[test]
    fn the_promise_follows_the_angle_asked_for_where_it_is_asked() {
        let angle = |p: &Params| TriangleMesher.promise(p).min_angle;
        assert_eq!(angle(&Params::default()), Some(20.0));
        assert_eq!(angle(&Params::default().with_min_angle(31.0)), Some(31.0));
        assert_eq!(angle(&Params::default().with_switches("q27.5")), Some(27.5));
        assert_eq!(angle(&Params::default().with_switches("q")), Some(20.0));
        // S and Y let Triangle stop short of the angle: validity and conformity only.
        let capped = TriangleMesher.promise(&Params::default().with_switches("q30S5"));
        assert_eq!(capped.min_angle, None);
        assert!(capped.conforming);
        assert_eq!(angle(&Params::default().with_switches("q30Y")), None);
    }

    #[test]
    fn areas_triangle_would_exit_on_are_refused() {
        assert!(triangle_switches(&Params::default().with_max_area(0.0)).is_err());
        assert!(triangle_switches(&Params::default().with_max_area(f64::INFINITY)).is_err());
        assert!(triangle_switches(&Params::default().with_switches("a0")).is_err());
        assert!(triangle_switches(&Params::default().with_max_area(1e300)).is_ok());
    }

    #[test]
    fn two_segments_are_refused_before_triangle_sees_them() {
        let input = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            segments: vec![[0, 1], [1, 2]],
            ..Pslg::default()
        };
        assert!(TriangleMesher.mesh(&input, &Params::default()).is_err());
    }

    /// The unit square as one region with `attribute` and `max_area`.
    fn square_region(attribute: f64, max_area: Option<f64>) -> Pslg {
        Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            labels: Labels {
                regions: vec![Region {
                    point: [0.5, 0.5],
                    attribute,
                    max_area,
                }],
                ..Labels::default()
            },
            ..Pslg::default()
        }
    }

    fn largest_area(run: &MeshRun) -> f64 {
        (0..run.mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = run.mesh.corners(t);
                0.5 * crate::geom::orient2d(a, b, c)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_region_without_an_area_is_bounded_by_its_attribute_as_triangle_reads_it() {
        let run = TriangleMesher
            .mesh(&square_region(0.02, None), &Params::default())
            .unwrap();
        let largest = largest_area(&run);
        assert!(
            largest <= 0.02 && run.mesh.triangles.len() >= 50,
            "{largest}"
        );
        // A bound of zero or less is no bound, in Triangle's words "unconstrained".
        let free = TriangleMesher
            .mesh(&square_region(0.02, Some(0.0)), &Params::default())
            .unwrap();
        assert!(largest_area(&free) > 0.02, "{}", largest_area(&free));
    }

    #[test]
    fn a_region_with_a_non_finite_value_is_refused_before_triangle_sees_it() {
        let mut input = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            labels: Labels {
                regions: vec![Region {
                    point: [0.5, 0.5],
                    attribute: 1.0,
                    max_area: Some(f64::NAN),
                }],
                ..Labels::default()
            },
            ..Pslg::default()
        };
        let e = TriangleMesher.mesh(&input, &Params::default()).unwrap_err();
        assert!(e.to_string().contains("region 0"), "{e}");
        input.labels.regions[0].max_area = Some(0.05);
        let run = TriangleMesher.mesh(&input, &Params::default()).unwrap();
        assert!(
            run.mesh.triangles.len() >= 20,
            "{}",
            run.mesh.triangles.len()
        );
    }
}
