//! Input corners (paper 001 Sec. 5.6–5.8), our construction: the lattice corners near the
//! input corner c are left out, and the hole between c and the front of the moved lattice
//! corners around it is filled by one ladder (`boxes::ladder`) whose inner chain runs along
//! W towards c and along V away from it. Either c itself is on that chain (`Tip::Apex`: the
//! ladder's triangles meet at c), or a fan of triangles at c cuts it off (`Tip::Fan`): the
//! chain passes from a point on W through points on rays from c to a point on V, each step
//! between two of them closing a fan triangle with c whose angles count like the ladder's;
//! a fan of one triangle is the whole corner, exempt at c when sharper than 30°.
//!
//! Departure: the paper centres the corner in a rhomb and moves a lattice vertex onto it
//! (≥ 150°, Sec. 5.8), shifts rows of rhombs to put a vertex on the bisector (60°–150°,
//! Sec. 5.7) or cuts the corner off with right triangles and small border-boxes (≤ 60°,
//! Sec. 5.6), with cases its text leaves partly open (the figures are missing from it). The
//! fan leaves the lattice as the tree made it and searches the rays' angles and radii.

use super::boxes::{key, ladder, Failure, Vertex};
use super::wedge::{wedge, wedge_triangles, whole_corner_key, WedgeVertex};
use crate::geom::{angle_deg, dist, orient2d, Point};

/// Numbers in [0, 1) from `seed`, the same on every machine (a linear congruential
/// generator): the surveys' and tests' random shapes.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// How the ladder meets the corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tip {
    /// c is a vertex of the ladder's triangles.
    Apex,
    /// A fan at c: rays every `angle` degrees, points on them at the `radii` (in units of
    /// the lattice side).
    Fan { angle: f64, radii: &'static [f64] },
    /// A wedge: the chain passes from a point on W straight to a point on V, and the
    /// triangle they make with c is cut into triangles with a side on V or W and the third
    /// corner on the other (`wedge`), from the whole corner at c outwards; points along V
    /// and W also at distances growing by 5 % from c.
    Wedge,
}

/// A corner's triangulation: every triangle between c, W, V and the front,
/// counter-clockwise, and the smallest angle's margin over 30° (the whole corner's angle
/// at c left out when sharper than 30°).
#[derive(Debug, Clone)]
pub struct Corner {
    pub triangles: Vec<[Point; 3]>,
    pub margin: f64,
}

/// What a point of the inner chain is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// On W, at this distance from c.
    W(f64),
    /// c itself.
    C,
    /// On the ray at this angle from V (degrees, 0 < θ < α).
    Ray(f64),
    /// On V, at this distance from c.
    V(f64),
}

/// Fills the corner c between W (arriving from `w`) and V (leaving towards `v`), the domain
/// on the left, up to `front` (from beside W to beside V; its first corner's foot on W and
/// its last one's on V are the ladder's ends). `side` is the lattice side there; candidate
/// points along V and W are the feet and box points of the front and every `side/10`;
/// front corners meet inner points within `2·side`.
pub fn corner(
    c: Point,
    v: Point,
    w: Point,
    front: &[Point],
    side: f64,
    tip: Tip,
) -> Result<Corner, Failure> {
    let (m, last) = (front.len(), front.len().saturating_sub(1));
    if m < 2 {
        return Err(Failure::Front(0));
    }
    let unit = |p: Point| {
        let d = dist(c, p);
        [(p[0] - c[0]) / d, (p[1] - c[1]) / d]
    };
    let (dv, dw) = (unit(v), unit(w));
    let alpha = {
        let a = angle_deg(c, v, w);
        if orient2d(c, v, w) >= 0.0 {
            a
        } else {
            360.0 - a
        }
    };
    let along = |d: [f64; 2], p: Point| (p[0] - c[0]) * d[0] + (p[1] - c[1]) * d[1];
    let (sw, sv) = (along(dw, front[0]), along(dv, front[last]));
    let least = 0.2 * side;
    if sw <= least || sv <= least {
        return Err(Failure::Front(if sw <= least { 0 } else { last }));
    }
    // Distances along a line from c: the feet of the front corners and their boxes' points
    // (`boxes::box_points`, with the line oriented the domain's way), and every side/10.
    let stops = |d: [f64; 2], far: Point, toward_c: bool, end: f64| {
        let (a, b) = if toward_c { (far, c) } else { (c, far) };
        let feet: Vec<(usize, f64)> = front
            .iter()
            .enumerate()
            .map(|(i, &p)| (i, along(d, p)))
            .filter(|&(_, x)| x > least && x < end)
            .collect();
        let mut s: Vec<f64> = feet.iter().map(|f| f.1).collect();
        for pair in feet.windows(2) {
            let (i, j) = (pair[0].0, pair[1].0);
            if j == i + 1 && orient2d(a, b, front[i]) > 0.0 && orient2d(a, b, front[j]) > 0.0 {
                let pts = super::boxes::box_points(front[i], front[j], a, b);
                s.extend(pts.into_iter().map(|p| along(d, p)));
            }
        }
        let count = ((end - least) / (side / 10.0)).ceil() as usize;
        s.extend((0..count).map(|k| least + (end - least) * k as f64 / count as f64));
        if tip == Tip::Wedge {
            let mut x = least;
            while x < end {
                s.push(x);
                x *= 1.05;
            }
        }
        s.retain(|&x| x >= least && x < end);
        s.sort_by(f64::total_cmp);
        s.dedup();
        s
    };
    let on = |d: [f64; 2], s: f64| [c[0] + s * d[0], c[1] + s * d[1]];
    let mut inner = vec![on(dw, sw)];
    let mut place = vec![Place::W(sw)];
    for x in stops(dw, w, true, sw).into_iter().rev() {
        inner.push(on(dw, x));
        place.push(Place::W(x));
    }
    let w_end = inner.len();
    match tip {
        Tip::Wedge => {}
        Tip::Apex => {
            inner.push(c);
            place.push(Place::C);
        }
        Tip::Fan { angle, radii } => {
            let base = dv[1].atan2(dv[0]);
            let rays = (alpha / angle).ceil() as usize;
            for j in (1..rays).rev() {
                let theta = alpha * j as f64 / rays as f64;
                let t = base + theta.to_radians();
                for &r in radii {
                    inner.push([c[0] + r * side * t.cos(), c[1] + r * side * t.sin()]);
                    place.push(Place::Ray(theta));
                }
            }
        }
    }
    for x in stops(dv, v, false, sv) {
        inner.push(on(dv, x));
        place.push(Place::V(x));
    }
    inner.push(on(dv, sv));
    place.push(Place::V(sv));
    let n = inner.len();
    // The wedge's table: W points by distance from c (the chain runs towards c on W), V's.
    let v_start = place
        .iter()
        .position(|p| matches!(p, Place::V(_)))
        .unwrap_or(n);
    let cut = if tip == Tip::Wedge {
        let ws: Vec<Point> = inner[..w_end].iter().rev().copied().collect();
        let vs = &inner[v_start..];
        wedge(c, alpha, &ws, vs, &vec![vs.len(); ws.len()], None)
    } else {
        Vec::new()
    };
    // Which sides along the chain are allowed, and the fan triangle each closes.
    let angle_of = |p: Place| match p {
        Place::W(_) => alpha,
        Place::Ray(t) => t,
        Place::V(_) => 0.0,
        Place::C => f64::NAN,
    };
    let link = |k0: usize, k: usize| -> Option<f64> {
        match (place[k0], place[k]) {
            (Place::W(_), Place::W(_)) | (Place::V(_), Place::V(_)) => Some(f64::INFINITY),
            (Place::W(_), Place::C) | (Place::C, Place::V(_)) => Some(f64::INFINITY),
            (Place::C, _) | (_, Place::C) => None,
            (a, b) => {
                if angle_of(b) >= angle_of(a) {
                    return None;
                }
                if tip == Tip::Wedge {
                    // W to V: the wedge below the rung (a by distance from c on W).
                    let a = w_end - 1 - k0;
                    let value = cut[a][k - v_start].0;
                    return (value > f64::NEG_INFINITY).then_some(value);
                }
                // The fan triangle (c, inner[k], inner[k0]); the whole corner at c is exempt
                // when sharper than 30°.
                let (p, q) = (inner[k], inner[k0]);
                if matches!((a, b), (Place::W(_), Place::V(_))) && alpha < 30.0 {
                    let g = whole_corner_key(c, p, q);
                    return (g > f64::NEG_INFINITY).then_some(g);
                }
                key(c, p, q)
            }
        }
    };
    let reach = 2.0 * side;
    let mut window: Vec<(usize, usize)> = front
        .iter()
        .map(|&p| {
            let near: Vec<usize> = (0..n).filter(|&k| dist(p, inner[k]) <= reach).collect();
            (
                near.first().copied().unwrap_or(n),
                near.last().copied().unwrap_or(0),
            )
        })
        .collect();
    window[0].0 = 0;
    window[last].1 = n - 1;
    for i in 1..m {
        window[i].0 = window[i].0.max(window[i - 1].0).min(window[i - 1].1);
    }
    for i in (0..last).rev() {
        window[i].1 = window[i].1.min(window[i + 1].1).max(window[i + 1].0);
    }
    let (margin, ladder) = ladder(front, &inner, &window, (n, &[]), &link)?;
    // Every triangle: the ladder's, and on the far side of each side along the chain that
    // is not a piece of W or V, the fan triangle or the wedge it closes.
    let mut triangles = Vec::with_capacity(ladder.len());
    let at = |v: Vertex| match v {
        Vertex::Front(i) => front[i],
        Vertex::Segment(k) => inner[k],
    };
    for t in &ladder {
        triangles.push(t.map(at));
        if let [Vertex::Segment(k0), Vertex::Segment(k), _] = *t {
            match (place[k0], place[k]) {
                (Place::W(_), Place::W(_) | Place::C) | (Place::C | Place::V(_), Place::V(_)) => {}
                (Place::W(_), Place::V(_)) if tip == Tip::Wedge => {
                    let ws: Vec<Point> = inner[..w_end].iter().rev().copied().collect();
                    let rung = (w_end - 1 - k0, k - v_start);
                    let vs = &inner[v_start..];
                    triangles.extend(wedge_triangles(&cut, rung).into_iter().map(|t| {
                        t.map(|x| match x {
                            WedgeVertex::C => c,
                            WedgeVertex::W(a) => ws[a],
                            WedgeVertex::V(b) => vs[b],
                        })
                    }));
                }
                _ => triangles.push([c, inner[k], inner[k0]]),
            }
        }
    }
    Ok(Corner { triangles, margin })
}

#[cfg(test)]
mod tests {
    use super::super::boxes::Failure;
    use super::*;

    fn lattice(i: i64, j: i64) -> Point {
        [i as f64 + j as f64 / 2.0, j as f64 * 3f64.sqrt() / 2.0]
    }

    fn crosses(p: Point, q: Point, a: Point, b: Point) -> bool {
        let s = |x: f64| x.signum();
        s(orient2d(a, b, p)) * s(orient2d(a, b, q)) < 0.0
            && s(orient2d(p, q, a)) * s(orient2d(p, q, b)) < 0.0
    }

    /// The corner c of angle `alpha` (degrees) turned by `turn`, W arriving and V leaving,
    /// in a unit lattice: corners inside moved by Sec. 5.2 case 1, those within `clear` of
    /// c left out, the triangles with three corners kept and crossing no segment kept.
    /// Returns the kept triangles, the front near c (within 5, more at sharp corners; from
    /// W's side to V's), v, w.
    #[allow(clippy::type_complexity)]
    fn cut_corner(
        c: Point,
        alpha: f64,
        turn: f64,
        clear: f64,
        eroded: &std::collections::BTreeSet<(i64, i64)>,
    ) -> (Vec<[Point; 3]>, Vec<(Point, (i64, i64))>, Point, Point) {
        let v = [c[0] + 300.0 * turn.cos(), c[1] + 300.0 * turn.sin()];
        let t = turn + alpha.to_radians();
        let w = [c[0] + 300.0 * t.cos(), c[1] + 300.0 * t.sin()];
        let sides = [[w, c], [c, v]];
        let inside = |p: Point| {
            let (l, r) = (orient2d(c, v, p) > 0.0, orient2d(w, c, p) > 0.0);
            if alpha <= 180.0 {
                l && r
            } else {
                l || r
            }
        };
        let moved = |i: i64, j: i64| {
            let p = lattice(i, j);
            let hexagon = super::super::near::DIRECTIONS.map(|(di, dj)| lattice(i + di, j + dj));
            match super::super::near::nearest(p, &hexagon, &sides, 0) {
                Some(near) if near.within_half => {
                    let (di, dj) = super::super::near::DIRECTIONS[(near.side + 3) % 6];
                    let q = lattice(i + di, j + dj);
                    [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0]
                }
                _ => p,
            }
        };
        // A corner is kept when inside, farther than `clear` from c and not eroded.
        let id = |i: i64, j: i64| {
            inside(lattice(i, j)) && dist(lattice(i, j), c) > clear && !eroded.contains(&(i, j))
        };
        // A triangle two of whose corners moved to one point has degenerated (paper 001
        // footnote 4): it is not kept.
        let keep = |t: [(i64, i64); 3]| {
            t.iter().all(|&(i, j)| id(i, j))
                && {
                    let m = t.map(|(i, j)| moved(i, j));
                    orient2d(m[0], m[1], m[2]) > 0.0
                }
                && (0..3).all(|k| {
                    let (p, q) = (
                        lattice(t[k].0, t[k].1),
                        lattice(t[(k + 1) % 3].0, t[(k + 1) % 3].1),
                    );
                    !sides.iter().any(|s| crosses(p, q, s[0], s[1]))
                })
        };
        let window = if alpha < 90.0 {
            (4.0 / (alpha / 2.0).to_radians().sin()).max(5.0)
        } else {
            5.0
        };
        let n = window as i64 + 9;
        let (ci, cj) = (
            (c[0] - c[1] / 3f64.sqrt()) as i64,
            (c[1] * 2.0 / 3f64.sqrt()) as i64,
        );
        let mut kept = Vec::new();
        let mut front_sides = std::collections::BTreeMap::new();
        for i in ci - n..ci + n {
            for j in cj - n..cj + n {
                for t in [
                    [(i, j), (i + 1, j), (i, j + 1)],
                    [(i + 1, j), (i + 1, j + 1), (i, j + 1)],
                ] {
                    if !keep(t) {
                        continue;
                    }
                    kept.push(t.map(|(i, j)| moved(i, j)));
                    for k in 0..3 {
                        let (p, q, r) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                        let o = (p.0 + q.0 - r.0, p.1 + q.1 - r.1);
                        if !keep([q, p, o]) {
                            let (mp, mq) = (moved(p.0, p.1), moved(q.0, q.1));
                            if dist(mp, c) <= window && dist(mq, c) <= window {
                                front_sides.insert(p, (q, (mq, q), (mp, p)));
                            }
                        }
                    }
                }
            }
        }
        let mut front = vec![];
        if let Some(&first) = front_sides.keys().next() {
            let mut start = first;
            let mut guard = 0;
            while let Some((&p, _)) = front_sides.iter().find(|(_, x)| x.0 == start) {
                start = p;
                guard += 1;
                if guard > front_sides.len() {
                    break;
                }
            }
            let mut at = start;
            while let Some(&(q, mq, mp)) = front_sides.get(&at) {
                if front.is_empty() {
                    front.push(mp);
                }
                front.push(mq);
                at = q;
                if front.len() > front_sides.len() + 1 {
                    break;
                }
            }
        }
        // Corners moved onto one point are one vertex: drop repeats and spikes out and back.
        let mut clean: Vec<(Point, (i64, i64))> = Vec::new();
        for p in front {
            if clean.last().map(|x| x.0) == Some(p.0) {
                continue;
            }
            if clean.len() >= 2 && clean[clean.len() - 2].0 == p.0 {
                clean.pop();
                continue;
            }
            clean.push(p);
        }
        (kept, clean, v, w)
    }

    /// Every triangle of a filled corner is counter-clockwise with its angles in [30°, 90°]
    /// within `SLACK`, but the whole corner's angle at c when sharper than 30°.
    fn check(k: &Corner, c: Point, alpha: f64) {
        for t in &k.triangles {
            assert!(orient2d(t[0], t[1], t[2]) > 0.0, "{t:?}");
            for i in 0..3 {
                let x = angle_deg(t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
                if t[i] == c && alpha < 30.0 {
                    assert!(
                        (x - alpha).abs() < 1e-6,
                        "{t:?}: {x} at c, the corner is {alpha}"
                    );
                    continue;
                }
                let slack = super::super::boxes::SLACK;
                assert!((30.0 - slack..=90.0 + slack).contains(&x), "{t:?}: {x}");
            }
        }
    }

    /// Tries the tips in a fixed order; the first ladder in bounds wins. When none is, the
    /// lattice corner where the least bad ladder fails is eroded and the front rebuilt, up to
    /// ERODE times.
    fn best_corner(c: Point, alpha: f64, turn: f64) -> Option<(f64, String)> {
        const RADII: &[f64] = &[0.5, 0.75, 1.0, 1.25, 1.5];
        const ERODE: usize = 6;
        for clear in [0.5, 1.0, 1.5] {
            let mut eroded = std::collections::BTreeSet::new();
            for round in 0..=ERODE {
                let (kept, front, v, w) = cut_corner(c, alpha, turn, clear, &eroded);
                if kept.iter().any(|t| orient2d(t[0], t[1], t[2]) <= 0.0) || front.len() < 3 {
                    break;
                }
                let points: Vec<Point> = front.iter().map(|f| f.0).collect();
                let mut least_bad: Option<(f64, usize)> = None;
                for tip in [
                    Tip::Apex,
                    Tip::Fan {
                        angle: 10.0,
                        radii: RADII,
                    },
                    Tip::Wedge,
                ] {
                    if tip == Tip::Apex && alpha < 30.0 {
                        continue;
                    }
                    match corner(c, v, w, &points, 1.0, tip) {
                        Ok(k) => {
                            check(&k, c, alpha);
                            let name = format!("{tip:?}");
                            let how = format!("{} clear {clear} eroded {round}", &name[..4]);
                            return Some((k.margin, how));
                        }
                        Err(Failure::Bounds { at, margin }) => {
                            if least_bad.is_none_or(|(m, _)| margin > m) {
                                least_bad = Some((margin, at));
                            }
                        }
                        Err(Failure::Front(_)) => {}
                    }
                }
                let Some((_, at)) = least_bad else { break };
                eroded.insert(front[at].1);
            }
        }
        None
    }

    /// Every corner of a grid of angles (10° to 350°), directions and positions in the unit
    /// lattice is filled in bounds by one of the tips.
    #[test]
    fn corners_of_every_angle_in_a_unit_lattice_are_filled_within_30_to_90_degrees() {
        let mut failed = Vec::new();
        for alpha in [
            10.0, 25.0, 45.0, 60.0, 90.0, 120.0, 150.0, 180.0, 210.0, 270.0, 300.0, 350.0,
        ] {
            for turn in [0.0, 0.37, 1.1, 2.9, 4.4] {
                for c in [[0.2, 0.3], [0.71, 0.45]] {
                    if best_corner(c, alpha, turn).is_none() {
                        failed.push((alpha, turn, c));
                    }
                }
            }
        }
        assert!(
            failed.is_empty(),
            "{} corners not filled: {failed:?}",
            failed.len()
        );
    }

    /// The survey behind the tips: 400 random corners (1° to 359°), how each was filled and
    /// which were not (`cargo test -p hexmesh-core corner_survey -- --ignored --nocapture`).
    #[test]
    #[ignore]
    fn corner_survey() {
        let mut fails = Vec::new();
        let mut wins = std::collections::BTreeMap::new();
        let mut next = uniform(12345);
        for _ in 0..400 {
            let alpha = 1.0 + 358.0 * next();
            let turn = std::f64::consts::TAU * next();
            let c = [next(), next()];
            match best_corner(c, alpha, turn) {
                None => fails.push((alpha, turn, c)),
                Some((_, how)) => *wins.entry(how).or_insert(0) += 1,
            }
        }
        eprintln!("{wins:?}");
        eprintln!("not filled: {} of 400: {fails:?}", fails.len());
    }
}
