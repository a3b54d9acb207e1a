//! The rounding allowance: how far a figure measured on f64 vertices may lie beyond a bound
//! that holds in real arithmetic (README "Checks", "Rounding").
//!
//! A mesher places its vertices in f64, each a few roundings of its own coordinates away from
//! where real arithmetic puts it. Vertex v moves by at most δv = 2^-50·max(|xv|, |yv|) (a
//! rounding of a coordinate is at most 2^-53 of it; δv leaves room for several). The angle at
//! a of triangle abc changes, to first order, by at most (δa + δb)/|ab| when a and b move
//! across ab, and likewise along ac, so
//!
//!   A(a) = (δa + δb)/|ab| + (δa + δc)/|ac|   radians, plus `ANGLE_FLOOR_DEG`,
//!
//! and an angle θ meets [lo, hi] when lo − A(a) ≤ θ ≤ hi + A(a). The floor covers what no
//! vertex move explains: the check's own arithmetic and the once-rounded constants (√3, the
//! turn) that change the whole lattice alike.
//!
//! The radius ratio ρ = R/(2r) = 1/(8·∏ sin(θi/2)) of a triangle with angles θi has
//! ∂ρ/∂θi = −ρ·½·cot(θi/2), so angle changes of at most A(i) change it by at most
//! ρ·½·Σ cot(θi/2)·A(i). An edge ab changes by at most δa + δb; d_min is measured between
//! input points, which every mesher keeps bit for bit, so shortest-edge/d_min may fall short
//! by (δa + δb)/d_min.
//!
//! The allowance *used* by a figure is how far it lies beyond the exact bound (zero inside
//! it). A check passes when no figure uses more than its allowance; our meshers also refuse
//! to hand out a mesh any of whose angles uses more than `max_rounding` degrees (default
//! `DEFAULT_MAX_ROUNDING_DEG`; `check_angles`), naming the input points that forced it.
//!
//! Every quantity is a ratio of lengths, computed from differences scaled by an exact power of
//! two, so it neither overflows nor underflows for finite coordinates up to 1e150.

use crate::geom::{dist_scaled, Point};

/// δv over max(|xv|, |yv|): 2^-50, a few roundings of a coordinate.
pub const ROUNDING_UNIT: f64 = 1.0 / (1u64 << 50) as f64;

/// The part of every angle allowance that no vertex move explains, in degrees.
pub const ANGLE_FLOOR_DEG: f64 = 1e-6;

/// The largest allowance a mesh of ours may use before the input is refused, in degrees
/// (`--max-rounding`); defined beside `Params`, which falls back to it.
pub use crate::mesher::DEFAULT_MAX_ROUNDING_DEG;

/// δv: how far rounding may have moved vertex `p` from its place in real arithmetic.
pub fn delta(p: Point) -> f64 {
    ROUNDING_UNIT * p[0].abs().max(p[1].abs())
}

/// The allowance of the angle at `a` of triangle (a, b, c), in degrees (module docs).
pub fn angle_allowance(a: Point, b: Point, c: Point) -> f64 {
    let da = delta(a);
    let rad = (da + delta(b)) / dist_scaled(a, b) + (da + delta(c)) / dist_scaled(a, c);
    rad.to_degrees() + ANGLE_FLOOR_DEG
}

/// What one rounding of each coordinate can move a vertex, over max(|xv|, |yv|): at most
/// √2·2^-53 < 2^-52. A lattice vertex our meshers place is rounded once from its exact
/// position (an fma, or an accurate sum for a turned lattice), so it lies within this of it.
pub const PLACEMENT_UNIT: f64 = f64::EPSILON;

/// How far placing the corners of (a, b, c) by one rounding each can move the angle at `a`,
/// in degrees: `angle_allowance` with δ = `PLACEMENT_UNIT`·max(|x|, |y|) and no floor, a
/// quarter of the allowance's rounding part. A mesher's self-check grants its own
/// construction no more than this: an angle beyond it is a configuration the rules must fix.
/// Granting the whole allowance there let rules whose exact angles break the bound through
/// wherever the triangles were small against their coordinates (a pair 1e-11 of its
/// coordinates apart), and the finished mesh was then refused for rounding it did not make.
pub fn placement_allowance(a: Point, b: Point, c: Point) -> f64 {
    (angle_allowance(a, b, c) - ANGLE_FLOOR_DEG) * (PLACEMENT_UNIT / ROUNDING_UNIT)
}

/// The allowances of the three angles of triangle `t`, corner by corner, in degrees.
pub fn angle_allowances(t: [Point; 3]) -> [f64; 3] {
    std::array::from_fn(|m| angle_allowance(t[m], t[(m + 1) % 3], t[(m + 2) % 3]))
}

/// The allowance of the radius ratio `rho` of triangle `t` whose angles (degrees) are
/// `angles`: ρ·½·Σ cot(θi/2)·A(i) (module docs).
pub fn radius_ratio_allowance(t: [Point; 3], angles: [f64; 3], rho: f64) -> f64 {
    let a = angle_allowances(t);
    let sum: f64 = (0..3)
        .map(|i| a[i].to_radians() / (angles[i].to_radians() / 2.0).tan())
        .sum();
    rho * 0.5 * sum
}

/// The allowance of edge (a, b) against a length bound: δa + δb.
pub fn edge_allowance(a: Point, b: Point) -> f64 {
    delta(a) + delta(b)
}

/// How far `value` lies beyond [lo, hi] (zero inside): the allowance it uses.
pub fn beyond(value: f64, lo: f64, hi: f64) -> f64 {
    (lo - value).max(value - hi).max(0.0)
}

/// One figure of one triangle against its bound: the allowance it uses and the one it has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Use {
    /// How far the figure lies beyond its bound (zero inside it).
    pub used: f64,
    /// How far rounding may move it.
    pub allowance: f64,
    /// The figure itself.
    pub value: f64,
    /// The triangle's 0-based index.
    pub triangle: usize,
}

/// A bound over many figures: the one that uses the most allowance, and the one that comes
/// nearest to breaking it (largest used − allowance). The bound holds when `nearest` does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// The figure using the largest allowance.
    pub most: Use,
    /// The figure with the largest `used − allowance`.
    pub nearest: Use,
}

impl Fit {
    /// True when no figure uses more than its allowance.
    pub fn holds(&self) -> bool {
        self.nearest.used <= self.nearest.allowance
    }
}

/// The `Fit` of a set of figures; `None` for none.
pub fn fit_of(uses: impl IntoIterator<Item = Use>) -> Option<Fit> {
    let mut fit: Option<Fit> = None;
    for u in uses {
        match &mut fit {
            None => {
                fit = Some(Fit {
                    most: u,
                    nearest: u,
                })
            }
            Some(f) => {
                if u.used > f.most.used {
                    f.most = u;
                }
                if u.used - u.allowance > f.nearest.used - f.nearest.allowance {
                    f.nearest = u;
                }
            }
        }
    }
    fit
}

/// The angles of triangle `triangle` with corners `t` against [lo, hi], in degrees. The
/// allowance is computed only for an angle beyond the bound (inside, the angle uses none and
/// cannot break it; its allowance is reported as the floor).
pub fn angle_uses(triangle: usize, t: [Point; 3], lo: f64, hi: f64) -> [Use; 3] {
    let th = [
        crate::geom::angle_deg(t[0], t[1], t[2]),
        crate::geom::angle_deg(t[1], t[2], t[0]),
        crate::geom::angle_deg(t[2], t[0], t[1]),
    ];
    std::array::from_fn(|m| {
        let used = beyond(th[m], lo, hi);
        Use {
            used,
            allowance: if used > 0.0 {
                angle_allowance(t[m], t[(m + 1) % 3], t[(m + 2) % 3])
            } else {
                ANGLE_FLOOR_DEG
            },
            value: th[m],
            triangle,
        }
    })
}

/// The `Fit` of every angle of the triangles `tris` (index, corners) against [lo, hi].
pub fn angle_fit(tris: impl Iterator<Item = (usize, [Point; 3])>, lo: f64, hi: f64) -> Option<Fit> {
    fit_of(tris.flat_map(|(t, c)| angle_uses(t, c, lo, hi)))
}

/// The refusal of an input whose mesh would use `needed` degrees of rounding allowance (more
/// than `allowed`) at the triangle with corners `t`: the input point nearest the triangle and
/// the input point nearest that one, with their distance. O(n) in the points.
pub fn refusal_near(
    points: &[Point],
    t: [Point; 3],
    needed: f64,
    allowed: f64,
) -> crate::error::InputError {
    let centre = [
        (t[0][0] + t[1][0] + t[2][0]) / 3.0,
        (t[0][1] + t[1][1] + t[2][1]) / 3.0,
    ];
    let nearest = |to: Point, skip: Option<usize>| {
        (0..points.len())
            .filter(|&i| Some(i) != skip)
            .min_by(|&i, &j| dist_scaled(points[i], to).total_cmp(&dist_scaled(points[j], to)))
    };
    let first = nearest(centre, None).unwrap_or(0);
    let second =
        nearest(points.get(first).copied().unwrap_or(centre), Some(first)).unwrap_or(first);
    let distance = match (points.get(first), points.get(second)) {
        (Some(&a), Some(&b)) => dist_scaled(a, b),
        _ => 0.0,
    };
    crate::error::InputError::Rounding {
        first: first.min(second),
        second: first.max(second),
        distance,
        needed,
        allowed,
    }
}

/// A cheap test that every angle of a triangle lies clearly inside [lo − slack, hi + slack]
/// for lo < 90° ≤ hi, without `atan2`: `false` means "not clearly", and the caller then
/// measures the angles, so every decision is the one the measured angles give. At a corner
/// with edge vectors u, v the angle is atan2(|u×v|, u·v): when u·v > 0 it is clearly
/// ≥ lo − slack if |u×v| ≥ (u·v)·tan(lo − slack)·(1 + 1e-12), and below 90°; when u·v ≤ 0 it
/// is clearly ≤ hi + slack if −u·v ≤ |u×v|·tan(hi − 90° + slack)·(1 − 1e-5). The guard
/// factors are far wider than the rounding of `atan2` and of the degree conversion (below
/// 1e-14°), and far narrower than any slack it is used with (1e-7°).
#[derive(Debug, Clone, Copy)]
pub(crate) struct AngleWindow {
    tan_lo: f64,
    tan_hi: f64,
}

impl AngleWindow {
    /// The window [lo − slack, hi + slack], all in degrees, for lo < 90° ≤ hi.
    pub fn new(lo: f64, hi: f64, slack: f64) -> AngleWindow {
        debug_assert!(lo < 90.0 && hi >= 90.0, "[{lo}, {hi}]");
        AngleWindow {
            tan_lo: (lo - slack).to_radians().tan() * (1.0 + 1e-12),
            tan_hi: ((hi - 90.0) + slack).to_radians().tan() * (1.0 - 1e-5),
        }
    }

    /// True when every angle of the triangle `t` is clearly inside the window; false means
    /// the angles must be measured.
    pub fn clearly_within(&self, t: &[Point; 3]) -> bool {
        (0..3).all(|m| {
            let (a, b, c) = (t[m], t[(m + 1) % 3], t[(m + 2) % 3]);
            let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
            let (vx, vy) = (c[0] - a[0], c[1] - a[1]);
            let cross = (ux * vy - uy * vx).abs();
            let dot = ux * vx + uy * vy;
            if dot > 0.0 {
                cross >= dot * self.tan_lo
            } else {
                cross > 0.0 && -dot <= cross * self.tan_hi
            }
        })
    }
}

/// The slack of the window `check_angles` skips triangles with: an angle inside it uses less
/// than any allowance (whose floor is 1e-6°) and than any `max_rounding` at least as large.
const SKIP_SLACK_DEG: f64 = 1e-7;

/// A finished mesh of one of our meshers (`mesher`) against its angle bounds (lo, hi), with
/// the rounding allowance: refused, naming the two input points near the worst angle
/// (`refusal_near`), when an angle lies beyond the bounds by more than `max_rounding`
/// degrees. An angle beyond its allowance is a defect of the mesher, reported as such even
/// when it also passes `max_rounding`: rounding cannot explain it, so a refusal blaming the
/// input's closeness would be a false statement.
pub fn check_angles(
    mesh: &crate::mesh::TriMesh,
    points: &[Point],
    bounds: (f64, f64),
    max_rounding: f64,
    mesher: &str,
) -> crate::error::Result<()> {
    check_triangle_angles(
        mesh,
        0..mesh.triangles.len(),
        points,
        bounds,
        max_rounding,
        mesher,
    )
}

/// `check_angles` with the triangles clearly inside the bounds' window (most of them) found
/// over `threads` threads first: the same verdict and message for every count.
pub fn check_angles_over(
    mesh: &crate::mesh::TriMesh,
    points: &[Point],
    (lo, hi): (f64, f64),
    max_rounding: f64,
    mesher: &str,
    threads: usize,
) -> crate::error::Result<()> {
    if !(lo < 90.0 && hi >= 90.0 && max_rounding >= SKIP_SLACK_DEG) {
        return check_angles(mesh, points, (lo, hi), max_rounding, mesher);
    }
    let window = AngleWindow::new(lo, hi, SKIP_SLACK_DEG);
    let n = mesh.triangles.len();
    let measured = crate::hex::parallel::ranges_in_parallel(
        threads,
        n,
        crate::hex::parallel::PARALLEL_MIN,
        |range| {
            range
                .filter(|&t| !window.clearly_within(&mesh.corners(t)))
                .collect::<Vec<usize>>()
        },
    );
    check_triangle_angles(
        mesh,
        measured.into_iter().flatten(),
        points,
        (lo, hi),
        max_rounding,
        mesher,
    )
}

/// `check_angles` on the triangles `triangles` of `mesh` only (indices into the whole mesh,
/// which the messages use).
pub fn check_triangle_angles(
    mesh: &crate::mesh::TriMesh,
    triangles: impl Iterator<Item = usize>,
    points: &[Point],
    (lo, hi): (f64, f64),
    max_rounding: f64,
    mesher: &str,
) -> crate::error::Result<()> {
    use crate::error::Error;
    // Triangles clearly inside a window narrower than both thresholds cannot decide either;
    // most are, so only the rest are measured.
    let window = (lo < 90.0 && hi >= 90.0 && max_rounding >= SKIP_SLACK_DEG)
        .then(|| AngleWindow::new(lo, hi, SKIP_SLACK_DEG));
    let tris = triangles
        .map(|t| (t, mesh.corners(t)))
        .filter(|(_, c)| !window.is_some_and(|w| w.clearly_within(c)));
    let Some(fit) = angle_fit(tris, lo, hi) else {
        return Ok(());
    };
    if !fit.holds() {
        let n = fit.nearest;
        return Err(Error::mesher(
            mesher,
            format!(
                "internal error: an angle of triangle {} (numbered from 1) is {}°, beyond \
                 [{lo}°, {hi}°] by more than its rounding allowance of {:e}°",
                n.triangle + 1,
                n.value,
                n.allowance
            ),
        ));
    }
    if fit.most.used > max_rounding {
        return Err(Error::input(refusal_near(
            points,
            mesh.corners(fit.most.triangle),
            fit.most.used,
            max_rounding,
        )));
    }
    Ok(())
}

/// `check_angles` on the triangles of a mesh of a PSLG that the verdict counts as interior
/// (no corner on, and none within the on-segment tolerance of, an input segment): where the
/// bounds of a mesher hold away from the segments only (paper 000 Sec. 7), those are the
/// angles the rounding contract covers.
pub fn check_interior_angles(
    mesh: &crate::mesh::TriMesh,
    input: &crate::mesh::Pslg,
    bounds: (f64, f64),
    max_rounding: f64,
    mesher: &str,
) -> crate::error::Result<()> {
    let band = crate::quality::metrics::on_segment_tolerance(input);
    let near = crate::quality::metrics::near_segment_triangles(mesh, input, band);
    let mut is_near = vec![false; mesh.triangles.len()];
    for t in near {
        is_near[t] = true;
    }
    let interior = (0..mesh.triangles.len()).filter(|&t| !is_near[t]);
    check_triangle_angles(mesh, interior, &input.points, bounds, max_rounding, mesher)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_allowance_is_the_floor_plus_a_few_roundings_over_the_edges() {
        // A unit right triangle at 1e7: δ = 2^-50·1e7 at each corner, edges of 1.
        let off = 1e7;
        let t = [[off, off], [off + 1.0, off], [off, off + 1.0]];
        let a = angle_allowance(t[0], t[1], t[2]);
        let d = ROUNDING_UNIT * (off + 1.0);
        let expected = (2.0 * ROUNDING_UNIT * off + 2.0 * d).to_degrees() + ANGLE_FLOOR_DEG;
        assert!((a - expected).abs() < 1e-15, "{a} {expected}");
        // Near the origin it is the floor and a few roundings of unit coordinates.
        let u = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let b = angle_allowance(u[0], u[1], u[2]);
        assert!(b > ANGLE_FLOOR_DEG && b < ANGLE_FLOOR_DEG + 1e-12, "{b}");
    }

    #[test]
    fn allowances_do_not_overflow_or_underflow_at_extreme_scales() {
        for s in [1e-150, 1e-80, 1.0, 1e80, 1e150] {
            let t = [[s, 0.0], [2.0 * s, 0.0], [s, s]];
            let a = angle_allowances(t);
            assert!(a.iter().all(|x| x.is_finite() && *x > 0.0), "{s}: {a:?}");
            let r = radius_ratio_allowance(t, [90.0, 45.0, 45.0], 1.2071);
            assert!(r.is_finite() && r > 0.0, "{s}: {r}");
        }
    }

    #[test]
    fn an_angle_beyond_its_allowance_is_a_mesher_defect_even_past_max_rounding() {
        // 1° below 30° at unit coordinates: far past 0.01°, but rounding explains none of it,
        // so blaming the input's closeness would be false.
        let e = 1f64.to_radians();
        let (c, s) = (
            (30f64.to_radians() - e).cos(),
            (30f64.to_radians() - e).sin(),
        );
        let mesh = crate::mesh::TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [c, s]],
            triangles: vec![[0, 1, 2]],
        };
        let err = check_angles(&mesh, &mesh.vertices, (29.0 - 1e-3, 180.0), 0.01, "m");
        assert!(err.is_ok(), "{err:?}");
        let err = check_angles(&mesh, &mesh.vertices, (30.0, 180.0), 0.01, "m").unwrap_err();
        assert!(
            matches!(err, crate::error::Error::Mesher { .. }),
            "not a defect: {err}"
        );
    }

    #[test]
    fn interior_angles_of_a_domain_are_held_to_max_rounding_and_those_at_segments_are_not() {
        // A square at 1e7 with its four segments, one interior triangle 1e-3 across whose
        // smallest angle is 1e-3° below 43.8978862° (its allowance there is about 2e-3°), and
        // one triangle on a corner with a 10° angle (near a segment: not checked here).
        let o = 1e7;
        let lo: f64 = 43.897_886_2 - 1e-3;
        let (c, s) = (lo.to_radians().cos(), lo.to_radians().sin());
        let a = [o + 0.5, o + 0.5];
        let t = [a, [a[0] + 1e-3, a[1]], [a[0] + 1e-3 * c, a[1] + 1e-3 * s]];
        let input = crate::mesh::Pslg {
            points: vec![[o, o], [o + 1.0, o], [o + 1.0, o + 1.0], [o, o + 1.0]],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            ..crate::mesh::Pslg::default()
        };
        let ten = 10f64.to_radians();
        let mut vertices = input.points.clone();
        vertices.extend(t);
        vertices.push([o + 0.1 * ten.cos(), o + 0.1 * ten.sin()]);
        let mesh = crate::mesh::TriMesh {
            vertices,
            triangles: vec![[4, 5, 6], [0, 1, 7]],
        };
        let bounds = (43.897_886_2, 90.0);
        assert!(check_interior_angles(&mesh, &input, bounds, 0.01, "m").is_ok());
        match check_interior_angles(&mesh, &input, bounds, 1e-4, "m") {
            Err(crate::error::Error::Input {
                problem: crate::error::InputError::Rounding { .. },
                ..
            }) => {}
            other => panic!("expected a refusal, got {other:?}"),
        }
    }

    /// A strip of `n` right isosceles triangles along the x axis (angles 45°, 45°, 90°).
    fn strip(n: usize) -> crate::mesh::TriMesh {
        let mut vertices = Vec::new();
        for i in 0..=n / 2 + 1 {
            vertices.push([i as f64, 0.0]);
            vertices.push([i as f64, 1.0]);
        }
        let triangles = (0..n as u32)
            .map(|t| {
                let (i, up) = (2 * (t / 2), t % 2 == 1);
                if up {
                    [i + 2, i + 3, i + 1]
                } else {
                    [i, i + 2, i + 1]
                }
            })
            .collect();
        crate::mesh::TriMesh {
            vertices,
            triangles,
        }
    }

    #[test]
    fn angles_checked_over_threads_give_the_verdict_and_message_of_one() {
        // 20,000 triangles (ranges split from 8,192 on), spoiled in two places: first in the
        // last range, then also in the first, so that a later range's finding must not win.
        let mut mesh = strip(20_000);
        let bounds = (44.0, 90.0);
        let one = check_angles(&mesh, &mesh.vertices, bounds, 0.01, "m");
        assert!(one.is_ok(), "{one:?}");
        for threads in [2, 3] {
            let many = check_angles_over(&mesh, &mesh.vertices, bounds, 0.01, "m", threads);
            assert!(many.is_ok(), "{threads}: {many:?}");
        }
        for t in [19_000, 3_000] {
            // The triangle's apex moved along x: its angles leave [44°, 90°] by degrees.
            let v = mesh.triangles[t][2] as usize;
            mesh.vertices[v][0] += 0.3;
            let one = check_angles(&mesh, &mesh.vertices, bounds, 0.01, "m").unwrap_err();
            for threads in [2, 3] {
                let many = check_angles_over(&mesh, &mesh.vertices, bounds, 0.01, "m", threads);
                assert_eq!(many.unwrap_err().to_string(), one.to_string(), "{threads}");
            }
        }
    }

    #[test]
    fn beyond_is_zero_inside_and_the_distance_outside() {
        assert_eq!(beyond(45.0, 43.9, 90.0), 0.0);
        assert_eq!(beyond(90.5, 43.9, 90.0), 0.5);
        assert!((beyond(43.0, 43.9, 90.0) - 0.9).abs() < 1e-12);
    }

    #[test]
    fn the_nearest_angle_is_the_one_closest_to_breaking_its_allowance() {
        // Triangle 0 misses 90° by 1e-7° near the origin, triangle 1 by 2e-7° at 1e7, where
        // its allowance is far larger: the first uses less but comes nearer to breaking.
        let right = |o: f64, eps_deg: f64| {
            let e = eps_deg.to_radians();
            [[o, o], [o + e.cos(), o - e.sin()], [o, o + 1.0]]
        };
        let tris = [right(0.0, 1e-7), right(1e7, 2e-7)];
        let fit = angle_fit(tris.iter().copied().enumerate(), 30.0, 90.0).unwrap();
        assert_eq!(fit.most.triangle, 1);
        assert_eq!(fit.nearest.triangle, 0);
        assert!(fit.most.used > 1.5e-7 && fit.most.used < fit.most.allowance);
        assert!(fit.holds());
        // 1e-5° beyond 90° near the origin is more than rounding explains.
        let bad = [right(0.0, 1e-5)];
        assert!(!angle_fit(bad.iter().copied().enumerate(), 30.0, 90.0)
            .unwrap()
            .holds());
    }
}
