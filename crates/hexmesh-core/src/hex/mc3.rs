//! MOVED_CENTER_3 hexagons, their MOVED_CENTER_4 top neighbours and their dual topology,
//! paper 000 Sec. 5.2 (the rules on MOVED_CENTER_3/4) and Sec. 5.4 ("Centers of single
//! MOVED_CENTER_3-hexagons", "… consecutive …", "Centers of MOVED_CENTER_4-hexagons").
//!
//! # What the figures (missing from the text) had to supply
//!
//! A MOVED_CENTER_3 hexagon K of level k with fins in directions d, d+1, d+2 has subdivided
//! neighbours N_0, N_1, N_2 = K + e_d, e_{d+1}, e_{d+2}; its top neighbour T = K + e_{d+4}, its
//! left neighbour L = K + e_{d-1}, its right neighbour R = K + e_{d+3}. The fin f_m is the
//! half, inside N_m, of the level-(k+1) cell on the edge K|N_m. The hexagon "h_{f_m}" beyond
//! fin f_m is the central child of N_m (centre C_{N_m}); the two other full hexagons beside the
//! fins are the level-(k+1) cells between N_0, N_1 and between N_1, N_2 (M_01, M_12, the
//! "five FIXED_CENTER_x hexagons" of the text). Seen from T the MOVED_CENTER_3 hexagons that
//! have T as top neighbour are T + e_j with fins at j-1, j, j+1; consecutive ones are
//! consecutive directions around T, and two neighbours of a chain share the subdivided hexagon
//! N_2 = N'_0 between them.
//!
//! The standard dual has, around K, the eight triangles of its star (L, N_0, M_01, N_1, M_12,
//! N_2, R, T). For a chain of n MOVED_CENTER_3 hexagons around T the union of their stars is
//! dropped and rebuilt (vertices named as above, chain K_0 … K_{n-1} counter-clockwise around
//! T, f_{i,2} = f_{i+1,0} shared):
//!
//! - along the fins of each K_i: (N_0, M_01, f_0), (f_0, M_01, f_1), (M_01, N_1, f_1),
//!   (N_1, M_12, f_1), (f_1, M_12, f_2), (M_12, N_2, f_2); at the ends (L, N_{0,0}, f_{0,0})
//!   and (N_{n-1,2}, R, f_{n-1,2});
//! - n = 1 (K dropped): (L, f_0, T), (f_0, f_2, T), (f_0, f_1, f_2), (f_2, R, T);
//! - n ≥ 2 (centres kept): (L, f_{0,0}, K_0), (f_{i,0}, f_{i,1}, K_i), (f_{i,1}, f_{i,2}, K_i),
//!   (f_{i,2}, K_{i+1}, K_i), (K_{i+1}, T, K_i), (f_{n-1,2}, R, K_{n-1}), (R, T, K_{n-1}),
//!   (K_0, T, L); a blossom (n = 6) is the same ring closed on itself, 60 triangles.
//!
//! Positions are the paper's: single f_0 = 3/5·C + 2/5·C_{N_0}, f_1 = 2/5·C + 3/5·C_{N_1},
//! f_2 = 3/5·C + 2/5·C_{N_2}; consecutive Ĉ = 2/3·C + 1/3·C_T, end fins 25/52·Ĉ + 27/52·C_N,
//! middle fins 3/5·C + 2/5·C_{N_1}, shared fins 9/20·C_M + 11/20·C_N (C_M the mean of the two
//! relocated centres); MOVED_CENTER_4 n = 1: 3/5·C_T + 2/5·C_K, n = 2: 5/4·C_T − 1/4·C_M,
//! n = 3: 7/6·C_T − 1/6·C_{K_1}, n = 4: 4/3·C_T − 1/3·C_M, n = 6 (blossom): unmoved.
//!
//! Where the text leaves a choice open, the choice that meets [α, 90°] was taken, found by
//! computing every angle (unit tests below and tests/hex_mc3.rs):
//! - C_M of MOVED_CENTER_4 for n = 2 and 4 is the mean of the *relocated* centres (as for the
//!   shared fins); with the lattice centres the triangles below T drop to 41.6° (n = 2) and to
//!   40.9°/98.2° (n = 4). For n = 3 the formula names the lattice centre C_{K_1}, and that one
//!   is right: the relocated one gives 43.17°.
//! - The two fins at the common edge of consecutive MOVED_CENTER_3 hexagons ("the corresponding
//!   neighbors coincide") are one vertex.
//! - A single MOVED_CENTER_3 hexagon beside a MOVED_CENTER_2 one meets the bounds (min 43.9°,
//!   max 83.4°), a chain beside one does not (34.2°, 109.2°): the Fig. 6 rule is applied to
//!   chains only, on the end neighbour whose fin strip does not border the chain.
//!
//! Departures (all but the last refine more than the paper):
//! - The paper's formulas assume T is a plain hexagon (no fins, no point, in no ring, not on
//!   the boundary), its neighbours outside the chain and its ends FIXED_CENTER_x (they were
//!   fixed in the derivation; a moved one, e.g. the top of another chain next to T, spoils the
//!   triangles below T), and the end neighbours MOVED_CENTER_1 (or, for a single one, 2). When
//!   they are not, the MOVED_CENTER_3 hexagons of that top are subdivided, as all of them were
//!   before. So is a chain whose Fig. 6 neighbour lies outside the bounding hexagon.
//! - A MOVED_CENTER_4 hexagon counts as a moved centre in the rule "every full hexagon
//!   adjacent to a fin must be FIXED_CENTER_x" (it is not FIXED, though Sec. 5.1 lists it
//!   among the classes without fins).
//! - Two chains facing each other (tops two apart) share both end neighbours E and the
//!   subdivided hexagons N beside them; the end triangles (E, N, f) of both have their right
//!   angle at the fin, so the four points lie on one circle and rounding decided the exact
//!   empty-circle test (the other diagonal has a 92.2° angle). Both end fins are moved off
//!   that circle, outwards, by 2^-36·|EN|: every angle changes by less than 1e-9°.
//!
//! Blossoms are built when six MOVED_CENTER_3 hexagons surround a top; the local coarsening
//! of Sec. 5.3 that creates them from plain regions is not implemented.

use crate::geom::Point;
use crate::hex::classify::{classify, Class, Rings};
use crate::hex::lattice::{FxHashMap, FxHashSet, Key, DIRS};
use crate::hex::parallel::in_parallel_from;
use crate::hex::refine::is_fin;
use crate::hex::subdivision::Hierarchy;

/// Triangles of the dual rebuilt around MOVED_CENTER_3 hexagons (Sec. 5.4).
#[derive(Debug, Clone, Default)]
pub struct Patch {
    /// Canonical keys of the centres whose triangles (their whole star) are dropped.
    pub dropped: FxHashSet<Key>,
    /// The triangles emitted instead, counter-clockwise, by cell keys; a vertex is placed like
    /// any other (relocated position, input point, lattice centre).
    pub triangles: Vec<[Key; 3]>,
    /// The MOVED_CENTER_3 hexagon each fin vertex belongs to (the hexagon to subdivide when a
    /// triangle at the fin fails).
    pub fin_owner: FxHashMap<Key, Key>,
    /// The MOVED_CENTER_3 hexagons and tops of the chains built.
    pub chain_cells: FxHashSet<Key>,
}

impl Patch {
    /// Whether the patch changes nothing: no star dropped, no triangle added.
    pub fn is_empty(&self) -> bool {
        self.dropped.is_empty() && self.triangles.is_empty()
    }
}

/// A run of n consecutive MOVED_CENTER_3 hexagons T + e_s, …, T + e_{s+n-1} around their
/// common top neighbour T (n = 6: a blossom).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Chain {
    /// The common top neighbour T.
    pub top: Key,
    /// The direction s of the first hexagon from T, an index into `DIRS` (0..6).
    pub start: usize,
    /// How many hexagons, n: 1 to 4, or 6 for a blossom (a run of 5 is subdivided).
    pub len: usize,
}

/// What the rules of Sec. 5.2 make of the MOVED_CENTER_3 hexagons around a top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    /// Not the top of any MOVED_CENTER_3 hexagon.
    None,
    /// A chain the dual can be built for.
    Chain(Chain),
    /// Hexagons to subdivide first.
    Subdivide(Vec<Key>),
}

/// True when the full leaf `key` is MOVED_CENTER_3 with top neighbour `top`.
fn is_mc3_below(h: &Hierarchy, r: &Rings, key: Key, top: Key) -> bool {
    if !h.is_full_leaf(key) {
        return false;
    }
    let (class, strip) = classify(h, r, key);
    class == Class::MovedCenter3 && strip.is_some_and(|s| key.neighbor(s.top()) == top)
}

/// The directions j around `top` in which `top + e_j` is a MOVED_CENTER_3 hexagon whose top
/// neighbour is `top`, as a bit mask.
pub fn mc3_below(h: &Hierarchy, r: &Rings, top: Key) -> u8 {
    // The middle fin of a MOVED_CENTER_3 hexagon below `top` points away from it, which
    // rules out most neighbours before they are classified. The edge child between n = top +
    // e_j and n + e_j is a fin of n (`refine::is_fin`) exactly when both lie inside the
    // bounding hexagon and one of them is subdivided: the twelve cells come from the few
    // blocks around `top` instead of a parent lookup per cell.
    const NEAR_AND_FAR: [(i64, i64); 12] = {
        let mut out = [(0, 0); 12];
        let mut d = 0;
        while d < 6 {
            out[d] = DIRS[d];
            out[d + 6] = (2 * DIRS[d].0, 2 * DIRS[d].1);
            d += 1;
        }
        out
    };
    let s = h.subdivided_at(top, &NEAR_AND_FAR);
    let one_subdivided = (s ^ (s >> 6)) & 0x3f;
    let fin = |j: usize| {
        let n = top.neighbor(j);
        one_subdivided & (1 << j) != 0 && n.inside() && n.neighbor(j).inside()
    };
    debug_assert!((0..6).all(|j| fin(j) == is_fin(h, top.neighbor(j).edge_child(j))));
    if one_subdivided == 0 {
        return 0;
    }
    (0..6)
        .filter(|&j| fin(j))
        .filter(|&j| is_mc3_below(h, r, top.neighbor(j), top))
        .fold(0u8, |m, j| m | (1 << j))
}

/// True when `key` is MOVED_CENTER_4 (Sec. 5.1): a full leaf without fins, point or ring role
/// that is the top neighbour of a MOVED_CENTER_3 hexagon.
pub fn is_mc4(h: &Hierarchy, r: &Rings, key: Key) -> bool {
    h.is_full_leaf(key)
        && mc3_below(h, r, key) != 0
        && classify(h, r, key).0 == Class::FixedCenterRegular
}

/// The cyclic runs of set bits of a 6-bit mask as (start, length); all six as (0, 6).
fn runs(mask: u8) -> Vec<(usize, usize)> {
    if mask == 0b11_1111 {
        return vec![(0, 6)];
    }
    (0..6)
        .filter(|&j| mask & (1 << j) != 0 && mask & (1 << ((j + 5) % 6)) == 0)
        .map(|j| {
            let len = (0..6)
                .take_while(|&t| mask & (1 << ((j + t) % 6)) != 0)
                .count();
            (j, len)
        })
        .collect()
}

/// The rules of Sec. 5.2 on the MOVED_CENTER_3 hexagons whose top neighbour is `top`, with
/// the departures of the module docs.
pub fn verdict(h: &Hierarchy, r: &Rings, top: Key) -> Verdict {
    let mask = mc3_below(h, r, top);
    if mask == 0 {
        return Verdict::None;
    }
    let below: Vec<Key> = (0..6)
        .filter(|&j| mask & (1 << j) != 0)
        .map(|j| top.neighbor(j))
        .collect();
    let free = h.is_full_leaf(top)
        && !top.on_boundary()
        && classify(h, r, top).0 == Class::FixedCenterRegular;
    if !free {
        return Verdict::Subdivide(below);
    }
    let rs = runs(mask);
    // "Subdivide a hexagon of type MOVED_CENTER_4 if it is the top neighbor of more than one
    // non-consecutive hexagons of type MOVED_CENTER_3."
    if rs.len() > 1 {
        return Verdict::Subdivide(vec![top]);
    }
    let (start, len) = rs[0];
    if len == 5 {
        return Verdict::Subdivide(below);
    }
    let chain = Chain { top, start, len };
    if len == 6 {
        return Verdict::Chain(chain);
    }
    // The neighbours of T outside the chain and its two ends stay where they are in the
    // derivation; a moved one (a hexagon with fins, another top, a moved ring cell) spoils the
    // triangles below T.
    for t in len + 1..5 {
        let y = top.neighbor((start + t) % 6);
        let fixed = h.is_full_leaf(y) && classify(h, r, y).0.is_fixed() && mc3_below(h, r, y) == 0;
        if !fixed {
            return Verdict::Subdivide(below);
        }
    }
    let mut far = Vec::new();
    // The end neighbours: L = T + e_{s-1} with its fin towards T + e_s + e_{s-1}, R = T +
    // e_{s+n} with its fin towards T + e_{s+n-1} + e_{s+n}.
    for (end, chain_side) in [
        (top.neighbor((start + 5) % 6), (start + 1) % 6),
        (top.neighbor((start + len) % 6), (start + len + 4) % 6),
    ] {
        if !end.inside() || !h.is_full_leaf(end) || end.on_boundary() {
            return Verdict::Subdivide(below);
        }
        match classify(h, r, end) {
            (Class::MovedCenter1, _) => {}
            (Class::MovedCenter2, _) if len == 1 => {}
            // Fig. 6: a MOVED_CENTER_2 hexagon beside a chain; subdividing its neighbour
            // beyond its fins (the one away from the chain) makes it MOVED_CENTER_3 of the
            // same top.
            (Class::MovedCenter2, Some(s)) => {
                let beyond = if s.left() == chain_side {
                    s.right()
                } else {
                    s.left()
                };
                let f = end.neighbor(beyond);
                // Beyond the bounding hexagon there is nothing to subdivide.
                if !f.inside() {
                    return Verdict::Subdivide(below);
                }
                far.push(f);
            }
            _ => return Verdict::Subdivide(below),
        }
    }
    if !far.is_empty() {
        return Verdict::Subdivide(far);
    }
    Verdict::Chain(chain)
}

/// Lists of at least this many hexagons or tops are shared over the threads (`chains`): a
/// hexagon's class or a top's verdict takes microseconds, and plane-10k's lists are split
/// too (`tests/hex_threads.rs`).
const PARALLEL_MIN: usize = 512;

/// The valid chains of the current subdivision, sorted by top. The hexagons' classes and the
/// tops' verdicts only read the hierarchy and the rings: both are found over the hierarchy's
/// threads, in runs kept in order.
pub fn chains(h: &Hierarchy, r: &Rings, mc3: &[Key]) -> Vec<Chain> {
    let mut tops: Vec<Key> = in_parallel_from(h.threads(), mc3, PARALLEL_MIN, |run| {
        run.iter()
            .filter_map(|&k| {
                let (class, strip) = classify(h, r, k);
                (class == Class::MovedCenter3).then_some(k.neighbor(strip?.top()))
            })
            .collect::<Vec<Key>>()
    })
    .concat();
    tops.sort_unstable();
    tops.dedup();
    in_parallel_from(h.threads(), &tops, PARALLEL_MIN, |run| {
        run.iter()
            .filter_map(|&t| match verdict(h, r, t) {
                Verdict::Chain(c) => Some(c),
                _ => None,
            })
            .collect::<Vec<Chain>>()
    })
    .concat()
}

fn lerp(a: Point, b: Point, t: f64) -> Point {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
}

fn mid(a: Point, b: Point) -> Point {
    lerp(a, b, 0.5)
}

/// The level-(k+1) cell between two adjacent cells of level k.
fn between(a: Key, b: Key) -> Key {
    Key::new(a.k + 1, a.i + b.i, a.j + b.j)
}

/// Adds the relocated centres (into `moved`, keyed canonically) and the rebuilt triangles of
/// a chain (into `patch`), as the module docs derive them.
pub fn build(
    h: &Hierarchy,
    r: &Rings,
    c: Chain,
    moved: &mut FxHashMap<Key, Point>,
    patch: &mut Patch,
) {
    let n = c.len;
    let cyclic = n == 6;
    let t = c.top;
    let ct = h.lattice.center(t);
    let ks: Vec<Key> = (0..n).map(|i| t.neighbor((c.start + i) % 6)).collect();
    let cs: Vec<Point> = ks.iter().map(|&k| h.lattice.center(k)).collect();
    // n[i][m]: the subdivided neighbour beyond fin m of K_i; fins[i][m] its fin cell.
    let dir = |i: usize, m: usize| (c.start + i + 5 + m) % 6;
    let nb: Vec<[Key; 3]> = (0..n)
        .map(|i| [0, 1, 2].map(|m| ks[i].neighbor(dir(i, m))))
        .collect();
    let cn = |i: usize, m: usize| h.lattice.center(nb[i][m]);
    // The shared fin of K_i and K_{i+1} is K_i's fin 2.
    let fin = |i: usize, m: usize| -> Key {
        if m == 0 && (cyclic || i > 0) {
            let p = (i + n - 1) % n;
            ks[p].edge_child(dir(p, 2))
        } else {
            ks[i].edge_child(dir(i, m))
        }
    };
    patch.chain_cells.insert(t);
    for (i, &k) in ks.iter().enumerate() {
        patch.chain_cells.insert(k);
        patch.dropped.insert(k.canonical());
        for m in 0..3 {
            patch.fin_owner.insert(fin(i, m), k);
        }
    }
    let hat: Vec<Point> = if n == 1 {
        cs.clone()
    } else {
        cs.iter().map(|&ck| lerp(ck, ct, 1.0 / 3.0)).collect()
    };
    let mut put = |key: Key, p: Point| {
        moved.insert(key.canonical(), p);
    };
    if n == 1 {
        put(fin(0, 0), lerp(cs[0], cn(0, 0), 2.0 / 5.0));
        put(fin(0, 1), lerp(cs[0], cn(0, 1), 3.0 / 5.0));
        put(fin(0, 2), lerp(cs[0], cn(0, 2), 2.0 / 5.0));
        put(t, lerp(ct, cs[0], 2.0 / 5.0));
    } else {
        for i in 0..n {
            put(ks[i], hat[i]);
            put(fin(i, 1), lerp(cs[i], cn(i, 1), 2.0 / 5.0));
            if cyclic || i + 1 < n {
                let j = (i + 1) % n;
                put(fin(i, 2), lerp(mid(hat[i], hat[j]), cn(i, 2), 11.0 / 20.0));
            }
        }
        if !cyclic {
            let ends = [(0, 0, (c.start + 5) % 6), (n - 1, 2, (c.start + n) % 6)];
            for (i, m, d) in ends {
                let mut f = lerp(hat[i], cn(i, m), 27.0 / 52.0);
                // The end triangle (E, N, f) has its right angle at f. When another chain
                // ends at the same E and N (chains facing each other), its end fin lies on the
                // same circle over E–N, and rounding decides the exact empty-circle test.
                // Moving both fins off that circle by 2^-36·|EN| (an angle change below
                // 1e-9°) makes both triangles Delaunay for the exact test.
                let e = t.neighbor(d);
                let z = e.neighbor(d);
                if h.is_full_leaf(z) && classify(h, r, z).0 == Class::MovedCenter3 {
                    let pe = lerp(h.lattice.center(e), cn(i, m), 1.0 / 6.0);
                    let centre = mid(pe, cn(i, m));
                    let (dx, dy) = (f[0] - centre[0], f[1] - centre[1]);
                    let len = dx.hypot(dy);
                    let scale = (pe[0] - cn(i, m)[0]).hypot(pe[1] - cn(i, m)[1]) * 2f64.powi(-36);
                    if len > 0.0 {
                        f = [f[0] + dx / len * scale, f[1] + dy / len * scale];
                    }
                }
                put(fin(i, m), f);
            }
        }
        let away =
            |w: f64, from: Point| [ct[0] + w * (ct[0] - from[0]), ct[1] + w * (ct[1] - from[1])];
        match n {
            2 => put(t, away(0.25, mid(hat[0], hat[1]))),
            3 => put(t, away(1.0 / 6.0, cs[1])),
            4 => put(t, away(1.0 / 3.0, mid(hat[1], hat[2]))),
            _ => {}
        }
    }
    let tris = &mut patch.triangles;
    for (i, &[a, b, cc]) in nb.iter().enumerate() {
        let (m01, m12) = (between(a, b), between(b, cc));
        let (f0, f1, f2) = (fin(i, 0), fin(i, 1), fin(i, 2));
        tris.extend([
            [a, m01, f0],
            [f0, m01, f1],
            [m01, b, f1],
            [b, m12, f1],
            [f1, m12, f2],
            [m12, cc, f2],
        ]);
    }
    if !cyclic {
        let l = t.neighbor((c.start + 5) % 6);
        let r = t.neighbor((c.start + n) % 6);
        tris.push([l, nb[0][0], fin(0, 0)]);
        tris.push([nb[n - 1][2], r, fin(n - 1, 2)]);
        if n == 1 {
            let (f0, f1, f2) = (fin(0, 0), fin(0, 1), fin(0, 2));
            tris.extend([[l, f0, t], [f0, f2, t], [f0, f1, f2], [f2, r, t]]);
            return;
        }
        tris.push([l, fin(0, 0), ks[0]]);
        tris.push([fin(n - 1, 2), r, ks[n - 1]]);
        tris.push([r, t, ks[n - 1]]);
        tris.push([ks[0], t, l]);
    }
    for i in 0..n {
        tris.push([fin(i, 0), fin(i, 1), ks[i]]);
        tris.push([fin(i, 1), fin(i, 2), ks[i]]);
        if cyclic || i + 1 < n {
            let j = (i + 1) % n;
            tris.push([fin(i, 2), ks[j], ks[i]]);
            tris.push([ks[j], t, ks[i]]);
        }
    }
}

/// Every hexagon whose subdivision the MOVED_CENTER_3 rules ask for, around the MOVED_CENTER_3
/// hexagon `key` (its top's verdict).
pub fn actions_for(h: &Hierarchy, r: &Rings, key: Key) -> Vec<Key> {
    let (class, strip) = classify(h, r, key);
    let Some(s) = strip.filter(|_| class == Class::MovedCenter3) else {
        return Vec::new();
    };
    match verdict(h, r, key.neighbor(s.top())) {
        Verdict::Subdivide(v) => v,
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_cyclic_and_six_is_one_blossom() {
        assert_eq!(runs(0b00_0110), vec![(1, 2)]);
        assert_eq!(runs(0b10_0001), vec![(5, 2)]);
        assert_eq!(runs(0b00_0101), vec![(0, 1), (2, 1)]);
        assert_eq!(runs(0b11_1111), vec![(0, 6)]);
    }
}
