//! The wedge of a polygon's corner sharper than 90° (ours, in place of Sec. 5.6 and 5.7,
//! whose figures our copy of paper 001 lacks): the triangle between the corner c and the
//! points of its two sides, W before it and V after it, cut into triangles each with a side
//! along W or V, best first by the smallest angle's margin over 30° (the angle at c exempt
//! where the whole input corner is sharper than 30°). `fill` reads its table at every rung
//! the ladder may take across the corner.

use super::boxes::{key, key_of, over_key, sin_cos};
use crate::geom::{angle_deg, dist, orient2d, Point};

/// A table to take cells from (`wedge`): the table, its rows, and how many of its first W
/// and V points are the new table's first ones.
pub type From<'t> = (&'t WedgeTable, &'t [usize], usize, usize);

/// A wedge's table (`wedge`): the best cut of (c, ws[a], vs[b]) for every a, b.
pub type WedgeTable = Vec<Vec<(f64, WedgeStep)>>;

/// The margin of triangle (c, p, q) with its angle at c exempt (the whole input corner,
/// sharper than 30°): the smaller other angle over 30°, or the excess over 90° negated, or
/// −∞ when it is not counter-clockwise.
pub fn whole_corner(c: Point, p: Point, q: Point) -> f64 {
    if orient2d(c, p, q) <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let (x, y) = (angle_deg(p, q, c), angle_deg(q, c, p));
    if x.max(y) > 90.0 {
        return 90.0 - x.max(y);
    }
    x.min(y) - 30.0
}

/// `key_of(whole_corner(c, p, q))`, up to rounding, without an arc tangent (`boxes::key`).
pub fn whole_corner_key(c: Point, p: Point, q: Point) -> f64 {
    if orient2d(c, p, q) <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let scale = dist(p, q).max(dist(q, c)).max(dist(c, p));
    let (Some(at_p), Some(at_q)) = (sin_cos(p, q, c, scale), sin_cos(q, c, p, scale)) else {
        return key_of(whole_corner(c, p, q));
    };
    // At most one of the two exceeds 90°; within 1e-12 of a right angle the measured
    // degrees decide, as in `whole_corner` (even an exact right angle may measure
    // 90.00000000000001°).
    match (at_p, at_q) {
        ((_, cos), _) | (_, (_, cos)) if cos.abs() <= 1e-12 => key_of(whole_corner(c, p, q)),
        ((sin, cos), _) | (_, (sin, cos)) if cos < 0.0 => over_key(sin, cos),
        ((sp, _), (sq, _)) => sp.min(sq),
    }
}

/// How the wedge below rung (a, b) was reached: the triangle at c, or a piece of W from rung
/// (a0, b), or of V from (a, b0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WedgeStep {
    Tip,
    W(usize),
    V(usize),
}

/// The best way to cut the triangle (c, ws[a], vs[b]) into triangles each with a side along
/// W or V and its third corner on the other, for every a, b (`ws`, `vs` by distance from
/// c): the smallest angle's margin over 30° as a key (`boxes::key_of`; the angle at c
/// exempt when the corner, `alpha` degrees, is sharper than 30°), or −∞ when there is none.
///
/// Only the cells (a, b) with b < `rows[a]` are computed and kept (`rows` not increasing):
/// row a has `rows[a]` cells (at most `vs.len()`), and a cell past its row reads as −∞. A
/// cell reads only cells below and left of it, so each is what the whole table would hold.
/// Kept whole (W by V points), the table of the corner of a narrow spike whose band was
/// made finer along it (fuzz case 4076 of seed 20261123) asked for 122 million cells, and
/// the run was killed at the machine's 24 GB; by its rows it meshes in 234 MB.
///
/// A cell is computed from the points ws[..=a] and vs[..=b] alone, so where `from` (a table
/// for the same corner) shares the first W and V points, its cells there that it computed
/// are taken as they are: after an erosion away from the corner, most of them.
pub fn wedge(
    c: Point,
    alpha: f64,
    ws: &[Point],
    vs: &[Point],
    rows: &[usize],
    from: Option<From>,
) -> WedgeTable {
    const SPAN: usize = 24;
    let (na, nb) = (ws.len(), vs.len());
    debug_assert!(rows.len() == na && rows.windows(2).all(|r| r[0] >= r[1]));
    // Row a holds the cells the ladder may read (`rows`); a cell past its row is −∞.
    let mut best: WedgeTable = rows
        .iter()
        .map(|&r| vec![(f64::NEG_INFINITY, WedgeStep::Tip); r.min(nb)])
        .collect();
    for a in 0..na {
        for b in 0..rows[a].min(nb) {
            if let Some((old, old_rows, pa, pb)) = from {
                if a < pa && b < pb && b < old_rows[a] {
                    best[a][b] = old[a][b];
                    continue;
                }
            }
            let tip = if alpha < 30.0 {
                whole_corner_key(c, vs[b], ws[a])
            } else {
                key(c, vs[b], ws[a]).unwrap_or(f64::NEG_INFINITY)
            };
            let mut cell = (tip, WedgeStep::Tip);
            for a0 in a.saturating_sub(SPAN)..a {
                if best[a0][b].0 > cell.0 {
                    if let Some(g) = key(vs[b], ws[a], ws[a0]) {
                        if best[a0][b].0.min(g) > cell.0 {
                            cell = (best[a0][b].0.min(g), WedgeStep::W(a0));
                        }
                    }
                }
            }
            for b0 in b.saturating_sub(SPAN)..b {
                if best[a][b0].0 > cell.0 {
                    if let Some(g) = key(vs[b0], vs[b], ws[a]) {
                        if best[a][b0].0.min(g) > cell.0 {
                            cell = (best[a][b0].0.min(g), WedgeStep::V(b0));
                        }
                    }
                }
            }
            best[a][b] = cell;
        }
    }
    best
}

/// A corner of a wedge triangle: c, or a point of W or V by its index in `ws` / `vs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WedgeVertex {
    C,
    W(usize),
    V(usize),
}

/// The triangles of the wedge below rung (a, b) of `table`, counter-clockwise.
pub fn wedge_triangles(
    table: &[Vec<(f64, WedgeStep)>],
    (mut a, mut b): (usize, usize),
) -> Vec<[WedgeVertex; 3]> {
    use WedgeVertex::{C, V, W};
    let mut out = Vec::new();
    loop {
        match table[a][b].1 {
            WedgeStep::Tip => {
                out.push([C, V(b), W(a)]);
                return out;
            }
            WedgeStep::W(a0) => {
                out.push([V(b), W(a), W(a0)]);
                a = a0;
            }
            WedgeStep::V(b0) => {
                out.push([V(b0), V(b), W(a)]);
                b = b0;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rhomb::domain::boxes::score_of;
    use crate::rhomb::domain::boxes::tests::bent_right_triangles;

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(1000))]

        /// `whole_corner_key` orders triangles at a sharp corner as `whole_corner` does: its
        /// key turned back into a score is the measured one within 1e-9°, at any scale and
        /// with a right angle at p (rounded either way) or one turned a little past it.
        #[test]
        fn a_whole_corner_key_is_its_score_without_an_arc_tangent(
            tri in bent_right_triangles(3.0, vec![0.0, 1e-17, -1e-17, 1e-9, -1e-9, 0.3, -0.3, 1.2]),
        ) {
            // c on the perpendicular to pq at p (the strategy's right angle, at its second
            // corner).
            let [q, p, c] = tri;
            let (got, want) = (whole_corner_key(c, p, q), whole_corner(c, p, q));
            if want == f64::NEG_INFINITY {
                proptest::prop_assert_eq!(got, want);
            } else {
                proptest::prop_assert!(
                    (score_of(got) - want).abs() <= 1e-9,
                    "{:?}: key {} score {}", [c, p, q], got, want
                );
            }
        }
    }
}
