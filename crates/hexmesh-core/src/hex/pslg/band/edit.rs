//! The triangulation the band edits (ours): neighbours, undoable edits, Lawson flips,
//! Bowyer–Watson insertion on a segment piece, and removal of a vertex with its hole
//! triangulated again; every sign is an exact predicate.

use super::{Band, Cost, NONE};
use crate::geom::{incircle, orient2d, Point};

/// What an edit changed, to undo it.
#[derive(Default)]
pub(super) struct Log {
    pub(super) tris_len: usize,
    pub(super) verts_len: usize,
    pub(super) killed: Vec<u32>,
    pub(super) nbr: Vec<(u32, usize, u32)>,
    pub(super) vtri: Vec<(u32, u32)>,
    /// The measure of the triangles the edit removed that existed before it.
    pub(super) killed_cost: Cost,
    /// Vertices the edit moved, with their old position and segments.
    pub(super) moved: Vec<(u32, Point, Vec<u32>)>,
}

impl Band<'_> {
    pub(super) fn set_nbr(&mut self, t: u32, i: usize, n: u32) {
        if let Some(log) = &mut self.log {
            log.nbr.push((t, i, self.nbr[t as usize][i]));
        }
        self.nbr[t as usize][i] = n;
    }

    pub(super) fn set_vtri(&mut self, v: u32, t: u32) {
        if let Some(log) = &mut self.log {
            log.vtri.push((v, self.vtri[v as usize]));
        }
        self.vtri[v as usize] = t;
    }

    pub(super) fn begin(&mut self) {
        self.log = Some(Log {
            tris_len: self.tris.len(),
            verts_len: self.verts.len(),
            ..Log::default()
        });
    }

    pub(super) fn rollback(&mut self) {
        let Some(log) = self.log.take() else { return };
        for (v, p, segs) in log.moved.into_iter().rev() {
            self.verts[v as usize] = p;
            self.segs[v as usize] = segs;
        }
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

    /// The change of the measure the open edit made: its live new triangles less what the
    /// triangles it removed measured when they were removed.
    pub(super) fn edit_cost(&self) -> Cost {
        let Some(log) = &self.log else {
            return Cost::default();
        };
        let mut c = Cost::default();
        for t in log.tris_len..self.tris.len() {
            if self.alive[t] {
                c.add(self.cost(t as u32));
            }
        }
        c.sub(log.killed_cost);
        c
    }

    /// The slot of `t`'s edge from x to y, counter-clockwise.
    pub(super) fn slot(&self, t: u32, x: u32, y: u32) -> Option<usize> {
        let tri = self.tris[t as usize];
        (0..3).find(|&i| tri[(i + 1) % 3] == x && tri[(i + 2) % 3] == y)
    }

    /// The first edge of live triangle `t` that is not a segment piece, fails the exact
    /// empty-circle test against the triangle beyond it, and can be flipped (the
    /// quadrilateral is convex): its slot in `t`, the triangle beyond and that one's slot.
    fn illegal_edge(&self, t: u32) -> Option<(usize, u32, usize)> {
        (0..3).find_map(|i| {
            let o = self.nbr[t as usize][i];
            if o == NONE || !self.alive[o as usize] {
                return None;
            }
            let tri = self.tris[t as usize];
            let (x, y, w) = (tri[(i + 1) % 3], tri[(i + 2) % 3], tri[i]);
            if self.piece(x, y).is_some() {
                return None;
            }
            let j = self.slot(o, y, x)?;
            let d = self.tris[o as usize][j];
            let p = |v: u32| self.verts[v as usize];
            let flippable = incircle(p(w), p(x), p(y), p(d)) > 0.0
                && orient2d(p(w), p(x), p(d)) > 0.0
                && orient2d(p(w), p(d), p(y)) > 0.0;
            flippable.then_some((i, o, j))
        })
    }

    /// Lawson flips of every edge that is not a segment piece and fails the exact
    /// empty-circle test, until none does: the constrained Delaunay triangulation.
    pub(in super::super) fn make_delaunay(&mut self) {
        let mut stack: Vec<u32> = (0..self.tris.len() as u32).rev().collect();
        // Each flip strictly raises the triangulation in the lifting map: finite.
        while let Some(t) = stack.pop() {
            if !self.alive[t as usize] {
                continue;
            }
            if let Some((i, o, j)) = self.illegal_edge(t) {
                self.flip(t, i, o, j);
                self.flips += 1;
                stack.push(t);
                stack.push(o);
            }
        }
    }

    /// Flips the edge between `t` (opposite its corner i) and `o` (opposite its corner j).
    pub(super) fn flip(&mut self, t: u32, i: usize, o: u32, j: usize) {
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
    pub(super) fn param(&self, s: u32, p: Point) -> f64 {
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

    pub(super) fn at(&self, s: u32, t: f64) -> Point {
        let [a, b] = self.segments[s as usize];
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }

    /// Replaces the live triangles `killed` by `made` (which must tile the same region),
    /// inside an open edit: neighbours across the region's boundary are kept.
    pub(super) fn replace(&mut self, killed: &[u32], made: &[[u32; 3]]) {
        self.replace_with(killed, |_| {}, made);
    }

    /// `replace`, running `between` after the removal and before the new triangles are made
    /// (a vertex moved there is seen at its new place by them, at its old by the removed).
    pub(super) fn replace_with(
        &mut self,
        killed: &[u32],
        between: impl FnOnce(&mut Self),
        made: &[[u32; 3]],
    ) {
        // An edit touches a handful of triangles: its edges are looked up in short lists.
        let mut outer: Vec<((u32, u32), u32)> = Vec::with_capacity(3 * killed.len());
        for &t in killed {
            let tri = self.tris[t as usize];
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                if n != NONE && killed.contains(&n) {
                    continue;
                }
                outer.push(((tri[(i + 1) % 3], tri[(i + 2) % 3]), n));
            }
        }
        for &t in killed {
            let c = self.cost(t);
            self.alive[t as usize] = false;
            if let Some(log) = &mut self.log {
                if (t as usize) < log.tris_len {
                    log.killed_cost.add(c);
                }
                log.killed.push(t);
            }
        }
        between(self);
        let first = self.tris.len() as u32;
        let mut inner: Vec<((u32, u32), u32)> = Vec::with_capacity(3 * made.len());
        for (k, &tri) in made.iter().enumerate() {
            self.tris.push(tri);
            self.nbr.push([NONE; 3]);
            self.alive.push(true);
            for i in 0..3 {
                inner.push(((tri[(i + 1) % 3], tri[(i + 2) % 3]), first + k as u32));
            }
        }
        for (k, &tri) in made.iter().enumerate() {
            let t = first + k as u32;
            for i in 0..3 {
                let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                if let Some(&(_, o)) = inner.iter().find(|e| e.0 == (y, x)) {
                    self.nbr[t as usize][i] = o;
                } else if let Some(&(_, n)) = outer.iter().find(|e| e.0 == (x, y)) {
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
        // An outer edge no new triangle took is now on the mesh's boundary.
        for &((x, y), n) in &outer {
            if n != NONE && !inner.iter().any(|e| e.0 == (x, y)) {
                if let Some(sl) = self.slot(n, y, x) {
                    if self.nbr[n as usize][sl] != NONE
                        && !self.alive[self.nbr[n as usize][sl] as usize]
                    {
                        self.set_nbr(n, sl, NONE);
                    }
                }
            }
        }
    }

    /// Moves vertex `w` (off the segments, not an input point) onto the piece uv of segment
    /// `s` at parameter `q`, where uv is the edge opposite `w` in one of its triangles (paper
    /// 001 Sec. 5.1 moves lattice corners onto the boundary the same way): that triangle
    /// goes, the one beyond the piece is split at `w`, the others keep their corners, and
    /// Lawson flips restore the constrained Delaunay property. Inside an open edit; false
    /// when a triangle would turn over or the flips do not settle.
    pub(super) fn snap(&mut self, w: u32, u: u32, v: u32, s: u32, q: f64) -> bool {
        if (w as usize) < self.n_fixed || !self.segs[w as usize].is_empty() {
            return false;
        }
        let foot = self.at(s, q);
        let (star, _) = self.star_ccw(w);
        let Some(&t0) = star.iter().find(|&&t| {
            let tri = self.tris[t as usize];
            tri.contains(&u) && tri.contains(&v)
        }) else {
            return false;
        };
        let tri0 = self.tris[t0 as usize];
        let m = (0..3).find(|&k| tri0[k] == w).unwrap_or(0);
        let (a, b) = (tri0[(m + 1) % 3], tri0[(m + 2) % 3]);
        let t1 = self.nbr[t0 as usize][m];
        let mut made: Vec<[u32; 3]> = star
            .iter()
            .filter(|&&t| t != t0)
            .map(|&t| self.tris[t as usize])
            .collect();
        let mut killed = star.clone();
        if t1 != NONE {
            let o = self.tris[t1 as usize];
            let Some(k) = (0..3).find(|&k| o[k] != a && o[k] != b) else {
                return false;
            };
            let c = o[k];
            made.push([b, w, c]);
            made.push([w, a, c]);
            killed.push(t1);
        }
        self.move_vertex(w, foot, Some(s), &killed, &made)
    }

    /// Replaces the triangles `killed` by `made`, with vertex `w` moved to `to` (and onto
    /// segment `onto` when given) in between, then restores the constrained Delaunay property
    /// by Lawson flips; false, with nothing changed, when a triangle of `made` would not be
    /// counter-clockwise at the new place, and false when the flips do not settle.
    fn move_vertex(
        &mut self,
        w: u32,
        to: Point,
        onto: Option<u32>,
        killed: &[u32],
        made: &[[u32; 3]],
    ) -> bool {
        let pos = |x: u32| if x == w { to } else { self.verts[x as usize] };
        if made
            .iter()
            .any(|t| orient2d(pos(t[0]), pos(t[1]), pos(t[2])) <= 0.0)
        {
            return false;
        }
        let first = self.tris.len() as u32;
        self.replace_with(
            killed,
            |band| {
                if let Some(log) = &mut band.log {
                    log.moved
                        .push((w, band.verts[w as usize], band.segs[w as usize].clone()));
                }
                band.verts[w as usize] = to;
                if let Some(s) = onto {
                    band.segs[w as usize] = vec![s];
                }
            },
            made,
        );
        self.legalize((first..self.tris.len() as u32).collect())
    }

    /// Moves vertex `w` (off the segments, not an input point) to `to`, keeping its triangles
    /// and then restoring the constrained Delaunay property by Lawson flips (ours: the dual
    /// vertex beside a segment given room, as paper 001 Sec. 5.2 moves a lattice corner away
    /// from the boundary). Inside an open edit; false when a triangle of its star would turn
    /// over, or the flips do not settle.
    pub(super) fn shift(&mut self, w: u32, to: Point) -> bool {
        if (w as usize) < self.n_fixed || !self.segs[w as usize].is_empty() {
            return false;
        }
        let (star, closed) = self.star_ccw(w);
        if !closed {
            return false;
        }
        let made: Vec<[u32; 3]> = star.iter().map(|&t| self.tris[t as usize]).collect();
        self.move_vertex(w, to, None, &star, &made)
    }

    /// Lawson flips, recorded in the open edit, from the triangles `stack` until every edge
    /// that is not a segment piece passes the exact empty-circle test; false when more than
    /// `MAX_FLIPS` would be needed.
    fn legalize(&mut self, mut stack: Vec<u32>) -> bool {
        const MAX_FLIPS: usize = 256;
        let mut flips = 0;
        while let Some(t) = stack.pop() {
            if !self.alive[t as usize] {
                continue;
            }
            let Some((i, o, j)) = self.illegal_edge(t) else {
                continue;
            };
            flips += 1;
            if flips > MAX_FLIPS {
                return false;
            }
            let tri = self.tris[t as usize];
            let (w, x, y) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
            let d = self.tris[o as usize][j];
            let first = self.tris.len() as u32;
            self.replace(&[t, o], &[[w, x, d], [w, d, y]]);
            stack.push(first);
            stack.push(first + 1);
        }
        true
    }

    /// Inserts the point at parameter `param` of segment `s` into the piece uv (an edge of
    /// triangle `t0`), Bowyer–Watson (module docs), inside an open edit. False when the point
    /// cannot be inserted validly (nothing changed then).
    pub(super) fn insert_on_piece(&mut self, t0: u32, u: u32, v: u32, s: u32, param: f64) -> bool {
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
    pub(super) fn star_ccw(&self, w: u32) -> (Vec<u32>, bool) {
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
    pub(super) fn delete_vertex(&mut self, w: u32) -> bool {
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
    pub(super) fn polygon_delaunay(&self, poly: &[u32], out: &mut Vec<[u32; 3]>) -> bool {
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

    /// The live triangles around vertex `v`.
    pub(super) fn star(&self, v: u32) -> Vec<u32> {
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
    pub(super) fn edge_triangle(&self, u: u32, v: u32) -> Option<u32> {
        self.star(u)
            .into_iter()
            .find(|&t| self.tris[t as usize].contains(&v))
    }
}
