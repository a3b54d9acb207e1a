//! Steps 11 and 13–16 of paper 001 (Sec. 4), ours in their detail: between each polygon
//! and the front `cut` left around it, one cyclic ladder (`boxes::ladder`) joins the front's
//! corners to points on the polygon's sides, and each input corner c is met in one of three
//! ways the ladder chooses between (see `fan`): c is a vertex of the ladder's triangles; a
//! fan of triangles at c on rays every 10° at radii of half to one and a half lattice sides;
//! or, below 90°, a wedge of triangles between its two sides from the whole corner at c.
//!
//! The candidate points on a side are the feet of the front corners nearest it, the points of
//! the paper's border-boxes between neighbouring feet (`boxes::box_points`), points every
//! tenth of a lattice side out to three sides from each corner and, towards a corner sharper
//! than 90°, points at distances from it growing by 5 % and every tenth of a side around
//! where the front ends nearest it. A ladder that keeps no [30°, 90°] triangulation names
//! the front corner where its worst triangle is: the caller erodes it and cuts again.

use crate::hex::fxhash::FxHashMap;

use super::blocks::Blocks;
use super::boxes::{box_points, key, Vertex};
use super::cut::{Cut, Segments};
use super::input::Domain;
use super::pieces::{solve, Chain, Pieces, Words};
use super::wedge::{wedge, wedge_triangles, whole_corner_key, WedgeTable, WedgeVertex};
use crate::geom::{angle_deg, dist, orient2d, Point};
use crate::quality::feature_gap::point_segment_distance;

/// A vertex of the filled mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Id {
    /// A vertex of the lattice mesh (`Cut::position`).
    Lattice(u32),
    /// A domain point (an input corner).
    Point(u32),
    /// A point the fill adds, in `Fill::steiner`.
    Steiner(u32),
}

/// What the fill adds: its points and its triangles, counter-clockwise, and which of them
/// are whole input corners sharper than 30° (their angle there is the input's).
#[derive(Debug, Default)]
pub struct Fill {
    pub steiner: Vec<Point>,
    pub triangles: Vec<[Id; 3]>,
    pub whole: Vec<usize>,
}

/// What a fill keeps from one erosion round to the next: the wedge tables of the sharp
/// corners by their points (an erosion far from a corner leaves them as they were), and
/// each corner's latest table, whose cells a new one takes where its points near the
/// corner are the same (`wedge`'s `from`).
#[derive(Debug, Default)]
pub struct Memo {
    /// Each table with a number in order of first use (for the pieces' keys).
    wedges: FxHashMap<Words, (u64, std::sync::Arc<WedgeTable>)>,
    /// By the corner's place and angle (their bits): its latest table.
    latest: FxHashMap<[u64; 3], Latest>,
    pieces: Pieces,
}

/// A corner's latest wedge table with the W and V points and rows it was built for.
#[derive(Debug)]
struct Latest {
    ws: Vec<Point>,
    vs: Vec<Point>,
    rows: Vec<usize>,
    table: std::sync::Arc<WedgeTable>,
}

impl Memo {
    /// An empty memo whose pieces are solved on `threads` threads (`pieces::solve`).
    pub fn with_threads(threads: usize) -> Memo {
        let mut memo = Memo::default();
        memo.pieces.threads = threads;
        memo
    }
}

/// Why a fill failed.
#[derive(Debug, Clone, PartialEq)]
pub enum Stuck {
    /// The ladder around a polygon fails at this lattice vertex, by this margin (degrees
    /// below the bounds when negative; −∞ where no ladder was tried): the caller moves or
    /// erodes it.
    At(u32, f64),
    /// Two fronts face one polygon: all but the longest are islands the cut left between
    /// deleted triangles; these are their corners, every polygon's at once, and the caller
    /// erodes them all.
    Island(Vec<u32>),
    /// The fronts do not pair with the polygons one to one: the kept lattice does not
    /// separate two polygons (one front faces both), or a polygon faces none. The tree must
    /// be finer at these points.
    Finer(Vec<Point>),
}

impl Stuck {
    /// The lattice corner a failure names (an island's first), if any.
    pub fn corner(&self) -> Option<u32> {
        match self {
            Stuck::At(v, _) => Some(*v),
            Stuck::Island(corners) => corners.first().copied(),
            Stuck::Finer(_) => None,
        }
    }
}

/// What a point of a polygon's inner chain is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// On side `side` (corners[side] → corners[side + 1]) at this distance from its start.
    Side(usize, f64),
    /// Corner `j` itself.
    Corner(usize),
    /// On a ray of corner `j` at this angle (degrees) from its outgoing side.
    Ray(usize, f64),
}

/// The angle of the domain at corner `j` of a ring (degrees, in (0, 360)).
fn corner_angle(ring: &[Point], j: usize) -> f64 {
    let n = ring.len();
    let (w, c, v) = (ring[(j + n - 1) % n], ring[j], ring[(j + 1) % n]);
    let a = angle_deg(c, v, w);
    if orient2d(c, v, w) >= 0.0 {
        a
    } else {
        360.0 - a
    }
}

/// How far from corner c, between sides (w, c) and (c, v), a rung of its wedge may lie:
/// each front corner (p, r) meets the inner points within r of it, so a rung needs a front
/// corner whose reach meets both sides, and lies no farther from c than the farthest such
/// corner's distance and reach. None when no front corner meets both. (A window made
/// monotone may reach farther; a rung there closes with the one triangle at c, as `link`
/// falls back to.)
fn rung_reach((w, c, v): (Point, Point, Point), reaches: &[(Point, f64)]) -> Option<f64> {
    reaches
        .iter()
        .filter(|&&(p, r)| {
            point_segment_distance(p, w, c) <= r && point_segment_distance(p, c, v) <= r
        })
        .map(|&(p, r)| dist(p, c) + r)
        .max_by(f64::total_cmp)
}

/// A corner's wedge: its W and V points (indices into the inner chain, by distance from the
/// corner) and its table (`wedge`).
type Wedge = (Vec<usize>, Vec<usize>, std::sync::Arc<WedgeTable>);

/// How many points back a side along a polygon side may reach (about three boxes).
const SIDE_SPAN: usize = 48;

/// How long a piece of the ladder is, in lattice sides along its side (`pieces`).
const PIECE: f64 = 24.0;

/// How far back a side may reach across a corner sharper than 90° (its wedge).
const SHARP_SPAN: usize = 400;

/// How many rays' points follow the corner at index j of the chain.
fn tip_len(place: &[Place], j: usize) -> usize {
    place[j + 1..]
        .iter()
        .take_while(|p| matches!(p, Place::Ray(..)))
        .count()
}

/// Distances from a corner to the wedge's extra points: from a fifth of a side, growing by
/// 5 %, up to `end`.
fn growing(side: f64, end: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut x = 0.2 * side;
    while x < end {
        out.push(x);
        x *= 1.05;
    }
    out
}

/// Fills every polygon's gap to its front (see the module notes). `corner_side[k][j]` is
/// the lattice side at corner j of polygon k.
pub fn fill(
    domain: &Domain,
    segments: &Segments,
    cut: &Cut,
    corner_side: &[Vec<f64>],
    memo: &mut Memo,
) -> Result<Fill, Stuck> {
    // Each front goes with the polygon its corners are nearest to (by majority).
    let mut front_of: Vec<Vec<usize>> = vec![Vec::new(); domain.polygons.len()];
    let mut finer = Vec::new();
    let mut stranded = Vec::new();
    for (f, l) in cut.loops.iter().enumerate() {
        let mut votes = vec![0usize; domain.polygons.len()];
        let nearest: Vec<Option<usize>> = l
            .iter()
            .map(|&v| nearest_side(segments, cut, v, None).map(|(s, _, _)| segments.owner[s].0))
            .collect();
        for k in nearest.iter().flatten() {
            votes[*k] += 1;
        }
        let best = (0..votes.len()).max_by_key(|&k| (votes[k], std::cmp::Reverse(k)));
        if votes.iter().all(|&n| n == 0) {
            // No side within reach of any corner: a patch of fine lattice (a single
            // point's, `band::around_single`) inside a gap the fill spans, which its
            // triangles would cover a second time.
            stranded.extend(l.iter().copied());
        }
        if let Some(k) = best.filter(|&k| votes[k] > 0) {
            front_of[k].push(f);
            // Corners of this front nearest another polygon: the lattice between the two
            // polygons is too coarse to keep a triangle there.
            for (&v, near) in l.iter().zip(&nearest) {
                if near.is_some_and(|x| x != k) {
                    finer.push(cut.position[v as usize]);
                }
            }
        }
    }
    if !finer.is_empty() {
        return Err(Stuck::Finer(finer));
    }
    // Two fronts facing one polygon: all but the longest are islands the cut left between
    // deleted triangles (a kept triangle cut off, or a hole in the kept lattice); eroding
    // their corners joins them to the gap. Every polygon's islands are named at once, so
    // that one erosion round takes them all.
    let mut islands: Vec<u32> = front_of
        .iter()
        .filter(|fronts| fronts.len() > 1)
        .flat_map(|fronts| {
            let longest = fronts
                .iter()
                .copied()
                .max_by_key(|&f| (cut.loops[f].len(), std::cmp::Reverse(f)))
                .expect("two");
            fronts
                .iter()
                .filter(move |&&f| f != longest)
                .flat_map(|&f| cut.loops[f].iter().copied())
        })
        .collect();
    islands.extend(stranded);
    if !islands.is_empty() {
        return Err(Stuck::Island(islands));
    }
    let mut out = Fill::default();
    for (k, fronts) in front_of.iter().enumerate() {
        if fronts.is_empty() {
            let poly = &domain.polygons[k];
            return Err(Stuck::Finer(
                poly.corners
                    .iter()
                    .map(|&c| domain.points[c as usize])
                    .collect(),
            ));
        }
        let target = Target {
            k,
            front: &cut.loops[fronts[0]],
            sides_at: &corner_side[k],
        };
        fill_polygon(domain, segments, cut, &target, memo, &mut out)?;
    }
    Ok(out)
}

/// The side nearest lattice vertex v within sixteen of its sides (of polygon `only`, if given):
/// (segment index, distance along it from its start, distance to it).
fn nearest_side(
    segments: &Segments,
    cut: &Cut,
    v: u32,
    only: Option<usize>,
) -> Option<(usize, f64, f64)> {
    let p = cut.position[v as usize];
    let r = 16.0 * cut.side[v as usize];
    let mut best: Option<(usize, f64, f64)> = None;
    for s in segments.near([p[0] - r, p[1] - r, p[0] + r, p[1] + r]) {
        let s = s as usize;
        if only.is_some_and(|k| segments.owner[s].0 != k) {
            continue;
        }
        let [a, b] = segments.ends[s];
        let len = dist(a, b);
        let u = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
        let t = ((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]).clamp(0.0, len);
        let d = dist(p, [a[0] + t * u[0], a[1] + t * u[1]]);
        if d <= r && best.is_none_or(|x| d < x.2) {
            best = Some((s, t, d));
        }
    }
    best
}

/// One polygon's fill: polygon `k`, its front and the lattice side at each of its corners.
struct Target<'t> {
    k: usize,
    front: &'t [u32],
    sides_at: &'t [f64],
}

/// The cyclic ladder between polygon `target.k` and its front.
fn fill_polygon(
    domain: &Domain,
    segments: &Segments,
    cut: &Cut,
    target: &Target,
    memo: &mut Memo,
    out: &mut Fill,
) -> Result<(), Stuck> {
    let (k, front, sides_at) = (target.k, target.front, target.sides_at);
    let poly = &domain.polygons[k];
    let nc = poly.corners.len();
    let ring: Vec<Point> = poly
        .corners
        .iter()
        .map(|&c| domain.points[c as usize])
        .collect();
    let first_segment = segments
        .owner
        .iter()
        .position(|o| o.0 == k)
        .expect("a side");
    let length: Vec<f64> = (0..nc).map(|j| dist(ring[j], ring[(j + 1) % nc])).collect();
    let alpha: Vec<f64> = (0..nc).map(|j| corner_angle(&ring, j)).collect();
    let at = |side: usize, t: f64| {
        let (a, b) = (ring[side], ring[(side + 1) % nc]);
        let f = t / length[side];
        [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]
    };
    // Each front corner's nearest side of this polygon and its foot there.
    let found: Vec<Option<(usize, f64, f64)>> = front
        .iter()
        .map(|&v| {
            nearest_side(segments, cut, v, Some(k)).map(|(s, t, d)| (s - first_segment, t, d))
        })
        .collect();
    let feet: Vec<Option<(usize, f64)>> = found.iter().map(|f| f.map(|(s, t, _)| (s, t))).collect();
    // Start at the front corner whose foot is farthest from the tips of its side's corners
    // (four lattice sides at each: the chain's last stretch must not cut a corner's fan or
    // wedge short), and at least two of its own sides from either.
    let clearance = |i: usize| -> Option<f64> {
        let (s, t) = feet[i]?;
        let own = 2.0 * cut.side[front[i] as usize];
        let c = (t - own.max(4.0 * sides_at[s]))
            .min(length[s] - t - own.max(4.0 * sides_at[(s + 1) % nc]));
        (c > 0.0).then_some(c)
    };
    let start = (0..front.len())
        .filter_map(|i| clearance(i).map(|c| (c, i)))
        .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)))
        .map(|x| x.1)
        .ok_or(Stuck::At(front[0], f64::NEG_INFINITY))?;
    let (s0, t0) = feet[start].expect("a foot");
    let m = front.len() + 1;
    let order: Vec<usize> = (0..m).map(|i| (start + i) % front.len()).collect();
    let fpos: Vec<Point> = order
        .iter()
        .map(|&i| cut.position[front[i] as usize])
        .collect();
    // The inner chain: from the start foot along the sides, around, back to it.
    let mut inner: Vec<Point> = Vec::new();
    let mut place: Vec<Place> = Vec::new();
    let mut stops: Vec<Vec<f64>> = vec![Vec::new(); nc];
    for (i, f) in feet.iter().enumerate() {
        if let Some((s, t)) = *f {
            stops[s].push(t);
            let j = (i + 1) % front.len();
            if let Some((s2, _)) = feet[j] {
                if s2 == s {
                    let (a, b) = (ring[s], ring[(s + 1) % nc]);
                    let (p, q) = (
                        cut.position[front[i] as usize],
                        cut.position[front[j] as usize],
                    );
                    for x in box_points(p, q, a, b) {
                        stops[s].push(dist(a, x));
                    }
                }
            }
        }
    }
    // Each corner's distance to the nearest front corner (the fan's radii span it: the
    // outer ray points stay inside the gap, whether the lattice beside the corner is finer
    // than at it or coarser; a sharp corner's wedge reaches past it), and the lattice side
    // at that front corner.
    let (gap, tip_side): (Vec<f64>, Vec<f64>) = (0..nc)
        .map(|j| {
            (0..m)
                .map(|i| (dist(fpos[i], ring[j]), cut.side[front[order[i]] as usize]))
                .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
        })
        .unzip();
    for s in 0..nc {
        let e = (s + 1) % nc;
        let far = length[s];
        // Below 90°, every tenth of a side along both sides where the front ends nearest the
        // corner, from four sides short of it to one past: the wedge's rung under the
        // lattice's tip lies there, where the points growing by 5 % from the corner are
        // sides apart (fuzz case 84: 3.3 and 3.9 sides, 80 sides from a corner of 1.5°).
        for (j, from_end) in [(s, false), (e, true)] {
            if alpha[j] < 90.0 && gap[j].is_finite() {
                let unit = tip_side[j] / 10.0;
                for q in -40..=10 {
                    let x = gap[j] + q as f64 * unit;
                    if x > 0.0 && x < far / 2.0 {
                        stops[s].push(if from_end { far - x } else { x });
                    }
                }
            }
        }
        if alpha[s] < 90.0 {
            stops[s].extend(growing(sides_at[s], far / 2.0));
        }
        if alpha[e] < 90.0 {
            stops[s].extend(growing(sides_at[e], far / 2.0).into_iter().map(|x| far - x));
        }
        // Near both corners, every tenth of a side out to three sides.
        for (side, from_end) in [(sides_at[s], false), (sides_at[e], true)] {
            for q in 2..=30 {
                let x = (q as f64 / 10.0 * side).min(far / 2.0);
                stops[s].push(if from_end { far - x } else { x });
            }
        }
        stops[s].retain(|&t| t > 0.0 && t < length[s]);
        stops[s].sort_by(f64::total_cmp);
        stops[s].dedup();
    }
    let push = |inner: &mut Vec<Point>, place: &mut Vec<Place>, pl: Place, p: Point| {
        inner.push(p);
        place.push(pl);
    };
    push(&mut inner, &mut place, Place::Side(s0, t0), at(s0, t0));
    for &t in stops[s0].iter().filter(|&&t| t > t0) {
        push(&mut inner, &mut place, Place::Side(s0, t), at(s0, t));
    }
    let fan_unit: Vec<f64> = gap.iter().map(|g| g / 1.5).collect();
    for step in 1..=nc {
        let j = (s0 + step) % nc; // the corner at the end of the side before
        push(&mut inner, &mut place, Place::Corner(j), ring[j]);
        if alpha[j] >= 60.0 {
            let (c, v) = (ring[j], ring[(j + 1) % nc]);
            let base = (v[1] - c[1]).atan2(v[0] - c[0]);
            let rays = (alpha[j] / 10.0).ceil() as usize;
            for r in (1..rays).rev() {
                let theta = alpha[j] * r as f64 / rays as f64;
                let tt = base + theta.to_radians();
                for radius in [0.35, 0.5, 0.65, 0.75, 0.9, 1.0, 1.25, 1.5] {
                    let d = radius * fan_unit[j];
                    push(
                        &mut inner,
                        &mut place,
                        Place::Ray(j, theta),
                        [c[0] + d * tt.cos(), c[1] + d * tt.sin()],
                    );
                }
            }
        }
        let s = j;
        let last = step == nc;
        for &t in stops[s].iter().filter(|&&t| !last || t < t0) {
            push(&mut inner, &mut place, Place::Side(s, t), at(s, t));
        }
    }
    push(&mut inner, &mut place, Place::Side(s0, t0), at(s0, t0));
    let n = inner.len();
    // Each front corner with its reach: the inner points within two sides of it, and half
    // again its distance to the polygon (its window below, and `rung_reach`).
    let reaches: Vec<(Point, f64)> = (0..m)
        .map(|i| {
            let r = 2.0 * cut.side[front[order[i]] as usize]
                + 1.5 * found[order[i]].map_or(0.0, |f| f.2);
            (fpos[i], r)
        })
        .collect();
    // How far back a side along the chain may reach: a few boxes along a side; from a
    // corner's rays or the side after it, back over the whole tip to the side before (far
    // back at a sharp corner, whose wedge spans many points on both sides).
    let mut back: Vec<usize> = (0..n).map(|k| k.saturating_sub(SIDE_SPAN)).collect();
    for (j, _) in place
        .iter()
        .enumerate()
        .filter(|x| matches!(x.1, Place::Corner(_)))
    {
        let Place::Corner(c) = place[j] else { continue };
        let reach = if alpha[c] < 90.0 {
            SHARP_SPAN
        } else {
            SIDE_SPAN
        };
        let from = j.saturating_sub(reach);
        let mut k = j;
        while k < n
            && (k == j
                || matches!(place[k], Place::Ray(..))
                || k < j + reach + 1 + tip_len(&place, j))
        {
            back[k] = back[k].min(from);
            k += 1;
        }
    }
    // The wedges of corners below 90°: W points (the side before, by distance from c) and V
    // points (the side after), as indices into `inner`.
    let mut wedges: Vec<Option<Wedge>> = vec![None; nc];
    let mut table_number: Vec<u64> = vec![u64::MAX; nc];
    let (mut w_pos, mut v_pos) = (vec![None; n], vec![None; n]);
    for j in 0..nc {
        if alpha[j] >= 90.0 {
            continue;
        }
        let w_side = (j + nc - 1) % nc;
        // Past the front's nearest corner and out to where the corner is four lattice
        // sides wide (the front meets the wedge before that), and at most half of either
        // side, and no farther than a rung may lie (`rung_reach`): at a corner of 2.6° whose
        // lattice ends as a thin strip 39 sides from it (fuzz case 10), the table had 2,000
        // points a side, four million cells rebuilt at every fill, 97 % of the run.
        let wide = (3.0 * gap[j]).max(4.0 * sides_at[j] / (alpha[j].to_radians() / 2.0).sin());
        let sides = (ring[w_side], ring[j], ring[(j + 1) % nc]);
        let wide = rung_reach(sides, &reaches).map_or(wide, |r| wide.min(r));
        let reach = (length[w_side].min(length[j]) / 2.0).min(wide);
        let mut ws: Vec<(f64, usize)> = Vec::new();
        let mut vs: Vec<(f64, usize)> = Vec::new();
        for (idx, p) in place.iter().enumerate() {
            match *p {
                Place::Side(s, t) if s == w_side && length[s] - t <= reach && idx > 0 => {
                    ws.push((length[s] - t, idx))
                }
                Place::Side(s, t) if s == j && t <= reach && idx + 1 < n => vs.push((t, idx)),
                _ => {}
            }
        }
        ws.sort_by(|a, b| a.0.total_cmp(&b.0));
        vs.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (a, x) in ws.iter().enumerate() {
            w_pos[x.1] = Some(a);
        }
        for (b, x) in vs.iter().enumerate() {
            v_pos[x.1] = Some(b);
        }
        // The rungs the ladder may read (`link`: from W point x to V point y only when
        // back[y] <= x < y), and below and left of them what they are computed from: at a
        // thin channel's corner, whose wedge runs along the channel, the whole table was
        // 640,000 cells rebuilt at every fill (fuzz case 72), the rungs a sixth of them.
        // Only this wedge's W points: `w_pos` also holds the earlier wedges' (the side
        // before a sharp corner that is short lies within reach of the next corner).
        let mut rows = vec![0usize; ws.len()];
        for (b, &(_, y)) in vs.iter().enumerate() {
            let own = |x: &usize| matches!(place[*x], Place::Side(s, _) if s == w_side);
            for a in (back[y]..y).filter(own).filter_map(|x| w_pos[x]) {
                rows[a] = rows[a].max(b + 1);
            }
        }
        for a in (1..rows.len()).rev() {
            rows[a - 1] = rows[a - 1].max(rows[a]);
        }
        let wp: Vec<Point> = ws.iter().map(|x| inner[x.1]).collect();
        let vp: Vec<Point> = vs.iter().map(|x| inner[x.1]).collect();
        let key = Words(
            [ring[j][0], ring[j][1], alpha[j], wp.len() as f64]
                .into_iter()
                .chain(wp.iter().chain(&vp).flat_map(|p| [p[0], p[1]]))
                .map(f64::to_bits)
                .chain(rows.iter().map(|&r| r as u64))
                .collect(),
        );
        let number = memo.wedges.len() as u64;
        let corner = [ring[j][0], ring[j][1], alpha[j]].map(f64::to_bits);
        let latest = memo.latest.get(&corner);
        let (number, table) = memo
            .wedges
            .entry(key)
            .or_insert_with(|| {
                let shared =
                    |x: &[Point], y: &[Point]| x.iter().zip(y).take_while(|(p, q)| p == q).count();
                let from = latest.map(|l| {
                    (
                        &*l.table,
                        &l.rows[..],
                        shared(&l.ws, &wp),
                        shared(&l.vs, &vp),
                    )
                });
                let table = wedge(ring[j], alpha[j], &wp, &vp, &rows, from);
                (number, std::sync::Arc::new(table))
            })
            .clone();
        memo.latest.insert(
            corner,
            Latest {
                ws: wp,
                vs: vp,
                rows,
                table: table.clone(),
            },
        );
        table_number[j] = number;
        wedges[j] = Some((
            ws.into_iter().map(|x| x.1).collect(),
            vs.into_iter().map(|x| x.1).collect(),
            table,
        ));
    }
    // A point of W (V) belongs to the wedge of the corner its side runs into (starts from).
    let wedge_value = |j: usize, k0: usize, k1: usize| -> Option<(usize, usize, f64)> {
        let (_, _, table) = wedges[j].as_ref()?;
        let (a, b) = (w_pos[k0]?, v_pos[k1]?);
        let v = table[a].get(b).map_or(f64::NEG_INFINITY, |c| c.0);
        (v > f64::NEG_INFINITY).then_some((a, b, v))
    };
    let link = |k0: usize, k1: usize| -> Option<f64> {
        let corner_of = |s: usize| (s + 1) % nc; // the corner a side runs into
        match (place[k0], place[k1]) {
            (Place::Side(s, t), Place::Side(s1, t1)) if s == s1 && t1 > t => Some(f64::INFINITY),
            (Place::Side(s, _), Place::Corner(j)) if corner_of(s) == j => Some(f64::INFINITY),
            (Place::Corner(j), Place::Side(s, _)) if s == j => Some(f64::INFINITY),
            (Place::Side(s, _), Place::Side(s1, _)) if s1 == corner_of(s) => {
                let j = s1;
                if let Some((_, _, v)) = wedge_value(j, k0, k1) {
                    return Some(v);
                }
                let g = if alpha[j] < 30.0 {
                    whole_corner_key(ring[j], inner[k1], inner[k0])
                } else {
                    key(ring[j], inner[k1], inner[k0]).unwrap_or(f64::NEG_INFINITY)
                };
                (g > f64::NEG_INFINITY).then_some(g)
            }
            (Place::Side(s, _), Place::Ray(j, _)) if corner_of(s) == j => {
                key(ring[j], inner[k1], inner[k0])
            }
            (Place::Ray(j, a), Place::Ray(j1, b)) if j == j1 && b < a => {
                key(ring[j], inner[k1], inner[k0])
            }
            (Place::Ray(j, _), Place::Side(s, _)) if s == j => key(ring[j], inner[k1], inner[k0]),
            _ => None,
        }
    };
    // Windows: the inner points within two sides of each front corner, found around the
    // corner's foot, kept in order along the chain.
    let mut index_of_point: FxHashMap<(usize, u64), usize> =
        FxHashMap::with_capacity_and_hasher(n, Default::default());
    for (k, p) in place.iter().enumerate() {
        if let Place::Side(s, t) = *p {
            index_of_point.entry((s, t.to_bits())).or_insert(k);
        }
    }
    let blocks = Blocks::new(&inner);
    let mut window: Vec<(usize, usize)> = Vec::with_capacity(m);
    let mut anchor = 0usize;
    for i in 0..m {
        // The last front corner is the first again: its foot ends the chain.
        if i + 1 == m {
            anchor = n - 1;
        } else if let Some(a) =
            feet[order[i]].and_then(|(s, t)| index_of_point.get(&(s, t.to_bits())))
        {
            anchor = *a;
        }
        let (p, reach) = reaches[i];
        let lo_scan = anchor.saturating_sub(600);
        let hi_scan = (anchor + 600).min(n - 1);
        let near = blocks.within(&inner, p, reach, lo_scan..=hi_scan);
        window.push(near.unwrap_or((anchor, anchor)));
    }
    window[0].0 = 0;
    window[m - 1].1 = n - 1;
    for i in 1..m {
        window[i].0 = window[i].0.max(window[i - 1].0).min(window[i - 1].1);
    }
    for i in (0..m - 1).rev() {
        window[i].1 = window[i].1.min(window[i + 1].1).max(window[i + 1].0);
    }
    // Anchor rungs: a front corner with its own foot, clear of the side's corner tips, the
    // first in each stretch of PIECE of its sides along its side (so an erosion moves only
    // the anchors near it).
    let mut anchors: Vec<(usize, usize)> = vec![(0, 0)];
    let mut bucket: Option<(usize, i64)> = None;
    for (i, &f) in order.iter().enumerate().take(m - 1).skip(1) {
        let (Some((s, t)), Some(_)) = (feet[f], clearance(f)) else {
            continue;
        };
        let Some(&x) = index_of_point.get(&(s, t.to_bits())) else {
            continue;
        };
        let b = (
            s,
            (t / (PIECE * cut.side[front[f] as usize])).floor() as i64,
        );
        let last = *anchors.last().expect("the start");
        if bucket != Some(b) && x > last.1 && x < n - 1 && (window[i].0..=window[i].1).contains(&x)
        {
            anchors.push((i, x));
            bucket = Some(b);
        }
    }
    anchors.push((m - 1, n - 1));
    // What each inner point is, for the pieces' keys: a wedge's point by its place in the
    // wedge and the wedge's table by number (its links read the table).
    let slot = |x: Option<usize>| x.map_or(0, |a| a as u64 + 1);
    let tags: Vec<[u64; 4]> = (0..n)
        .map(|x| match place[x] {
            Place::Side(s, t) => {
                // A table's number only where the point is in its wedge: the link reads a
                // table only between two of its points.
                let (w, v) = (
                    w_pos[x].map_or(u64::MAX, |_| table_number[(s + 1) % nc]),
                    v_pos[x].map_or(u64::MAX, |_| table_number[s]),
                );
                [
                    slot(w_pos[x]) << 32 | slot(v_pos[x]),
                    w,
                    v,
                    (s as u64) << 32 ^ t.to_bits(),
                ]
            }
            Place::Corner(j) => [u64::MAX, 1, j as u64, 0],
            Place::Ray(j, a) => [u64::MAX, 2, j as u64, a.to_bits()],
        })
        .collect();
    let chain = Chain {
        front: &fpos,
        inner: &inner,
        window: &window,
        back: &back,
        tags: &tags,
        salt: k as u64,
    };
    let result = solve(&chain, &anchors, &link, &mut memo.pieces);
    // Debugging aids of the tests' survey (`attempt_survey`), never read by a build for use.
    if cfg!(test) && (std::env::var("RHOMB_DEBUG").is_ok() || std::env::var("RHOMB_DUMP").is_ok()) {
        if let Err(f) = &result {
            let i = f.at().min(m - 1);
            if std::env::var("RHOMB_DEBUG").is_ok() {
                eprintln!("polygon {k} front {m} inner {n} start foot side {s0} t {t0}: {f:?}");
            }
            // The failure RHOMB_DUMP_NTH (counted from 1), or else each overwrites the last.
            static FAILURES: std::sync::atomic::AtomicUsize =
                std::sync::atomic::AtomicUsize::new(0);
            let nth = 1 + FAILURES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let wanted = std::env::var("RHOMB_DUMP_NTH")
                .ok()
                .and_then(|x| x.parse::<usize>().ok())
                .is_none_or(|x| x == nth);
            if let Some(path) = std::env::var("RHOMB_DUMP").ok().filter(|_| wanted) {
                // The kept triangles, the segments and the front near the failure, as JSON.
                let c = fpos[i];
                let sides: f64 = std::env::var("RHOMB_DUMP_SIDES")
                    .ok()
                    .and_then(|x| x.parse().ok())
                    .unwrap_or(12.0);
                let r = sides * cut.side[front[order[i]] as usize];
                let near = |p: Point| (p[0] - c[0]).abs() < r && (p[1] - c[1]).abs() < r;
                let tris: Vec<[Point; 3]> = cut
                    .kept
                    .iter()
                    .map(|t| t.map(|v| cut.position[v as usize]))
                    .filter(|q| q.iter().any(|&p| near(p)))
                    .collect();
                let fr: Vec<(usize, Point)> = (0..m)
                    .filter(|&d| near(fpos[d]))
                    .map(|d| (d, fpos[d]))
                    .collect();
                let chain: Vec<Point> = inner.iter().copied().filter(|&p| near(p)).collect();
                let json = format!(
                    "{{\"centre\": {c:?}, \"r\": {r}, \"at\": {i}, \"tris\": {tris:?}, \"segs\": {:?}, \"front\": {fr:?}, \"inner\": {chain:?}}}",
                    segments.ends
                );
                let _ = std::fs::write(&path, json.replace('(', "[").replace(')', "]"));
            }
            for d in (i.saturating_sub(3)..(i + 4).min(m))
                .filter(|_| std::env::var("RHOMB_DEBUG").is_ok())
            {
                let (lo, hi) = window[d];
                eprintln!(
                    "  front {d} {:?} side {} window {lo}..{hi} {:?} .. {:?}",
                    fpos[d], cut.side[front[order[d]] as usize], place[lo], place[hi]
                );
            }
        }
    }
    let (_, triangles) =
        result.map_err(|f| Stuck::At(front[order[f.at().min(m - 1)]], f.margin()))?;
    // Output ids: lattice corners, input corners, and new points (the start foot once).
    let mut ids: Vec<Option<Id>> = vec![None; n];
    let mut id_of = |x: usize, out: &mut Fill| -> Id {
        let x = if x == n - 1 { 0 } else { x };
        if let Some(id) = ids[x] {
            return id;
        }
        let id = match place[x] {
            Place::Corner(j) => Id::Point(poly.corners[j]),
            _ => {
                out.steiner.push(inner[x]);
                Id::Steiner(out.steiner.len() as u32 - 1)
            }
        };
        ids[x] = Some(id);
        id
    };
    for t in &triangles {
        let tri = t.map(|v| match v {
            Vertex::Front(i) => Id::Lattice(front[order[i]]),
            Vertex::Segment(x) => id_of(x, out),
        });
        out.triangles.push(tri);
        let [Vertex::Segment(k0), Vertex::Segment(k1), _] = *t else {
            continue;
        };
        match (place[k0], place[k1]) {
            (Place::Side(s, _), Place::Side(s1, _)) if s == s1 => {}
            (Place::Side(_, _), Place::Corner(_)) | (Place::Corner(_), Place::Side(_, _)) => {}
            (Place::Side(_, _), Place::Side(s1, _)) if wedge_value(s1, k0, k1).is_some() => {
                let (a, b, _) = wedge_value(s1, k0, k1).expect("checked");
                let (ws, vs, table) = wedges[s1].as_ref().expect("a wedge");
                for w in wedge_triangles(table, (a, b)) {
                    let tri = w.map(|x| match x {
                        WedgeVertex::C => Id::Point(poly.corners[s1]),
                        WedgeVertex::W(a) => id_of(ws[a], out),
                        WedgeVertex::V(b) => id_of(vs[b], out),
                    });
                    if w[0] == WedgeVertex::C && alpha[s1] < 30.0 {
                        out.whole.push(out.triangles.len());
                    }
                    out.triangles.push(tri);
                }
            }
            // A fan triangle at corner j: of the rays' corner, or of the side the chain
            // passes on to.
            (Place::Ray(j, _), _) | (_, Place::Ray(j, _)) | (_, Place::Side(j, _)) => {
                let c = Id::Point(poly.corners[j]);
                let (a, b) = (id_of(k1, out), id_of(k0, out));
                let whole = alpha[j] < 30.0
                    && matches!((place[k0], place[k1]), (Place::Side(..), Place::Side(..)));
                if whole {
                    out.whole.push(out.triangles.len());
                }
                out.triangles.push([c, a, b]);
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A corner of 10° at the origin: V along +x, W arriving along the ray at 10°.
    fn corner() -> (Point, Point, Point) {
        let t = 10f64.to_radians();
        ([100.0 * t.cos(), 100.0 * t.sin()], [0.0, 0.0], [100.0, 0.0])
    }

    #[test]
    fn a_rung_lies_no_farther_than_the_farthest_front_corner_that_reaches_both_sides() {
        let (w, c, v) = corner();
        let width_at = |x: f64| x * 10f64.to_radians().tan();
        // On the bisector at 10 and 20 from c, each reaching just over the wedge's half
        // width there: both meet both sides; the farther one decides.
        let bisector = |x: f64| [x * 5f64.to_radians().cos(), x * 5f64.to_radians().sin()];
        let near = (bisector(10.0), 0.6 * width_at(10.0));
        let far = (bisector(20.0), 0.6 * width_at(20.0));
        // Beside V at 60, reaching well short of W: it meets one side only.
        let one_side = ([60.0, 0.5], 2.0);
        let reach = rung_reach((w, c, v), &[near, one_side, far]).expect("two meet both");
        assert!((reach - (20.0 + far.1)).abs() < 1e-12, "{reach}");
        assert_eq!(rung_reach((w, c, v), &[one_side]), None);
        // At 20 from c, reaching less than its distance to the sides: it meets neither.
        let short = (bisector(20.0), 0.4 * width_at(20.0));
        assert_eq!(rung_reach((w, c, v), &[short]), None);
    }

    /// `n` points along the ray from the origin at angle `turn` (radians), at uneven
    /// distances (growing, with a jitter that `j` varies): one side of a wedge.
    fn side(n: usize, j: usize, turn: f64) -> Vec<Point> {
        (0..n)
            .map(|k| 0.3 * 1.04f64.powi(k as i32) + 0.01 * ((k * j) % 7) as f64)
            .map(|d| [d * turn.cos(), d * turn.sin()])
            .collect()
    }

    #[test]
    fn a_wedge_table_cut_to_the_rungs_read_holds_what_the_whole_table_holds_there() {
        for alpha in [12.0f64, 45.0] {
            let c = [0.0, 0.0];
            let (ws, vs) = (side(60, 5, alpha.to_radians()), side(60, 3, 0.0));
            let whole = wedge(c, alpha, &ws, &vs, &vec![vs.len(); ws.len()], None);
            // A staircase: row a keeps its first 60 − a cells, as rungs across a channel do.
            let rows: Vec<usize> = (0..ws.len()).map(|a| vs.len() - a).collect();
            let cut = wedge(c, alpha, &ws, &vs, &rows, None);
            let mut finite = 0;
            for a in 0..ws.len() {
                for b in 0..vs.len() {
                    if b < rows[a] {
                        assert_eq!(cut[a][b], whole[a][b], "{alpha} ({a}, {b})");
                        finite += usize::from(whole[a][b].0 > f64::NEG_INFINITY);
                    }
                }
                // A row holds its cells and no more (a cell past it reads as −∞).
                assert_eq!(cut[a].len(), rows[a], "{alpha} row {a}");
            }
            assert!(finite > 1000, "{alpha}: {finite}");
        }
    }

    #[test]
    fn a_wedge_table_taking_the_cells_of_one_with_the_same_first_points_is_the_table_built_whole() {
        for alpha in [12.0f64, 45.0] {
            let t = alpha.to_radians();
            let c = [0.0, 0.0];
            // The first table: 50 W points, 55 V points, a staircase of rows.
            let (ws, vs) = (side(50, 5, t), side(55, 3, 0.0));
            let rows: Vec<usize> = (0..ws.len())
                .map(|a| (vs.len() - a / 2).min(vs.len()))
                .collect();
            let old = wedge(c, alpha, &ws, &vs, &rows, None);
            // The next: W points from 30 on and V points from 40 on moved (an erosion), more
            // of them, and other rows.
            let mut ws2 = side(60, 5, t);
            let mut vs2 = side(58, 3, 0.0);
            for p in ws2.iter_mut().skip(30) {
                *p = [p[0] * 1.01, p[1] * 1.01];
            }
            for p in vs2.iter_mut().skip(40) {
                p[0] *= 1.02;
            }
            let rows2: Vec<usize> = (0..ws2.len()).map(|a| vs2.len() - a / 3).collect();
            let whole = wedge(c, alpha, &ws2, &vs2, &rows2, None);
            let taken = wedge(c, alpha, &ws2, &vs2, &rows2, Some((&old, &rows, 30, 40)));
            assert_eq!(taken, whole, "{alpha}");
            // The cells it may take are the old table's where the points are the same; had it
            // taken the old cells past them, the tables would differ.
            let wrong = wedge(c, alpha, &ws2, &vs2, &rows2, Some((&old, &rows, 50, 55)));
            assert_ne!(wrong, whole, "{alpha}");
        }
    }
}
