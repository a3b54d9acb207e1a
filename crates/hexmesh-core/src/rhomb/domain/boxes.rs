//! Border-boxes (paper 001 Sec. 5.3 with steps 8, 11 and 16): the strip between the moved
//! tree corners nearest a segment (the front) and the segment itself.
//!
//! In the paper each front corner p is joined to the segment S by the perpendicular (p, S),
//! so that two neighbouring front corners p, q and their feet bound a border-box (Fig. 10);
//! a Steiner point v on S between the feet cuts the box into two right triangles and the
//! triangle (p, v, q) (step 11), and where a right triangle would get an angle below 30° it
//! is melted with its neighbour (step 16). Table 1 bounds the boxes the corner moves create
//! (BB_1–BB_7), but the paper leaves open where v goes ("missing is an analysis of where to
//! place the steiner point") and its closed form for the angle is garbled in the text.
//!
//! Departure (ours): rather than a formula for v and a case list for melting, `strip` chooses
//! among candidate points on S: the feet of every front corner and nine points evenly spread
//! between each two neighbouring feet. A triangulation of the strip whose triangles each
//! join a front edge or a piece of S to one vertex of the other side (a ladder between the
//! two chains) is found by dynamic programming over (front corner, point on S), maximising
//! the smallest margin of any angle to [30°, 90°]. The paper's box with its Steiner point
//! is one such ladder, its melting (leaving a foot out) another, and the shortest diagonal
//! it uses for BB_3–BB_7 a third, so the strip is triangulated wherever the paper's
//! construction is, within the candidates' spacing. The strip's two end feet are kept: the
//! neighbouring strips or corner constructions end at the same perpendiculars.
//!
//! Everything here is computed in f64 on the moved positions; a triangle is accepted only
//! with a positive exact orientation and every angle within `SLACK` of the bounds.

use crate::geom::{angle_deg, dist, orient2d, Point};

/// How far (degrees) an angle computed in f64 may lie beyond [30°, 90°] and still count as
/// on it: exact constructions (a foot's right angle, the 30° of a BB_1 box at its extreme)
/// come out within a few ulps; verify allows 1e-6° plus the rounding terms.
pub const SLACK: f64 = 1e-9;

/// Points on S put between two neighbouring feet, evenly spread (fractions 1/10..9/10).
const BETWEEN: usize = 9;

/// How many candidates on S one triangle's side along S may span (a gap holds BETWEEN + 6
/// at most besides its foot): wide enough to melt the
/// triangles of two neighbouring boxes (leaving out the foot between them), narrow enough
/// that a long strip stays linear in its length.
#[cfg(test)]
const SPAN: usize = 2 * (BETWEEN + 7);

/// A vertex of the strip's triangulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Vertex {
    /// The front corner of that index.
    Front(usize),
    /// The point of that index in `Strip::on_segment`.
    Segment(usize),
}

/// The triangulation of a strip: the points it puts on S (in order from the first front
/// corner's foot to the last one's, both included) and its triangles, counter-clockwise.
#[cfg(test)]
#[derive(Debug, Clone, PartialEq)]
pub struct Strip {
    pub on_segment: Vec<Point>,
    pub triangles: Vec<[Vertex; 3]>,
    /// The smallest angle's margin above 30°, degrees (≥ −SLACK; every angle ≤ 90° + SLACK).
    pub margin: f64,
}

/// Why a strip has no triangulation.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// Front corner `0` is not strictly on the domain's side of S, or its foot does not lie
    /// strictly after the previous corner's foot between S's ends (`strip`, tests only).
    #[cfg(test)]
    Front(usize),
    /// No ladder keeps the bounds: the best one's worst triangle (its margin) touches front
    /// corner `at`, or no ladder gets past front corner `at` at all.
    Bounds { at: usize, margin: f64 },
}

impl Failure {
    /// The front corner the failure names.
    pub fn at(&self) -> usize {
        match *self {
            #[cfg(test)]
            Failure::Front(i) => i,
            Failure::Bounds { at, .. } => at,
        }
    }

    /// By how much the best ladder keeps the bounds (negative: misses them), or −∞ where no
    /// ladder was scored.
    pub fn margin(&self) -> f64 {
        match *self {
            #[cfg(test)]
            Failure::Front(_) => f64::NEG_INFINITY,
            Failure::Bounds { margin, .. } => margin,
        }
    }
}

/// The score of triangle abc: its smallest angle's margin above 30°, or, when an angle
/// exceeds 90°, that excess negated if it is worse; `None` when abc is not counter-clockwise
/// by the exact sign. Right angles are the construction's (the feet), so only the smallest
/// angle is maximised.
pub fn score(a: Point, b: Point, c: Point) -> Option<f64> {
    if orient2d(a, b, c) <= 0.0 {
        return None;
    }
    // The smallest angle is opposite the shortest side and the largest opposite the
    // longest (ties give the same angle either way). The largest is measured only where it
    // may exceed 90° (`may_exceed_90`), so the scores are those of measuring it always:
    // most of the ladder's candidates are clear of it, and atan2 was a quarter of the
    // ladder's time.
    let sides = (dist(a, b), dist(b, c), dist(c, a));
    let (ab, bc, ca) = sides;
    let (x, y, z) = opposite(a, b, c, sides, ab.min(bc).min(ca));
    let min = angle_deg(x, y, z);
    let over = if may_exceed_90(a, b, c, sides) {
        let (x, y, z) = opposite(a, b, c, sides, ab.max(bc).max(ca));
        let max = angle_deg(x, y, z);
        if max > 90.0 {
            90.0 - max
        } else {
            f64::INFINITY
        }
    } else {
        f64::INFINITY
    };
    Some((min - 30.0).min(over))
}

/// A score on the ladder's scale: the sine of 30° + `score` (the sine of the smallest
/// angle where no angle exceeds 90°), continued linearly past ±90° so that it stays
/// increasing (±∞ stay as they are). Comparisons of keys are comparisons of scores, and a
/// triangle's key (`key`) needs no arc tangent.
pub fn key_of(score: f64) -> f64 {
    let angle = 30.0 + score;
    if angle >= 90.0 {
        1.0 + (angle - 90.0)
    } else if angle <= -90.0 {
        -1.0 + (angle + 90.0)
    } else {
        angle.to_radians().sin()
    }
}

/// The score of a key (`key_of` inverted).
pub fn score_of(key: f64) -> f64 {
    if key >= 1.0 {
        60.0 + (key - 1.0)
    } else if key <= -1.0 {
        -120.0 + (key + 1.0)
    } else {
        key.asin().to_degrees() - 30.0
    }
}

/// `key_of(score(a, b, c))`, up to rounding, without an arc tangent: the sine of the
/// smallest angle (the cross product over the two sides beside it), or, where the largest
/// angle exceeds 90°, the key of its excess if that is smaller (`over_key`). Squared
/// lengths stand for lengths (`hypot` took as long as the arc tangents it replaced); where
/// one of them, the cross product or their products is not a normal number (underflow at
/// tiny scales, overflow at huge ones) the score is measured (`score`) and turned into a
/// key.
pub fn key(a: Point, b: Point, c: Point) -> Option<f64> {
    if orient2d(a, b, c) <= 0.0 {
        return None;
    }
    let measured = || score(a, b, c).map(key_of);
    let square = |p: Point, q: Point| (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]);
    let sides = (square(a, b), square(b, c), square(c, a));
    let cross = ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
    let (long, middle) = beside_smallest(sides);
    let beside = long * middle;
    let normal = [cross, sides.0, sides.1, sides.2, beside];
    if !normal.iter().all(|x| x.is_normal()) {
        return measured();
    }
    let sine = cross / beside.sqrt();
    // The largest angle, opposite the longest side, between the two others.
    let (x, y, z) = opposite(a, b, c, sides, sides.0.max(sides.1).max(sides.2));
    let (u, w) = ([y[0] - x[0], y[1] - x[1]], [z[0] - x[0], z[1] - x[1]]);
    let dot = u[0] * w[0] + u[1] * w[1];
    let n2 = square(x, y) * square(x, z);
    // Within 1e-12 of a right angle (a foot's, rounded), `score` decides by its measured
    // degrees whether the angle exceeds 90° (even an exact right angle may measure
    // 90.00000000000001°), and so does the key.
    if !n2.is_normal() || !dot.is_finite() || dot * dot <= 1e-24 * n2 {
        return measured();
    }
    if dot > 0.0 {
        return Some(sine);
    }
    let n = n2.sqrt();
    Some(sine.min(over_key(cross / n, dot / n)))
}

/// The key of an angle θ above 90° from its sine and cosine: that of the score 90° − θ,
/// sin(120° − θ) = (√3/2)·cos θ + sin θ / 2.
pub fn over_key(sin: f64, cos: f64) -> f64 {
    0.75f64.sqrt() * cos + 0.5 * sin
}

/// The sine and cosine of the angle at x between xy and xz, from the sides divided by
/// `scale` (a triangle's longest side: no overflow); `None` where they are not finite (a
/// side of length 0, or one whose square underflows at that scale).
pub fn sin_cos(x: Point, y: Point, z: Point, scale: f64) -> Option<(f64, f64)> {
    let unit = |p: Point| [(p[0] - x[0]) / scale, (p[1] - x[1]) / scale];
    let (u, w) = (unit(y), unit(z));
    let n = ((u[0] * u[0] + u[1] * u[1]) * (w[0] * w[0] + w[1] * w[1])).sqrt();
    let sin = (u[0] * w[1] - u[1] * w[0]).abs() / n;
    let cos = (u[0] * w[0] + u[1] * w[1]) / n;
    (sin.is_finite() && cos.is_finite()).then_some((sin, cos))
}

/// The two sides beside a triangle's smallest angle (all but the shortest), longer first,
/// from its sides ab, bc, ca.
fn beside_smallest((ab, bc, ca): (f64, f64, f64)) -> (f64, f64) {
    if ab <= bc && ab <= ca {
        (bc.max(ca), bc.min(ca))
    } else if bc <= ca {
        (ab.max(ca), ab.min(ca))
    } else {
        (ab.max(bc), ab.min(bc))
    }
}

/// Whether triangle abc's largest angle may exceed 90°: its cosine, from the sides scaled
/// by the longest (no overflow or underflow at any scale), is not clearly positive (at
/// least 1e-6, 89.99994°). A NaN answers true.
fn may_exceed_90(a: Point, b: Point, c: Point, sides: (f64, f64, f64)) -> bool {
    let longest = sides.0.max(sides.1).max(sides.2);
    let (x, y, z) = opposite(a, b, c, sides, longest);
    let unit = |p: Point| [(p[0] - x[0]) / longest, (p[1] - x[1]) / longest];
    let (u, w) = (unit(y), unit(z));
    let cos = u[0] * w[0] + u[1] * w[1];
    cos < 1e-6 || cos.is_nan()
}

/// The corner of triangle abc opposite its side of length `side` (one of ab, bc, ca), with
/// the other two after it counter-clockwise.
fn opposite(
    a: Point,
    b: Point,
    c: Point,
    (ab, bc, _): (f64, f64, f64),
    side: f64,
) -> (Point, Point, Point) {
    if side == ab {
        (c, a, b)
    } else if side == bc {
        (a, b, c)
    } else {
        (b, c, a)
    }
}

/// Where, between the feet of front corners p and q (heights `hp`, `hq` above S, feet `gap`
/// apart), one Steiner point v keeps the paper's three triangles (p, f_p, v), (p, v, q),
/// (q, v, f_q) in bounds, as distances x = |f_p v|. The right triangles need
/// x/hp, y/hq ∈ [tan 30°, tan 60°] (y = gap − x); (p, v, q) needs its angle at v,
/// atan(x/hp) + atan(y/hq), at most 90° (x·y ≤ hp·hq) and its angles at p and q at least
/// 30°: x ≤ hp·tan(βp − 30°), y ≤ hq·tan(βq − 30°) with βp, βq the box's angles at p, q.
/// Returns the ends and middles of the (at most two) intervals this leaves.
fn steiner_offsets(hp: f64, hq: f64, gap: f64, beta_p: f64, beta_q: f64) -> Vec<f64> {
    let (t30, t60) = (30f64.to_radians().tan(), 60f64.to_radians().tan());
    let reach = |h: f64, beta: f64| {
        if beta <= 30.0 {
            -1.0
        } else if beta >= 120.0 {
            f64::INFINITY
        } else {
            h * (beta - 30.0).to_radians().tan()
        }
    };
    let lo = (hp * t30).max(gap - hq * t60).max(gap - reach(hq, beta_q));
    let hi = (hp * t60).min(gap - hq * t30).min(reach(hp, beta_p));
    let mut pieces = vec![(lo, hi)];
    let disc = gap * gap - 4.0 * hp * hq;
    if disc > 0.0 {
        let (r1, r2) = ((gap - disc.sqrt()) / 2.0, (gap + disc.sqrt()) / 2.0);
        pieces = vec![(lo, hi.min(r1)), (lo.max(r2), hi)];
    }
    let mut out = Vec::new();
    for (a, b) in pieces {
        if a <= b && a > 0.0 && b < gap {
            out.extend([a, (a + b) / 2.0, b]);
        }
    }
    out
}

/// The candidate points on the line ab (the domain on its left) strictly between the feet of
/// neighbouring front corners p and q (p's foot first along ab): the ends and middles of
/// the intervals where one Steiner point makes the paper's box triangles in bounds
/// (`steiner_offsets`), and BETWEEN points evenly spread; in order from p's foot.
pub fn box_points(p: Point, q: Point, a: Point, b: Point) -> Vec<Point> {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = ux * ux + uy * uy;
    let len = len2.sqrt();
    let foot = |p: Point| ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len2;
    let (t, next) = (foot(p), foot(q));
    let at = |t: f64| [a[0] + t * ux, a[1] + t * uy];
    let height = |p: Point| orient2d(a, b, p) / len;
    let gap = (next - t) * len;
    if gap.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Vec::new();
    }
    let beta_p = angle_deg(p, at(t), q);
    let beta_q = angle_deg(q, p, at(next));
    let mut fractions: Vec<f64> = steiner_offsets(height(p), height(q), gap, beta_p, beta_q)
        .into_iter()
        .map(|x| x / gap)
        .chain((1..=BETWEEN).map(|s| s as f64 / (BETWEEN + 1) as f64))
        .filter(|f| *f > 0.0 && *f < 1.0)
        .collect();
    fractions.sort_by(f64::total_cmp);
    fractions.dedup();
    fractions
        .into_iter()
        .map(|f| at(t + f * (next - t)))
        .collect()
}

/// Triangulates the strip between `front` (the moved corners, ordered from S's end `a`
/// towards `b`, all on S's left: the domain's side) and the segment ab, keeping every angle
/// in [30°, 90°] (within `SLACK`).
#[cfg(test)]
pub fn strip(front: &[Point], a: Point, b: Point) -> Result<Strip, Failure> {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = ux * ux + uy * uy;
    // Abscissae of the feet along ab, as fractions of |ab|.
    let mut feet = Vec::with_capacity(front.len());
    for (k, &p) in front.iter().enumerate() {
        let t = ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / len2;
        let after = feet.last().is_none_or(|&last| t > last);
        if orient2d(a, b, p) <= 0.0 || !(0.0..=1.0).contains(&t) || !after {
            return Err(Failure::Front(k));
        }
        feet.push(t);
    }
    let at = |t: f64| [a[0] + t * ux, a[1] + t * uy];
    // Candidates on S: each foot, then the points of the box it starts, before the next foot.
    let mut on = Vec::new();
    let mut foot_index = Vec::with_capacity(front.len());
    for (k, &t) in feet.iter().enumerate() {
        foot_index.push(on.len());
        on.push(at(t));
        if k + 1 < front.len() {
            on.extend(box_points(front[k], front[k + 1], a, b));
        }
    }
    let m = front.len();
    if m == 0 {
        return Err(Failure::Front(0));
    }
    // Candidates beyond front i's neighbours' feet are out of reach of a valid ladder (its
    // triangles would fold), so each front corner only meets the candidates between the
    // feet of its neighbours.
    let window: Vec<(usize, usize)> = (0..m)
        .map(|i| {
            (
                foot_index[i.saturating_sub(1)],
                foot_index[(i + 1).min(m - 1)],
            )
        })
        .collect();
    let (margin, mut triangles) = ladder(front, &on, &window, (SPAN, &[]), &|_, _| {
        Some(f64::INFINITY)
    })?;
    // Keep only the candidates the triangles use.
    let mut renumber = vec![usize::MAX; on.len()];
    let mut on_segment = Vec::new();
    for t in &triangles {
        for v in t {
            if let Vertex::Segment(k) = *v {
                if renumber[k] == usize::MAX {
                    renumber[k] = usize::MAX - 1;
                }
            }
        }
    }
    for (k, r) in renumber.iter_mut().enumerate() {
        if *r == usize::MAX - 1 {
            *r = on_segment.len();
            on_segment.push(on[k]);
        }
    }
    for t in &mut triangles {
        for v in t.iter_mut() {
            if let Vertex::Segment(k) = *v {
                *v = Vertex::Segment(renumber[k]);
            }
        }
    }
    Ok(Strip {
        on_segment,
        triangles,
        margin,
    })
}

/// The ladder between two chains (paper 001's border-boxes generalised, ours): `front` (the
/// moved corners, in order) above and `inner` below (points on the segments and whatever
/// lies between them, in order, the domain on the left walking along `inner`). Each
/// triangle joins a side of one chain to a vertex of the other, counter-clockwise. A side
/// along `inner` may run from point k0 to a later point k (k0 at least `back[k]`, or `span`
/// before k when `back` is empty), leaving out those between, when `link(k0, k)` allows
/// it: `Some(key)` of the triangle that side brings on its other side (a fan triangle at a
/// corner, its score as a `key_of`; infinity when none), `None` when it may not. Front
/// corner i meets only the inner points of `window[i]` (inclusive). The ladder runs from
/// the edge (front[0], inner[window[0].0]) to (front[m−1], inner[window[m−1].1]) and
/// maximises the smallest angle with every angle in [30°, 90°] within `SLACK`. Returns
/// that margin above 30° (degrees) and the triangles, `Segment(k)` naming inner point k.
pub fn ladder(
    front: &[Point],
    inner: &[Point],
    window: &[(usize, usize)],
    (span, back): (usize, &[usize]),
    link: &dyn Fn(usize, usize) -> Option<f64>,
) -> Result<(f64, Vec<[Vertex; 3]>), Failure> {
    #[derive(Clone, Copy)]
    enum Step {
        Start,
        Front(usize),   // from (i − 1, k): triangle (s_k, p_i, p_{i−1})
        Segment(usize), // from (i, k'): triangle (s_k', s_k, p_i)
    }
    type Cell = Option<(f64, usize, Step)>;
    let (m, n) = (front.len(), inner.len());
    // best[i]: for k in its window (from `lo`), the best (margin, triangle count, step) of a
    // ladder from the start to the edge (front i, inner k), the margin as a key (`key_of`:
    // the sine of the smallest angle, which orders ladders as the angle does and is
    // computed without an arc tangent; those were two thirds of a campaign's time). Only
    // the window is stored: a polygon's chain may hold tens of thousands of points.
    let mut best: Vec<(usize, Vec<Cell>)> = Vec::with_capacity(m);
    let get = |best: &[(usize, Vec<Cell>)], i: usize, k: usize| -> Cell {
        let (lo, row) = &best[i];
        k.checked_sub(*lo)
            .and_then(|x| row.get(x).copied())
            .flatten()
    };
    for i in 0..m {
        let (lo, hi) = window[i];
        let hi = hi.min(n - 1);
        let mut row: Vec<Cell> = vec![None; (hi + 1).saturating_sub(lo)];
        for k in lo..=hi {
            let mut cell: Cell = None;
            let take = |cell: &mut Cell, cand: (f64, usize, Step)| {
                let better = match *cell {
                    None => true,
                    // Larger margin first, then fewer triangles.
                    Some((mm, c, _)) => cand.0 > mm || (cand.0 == mm && cand.1 < c),
                };
                if better {
                    *cell = Some(cand);
                }
            };
            if i == 0 && k == window[0].0 {
                take(&mut cell, (f64::INFINITY, 0, Step::Start));
            }
            // A candidate whose path is already worse than the cell cannot win: its key is
            // not needed.
            let hopeless = |cell: &Cell, mm: f64, c: usize| {
                cell.is_some_and(|(best, count, _)| mm < best || (mm == best && c + 1 >= count))
            };
            if i > 0 {
                let from = get(&best, i - 1, k).filter(|&(mm, c, _)| !hopeless(&cell, mm, c));
                if let Some((mm, c, _)) = from {
                    let (p, q, r) = (inner[k], front[i], front[i - 1]);
                    if let Some(g) = key(p, q, r) {
                        take(&mut cell, (mm.min(g), c + 1, Step::Front(k)));
                    }
                }
            }
            // The sides along the segment, nearest first: the best one lies a box or so
            // back, and tried from the farthest each was better than the last, so every
            // one was scored (three in five took the cell). The cell is the one trying them
            // in increasing k0 gives: the largest margin, then the fewest triangles, then
            // the first tried in that order (the step before, then the smallest k0).
            let first = back.get(k).copied().unwrap_or(k.saturating_sub(span));
            let earlier = |step: Step| !matches!(step, Step::Segment(_));
            for k0 in (first.max(lo)..k).rev() {
                let Some((mm, c, _)) = row[k0 - lo] else {
                    continue;
                };
                let lost = cell.is_some_and(|(best, count, step)| {
                    mm < best
                        || (mm == best && (c + 1 > count || (c + 1 == count && earlier(step))))
                });
                if lost {
                    continue;
                }
                let Some(extra) = link(k0, k) else {
                    continue;
                };
                if let Some(g) = key(inner[k0], inner[k], front[i]) {
                    let v = mm.min(g).min(extra);
                    let wins = cell.is_none_or(|(best, count, step)| {
                        v > best
                            || (v == best && (c + 1 < count || (c + 1 == count && !earlier(step))))
                    });
                    if wins {
                        cell = Some((v, c + 1, Step::Segment(k0)));
                    }
                }
            }
            row[k - lo] = cell;
        }
        best.push((lo, row));
    }
    let end = window[m - 1].1;
    let Some((value, _, _)) = get(&best, m - 1, end).map(|(v, c, s)| (score_of(v), c, s)) else {
        let i = (0..m)
            .rev()
            .find(|&i| best[i].1.iter().any(Option::is_some));
        let margin = i.map_or(f64::NEG_INFINITY, |i| {
            best[i]
                .1
                .iter()
                .flatten()
                .map(|e| score_of(e.0))
                .fold(f64::NEG_INFINITY, f64::max)
        });
        return Err(Failure::Bounds {
            at: i.map_or(0, |i| (i + 1).min(m - 1)),
            margin,
        });
    };
    let mut triangles = Vec::new();
    let mut worst = (f64::INFINITY, 0);
    let (mut i, mut k) = (m - 1, end);
    loop {
        match get(&best, i, k).expect("on the path").2 {
            Step::Start => break,
            Step::Front(k0) => {
                let g = score(inner[k0], front[i], front[i - 1]).unwrap_or(f64::NEG_INFINITY);
                if g < worst.0 {
                    worst = (g, i);
                }
                triangles.push([Vertex::Segment(k0), Vertex::Front(i), Vertex::Front(i - 1)]);
                i -= 1;
                k = k0;
            }
            Step::Segment(k0) => {
                let g = score(inner[k0], inner[k], front[i]).unwrap_or(f64::NEG_INFINITY);
                let extra = link(k0, k).map_or(f64::NEG_INFINITY, score_of);
                if g.min(extra) < worst.0 {
                    worst = (g.min(extra), i);
                }
                triangles.push([Vertex::Segment(k0), Vertex::Segment(k), Vertex::Front(i)]);
                k = k0;
            }
        }
    }
    if value < -SLACK {
        if cfg!(test) && std::env::var("RHOMB_DEBUG").is_ok() {
            // The path's triangles at its worst margin.
            let at = |v: Vertex| match v {
                Vertex::Front(i) => front[i],
                Vertex::Segment(k) => inner[k],
            };
            for t in &triangles {
                let [p, q, r] = t.map(at);
                let g = score(p, q, r).unwrap_or(f64::NEG_INFINITY);
                if g <= value + SLACK {
                    eprintln!("  worst {t:?} {:?} margin {g}", [p, q, r]);
                }
            }
        }
        return Err(Failure::Bounds {
            at: worst.1,
            margin: value,
        });
    }
    triangles.reverse();
    Ok((value, triangles))
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// Triangles (p, q, r), p and q in the square [−1, 1]², r on the perpendicular to pq at
    /// q (up to `lift` times |pq| away) turned by a bend among `bends` (radians): a right
    /// angle at q when the bend is 0 (rounded either way), near-right ones, and others, all
    /// scaled by 2^e for e in [−300, 300).
    pub(in super::super) fn bent_right_triangles(
        lift: f64,
        bends: Vec<f64>,
    ) -> impl proptest::strategy::Strategy<Value = [Point; 3]> {
        use proptest::strategy::Strategy;
        let corner = (-1.0..1.0f64, -1.0..1.0f64);
        (
            corner.clone(),
            corner,
            -lift..lift,
            proptest::sample::select(bends),
            -300i32..300,
        )
            .prop_map(|(p, q, lift, bend, exponent)| {
                let (d, scale) = ([q.0 - p.0, q.1 - p.1], 2f64.powi(exponent));
                let (cos, sin) = (bend.cos(), bend.sin());
                let n = [-d[1] * cos - d[0] * sin, d[0] * cos - d[1] * sin];
                [
                    [p.0, p.1],
                    [q.0, q.1],
                    [q.0 + lift * n[0], q.1 + lift * n[1]],
                ]
                .map(|x| [x[0] * scale, x[1] * scale])
            })
    }

    fn point(s: &Strip, front: &[Point], v: Vertex) -> Point {
        match v {
            Vertex::Front(i) => front[i],
            Vertex::Segment(k) => s.on_segment[k],
        }
    }

    /// Checks a strip's triangles: counter-clockwise, angles in bounds, and their areas
    /// summing to the strip polygon's (so that, each positive, they tile it).
    fn check(s: &Strip, front: &[Point], a: Point, b: Point) {
        let mut area = 0.0;
        for t in &s.triangles {
            let [p, q, r] = t.map(|v| point(s, front, v));
            let g = score(p, q, r).expect("counter-clockwise");
            assert!(g >= -SLACK, "{t:?}: margin {g}");
            area += orient2d(p, q, r) / 2.0;
        }
        let (first, last) = (s.on_segment[0], *s.on_segment.last().unwrap());
        let mut ring = vec![first, last];
        ring.extend(front.iter().rev());
        let n = ring.len();
        let polygon: f64 = (0..n)
            .map(|k| {
                let (p, q) = (ring[k], ring[(k + 1) % n]);
                p[0] * q[1] - p[1] * q[0]
            })
            .sum::<f64>()
            / 2.0;
        assert!(
            (area - polygon).abs() <= 1e-12 * polygon.abs().max(1.0),
            "{area} {polygon}"
        );
        // The end feet are the perpendiculars' feet.
        for (foot, p) in [(first, front[0]), (last, *front.last().unwrap())] {
            let d = [foot[0] - p[0], foot[1] - p[1]];
            let u = [b[0] - a[0], b[1] - a[1]];
            let scale = (d[0].hypot(d[1])) * (u[0].hypot(u[1]));
            assert!(
                (d[0] * u[0] + d[1] * u[1]).abs() < 1e-12 * scale,
                "{foot:?} {p:?}"
            );
        }
    }

    #[test]
    fn a_box_of_two_equal_heights_is_cut_where_its_smallest_angle_is_largest() {
        // Front corners 0.75 above S, 1 apart: the diagonal (36.9°) beats v halfway (33.7°).
        let (a, b) = ([-1.0, 0.0], [2.0, 0.0]);
        let front = [[0.0, 0.75], [1.0, 0.75]];
        let s = strip(&front, a, b).unwrap();
        check(&s, &front, a, b);
        assert_eq!(s.on_segment, vec![[0.0, 0.0], [1.0, 0.0]], "{s:?}");
        assert_eq!(s.triangles.len(), 2);
        assert!((s.margin - (0.75f64.atan2(1.0).to_degrees() - 30.0)).abs() < 1e-9);
    }

    #[test]
    fn a_front_corner_on_the_wrong_side_or_out_of_order_is_named() {
        let (a, b) = ([0.0, 0.0], [4.0, 0.0]);
        assert_eq!(
            strip(&[[1.0, 0.5], [2.0, -0.1]], a, b),
            Err(Failure::Front(1))
        );
        assert_eq!(
            strip(&[[1.0, 0.5], [2.0, 0.5], [1.5, 0.6]], a, b),
            Err(Failure::Front(2))
        );
    }

    #[test]
    fn a_box_too_tall_for_its_width_has_no_triangulation() {
        // Heights 1 and widths 0.2: every triangle on S would be needle-thin.
        let (a, b) = ([0.0, 0.0], [4.0, 0.0]);
        let err = strip(&[[1.0, 1.0], [1.2, 1.0]], a, b).unwrap_err();
        assert!(matches!(err, Failure::Bounds { .. }), "{err:?}");
    }

    /// The unit triangular lattice: vertex (i, j) at i·e1 + j·e2.
    fn lattice(i: i64, j: i64) -> Point {
        [i as f64 + j as f64 / 2.0, j as f64 * 3f64.sqrt() / 2.0]
    }

    /// A uniform lattice of side 1 cut by the line through `c` at angle `turn`, the domain on
    /// its left: every corner inside moved by Sec. 5.2 case 1 (`near`), the triangles with
    /// three corners inside kept. Returns the kept triangles (moved corners) and the front: the
    /// kept triangles' sides whose other triangle is cut, chained along the line within
    /// `reach` of c, as the moved corners in order from a to b; and a, b.
    #[allow(clippy::type_complexity)]
    fn cut_lattice(c: Point, turn: f64, reach: f64) -> (Vec<[Point; 3]>, Vec<Point>, Point, Point) {
        let u = [turn.cos(), turn.sin()];
        let (a, b) = (
            [c[0] - 40.0 * u[0], c[1] - 40.0 * u[1]],
            [c[0] + 40.0 * u[0], c[1] + 40.0 * u[1]],
        );
        let n = 12i64;
        let inside = |i: i64, j: i64| orient2d(a, b, lattice(i, j)) > 0.0;
        let moved = |i: i64, j: i64| {
            let p = lattice(i, j);
            let hexagon = super::super::near::DIRECTIONS.map(|(di, dj)| lattice(i + di, j + dj));
            match super::super::near::nearest(p, &hexagon, &[[a, b]], 0) {
                Some(near) if near.within_half => {
                    let (di, dj) = super::super::near::DIRECTIONS[(near.side + 3) % 6];
                    let q = lattice(i + di, j + dj);
                    [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0]
                }
                _ => p,
            }
        };
        let along = |p: Point| (p[0] - c[0]) * u[0] + (p[1] - c[1]) * u[1];
        let mut kept = Vec::new();
        let mut sides = std::collections::BTreeMap::new();
        for i in -n..n {
            for j in -n..n {
                let halves = [
                    [(i, j), (i + 1, j), (i, j + 1)],
                    [(i + 1, j), (i + 1, j + 1), (i, j + 1)],
                ];
                for t in halves {
                    if !t.iter().all(|&(i, j)| inside(i, j)) {
                        continue;
                    }
                    kept.push(t.map(|(i, j)| moved(i, j)));
                    for k in 0..3 {
                        let (p, q) = (t[k], t[(k + 1) % 3]);
                        // The other triangle across side pq has its third corner at
                        // p + q − r (r the third corner here): cut when that is outside.
                        let r = t[(k + 2) % 3];
                        let o = (p.0 + q.0 - r.0, p.1 + q.1 - r.1);
                        if !inside(o.0, o.1) {
                            let (mp, mq) = (moved(p.0, p.1), moved(q.0, q.1));
                            if along(mp).abs() <= reach && along(mq).abs() <= reach {
                                // Kept on the left of p -> q: from b's side towards a's.
                                sides.insert(p, (q, mq, mp));
                            }
                        }
                    }
                }
            }
        }
        // Chain the front sides: each runs q -> p backwards along the line.
        let mut start = *sides.keys().next().expect("a front");
        while let Some((&p, _)) = sides.iter().find(|(_, v)| v.0 == start) {
            start = p;
        }
        let mut front = vec![];
        let mut at = start;
        while let Some(&(q, mq, mp)) = sides.get(&at) {
            if front.is_empty() {
                front.push(mp);
            }
            front.push(mq);
            at = q;
        }
        if along(front[0]) > along(*front.last().unwrap()) {
            front.reverse();
        }
        (kept, front, a, b)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(1000))]

        /// Paper 001 on equal rhombs along a straight segment (Sec. 5.2 case 1, Table 1's
        /// BB_1): the lattice cut by a line in any direction and position, corners within
        /// half a side of it moved, keeps every triangle inside in [30°, 90°], its front
        /// runs along the line, and the strip to the line is triangulated in bounds.
        #[test]
        fn equal_rhombs_cut_by_a_line_keep_30_to_90_degrees_to_the_segment(
            c in (0.0..1.0f64, 0.0..1.0f64),
            turn in 0.0..std::f64::consts::TAU,
        ) {
            let (kept, front, a, b) = cut_lattice([c.0, c.1], turn, 5.0);
            for t in &kept {
                let g = score(t[0], t[1], t[2]);
                proptest::prop_assert!(g.is_some_and(|g| g >= -SLACK), "{:?}: {:?}", t, g);
            }
            proptest::prop_assert!(front.len() >= 8, "{:?}", front);
            let s = strip(&front, a, b);
            proptest::prop_assert!(s.is_ok(), "{:?}\nfront {:?}", s, front);
            check(&s.unwrap(), &front, a, b);
        }

        /// `score` measures the largest angle only where it may exceed 90°: its value is the
        /// one measuring all three angles gives, on triangles of any shape and scale, right
        /// triangles and near-right ones (where the two could part) among them.
        #[test]
        fn the_score_is_that_of_measuring_every_angle(
            tri in bent_right_triangles(1.0, vec![0.0, 1e-17, -1e-17, 1e-9, -1e-9, 1e-6, 0.3]),
        ) {
            let every = || -> Option<f64> {
                if orient2d(tri[0], tri[1], tri[2]) <= 0.0 {
                    return None;
                }
                let angles = [0, 1, 2].map(|k| angle_deg(tri[(k + 2) % 3], tri[k], tri[(k + 1) % 3]));
                let (min, max) = (angles.iter().copied().fold(f64::INFINITY, f64::min),
                    angles.iter().copied().fold(0.0, f64::max));
                Some((min - 30.0).min(if max > 90.0 { 90.0 - max } else { f64::INFINITY }))
            };
            let got = score(tri[0], tri[1], tri[2]);
            proptest::prop_assert_eq!(got, every(), "{:?}", tri);
        }

        /// A triangle's key orders it as its score does: turned back into a score, it is
        /// the score `score` measures within 1e-9°, on triangles of any shape and scale,
        /// right and near-right ones (where the excess over 90° decides) among them.
        #[test]
        fn a_key_is_the_score_without_an_arc_tangent(
            tri in bent_right_triangles(
                1.0,
                vec![0.0, 1e-17, -1e-17, 1e-9, -1e-9, 1e-6, 0.3, -0.3, 1.2],
            ),
        ) {
            let (got, want) = (key(tri[0], tri[1], tri[2]), score(tri[0], tri[1], tri[2]));
            proptest::prop_assert_eq!(got.is_some(), want.is_some(), "{:?}", tri);
            if let (Some(got), Some(want)) = (got, want) {
                proptest::prop_assert!(
                    (score_of(got) - want).abs() <= 1e-9,
                    "{:?}: key {} score {}", tri, got, want
                );
            }
        }

        /// `key_of` is increasing and `score_of` inverts it, from −120° to past 60° (a
        /// triangle's score lies in (−90°, 30°]; a corner's fan may be given more).
        #[test]
        fn keys_keep_the_order_of_scores_and_give_them_back(
            x in -120.0..100.0f64,
            dx in proptest::sample::select(vec![1e-9f64, 1e-6, 0.01, 1.0, 30.0]),
        ) {
            proptest::prop_assert!(key_of(x) < key_of(x + dx), "{} {}", x, dx);
            proptest::prop_assert!((score_of(key_of(x)) - x).abs() <= 1e-9, "{}", x);
        }
    }

    /// Infinite scores (a side with no triangle beyond it; no ladder) keep their keys.
    #[test]
    fn infinite_scores_are_their_own_keys() {
        for x in [f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(key_of(x), x);
            assert_eq!(score_of(x), x);
        }
    }

    /// The steps of a plain ladder, last first: (front index, inner index, a front step).
    type PlainSteps = Vec<(usize, usize, bool)>;

    /// The ladder's programme without its shortcuts: every candidate of a cell scored, the
    /// step before first, then the sides along S in increasing k0, a later one taking the
    /// cell only with a larger margin or as large a margin and fewer triangles.
    fn plain_ladder(
        front: &[Point],
        inner: &[Point],
        window: &[(usize, usize)],
        span: usize,
        link: &dyn Fn(usize, usize) -> Option<f64>,
    ) -> Option<(f64, PlainSteps)> {
        // best[i][k]: (margin as a key, triangles, from (i', k'), a front step).
        type Cell = Option<(f64, usize, (usize, usize), bool)>;
        let (m, n) = (front.len(), inner.len());
        let mut best: Vec<Vec<Cell>> = vec![vec![None; n]; m];
        for i in 0..m {
            for k in window[i].0..=window[i].1 {
                let mut cell: Cell = None;
                let mut take = |cand: (f64, usize, (usize, usize), bool)| {
                    if cell.is_none_or(|(v, c, _, _)| cand.0 > v || (cand.0 == v && cand.1 < c)) {
                        cell = Some(cand);
                    }
                };
                if i == 0 && k == window[0].0 {
                    take((f64::INFINITY, 0, (0, k), false));
                }
                if let Some((v, c, _, _)) = (i > 0).then(|| best[i - 1][k]).flatten() {
                    if let Some(g) = key(inner[k], front[i], front[i - 1]) {
                        take((v.min(g), c + 1, (i - 1, k), true));
                    }
                }
                for k0 in k.saturating_sub(span).max(window[i].0)..k {
                    let (Some((v, c, _, _)), Some(extra)) = (best[i][k0], link(k0, k)) else {
                        continue;
                    };
                    if let Some(g) = key(inner[k0], inner[k], front[i]) {
                        take((v.min(g).min(extra), c + 1, (i, k0), false));
                    }
                }
                best[i][k] = cell;
            }
        }
        let (mut i, mut k) = (m - 1, window[m - 1].1);
        let value = score_of(best[i][k]?.0);
        let mut steps = Vec::new();
        while let Some((_, c, from, front_step)) = best[i][k] {
            if c == 0 {
                break;
            }
            steps.push((i, k, front_step));
            (i, k) = from;
        }
        Some((value, steps))
    }

    #[test]
    fn the_ladder_chooses_what_scoring_every_candidate_in_order_chooses() {
        // Strips of front corners at uneven heights over S (the x axis), each foot and six
        // points between feet on S, and a link that caps some sides (as a fan triangle
        // does) at a margin shared by many ladders, so that ties of margin and count occur.
        let mut next = super::super::fan::uniform(20261207);
        let mut ties = 0;
        for case in 0..60 {
            let m = 10;
            let front: Vec<Point> = (0..m)
                .map(|i| [i as f64 + 0.3 * next(), 0.5 + 0.6 * next()])
                .collect();
            let mut inner: Vec<Point> = Vec::new();
            for i in 0..m {
                inner.push([front[i][0], 0.0]);
                if i + 1 < m {
                    let (x0, x1) = (front[i][0], front[i + 1][0]);
                    inner.extend((1..7).map(|q| [x0 + (x1 - x0) * q as f64 / 7.0, 0.0]));
                }
            }
            let n = inner.len();
            let window: Vec<(usize, usize)> = (0..m)
                .map(|i| ((7 * i).saturating_sub(10), (7 * i + 10).min(n - 1)))
                .collect();
            let capped = |k0: usize, k: usize| {
                if (k0 * 31 + k * 17 + case) % 5 == 0 {
                    Some(key_of(8.0))
                } else {
                    Some(f64::INFINITY)
                }
            };
            let span = 14;
            let back: Vec<usize> = (0..n).map(|k| k.saturating_sub(span)).collect();
            let want = plain_ladder(&front, &inner, &window, span, &capped);
            let got = ladder(&front, &inner, &window, (span, &back), &capped);
            match (want, got) {
                (Some((v, steps)), Ok((g, triangles))) if v >= -SLACK => {
                    assert_eq!(v, g, "case {case}");
                    assert_eq!(steps.len(), triangles.len(), "case {case}");
                    ties += usize::from(v == 8.0);
                    // The same triangles, last step first.
                    for (&(i, k, front_step), t) in steps.iter().zip(triangles.iter().rev()) {
                        assert_eq!(
                            t[1],
                            if front_step {
                                Vertex::Front(i)
                            } else {
                                Vertex::Segment(k)
                            },
                            "case {case}"
                        );
                        if !front_step {
                            assert_eq!(t[2], Vertex::Front(i), "case {case}");
                        } else {
                            assert_eq!(t[0], Vertex::Segment(k), "case {case}");
                        }
                    }
                }
                (Some((v, _)), Err(Failure::Bounds { margin, .. })) => {
                    assert!(v < -SLACK, "case {case}: {v}");
                    assert_eq!(v, margin, "case {case}");
                }
                (want, got) => panic!("case {case}: {want:?} against {got:?}"),
            }
        }
        // Ladders capped by a link: ties of margin, decided by count and then by order.
        assert!(ties >= 5, "{ties}");
    }
}
