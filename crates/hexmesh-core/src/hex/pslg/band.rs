//! Quality along the segments (ours; paper 000 Sec. 7 promises nothing there): the mesh after
//! `cavity` is made a constrained Delaunay triangulation by Lawson flips, then improved by
//! inserting points on the segments only, each chosen among a few candidates for the one that
//! lowers the measure (bad triangles, then their summed excess) the most.
//!
//! Why points on the segments only: a point inserted on a segment joins every triangle it
//! creates, so each new triangle touches a segment and needs only the near-segment bounds
//! (every angle in [30°, 120°], an input corner sharper than 30° taken whole); the interior
//! triangles that remain are triangles of the hexagon dual, whose bounds (43.9°–90°, radius
//! ratio, Delaunay) the insertion never touches. A free Steiner point (Ruppert's circumcentre)
//! would make triangles without a segment corner that have to meet the interior bounds.
//!
//! Insertion is Bowyer–Watson in the constrained Delaunay triangulation (the triangles whose
//! circumcircle holds the new point, reached without crossing a segment piece), so the mesh
//! stays constrained Delaunay: every empty-circle violation lies on a segment.
//!
//! Termination: an insertion is made only when it lowers the measure (the number of bad
//! triangles, then the sum of their excess over the bounds, lexicographically), and the
//! number of insertions is capped by a budget; triangles no candidate repairs are returned to
//! the driver, which subdivides the hexagons there and meshes again (`drive`).

use crate::geom::{angle_deg, circumcenter, dist, incircle, orient2d, Point};
use crate::hex::extended::check::breaks_bounds;
use crate::quality::bounds::HEX;
use crate::quality::rounding;

/// The smallest angle of a triangle touching a segment (Triangle's `-q30`), but at an input
/// corner sharper than it taken whole.
pub const NEAR_MIN_ANGLE: f64 = 30.0;

/// The largest angle of a triangle touching a segment (180° − 2·30°).
pub const NEAR_MAX_ANGLE: f64 = 120.0;

const NONE: u32 = u32::MAX;

/// What a triangle contributes to the measure.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Cost {
    /// Triangles that break their bounds.
    bad: i64,
    /// Their summed excess over the bounds, in degrees.
    excess: f64,
    /// Near-segment angles above 90° (the non-obtuse aim; a tie-breaker only).
    obtuse: i64,
}

impl Cost {
    fn add(&mut self, o: Cost) {
        self.bad += o.bad;
        self.excess += o.excess;
        self.obtuse += o.obtuse;
    }
    fn sub(&mut self, o: Cost) {
        self.bad -= o.bad;
        self.excess -= o.excess;
        self.obtuse -= o.obtuse;
    }
    /// True when this change of the measure is a strict improvement.
    fn improves(&self) -> bool {
        self.bad < 0 || (self.bad == 0 && self.excess < -1e-9)
    }
    /// Orders changes: fewer bad triangles, then less excess, then fewer obtuse angles.
    fn better_than(&self, o: &Cost) -> bool {
        if self.bad != o.bad {
            return self.bad < o.bad;
        }
        if (self.excess - o.excess).abs() > 1e-9 {
            return self.excess < o.excess;
        }
        self.obtuse < o.obtuse
    }
}

/// An edit of the band.
#[derive(Debug, Clone, Copy)]
enum Op {
    /// A point at parameter q of segment s, between its vertices u and v.
    Insert { u: u32, v: u32, s: u32, q: f64 },
    /// The point w on a segment removed.
    Delete { w: u32 },
    /// The point w on a segment moved to parameter q, between its neighbours u and v; or a
    /// vertex w off the segments moved onto the piece uv of segment s (snapped).
    Move {
        w: u32,
        u: u32,
        v: u32,
        s: u32,
        q: f64,
    },
}

/// What an edit changed, to undo it.
#[derive(Default)]
struct Log {
    tris_len: usize,
    verts_len: usize,
    killed: Vec<u32>,
    nbr: Vec<(u32, usize, u32)>,
    vtri: Vec<(u32, u32)>,
}

/// A triangulation with neighbours, the segments each vertex lies on, and undoable edits.
pub(super) struct Band<'a> {
    segments: &'a [[Point; 2]],
    /// Vertex positions.
    pub verts: Vec<Point>,
    /// The input segments each vertex lies on.
    pub segs: Vec<Vec<u32>>,
    /// For a vertex the band inserted, the vertex of the piece it split (its hexagon's owner).
    pub origin: Vec<u32>,
    /// Triangles, counter-clockwise.
    pub tris: Vec<[u32; 3]>,
    /// For each triangle, the neighbour across the edge opposite each corner.
    nbr: Vec<[u32; 3]>,
    /// False for triangles an edit removed.
    pub alive: Vec<bool>,
    /// One live triangle at each vertex.
    vtri: Vec<u32>,
    log: Option<Log>,
    /// Vertices below this index are input points: they never move.
    n_fixed: usize,
    /// Triangles below this index are the ones the band was given.
    n_given: usize,
    /// The shortest edge an interior triangle may have (Sec. 6.3: √7/(12√3)·d_min).
    min_edge: f64,
    /// Points inserted.
    pub inserted: u64,
    /// Points removed from the segments.
    pub deleted: u64,
    /// Points moved along the segments.
    pub moved: u64,
    /// Edges flipped to make the triangulation constrained Delaunay.
    pub flips: u64,
}

impl<'a> Band<'a> {
    /// The triangulation of `tris` on `verts`, vertex v lying on the segments `segs[v]`.
    pub fn new(
        segments: &'a [[Point; 2]],
        verts: Vec<Point>,
        segs: Vec<Vec<u32>>,
        tris: Vec<[u32; 3]>,
        n_fixed: usize,
    ) -> Band<'a> {
        let mut by_edge: crate::hex::lattice::FxHashMap<(u32, u32), (u32, usize)> =
            Default::default();
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                by_edge.insert((tri[(i + 1) % 3], tri[(i + 2) % 3]), (t as u32, i));
            }
        }
        let mut nbr = vec![[NONE; 3]; tris.len()];
        let mut vtri = vec![NONE; verts.len()];
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if let Some(&(o, _)) = by_edge.get(&(y, x)) {
                    nbr[t][i] = o;
                }
                vtri[tri[i] as usize] = t as u32;
            }
        }
        let n = verts.len();
        let n_tris = tris.len();
        Band {
            segments,
            verts,
            segs,
            origin: (0..n as u32).collect(),
            alive: vec![true; tris.len()],
            tris,
            nbr,
            vtri,
            log: None,
            n_fixed,
            n_given: n_tris,
            min_edge: 0.0,
            inserted: 0,
            deleted: 0,
            moved: 0,
            flips: 0,
        }
    }

    /// This band with interior triangles held to a shortest edge of `min_edge`.
    pub fn with_min_edge(mut self, min_edge: f64) -> Band<'a> {
        self.min_edge = min_edge;
        self
    }

    fn on_segment(&self, v: u32) -> bool {
        !self.segs[v as usize].is_empty()
    }

    /// The segment the edge uv runs along, if any: both ends on it.
    fn piece(&self, u: u32, v: u32) -> Option<u32> {
        let su = &self.segs[u as usize];
        self.segs[v as usize]
            .iter()
            .copied()
            .find(|s| su.contains(s))
    }

    fn corners(&self, t: u32) -> [Point; 3] {
        self.tris[t as usize].map(|v| self.verts[v as usize])
    }

    /// What triangle `t` adds to the measure (module docs).
    fn cost(&self, t: u32) -> Cost {
        let tri = self.tris[t as usize];
        let c = self.corners(t);
        if !tri.iter().any(|&v| self.on_segment(v)) {
            // The shortest edge is held against the triangles the band makes; the dual's own
            // are the self-check's (`drive`).
            let short = t as usize >= self.n_given
                && (0..3).any(|m| dist(c[m], c[(m + 1) % 3]) < self.min_edge);
            if breaks_bounds(&c) || short {
                let excess: f64 = (0..3)
                    .map(|m| {
                        let a = angle_deg(c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
                        rounding::beyond(a, HEX.min_angle, HEX.max_angle)
                    })
                    .sum();
                return Cost {
                    bad: 1,
                    excess: excess.max(1e-6),
                    obtuse: 0,
                };
            }
            return Cost::default();
        }
        let mut cost = Cost::default();
        let mut bad = false;
        for m in 0..3 {
            let (a, b, d) = (c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
            let angle = angle_deg(a, b, d);
            let whole = self.piece(tri[m], tri[(m + 1) % 3]).is_some()
                && self.piece(tri[m], tri[(m + 2) % 3]).is_some();
            let lo = if whole { 0.0 } else { NEAR_MIN_ANGLE };
            let beyond = rounding::beyond(angle, lo, NEAR_MAX_ANGLE);
            if beyond > HEX.self_check_slack + rounding::placement_allowance(a, b, d) {
                bad = true;
                cost.excess += beyond;
            }
            if angle > 90.0 + 1e-9 {
                cost.obtuse += 1;
            }
        }
        if bad {
            cost.bad = 1;
            cost.excess = cost.excess.max(1e-6);
        }
        cost
    }

    fn set_nbr(&mut self, t: u32, i: usize, n: u32) {
        if let Some(log) = &mut self.log {
            log.nbr.push((t, i, self.nbr[t as usize][i]));
        }
        self.nbr[t as usize][i] = n;
    }

    fn set_vtri(&mut self, v: u32, t: u32) {
        if let Some(log) = &mut self.log {
            log.vtri.push((v, self.vtri[v as usize]));
        }
        self.vtri[v as usize] = t;
    }

    fn begin(&mut self) {
        self.log = Some(Log {
            tris_len: self.tris.len(),
            verts_len: self.verts.len(),
            ..Log::default()
        });
    }

    fn rollback(&mut self) {
        let Some(log) = self.log.take() else { return };
        for &(t, i, old) in log.nbr.iter().rev() {
            self.nbr[t as usize][i] = old;
        }
        for &(v, old) in log.vtri.iter().rev() {
            self.vtri[v as usize] = old;
        }
        for &t in &log.killed {
            self.alive[t as usize] = true;
        }
        self.tris.truncate(log.tris_len);
        self.nbr.truncate(log.tris_len);
        self.alive.truncate(log.tris_len);
        self.verts.truncate(log.verts_len);
        self.segs.truncate(log.verts_len);
        self.origin.truncate(log.verts_len);
        self.vtri.truncate(log.verts_len);
    }

    /// The change of the measure the open edit made.
    fn edit_cost(&self) -> Cost {
        let Some(log) = &self.log else {
            return Cost::default();
        };
        let mut c = Cost::default();
        for t in log.tris_len..self.tris.len() {
            c.add(self.cost(t as u32));
        }
        for &t in &log.killed {
            c.sub(self.cost(t));
        }
        c
    }

    /// The slot of `t`'s edge from x to y, counter-clockwise.
    fn slot(&self, t: u32, x: u32, y: u32) -> Option<usize> {
        let tri = self.tris[t as usize];
        (0..3).find(|&i| tri[(i + 1) % 3] == x && tri[(i + 2) % 3] == y)
    }

    /// Lawson flips of every edge that is not a segment piece and fails the exact
    /// empty-circle test, until none does: the constrained Delaunay triangulation.
    pub fn make_delaunay(&mut self) {
        let mut stack: Vec<u32> = (0..self.tris.len() as u32).rev().collect();
        // Each flip strictly raises the triangulation in the lifting map: finite.
        while let Some(t) = stack.pop() {
            if !self.alive[t as usize] {
                continue;
            }
            for i in 0..3 {
                let o = self.nbr[t as usize][i];
                if o == NONE {
                    continue;
                }
                let tri = self.tris[t as usize];
                let (x, y, w) = (tri[(i + 1) % 3], tri[(i + 2) % 3], tri[i]);
                if self.piece(x, y).is_some() {
                    continue;
                }
                let Some(j) = self.slot(o, y, x) else {
                    continue;
                };
                let d = self.tris[o as usize][j];
                let p = |v: u32| self.verts[v as usize];
                if incircle(p(w), p(x), p(y), p(d)) <= 0.0 {
                    continue;
                }
                // The quadrilateral w x d y is convex when the circle test fails.
                if orient2d(p(w), p(x), p(d)) <= 0.0 || orient2d(p(w), p(d), p(y)) <= 0.0 {
                    continue;
                }
                self.flip(t, i, o, j);
                self.flips += 1;
                stack.push(t);
                stack.push(o);
                break;
            }
        }
    }

    /// Flips the edge between `t` (opposite its corner i) and `o` (opposite its corner j).
    fn flip(&mut self, t: u32, i: usize, o: u32, j: usize) {
        let tri = self.tris[t as usize];
        let (w, x, y) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
        let d = self.tris[o as usize][j];
        // Outer neighbours: across x-d (of o), d-y (of o), y-w (of t), w-x (of t).
        let n_yw = self.nbr[t as usize][(i + 1) % 3];
        let n_wx = self.nbr[t as usize][(i + 2) % 3];
        let ot = self.tris[o as usize];
        let n_xd = self.nbr[o as usize][(0..3).find(|&k| ot[k] == y).unwrap_or(0)];
        let n_dy = self.nbr[o as usize][(0..3).find(|&k| ot[k] == x).unwrap_or(0)];
        // t = (w, x, d), o = (w, d, y).
        self.tris[t as usize] = [w, x, d];
        self.tris[o as usize] = [w, d, y];
        self.nbr[t as usize] = [n_xd, o, n_wx];
        self.nbr[o as usize] = [n_dy, n_yw, t];
        for (n, a, b, new) in [(n_xd, d, x, t), (n_yw, w, y, o)] {
            if n != NONE {
                if let Some(s) = self.slot(n, a, b) {
                    self.nbr[n as usize][s] = new;
                }
            }
        }
        for v in [w, x, d] {
            self.vtri[v as usize] = t;
        }
        self.vtri[y as usize] = o;
    }

    /// The parameter of `p` along segment `s` (0 at its first end, 1 at its second).
    fn param(&self, s: u32, p: Point) -> f64 {
        let [a, b] = self.segments[s as usize];
        if p == a {
            return 0.0;
        }
        if p == b {
            return 1.0;
        }
        let d = [b[0] - a[0], b[1] - a[1]];
        ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])
    }

    fn at(&self, s: u32, t: f64) -> Point {
        let [a, b] = self.segments[s as usize];
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }

    /// Replaces the live triangles `killed` by `made` (which must tile the same region),
    /// inside an open edit: neighbours across the region's boundary are kept.
    fn replace(&mut self, killed: &[u32], made: &[[u32; 3]]) {
        let mut outer: crate::hex::lattice::FxHashMap<(u32, u32), u32> = Default::default();
        for &t in killed {
            let tri = self.tris[t as usize];
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                if n != NONE && killed.contains(&n) {
                    continue;
                }
                outer.insert((tri[(i + 1) % 3], tri[(i + 2) % 3]), n);
            }
        }
        for &t in killed {
            self.alive[t as usize] = false;
            if let Some(log) = &mut self.log {
                log.killed.push(t);
            }
        }
        let first = self.tris.len() as u32;
        let mut inner: crate::hex::lattice::FxHashMap<(u32, u32), u32> = Default::default();
        for (k, &tri) in made.iter().enumerate() {
            self.tris.push(tri);
            self.nbr.push([NONE; 3]);
            self.alive.push(true);
            for i in 0..3 {
                inner.insert((tri[(i + 1) % 3], tri[(i + 2) % 3]), first + k as u32);
            }
        }
        for (k, &tri) in made.iter().enumerate() {
            let t = first + k as u32;
            for i in 0..3 {
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if let Some(&o) = inner.get(&(y, x)) {
                    self.nbr[t as usize][i] = o;
                } else if let Some(&n) = outer.get(&(x, y)) {
                    self.nbr[t as usize][i] = n;
                    if n != NONE {
                        if let Some(sl) = self.slot(n, y, x) {
                            self.set_nbr(n, sl, t);
                        }
                    }
                }
            }
            for &v in &tri {
                self.set_vtri(v, t);
            }
        }
    }

    /// Inserts the point at parameter `param` of segment `s` into the piece uv (an edge of
    /// triangle `t0`), Bowyer–Watson (module docs), inside an open edit. False when the point
    /// cannot be inserted validly (nothing changed then).
    fn insert_on_piece(&mut self, t0: u32, u: u32, v: u32, s: u32, param: f64) -> bool {
        let p = self.at(s, param);
        if p == self.verts[u as usize] || p == self.verts[v as usize] {
            return false;
        }
        let Some(i0) = (0..3).find(|&i| {
            let tri = self.tris[t0 as usize];
            let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            (x, y) == (u, v) || (x, y) == (v, u)
        }) else {
            return false;
        };
        let mut region: Vec<u32> = vec![t0];
        let t1 = self.nbr[t0 as usize][i0];
        if t1 != NONE {
            region.push(t1);
        }
        let mut k = 0;
        while k < region.len() {
            let t = region[k];
            k += 1;
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                if n == NONE || region.contains(&n) {
                    continue;
                }
                let tri = self.tris[t as usize];
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if self.piece(x, y).is_some() {
                    continue;
                }
                let [a, b, c] = self.corners(n);
                if incircle(a, b, c, p) > 0.0 {
                    region.push(n);
                }
            }
            if region.len() > 64 {
                return false;
            }
        }
        let w = self.verts.len() as u32;
        // The region's boundary, counter-clockwise, without the split piece, fanned from w.
        let mut made: Vec<[u32; 3]> = Vec::new();
        for &t in &region {
            let tri = self.tris[t as usize];
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                if n != NONE && region.contains(&n) {
                    continue;
                }
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if (x, y) == (u, v) || (x, y) == (v, u) {
                    continue;
                }
                if orient2d(self.verts[x as usize], self.verts[y as usize], p) <= 0.0 {
                    return false;
                }
                made.push([x, y, w]);
            }
        }
        self.verts.push(p);
        self.segs.push(vec![s]);
        self.origin.push(u);
        self.vtri.push(NONE);
        self.replace(&region, &made);
        true
    }

    /// The triangles around `w` counter-clockwise (starting after the boundary when `w` lies
    /// on the mesh's boundary), and whether they close around it.
    fn star_ccw(&self, w: u32) -> (Vec<u32>, bool) {
        let start = self.vtri[w as usize];
        if start == NONE || !self.alive[start as usize] {
            return (Vec::new(), false);
        }
        let at = |t: u32| (0..3).find(|&k| self.tris[t as usize][k] == w);
        // Clockwise to the boundary (or all the way round).
        let mut first = start;
        let mut closed = false;
        for _ in 0..64 {
            let Some(m) = at(first) else {
                return (Vec::new(), false);
            };
            let n = self.nbr[first as usize][(m + 2) % 3];
            if n == NONE {
                break;
            }
            if n == start {
                closed = true;
                break;
            }
            first = n;
        }
        let first = if closed { start } else { first };
        let mut out = vec![first];
        let mut t = first;
        for _ in 0..64 {
            let Some(m) = at(t) else {
                return (Vec::new(), false);
            };
            let n = self.nbr[t as usize][(m + 1) % 3];
            if n == NONE || n == first {
                break;
            }
            out.push(n);
            t = n;
        }
        (out, closed)
    }

    /// Removes vertex `w` (not an input point) inside an open edit, and triangulates the hole
    /// again (`polygon_delaunay`): a point on a segment joins its two pieces and each side
    /// of the segment is triangulated apart; a vertex off the segments must have its star
    /// closed around it. False when that fails (nothing changed).
    fn delete_vertex(&mut self, w: u32) -> bool {
        if (w as usize) < self.n_fixed || self.segs[w as usize].len() > 1 {
            return false;
        }
        let (star, closed) = self.star_ccw(w);
        if star.is_empty() {
            return false;
        }
        // The ring of neighbours counter-clockwise.
        let mut ring: Vec<u32> = Vec::new();
        for &t in &star {
            let tri = self.tris[t as usize];
            let m = (0..3).find(|&k| tri[k] == w).unwrap_or(0);
            if ring.is_empty() {
                ring.push(tri[(m + 1) % 3]);
            }
            ring.push(tri[(m + 2) % 3]);
        }
        if closed {
            ring.pop();
        }
        let chains: Vec<Vec<u32>> = match self.segs[w as usize].first() {
            None => {
                if !closed {
                    return false;
                }
                vec![ring]
            }
            Some(&s) => {
                let on: Vec<usize> = (0..ring.len())
                    .filter(|&i| self.segs[ring[i] as usize].contains(&s))
                    .collect();
                if on.len() != 2 {
                    return false;
                }
                if closed {
                    let (i, j) = (on[0], on[1]);
                    let a: Vec<u32> = (i..=j).map(|k| ring[k]).collect();
                    let b: Vec<u32> = (j..=i + ring.len()).map(|k| ring[k % ring.len()]).collect();
                    vec![a, b]
                } else {
                    if on != [0, ring.len() - 1] {
                        return false;
                    }
                    vec![ring]
                }
            }
        };
        let mut made: Vec<[u32; 3]> = Vec::new();
        for chain in &chains {
            if !self.polygon_delaunay(chain, &mut made) {
                return false;
            }
        }
        self.replace(&star, &made);
        true
    }

    /// Triangulates the counter-clockwise polygon `poly` (closed by its last-to-first edge)
    /// as a Delaunay triangulation inside it: on the base edge, the apex whose circle holds no
    /// other vertex in front of the edge, its two sides inside the polygon, then both parts.
    fn polygon_delaunay(&self, poly: &[u32], out: &mut Vec<[u32; 3]>) -> bool {
        if poly.len() < 3 {
            return true;
        }
        let p = |v: u32| self.verts[v as usize];
        let (a, b) = (poly[poly.len() - 1], poly[0]);
        let mut best: Option<usize> = None;
        for k in 1..poly.len() - 1 {
            let c = poly[k];
            if orient2d(p(a), p(b), p(c)) <= 0.0 {
                continue;
            }
            if let Some(j) = best {
                if incircle(p(a), p(b), p(poly[j]), p(c)) > 0.0 {
                    best = Some(k);
                }
            } else {
                best = Some(k);
            }
        }
        let Some(k) = best else {
            return false;
        };
        let c = poly[k];
        // The sides a-c and c-b must not cross the polygon.
        let crosses = |x: u32, y: u32| {
            (0..poly.len()).any(|i| {
                let (e, f) = (poly[i], poly[(i + 1) % poly.len()]);
                if [e, f].contains(&x) || [e, f].contains(&y) {
                    return false;
                }
                let o1 = orient2d(p(x), p(y), p(e));
                let o2 = orient2d(p(x), p(y), p(f));
                let o3 = orient2d(p(e), p(f), p(x));
                let o4 = orient2d(p(e), p(f), p(y));
                o1 * o2 <= 0.0 && o3 * o4 <= 0.0
            })
        };
        if (k != poly.len() - 2 && crosses(a, c)) || (k != 1 && crosses(c, b)) {
            return false;
        }
        out.push([a, b, c]);
        self.polygon_delaunay(&poly[..=k], out) && self.polygon_delaunay(&poly[k..], out)
    }

    /// The segment pieces near triangle `t`: edges of the triangles around its corners.
    fn pieces_near(&self, t: u32) -> Vec<(u32, u32, u32, u32)> {
        let mut out: Vec<(u32, u32, u32, u32)> = Vec::new();
        let mut seen: Vec<u32> = vec![t];
        let mut tris = vec![t];
        for &v in &self.tris[t as usize] {
            for s in self.star(v) {
                if !seen.contains(&s) {
                    seen.push(s);
                    tris.push(s);
                }
            }
        }
        for &s in &tris {
            let tri = self.tris[s as usize];
            for i in 0..3 {
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if let Some(seg) = self.piece(x, y) {
                    let key = (x.min(y), x.max(y));
                    if !out.iter().any(|o| (o.0, o.1) == key) {
                        out.push((key.0, key.1, seg, s));
                    }
                }
            }
        }
        out
    }

    /// The live triangles around vertex `v`.
    fn star(&self, v: u32) -> Vec<u32> {
        let start = self.vtri[v as usize];
        if start == NONE || !self.alive[start as usize] {
            return Vec::new();
        }
        let mut out = vec![start];
        // Counter-clockwise: across the edge (v, next) ... walk both ways.
        for dir in 0..2 {
            let mut t = start;
            loop {
                let tri = self.tris[t as usize];
                let Some(m) = (0..3).find(|&k| tri[k] == v) else {
                    break;
                };
                // dir 0: across edge (v, tri[m+1]) i.e. opposite tri[m+2]; dir 1: opposite m+1.
                let i = if dir == 0 { (m + 2) % 3 } else { (m + 1) % 3 };
                let n = self.nbr[t as usize][i];
                if n == NONE || n == start || out.contains(&n) {
                    break;
                }
                out.push(n);
                t = n;
                if out.len() > 64 {
                    break;
                }
            }
        }
        out
    }

    /// A triangle with the edge uv.
    fn edge_triangle(&self, u: u32, v: u32) -> Option<u32> {
        self.star(u)
            .into_iter()
            .find(|&t| self.tris[t as usize].contains(&v))
    }

    /// Makes `op` inside an open edit; false when it cannot be made validly.
    fn apply(&mut self, op: Op) -> bool {
        match op {
            Op::Insert { u, v, s, q } => match self.edge_triangle(u, v) {
                Some(t) => self.insert_on_piece(t, u, v, s, q),
                None => false,
            },
            Op::Delete { w } => self.delete_vertex(w),
            Op::Move { w, u, v, s, q } => {
                self.delete_vertex(w)
                    && match self.edge_triangle(u, v) {
                        Some(t) => self.insert_on_piece(t, u, v, s, q),
                        None => false,
                    }
            }
        }
    }

    /// The parameters along segment `s` worth trying between the vertices u and v for a bad
    /// triangle with corners `tri`: the middle, the feet of the corners and of the
    /// circumcentre, and the points as far from u or v as a corner is.
    fn params(&self, s: u32, u: u32, v: u32, tri: [u32; 3], targets: &[Point]) -> Vec<f64> {
        let (tu, tv) = (
            self.param(s, self.verts[u as usize]),
            self.param(s, self.verts[v as usize]),
        );
        let (lo, hi) = (tu.min(tv), tu.max(tv));
        let len = dist(self.verts[u as usize], self.verts[v as usize]);
        if hi <= lo || hi.is_nan() || lo.is_nan() || len == 0.0 {
            return Vec::new();
        }
        let mut params: Vec<f64> = vec![(lo + hi) / 2.0];
        for &q in targets {
            params.push(self.param(s, q));
        }
        for &e in &[u, v] {
            let te = self.param(s, self.verts[e as usize]);
            let dir = if te == lo { 1.0 } else { -1.0 };
            for &x in &tri {
                if x == e {
                    continue;
                }
                let d = dist(self.verts[e as usize], self.verts[x as usize]);
                params.push(te + dir * (hi - lo) * d / len);
            }
        }
        let margin = (hi - lo) * 1e-6;
        params.retain(|&q| q > lo + margin && q < hi - margin);
        params
    }

    /// The two vertices next to `w` along its segment.
    fn along(&self, w: u32) -> Option<(u32, u32)> {
        let s = *self.segs[w as usize].first()?;
        let mut ends: Vec<u32> = Vec::new();
        for t in self.star(w) {
            for &x in &self.tris[t as usize] {
                if x != w && self.segs[x as usize].contains(&s) && !ends.contains(&x) {
                    ends.push(x);
                }
            }
        }
        (ends.len() == 2).then(|| (ends[0], ends[1]))
    }

    /// The edits worth trying for bad triangle `t`.
    fn ops(&self, t: u32) -> Vec<Op> {
        let tri = self.tris[t as usize];
        let c = self.corners(t);
        let mut targets: Vec<Point> = c.to_vec();
        if let Some(cc) = circumcenter(c[0], c[1], c[2]) {
            targets.push(cc);
        }
        let mut ops = Vec::new();
        let pieces = self.pieces_near(t);
        for &(u, v, s, _) in &pieces {
            for q in self.params(s, u, v, tri, &targets) {
                ops.push(Op::Insert { u, v, s, q });
            }
        }
        let mut movable: Vec<u32> = Vec::new();
        for &(u, v, _, _) in &pieces {
            for x in [u, v] {
                if (x as usize) >= self.n_fixed
                    && self.segs[x as usize].len() == 1
                    && !movable.contains(&x)
                {
                    movable.push(x);
                }
            }
        }
        for &w in &tri {
            if (w as usize) < self.n_fixed || self.on_segment(w) {
                continue;
            }
            ops.push(Op::Delete { w });
            for &(u, v, s, _) in &pieces {
                if u == w || v == w {
                    continue;
                }
                let q = self.param(s, self.verts[w as usize]);
                let (tu, tv) = (
                    self.param(s, self.verts[u as usize]),
                    self.param(s, self.verts[v as usize]),
                );
                let (lo, hi) = (tu.min(tv), tu.max(tv));
                let margin = (hi - lo) * 1e-6;
                if q > lo + margin && q < hi - margin {
                    ops.push(Op::Move { w, u, v, s, q });
                }
            }
        }
        for w in movable {
            ops.push(Op::Delete { w });
            let Some((u, v)) = self.along(w) else {
                continue;
            };
            let s = self.segs[w as usize][0];
            for q in self.params(s, u, v, tri, &targets) {
                ops.push(Op::Move { w, u, v, s, q });
            }
        }
        ops
    }

    /// The worst bad triangle the open edit made, if any.
    fn worst_made(&self) -> Option<u32> {
        let log = self.log.as_ref()?;
        (log.tris_len..self.tris.len())
            .map(|t| t as u32)
            .filter(|&t| self.alive[t as usize])
            .map(|t| (self.cost(t), t))
            .filter(|(c, _)| c.bad > 0)
            .max_by(|a, b| a.0.excess.total_cmp(&b.0.excess).then(b.1.cmp(&a.1)))
            .map(|(_, t)| t)
    }

    /// The edit near triangle `t` that improves the measure most, made: one edit, or when no
    /// single one improves, a pair of them (the second repairing the worst triangle the
    /// first made, or `t` itself if it survived).
    fn repair(&mut self, t: u32) -> bool {
        let mut best: Option<(Cost, Op, Option<Op>)> = None;
        let ops = self.ops(t);
        for &op in &ops {
            self.begin();
            if self.apply(op) {
                let cost = self.edit_cost();
                if cost.improves() && best.as_ref().is_none_or(|b| cost.better_than(&b.0)) {
                    best = Some((cost, op, None));
                }
            }
            self.rollback();
        }
        if best.is_none() {
            for &op in &ops {
                self.begin();
                if !self.apply(op) {
                    self.rollback();
                    continue;
                }
                let next = if self.alive[t as usize] {
                    Some(t)
                } else {
                    self.worst_made()
                };
                let Some(next) = next else {
                    self.rollback();
                    continue;
                };
                let second = self.ops(next);
                self.rollback();
                for &op2 in &second {
                    self.begin();
                    if self.apply(op) && self.apply(op2) {
                        let cost = self.edit_cost();
                        if cost.improves() && best.as_ref().is_none_or(|b| cost.better_than(&b.0)) {
                            best = Some((cost, op, Some(op2)));
                        }
                    }
                    self.rollback();
                }
            }
        }
        let Some((_, op, op2)) = best else {
            return false;
        };
        self.begin();
        let made = self.apply(op) && op2.is_none_or(|o| self.apply(o));
        if made {
            self.log = None;
            for o in std::iter::once(op).chain(op2) {
                match o {
                    Op::Insert { .. } => self.inserted += 1,
                    Op::Delete { .. } => self.deleted += 1,
                    Op::Move { .. } => self.moved += 1,
                }
            }
        } else {
            self.rollback();
        }
        made
    }

    /// Repairs bad triangles by insertions until none is left, none can be repaired, or
    /// `budget` insertions are made; returns the bad triangles left.
    pub fn improve(&mut self, budget: u64) -> Vec<u32> {
        let mut made = 0u64;
        loop {
            let mut bad: Vec<(f64, u32)> = (0..self.tris.len() as u32)
                .filter(|&t| self.alive[t as usize])
                .filter_map(|t| {
                    let c = self.cost(t);
                    (c.bad > 0).then_some((c.excess, t))
                })
                .collect();
            if bad.is_empty() {
                return Vec::new();
            }
            bad.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
            let mut progressed = false;
            for &(_, t) in &bad {
                if made >= budget {
                    break;
                }
                if !self.alive[t as usize] || self.cost(t).bad == 0 {
                    continue;
                }
                if self.repair(t) {
                    made += 1;
                    progressed = true;
                }
            }
            if !progressed || made >= budget {
                return (0..self.tris.len() as u32)
                    .filter(|&t| self.alive[t as usize] && self.cost(t).bad > 0)
                    .collect();
            }
        }
    }
}
