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
//! The other edits (removing, moving or snapping a point, shifting a dual vertex beside a
//! segment by a fraction of its shortest edge) do change triangles without a segment corner:
//! each such triangle an edit makes is measured against the interior bounds (Sec. 6 angles,
//! which imply the radius ratio, and the Sec. 6.3 shortest edge), so an edit that breaks them
//! is never chosen. The shift is what repaired imr's last two triangles below 30°, where a
//! dual vertex lay 0.45 of an edge from the segment (removing or snapping it left a hole
//! whose constrained Delaunay fill broke the interior bounds).
//!
//! Insertion is Bowyer–Watson in the constrained Delaunay triangulation (the triangles whose
//! circumcircle holds the new point, reached without crossing a segment piece), so the mesh
//! stays constrained Delaunay: every empty-circle violation lies on a segment.
//!
//! The measure, compared in this order: the triangles without a segment corner that break the
//! interior bounds, all triangles that break their bounds, the sum of their excess over the
//! bounds. Interior triangles come first so that no edit trades one for near-segment ones: the
//! driver can repair an interior triangle only by subdividing, which may put an edge below the
//! Sec. 6.3 bound (domain fuzz seed 20261123, case 122,
//! tests/fixtures/hex/domains-fuzz-seed20261123-case122-band-traded-an-interior-triangle.poly).
//! A triangle of the cavity's fill can be interior, its corners three dual vertices; its
//! edits are sought from the segment pieces within two rings when none is within one
//! (tests/fixtures/hex/pslg-star-hole-fill-ear-beyond-one-ring-proptest.poly).
//!
//! Where no single edit lowers the measure, a pair is tried: the single edits from the best
//! alone down, each completed by an edit (a shift excepted) aimed at the triangle or at the
//! worst ones the first made, stopping at the first pair that improves. Trying every pair
//! took 24 s on a domain fuzz case of 2,600 triangles, and shifts as second edits 420 s on
//! spade's issue 96 box; a triangle no edit repaired is tried again only after an edit
//! changed the triangles near it. The thorough search (`Effort::thorough`: every pair,
//! shifts as second edits, the best kept) is run once, on the mesh the driver is about to
//! return with triangles left (domain fuzz seed 20261123, cases 537 and 798,
//! tests/fixtures/hex/domains-fuzz-seed20261123-case537-thorough-band.poly and
//! tests/fixtures/hex/domains-fuzz-seed20261123-case798-thorough-band.poly).
//!
//! Termination: an edit is made only when it lowers the measure, and the number of edits is
//! capped by a budget; triangles no candidate repairs are returned to the driver, which
//! subdivides the hexagons there and meshes again (`drive`).

mod edit;

use crate::geom::{angle_deg, circumcenter, dist, Point};
use crate::hex::extended::check::breaks_bounds;
use crate::quality::bounds::HEX;
use crate::quality::rounding;
use edit::Log;

/// The smallest angle of a triangle touching a segment (Triangle's `-q30`), but at an input
/// corner sharper than it taken whole: hex's promise (`quality::bounds`).
pub const NEAR_MIN_ANGLE: f64 = crate::quality::bounds::NEAR_SEGMENT_ANGLES.0;

/// The largest angle of a triangle touching a segment (180° − 2·30°).
pub const NEAR_MAX_ANGLE: f64 = crate::quality::bounds::NEAR_SEGMENT_ANGLES.1;

const NONE: u32 = u32::MAX;

/// How many of the bad triangles a first edit made a second edit may aim at (`repair`).
const SECOND_TARGETS: usize = 3;

/// What a triangle contributes to the measure.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Cost {
    /// Triangles with no corner on a segment that break the interior bounds. They come first:
    /// an edit may not trade an interior triangle's bounds for near-segment ones, since the
    /// driver can only repair an interior triangle by subdividing below the Sec. 6.3 edge
    /// (domain fuzz seed 20261123, case 122: a removal made a 41.9° dual triangle).
    interior: i64,
    /// Triangles that break their bounds (interior ones included).
    bad: i64,
    /// Their summed excess over the bounds, in degrees.
    excess: f64,
    /// Near-segment angles above 90° (the non-obtuse aim; a tie-breaker only).
    obtuse: i64,
}

impl Cost {
    fn add(&mut self, o: Cost) {
        self.interior += o.interior;
        self.bad += o.bad;
        self.excess += o.excess;
        self.obtuse += o.obtuse;
    }
    fn sub(&mut self, o: Cost) {
        self.interior -= o.interior;
        self.bad -= o.bad;
        self.excess -= o.excess;
        self.obtuse -= o.obtuse;
    }
    /// True when this change of the measure is a strict improvement.
    fn improves(&self) -> bool {
        self.interior < 0
            || (self.interior == 0 && (self.bad < 0 || (self.bad == 0 && self.excess < -1e-9)))
    }
    /// A total order of changes, the best first: as `better_than`, but comparing the
    /// excess exactly (a sort needs transitivity, which the tolerance of `better_than`
    /// breaks).
    fn order(&self, o: &Cost) -> std::cmp::Ordering {
        self.interior
            .cmp(&o.interior)
            .then(self.bad.cmp(&o.bad))
            .then(self.excess.total_cmp(&o.excess))
            .then(self.obtuse.cmp(&o.obtuse))
    }
    /// Orders changes: fewer interior bad triangles, fewer bad triangles, then less excess,
    /// then fewer obtuse angles.
    fn better_than(&self, o: &Cost) -> bool {
        if self.interior != o.interior {
            return self.interior < o.interior;
        }
        if self.bad != o.bad {
            return self.bad < o.bad;
        }
        if (self.excess - o.excess).abs() > 1e-9 {
            return self.excess < o.excess;
        }
        self.obtuse < o.obtuse
    }
}

/// A point on one segment that is not an input point: the point, its segment, and its
/// neighbours along the segment when it has two.
type Movable = (u32, u32, Option<(u32, u32)>);

/// Where `Op::Snap` and `Op::Move` take vertex `w`: parameter `q` of segment `s`, on its
/// piece between the vertices u and v, in place of the point `also` when given.
#[derive(Debug, Clone, Copy)]
struct Onto {
    w: u32,
    also: Option<u32>,
    u: u32,
    v: u32,
    s: u32,
    q: f64,
}

/// What the repair is held to and how hard it searches.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Effort {
    /// The shortest edge an interior triangle the band makes may have (Sec. 6.3:
    /// √7/(12√3)·d_min).
    pub min_edge: f64,
    /// Search every pair of edits, shifts as second edits included, for the best one, rather
    /// than stop at the first pair that improves: for the driver's last mesh when the usual
    /// search left near-segment triangles (`drive`).
    pub thorough: bool,
}

/// An edit of the band.
#[derive(Debug, Clone, Copy)]
enum Op {
    /// A point at parameter q of segment s, between its vertices u and v.
    Insert { u: u32, v: u32, s: u32, q: f64 },
    /// The vertex w removed (a point on a segment, or a dual vertex beside one).
    Delete { w: u32 },
    /// The dual vertex w moved onto the piece uv of segment s at parameter q, after the
    /// point `also` on that segment is removed when given (`edit::snap`).
    Snap(Onto),
    /// The point w on a segment moved to parameter q, between its neighbours u and v; or a
    /// vertex w off the segments moved onto the piece uv of segment s (removed and inserted
    /// there), taking the place of the point `also` on that piece when given.
    Move(Onto),
    /// The dual vertex w moved to `to`, off the segments (`edit::shift`).
    Shift { w: u32, to: Point },
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
    /// What the repair is held to and how hard it searches.
    effort: Effort,
    /// Edits made so far.
    edits: u64,
    /// For each vertex, the number of the last edit that changed the triangles around it.
    changed: Vec<u64>,
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
            effort: Effort::default(),
            edits: 0,
            changed: vec![0; n],
            inserted: 0,
            deleted: 0,
            moved: 0,
            flips: 0,
        }
    }

    /// This band with interior triangles held to `effort.min_edge`, searching as `effort`
    /// says.
    pub fn with_effort(mut self, effort: Effort) -> Band<'a> {
        self.effort = effort;
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
                && (0..3).any(|m| dist(c[m], c[(m + 1) % 3]) < self.effort.min_edge);
            if breaks_bounds(&c) || short {
                let excess: f64 = (0..3)
                    .map(|m| {
                        let a = angle_deg(c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
                        rounding::beyond(a, HEX.min_angle, HEX.max_angle)
                    })
                    .sum();
                return Cost {
                    interior: 1,
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

    /// The segment pieces near triangle `t`: edges of the triangles around its corners, or
    /// when there are none (an interior triangle of the cavity's fill, whose corners are all
    /// dual vertices), of the triangles around their corners in turn.
    fn pieces_near(&self, t: u32) -> Vec<(u32, u32, u32, u32)> {
        let near = self.pieces_within(t, 1);
        if near.is_empty() {
            self.pieces_within(t, 2)
        } else {
            near
        }
    }

    /// The segment pieces on the triangles within `rings` stars of triangle `t`'s corners.
    fn pieces_within(&self, t: u32, rings: usize) -> Vec<(u32, u32, u32, u32)> {
        let mut out: Vec<(u32, u32, u32, u32)> = Vec::new();
        let mut tris = vec![t];
        let mut from = 0;
        for _ in 0..rings {
            let to = tris.len();
            for i in from..to {
                for v in self.tris[tris[i] as usize] {
                    for s in self.star(v) {
                        if !tris.contains(&s) {
                            tris.push(s);
                        }
                    }
                }
            }
            from = to;
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

    /// Makes `op` inside an open edit; false when it cannot be made validly.
    fn apply(&mut self, op: Op) -> bool {
        match op {
            Op::Insert { u, v, s, q } => match self.edge_triangle(u, v) {
                Some(t) => self.insert_on_piece(t, u, v, s, q),
                None => false,
            },
            Op::Delete { w } => self.delete_vertex(w),
            Op::Shift { w, to } => self.shift(w, to),
            Op::Snap(Onto {
                w,
                also,
                u,
                v,
                s,
                q,
            }) => also.is_none_or(|x| self.delete_vertex(x)) && self.snap(w, u, v, s, q),
            Op::Move(Onto {
                w,
                also,
                u,
                v,
                s,
                q,
            }) => {
                self.delete_vertex(w)
                    && also.is_none_or(|x| self.delete_vertex(x))
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

    /// True when parameter `q` of segment `s` lies strictly between its vertices u and v,
    /// clear of both by a millionth of the piece.
    fn strictly_between(&self, s: u32, u: u32, v: u32, q: f64) -> bool {
        let (tu, tv) = (
            self.param(s, self.verts[u as usize]),
            self.param(s, self.verts[v as usize]),
        );
        let (lo, hi) = (tu.min(tv), tu.max(tv));
        let margin = (hi - lo) * 1e-6;
        q > lo + margin && q < hi - margin
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
        // The points on one segment that are not input points, with their segment and their
        // neighbours along it.
        let mut movable: Vec<Movable> = Vec::new();
        for &(u, v, _, _) in &pieces {
            for x in [u, v] {
                if (x as usize) >= self.n_fixed
                    && self.segs[x as usize].len() == 1
                    && !movable.iter().any(|m| m.0 == x)
                {
                    movable.push((x, self.segs[x as usize][0], self.along(x)));
                }
            }
        }
        for &w in &tri {
            if (w as usize) < self.n_fixed || self.on_segment(w) {
                continue;
            }
            ops.push(Op::Delete { w });
            self.shifts(w, &pieces, &mut ops);
            // Onto a piece near the triangle, or in place of a point beside it.
            let places = pieces
                .iter()
                .filter(|p| p.0 != w && p.1 != w)
                .map(|&(u, v, s, _)| (None, u, v, s))
                .chain(
                    movable
                        .iter()
                        .filter_map(|&(x, s, uv)| uv.map(|(u, v)| (Some(x), u, v, s))),
                );
            for (also, u, v, s) in places {
                let q = self.param(s, self.verts[w as usize]);
                if self.strictly_between(s, u, v, q) {
                    let onto = Onto {
                        w,
                        also,
                        u,
                        v,
                        s,
                        q,
                    };
                    ops.push(Op::Move(onto));
                    ops.push(Op::Snap(onto));
                }
            }
        }
        for &(w, s, uv) in &movable {
            ops.push(Op::Delete { w });
            let Some((u, v)) = uv else {
                continue;
            };
            for q in self.params(s, u, v, tri, &targets) {
                ops.push(Op::Move(Onto {
                    w,
                    also: None,
                    u,
                    v,
                    s,
                    q,
                }));
            }
        }
        ops
    }

    /// The places worth trying for the dual vertex `w` off the segments (`Op::Shift`): steps
    /// of a twentieth, a tenth and a fifth of its shortest edge along and across the nearest
    /// segment piece and diagonally, so that its interior triangles may keep their bounds.
    fn shifts(&self, w: u32, pieces: &[(u32, u32, u32, u32)], ops: &mut Vec<Op>) {
        let p = self.verts[w as usize];
        let Some(&(u, v, _, _)) = pieces.iter().min_by(|a, b| {
            let d = |x: &(u32, u32, u32, u32)| {
                let (a, b) = (self.verts[x.0 as usize], self.verts[x.1 as usize]);
                dist(p, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0])
            };
            d(a).total_cmp(&d(b))
        }) else {
            return;
        };
        let (a, b) = (self.verts[u as usize], self.verts[v as usize]);
        let len = dist(a, b);
        let edge = self
            .star(w)
            .iter()
            .flat_map(|&t| self.tris[t as usize])
            .filter(|&x| x != w)
            .map(|x| dist(p, self.verts[x as usize]))
            .fold(f64::INFINITY, f64::min);
        if len == 0.0 || !edge.is_finite() {
            return;
        }
        let d = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
        let n = [-d[1], d[0]];
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let dirs = [
            d,
            [-d[0], -d[1]],
            n,
            [-n[0], -n[1]],
            [h * (d[0] + n[0]), h * (d[1] + n[1])],
            [h * (d[0] - n[0]), h * (d[1] - n[1])],
            [h * (-d[0] + n[0]), h * (-d[1] + n[1])],
            [h * (-d[0] - n[0]), h * (-d[1] - n[1])],
        ];
        for step in [0.05, 0.1, 0.2] {
            for e in dirs {
                let to = [p[0] + step * edge * e[0], p[1] + step * edge * e[1]];
                ops.push(Op::Shift { w, to });
            }
        }
    }

    /// The bad triangles the open edit made, worst first (at most `n`).
    fn worst_made(&self, n: usize) -> Vec<u32> {
        let Some(log) = self.log.as_ref() else {
            return Vec::new();
        };
        let mut made: Vec<(f64, u32)> = (log.tris_len..self.tris.len())
            .map(|t| t as u32)
            .filter(|&t| self.alive[t as usize])
            .filter_map(|t| {
                let c = self.cost(t);
                (c.bad > 0).then_some((c.excess, t))
            })
            .collect();
        made.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        made.into_iter().take(n).map(|(_, t)| t).collect()
    }

    /// The edit near triangle `t` that improves the measure most, made: one edit, or when no
    /// single one improves, a pair of them (the second repairing the worst triangle the
    /// first made, or `t` itself if it survived).
    fn repair(&mut self, t: u32) -> bool {
        let mut best: Option<(Cost, Op, Option<Op>)> = None;
        let ops = self.ops(t);
        // The single edits that could be made, with the change each makes.
        let mut tried: Vec<(Cost, Op)> = Vec::new();
        for &op in &ops {
            self.begin();
            if self.apply(op) {
                let cost = self.edit_cost();
                if cost.improves() && best.as_ref().is_none_or(|b| cost.better_than(&b.0)) {
                    best = Some((cost, op, None));
                }
                tried.push((cost, op));
            }
            self.rollback();
        }
        if best.is_none() {
            // The first edits of a pair, the best alone first (`Cost::order`; the sort is
            // stable, so ties keep the order of `ops`). The search stops at the first of
            // them that some second edit completes to an improvement.
            tried.sort_by(|a, b| a.0.order(&b.0));
            for &(_, op) in &tried {
                if best.is_some() && !self.effort.thorough {
                    break;
                }
                self.begin();
                if !self.apply(op) {
                    self.rollback();
                    continue;
                }
                let mut next = self.worst_made(SECOND_TARGETS);
                if self.alive[t as usize] {
                    next.insert(0, t);
                }
                let mut second: Vec<Op> = Vec::new();
                for n in next {
                    second.extend(
                        self.ops(n)
                            .into_iter()
                            .filter(|o| self.effort.thorough || !matches!(o, Op::Shift { .. })),
                    );
                }
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
            if let Some(log) = self.log.take() {
                self.edits += 1;
                self.changed.resize(self.verts.len(), 0);
                for t in log.tris_len..self.tris.len() {
                    for v in self.tris[t] {
                        self.changed[v as usize] = self.edits;
                    }
                }
                for &(v, _, _) in &log.moved {
                    self.changed[v as usize] = self.edits;
                }
            }
            for o in std::iter::once(op).chain(op2) {
                match o {
                    Op::Insert { .. } => self.inserted += 1,
                    Op::Delete { .. } => self.deleted += 1,
                    Op::Move(_) | Op::Snap(_) | Op::Shift { .. } => self.moved += 1,
                }
            }
        } else {
            self.rollback();
        }
        made
    }

    /// True when an edit made after edit number `since` changed the triangles on a vertex of
    /// the triangles around `t`'s corners: the edits `repair` would try for `t` may differ.
    fn changed_near(&self, t: u32, since: u64) -> bool {
        self.tris[t as usize].iter().any(|&v| {
            self.star(v).into_iter().any(|s| {
                self.tris[s as usize]
                    .iter()
                    .any(|&x| self.changed[x as usize] > since)
            })
        })
    }

    /// Repairs bad triangles by insertions until none is left, none can be repaired, or
    /// `budget` insertions are made; returns the bad triangles left. A triangle no edit
    /// repaired is tried again only once an edit has changed the triangles near it.
    pub fn improve(&mut self, budget: u64) -> Vec<u32> {
        if !self.effort.thorough {
            return self.improve_with(budget);
        }
        // The usual search first, then the thorough one on what it left: the thorough search
        // from the start orders its edits differently and can end worse (domain fuzz case
        // 798 kept an interior triangle at 40°).
        self.effort.thorough = false;
        let left = self.improve_with(budget);
        self.effort.thorough = true;
        if left.is_empty() {
            return left;
        }
        self.improve_with(budget)
    }

    /// One pass of `improve` with the search `self.effort` says: the bad triangles in turn,
    /// interior ones first, then the worst first.
    fn improve_with(&mut self, budget: u64) -> Vec<u32> {
        let mut made = 0u64;
        let mut failed: crate::hex::lattice::FxHashMap<u32, u64> = Default::default();
        loop {
            let mut bad: Vec<(i64, f64, u32)> = (0..self.tris.len() as u32)
                .filter(|&t| self.alive[t as usize])
                .filter_map(|t| {
                    let c = self.cost(t);
                    (c.bad > 0).then_some((c.interior, c.excess, t))
                })
                .collect();
            if bad.is_empty() {
                return Vec::new();
            }
            bad.sort_by(|a, b| b.0.cmp(&a.0).then(b.1.total_cmp(&a.1)).then(a.2.cmp(&b.2)));
            let mut progressed = false;
            for &(_, _, t) in &bad {
                if made >= budget {
                    break;
                }
                if !self.alive[t as usize] || self.cost(t).bad == 0 {
                    continue;
                }
                if failed.get(&t).is_some_and(|&f| !self.changed_near(t, f)) {
                    continue;
                }
                if self.repair(t) {
                    made += 1;
                    progressed = true;
                } else {
                    failed.insert(t, self.edits);
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
