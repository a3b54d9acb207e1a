//! Conforming Delaunay triangulation of a PSLG after A. Saalfeld, "Delaunay Edge Refinements".
//!
//! Default (Sec. 6, Theorem 2): V' = V; loop { T = DT(V'); P = crossings of the segments with
//! the edges of T; if P ⊆ V' stop, else V' ∪= P }. The crossings' existence is decided by
//! exact orientation signs (spade's line walk over `robust` predicates); a round budget and the
//! mesher budget bound the loop.
//!
//! Option (Sec. 5, Theorem 1): circles of radius ε/3 around every vertex cut each segment
//! near its ends, then the middle of each segment is cut into pieces shorter than δ. The paper
//! takes ε = the shortest edge and δ = the smallest vertex distance after the circles; its
//! "straightforward" Delaunay-disk argument needs two more facts that do not hold in general:
//! no vertex may lie within ε/3 of a segment it is not on, and no vertex may lie closer to a
//! segment than half a middle piece. So here ε is also bounded by every vertex–segment
//! distance, and the middle pieces of segment s are shorter than min(δ, g_s), g_s the
//! distance from s to the nearest vertex not on s; with these the diametral disk of every
//! piece is empty. Pieces that rounding still leaves out of the triangulation are finished by
//! Sec. 6 rounds, counted apart (`ConformingRun::constructive_points`).
//!
//! What "conforming" means here. A crossing point is constructed, so its f64 rounding need
//! not lie exactly on the segment. We insert the rounded point and keep each input segment as
//! the chain of the points inserted on it, in order along the segment; the next round walks
//! the straight pieces between consecutive chain points. On termination:
//! - the output is the exact Delaunay triangulation of its vertex set (every interior edge
//!   passes the exact incircle test), restricted to the domain;
//! - every input point is a vertex, bit-exactly;
//! - every input segment ab is a chain a = p0, p1, …, pk = b of mesh edges whose inner
//!   vertices are within a few ulps of ab (each constructed on the previous chain piece)
//!   and advance monotonically from a to b.

use std::collections::{HashMap, HashSet};

use spade::handles::FixedVertexHandle;
use spade::{DelaunayTriangulation, Intersection, LineIntersectionIterator, Point2, Triangulation};

use super::{
    carve, compact, domain, ekey, idx, insertion_error, spade_triangles, to_spade, Limits,
};
use crate::error::Result;
use crate::geom::{dist, orient2d, Point};
use crate::mesh::{opposite_signs, Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params, StopReason};
use crate::quality::Bounds;

/// Without a vertex budget, the constructive option refuses to place more points than this
/// (its piece length can be arbitrarily small next to the input's size).
const CONSTRUCTIVE_CAP: usize = 2_000_000;

/// The Saalfeld conforming Delaunay mesher. `constructive` selects the Sec. 5 construction
/// instead of the Sec. 6 iteration; `max_rounds` bounds the Sec. 6 rounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Saalfeld {
    /// The constructive refinement of Sec. 5 (mesher `saalfeld-sec5`) instead of the Sec. 6
    /// iteration.
    pub constructive: bool,
    /// The most rounds of the Sec. 6 iteration before it stops, incomplete (default 1000).
    pub max_rounds: u32,
}

impl Default for Saalfeld {
    fn default() -> Self {
        Saalfeld {
            constructive: false,
            max_rounds: 1000,
        }
    }
}

/// A conforming Delaunay mesh and the facts a report compares.
#[derive(Debug, Clone, PartialEq)]
pub struct ConformingRun {
    /// The mesh; `run.steps` is the number of points added to the input's vertices.
    pub run: MeshRun,
    /// What was meshed: the PSLG, or a point set with its bounding hexagon (`reference_domain`).
    pub domain: Pslg,
    /// For every segment of `domain`, its chain of mesh vertex indices from its first to its
    /// second endpoint.
    pub chains: Vec<Vec<u32>>,
    /// Points added in all (constructive and iterative).
    pub added_points: usize,
    /// Points placed by the Sec. 5 construction (0 for the iterative default).
    pub constructive_points: usize,
    /// Sec. 6 rounds run, counting the last one that found nothing to add.
    pub rounds: u32,
}

/// A point to splice into a chain piece, in walk order.
enum Splice {
    Existing(u32),
    New(Point),
}

/// The growing vertex set. Vertices are numbered in the order they join `points`; spade
/// numbers them in the order they were inserted, which differs after a shuffled bulk insertion.
struct State {
    dt: DelaunayTriangulation<Point2<f64>>,
    points: Vec<Point>,
    chains: Vec<Vec<u32>>,
    /// Our index -> spade's index, and back.
    to_sp: Vec<u32>,
    from_sp: Vec<u32>,
}

impl State {
    /// Inserts `p`; `None` when a vertex already sits there.
    fn insert(&mut self, p: Point) -> Result<Option<u32>> {
        let before = self.dt.num_vertices();
        let h = self
            .dt
            .insert(to_spade(p))
            .map_err(|e| insertion_error("saalfeld", e))?;
        if self.dt.num_vertices() == before {
            return Ok(None);
        }
        let pos = self.dt.vertex(h).position();
        let mine = self.points.len() as u32;
        self.points.push([pos.x, pos.y]);
        self.to_sp.push(idx(h));
        self.from_sp.push(mine);
        Ok(Some(mine))
    }

    fn handle(&self, v: u32) -> FixedVertexHandle {
        FixedVertexHandle::from_index(self.to_sp[v as usize] as usize)
    }

    fn is_edge(&self, a: u32, b: u32) -> bool {
        self.dt
            .get_edge_from_neighbors(self.handle(a), self.handle(b))
            .is_some()
    }

    /// The points where the straight piece p→q crosses edges of the current triangulation,
    /// and the vertices it runs through, in order from p to q.
    fn crossings(&self, p: u32, q: u32) -> Vec<Splice> {
        let (pp, qp) = (self.points[p as usize], self.points[q as usize]);
        let mut out = Vec::new();
        for hit in
            LineIntersectionIterator::new_from_handles(&self.dt, self.handle(p), self.handle(q))
        {
            match hit {
                Intersection::EdgeIntersection(e) => {
                    let [u, w] = e.vertices().map(|v| {
                        let pos = v.position();
                        [pos.x, pos.y]
                    });
                    if let Some(x) = crossing_point(pp, qp, u, w) {
                        out.push(Splice::New(x));
                    }
                }
                Intersection::VertexIntersection(v) => {
                    let v = self.from_sp[idx(v.fix()) as usize];
                    if v != p && v != q {
                        out.push(Splice::Existing(v));
                    }
                }
                Intersection::EdgeOverlap(_) => {}
            }
        }
        out
    }
}

/// The crossing of piece pq with edge uw, rounded to f64; `None` unless the exact signs say
/// they cross properly, or when rounding lands on an end of the piece.
fn crossing_point(p: Point, q: Point, u: Point, w: Point) -> Option<Point> {
    let (op, oq) = (orient2d(u, w, p), orient2d(u, w, q));
    let (ou, ow) = (orient2d(p, q, u), orient2d(p, q, w));
    if !(opposite_signs(op, oq) && opposite_signs(ou, ow)) {
        return None;
    }
    let t = op / (op - oq);
    let x = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
    (x != p && x != q).then_some(x)
}

/// Smallest distance from `p` to the segment ab.
fn point_segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0);
    dist(p, [a[0] + t * dx, a[1] + t * dy])
}

fn min_dt_edge<T: Triangulation<Vertex = Point2<f64>>>(t: &T) -> f64 {
    t.undirected_edges()
        .map(|e| {
            let [a, b] = e.positions();
            ((a.x - b.x).powi(2) + (a.y - b.y).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

impl Saalfeld {
    /// Meshes `input` and returns the mesh with its chains and point counts.
    pub fn refine(&self, input: &Pslg, params: &Params) -> Result<ConformingRun> {
        let limits = Limits::new(params.budget);
        input.validate_input()?;
        let dom = domain(input);
        let mut st = State {
            dt: DelaunayTriangulation::new(),
            points: Vec::with_capacity(dom.points.len()),
            chains: dom.segments.iter().map(|s| vec![s[0], s[1]]).collect(),
            to_sp: Vec::with_capacity(dom.points.len()),
            from_sp: Vec::with_capacity(dom.points.len()),
        };
        for &p in &dom.points {
            // `Pslg::check` refuses duplicates, so every input point becomes its own vertex.
            if st.insert(p)?.is_none() {
                return Err(crate::error::Error::mesher(
                    "saalfeld",
                    "two input points coincide after flushing tiny coordinates to zero",
                ));
            }
        }
        let n_input = st.points.len();
        let mut stop: Option<StopReason> = None;
        let mut constructive_points = 0;
        if self.constructive && !dom.segments.is_empty() {
            match self.construct(&mut st, &dom, params)? {
                Ok(added) => constructive_points = added,
                Err(reason) => stop = Some(reason),
            }
        }
        let mut rounds = 0;
        let mut complete = false;
        while stop.is_none() {
            rounds += 1;
            let mut pending: Vec<(usize, usize, Vec<Splice>)> = Vec::new();
            for (c, chain) in st.chains.iter().enumerate() {
                for i in 0..chain.len() - 1 {
                    if !st.is_edge(chain[i], chain[i + 1]) {
                        pending.push((c, i, st.crossings(chain[i], chain[i + 1])));
                    }
                }
            }
            if pending.is_empty() {
                complete = true;
                break;
            }
            if rounds > self.max_rounds {
                stop = Some(StopReason::Rounds(self.max_rounds));
                break;
            }
            let new_points: usize = pending
                .iter()
                .map(|(_, _, s)| s.iter().filter(|x| matches!(x, Splice::New(_))).count())
                .sum();
            let added = (st.points.len() - n_input) as u64;
            if let Some(reason) = limits.exceeded(added, st.points.len() + new_points) {
                stop = Some(reason);
                break;
            }
            if !self.splice(&mut st, pending)? {
                stop = Some(StopReason::Stalled(
                    "rounded crossing points coincide with existing vertices".into(),
                ));
            }
        }
        self.finish(
            st,
            dom,
            n_input,
            constructive_points,
            rounds,
            complete,
            stop,
            &limits,
        )
    }

    /// Inserts the round's crossing points and splices them into their chains. Returns whether
    /// anything changed.
    fn splice(&self, st: &mut State, pending: Vec<(usize, usize, Vec<Splice>)>) -> Result<bool> {
        let mut changed = false;
        // Walk the pieces back to front so that earlier piece indices stay valid.
        for (c, i, splices) in pending.into_iter().rev() {
            let mut inner: Vec<u32> = Vec::with_capacity(splices.len());
            for s in splices {
                let v = match s {
                    Splice::Existing(v) => Some(v),
                    Splice::New(p) => st.insert(p)?,
                };
                if let Some(v) = v {
                    let chain = &st.chains[c];
                    if v != chain[i] && v != chain[i + 1] && inner.last() != Some(&v) {
                        inner.push(v);
                    }
                }
            }
            if !inner.is_empty() {
                changed = true;
                st.chains[c].splice(i + 1..i + 1, inner);
            }
        }
        Ok(changed)
    }

    /// Sec. 5: places the circle points and the middle pieces. The inner result is the number
    /// of points placed, or the reason the construction was not attempted.
    fn construct(
        &self,
        st: &mut State,
        dom: &Pslg,
        params: &Params,
    ) -> Result<std::result::Result<usize, StopReason>> {
        let pts = &dom.points;
        let seg = |s: [u32; 2]| (pts[s[0] as usize], pts[s[1] as usize]);
        // ε: the closest pair is a Delaunay edge; vertex–segment distances are checked directly.
        let mut eps = min_dt_edge(&st.dt);
        for s in &dom.segments {
            let (a, b) = seg(*s);
            for (v, &p) in pts.iter().enumerate() {
                if v as u32 != s[0] && v as u32 != s[1] {
                    eps = eps.min(point_segment_distance(p, a, b));
                }
            }
        }
        let circle: Vec<(Point, Point)> = dom
            .segments
            .iter()
            .map(|s| {
                let (a, b) = seg(*s);
                let f = eps / 3.0 / dist(a, b);
                let d = [b[0] - a[0], b[1] - a[1]];
                (
                    [a[0] + f * d[0], a[1] + f * d[1]],
                    [b[0] - f * d[0], b[1] - f * d[1]],
                )
            })
            .collect();
        // δ over the augmented set: again the shortest Delaunay edge.
        let mut aug = st.dt.clone();
        for &(c1, c2) in &circle {
            for c in [c1, c2] {
                aug.insert(to_spade(c))
                    .map_err(|e| insertion_error("saalfeld", e))?;
            }
        }
        let delta = min_dt_edge(&aug);
        let mut pieces = Vec::with_capacity(dom.segments.len());
        let mut total = 2 * dom.segments.len();
        for (k, s) in dom.segments.iter().enumerate() {
            let (a, b) = seg(*s);
            let mut g = f64::INFINITY;
            for (v, &p) in pts.iter().enumerate() {
                if v as u32 != s[0] && v as u32 != s[1] {
                    g = g.min(point_segment_distance(p, a, b));
                }
            }
            for (j, &(c1, c2)) in circle.iter().enumerate() {
                if j != k {
                    g = g
                        .min(point_segment_distance(c1, a, b))
                        .min(point_segment_distance(c2, a, b));
                }
            }
            let h = delta.min(g);
            let middle = dist(circle[k].0, circle[k].1);
            let n = (middle / h).floor();
            if !n.is_finite() || n >= CONSTRUCTIVE_CAP as f64 {
                // Pieces of length h on this segment alone exceed the construction's cap.
                return Ok(Err(StopReason::VertexLimit {
                    needed: if n.is_finite() {
                        n as usize
                    } else {
                        usize::MAX
                    },
                    limit: CONSTRUCTIVE_CAP,
                }));
            }
            let n = n as usize + 1;
            total += n - 1;
            pieces.push(n);
        }
        let cap = params
            .budget
            .max_vertices
            .map_or(CONSTRUCTIVE_CAP, |m| m.min(CONSTRUCTIVE_CAP));
        if st.points.len() + total > cap {
            return Ok(Err(StopReason::VertexLimit {
                needed: st.points.len() + total,
                limit: cap,
            }));
        }
        // Placed points go in by one bulk load: inserted one by one, the points rounded just
        // outside a hull edge each add a fan of slivers, which is quadratic.
        let before = st.points.len();
        let mut at: HashMap<[u64; 2], u32> = st
            .points
            .iter()
            .enumerate()
            .map(|(i, p)| ([(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits()], i as u32))
            .collect();
        let mut placed: Vec<Point> = st.points.clone();
        for (k, s) in dom.segments.iter().enumerate() {
            let (c1, c2) = circle[k];
            let n = pieces[k];
            let mut targets = vec![c1];
            targets.extend((1..n).map(|j| {
                let t = j as f64 / n as f64;
                [c1[0] + t * (c2[0] - c1[0]), c1[1] + t * (c2[1] - c1[1])]
            }));
            targets.push(c2);
            let mut chain = vec![s[0]];
            for p in targets {
                let q = to_spade(p);
                let key = [(q.x + 0.0).to_bits(), (q.y + 0.0).to_bits()];
                // A rounded point may land on an existing one: the chain goes through it.
                let v = *at.entry(key).or_insert_with(|| {
                    placed.push([q.x, q.y]);
                    (placed.len() - 1) as u32
                });
                if chain.last() != Some(&v) && v != s[1] {
                    chain.push(v);
                }
            }
            chain.push(s[1]);
            st.chains[k] = chain;
        }
        // Inserted along each segment in order, each point with its predecessor as the hint,
        // so that locating it is a short walk.
        let mut hint: Option<FixedVertexHandle> = None;
        for v in before as u32..placed.len() as u32 {
            let p = to_spade(placed[v as usize]);
            let h = match hint {
                Some(hh) => st.dt.insert_with_hint(p, hh),
                None => st.dt.insert(p),
            }
            .map_err(|e| insertion_error("saalfeld", e))?;
            if idx(h) as usize != st.to_sp.len() {
                return Err(crate::error::Error::mesher(
                    "saalfeld",
                    "spade merged two placed points",
                ));
            }
            st.to_sp.push(idx(h));
            st.from_sp.push(v);
            hint = Some(h);
        }
        st.points = placed;
        Ok(Ok(st.points.len() - before))
    }

    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        st: State,
        dom: Pslg,
        n_input: usize,
        constructive_points: usize,
        rounds: u32,
        complete: bool,
        stop: Option<StopReason>,
        limits: &Limits,
    ) -> Result<ConformingRun> {
        let triangles: Vec<[u32; 3]> = spade_triangles(&st.dt)
            .into_iter()
            .map(|t| t.map(|v| st.from_sp[v as usize]))
            .collect();
        let barriers: HashSet<(u32, u32)> = st
            .chains
            .iter()
            .flat_map(|c| c.windows(2).map(|w| ekey(w[0], w[1])))
            .collect();
        let kept = carve(&st.points, &triangles, &barriers, &dom.holes);
        let (vertices, triangles, map) = compact(&st.points, &kept);
        let chains = st
            .chains
            .iter()
            .map(|c| c.iter().filter_map(|&v| map[v as usize]).collect())
            .collect();
        // A stopped run may leak the flood through a missing chain piece; it says so itself.
        if vertices.is_empty() && complete {
            return Err(crate::error::Error::mesher(
                "saalfeld",
                "the segments enclose no region to mesh",
            ));
        }
        let added = st.points.len() - n_input;
        Ok(ConformingRun {
            run: MeshRun {
                mesh: TriMesh {
                    vertices,
                    triangles,
                },
                complete,
                stop_reason: if complete { None } else { stop },
                steps: added as u64,
                elapsed: limits.elapsed(),
            },
            domain: dom,
            chains,
            added_points: added,
            constructive_points,
            rounds,
        })
    }
}

impl Mesher for Saalfeld {
    fn name(&self) -> &'static str {
        if self.constructive {
            "saalfeld-sec5"
        } else {
            "saalfeld"
        }
    }

    fn version(&self) -> String {
        format!("hexmesh {}", env!("CARGO_PKG_VERSION"))
    }

    fn settings(&self, params: &Params) -> String {
        let variant = if self.constructive {
            "constructive (Sec. 5: circles of radius eps/3, middle pieces < min(delta, g_s)), then Sec. 6 rounds"
        } else {
            "iterative (Sec. 6: segments x DT of the growing vertex set until no crossing)"
        };
        let ignored = match (params.min_angle, params.max_area) {
            (None, None) => String::new(),
            _ => "; min-angle and max-area ignored (conforming Delaunay, no quality refinement)"
                .into(),
        };
        format!(
            "{variant}; max {} rounds; point sets meshed in their bounding hexagon; steps = points added{ignored}",
            self.max_rounds
        )
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, _: &Params) -> Bounds {
        Bounds::conforming_delaunay(self.name())
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        crate::mesher::refuse_area_limits(self.name(), input)?;
        params.refuse_switches(self.name())?;
        params.refuse_max_edge(
            self.name(),
            "a conforming Delaunay triangulation without size refinement",
        )?;
        Ok(self.refine(input, params)?.run)
    }
}
