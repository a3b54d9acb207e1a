//! Modified longest-side bisection after C. Stamm, S. Eidenbenz, R. Pajarola, "A Modified
//! Longest Side Bisection Triangulation".
//!
//! A triangle ABC with longest side AB (midpoint C', A' and B' the midpoints of BC and AC,
//! |BC| ≤ |AC|) is bisected along CC' (Definition 2.1) unless condition (2)
//! |BC| ≥ |CC'| ≥ |BC'| holds; then it is split into four similar triangles by A'B'
//! (Definition 3.2), which keeps every angle ≥ 2/3 of the smallest angle of the triangle it
//! descends from (Theorem 3.4; plain bisection keeps ≥ 1/2, Rosenberg & Stenger).
//!
//! Refinement is conforming (Rivara propagation, Sec. 2): an edge is split only when it is a
//! longest side of both triangles on it; otherwise the neighbour's longest side is split first.
//! Adaptive refinement follows Sec. 4: a heap yields the longest edge to split, and rule 4.1
//! applies the quaternary split lazily. A (2)-triangle is bisected first; when both of its
//! children have been bisected (along AC and BC, their longest sides by Lemma 3.1), the edge
//! CC' between them is flipped to A'B', which turns the four grandchildren into the four
//! similar triangles of Definition 3.2. Uniform refinement applies Definition 3.2 to every
//! triangle alive at the start of a level; triangles that propagation bisects during the level
//! are left to rule 4.1 (see `Engine::uniform_level` for why). Theorem 3.4 itself speaks of
//! the family T(A, B, C) of one triangle, which is not conforming: `family` builds it.
//!
//! Midpoints are rounded to f64, so a bisected input segment is a chain of mesh edges whose
//! inner vertices lie within rounding of the segment (see `saalfeld.rs` for the same choice).

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap, HashMap};

use super::{domain, ekey, Limits};
use crate::error::{Error, Result};
use crate::geom::{dist2, orient2d, Point};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{Budget, MeshRun, Mesher, Params, StopReason};
use crate::quality::{Bounds, LSB_ADAPTIVE_RATIO};

/// The longest-side bisection mesher: `plain` selects plain bisection (Definition 2.1) instead
/// of the modified rule (Definition 3.2 / rule 4.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Lsb {
    /// Plain longest-side bisection (mesher `lsb-plain`) instead of the modified rule.
    pub plain: bool,
}

/// When adaptive refinement stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// Every edge at most this long.
    MaxEdge(f64),
    /// Every triangle's area at most this.
    MaxArea(f64),
    /// Every triangle's area at most `area` and every edge at most `edge` long.
    AreaAndEdge {
        /// The largest area.
        area: f64,
        /// The longest edge.
        edge: f64,
    },
}

/// A refined mesh with its ancestry and the figures a report compares.
#[derive(Debug, Clone, PartialEq)]
pub struct LsbRun {
    /// The mesh; `run.steps` counts edge splits.
    pub run: MeshRun,
    /// The triangulation refinement started from.
    pub initial: TriMesh,
    /// For every triangle of `run.mesh`, the index of the triangle of `initial` it lies in.
    pub parents: Vec<u32>,
    /// For every segment of the domain (empty when refining a bare mesh), its chain of
    /// vertex indices from its first endpoint to its second.
    pub chains: Vec<Vec<u32>>,
    /// Quaternary splits completed by flipping CC' to A'B'.
    pub quaternary_splits: u64,
    /// `lsb_descent_check(initial, mesh, parents)`: the smallest ratio of an output angle to
    /// the smallest angle of the initial triangle it descends from.
    pub min_descent_ratio: f64,
    /// What refinement aimed for (`None` for uniform refinement).
    pub target: Option<Target>,
}

/// The smallest angle of triangle `t`, in radians.
pub fn min_angle(mesh: &TriMesh, t: usize) -> f64 {
    smallest_angle(mesh.corners(t))
}

/// The smallest angle of the triangle with corners `c`, in radians.
fn smallest_angle(c: [Point; 3]) -> f64 {
    (0..3)
        .map(|k| crate::geom::angle_deg(c[k], c[(k + 1) % 3], c[(k + 2) % 3]).to_radians())
        .fold(f64::INFINITY, f64::min)
}

/// Theorem 3.4's quantity: the smallest, over the triangles of `refined`, of its smallest
/// angle divided by the smallest angle of the triangle `initial.triangles[parents[t]]` it
/// descends from. ≥ 2/3 under modified refinement, ≥ 1/2 under plain bisection.
/// Infinity when `refined` has no triangles; NaN when `parents` names a missing triangle.
pub fn lsb_descent_check(initial: &TriMesh, refined: &TriMesh, parents: &[u32]) -> f64 {
    let base: Vec<f64> = (0..initial.triangles.len())
        .map(|t| min_angle(initial, t))
        .collect();
    (0..refined.triangles.len())
        .map(
            |t| match parents.get(t).and_then(|&p| base.get(p as usize)) {
                Some(&b) => min_angle(refined, t) / b,
                None => f64::NAN,
            },
        )
        .fold(f64::INFINITY, |m, r| {
            if r.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.min(r)
            }
        })
}

/// A quaternary split waiting for its second child to be bisected: [A, B, C, C'].
type Pending = [u32; 4];

/// The refinement state: triangles are replaced, never edited, so indices stay stable.
struct Engine {
    v: Vec<Point>,
    t: Vec<[u32; 3]>,
    alive: Vec<bool>,
    root: Vec<u32>,
    by_edge: HashMap<(u32, u32), u32>,
    mid: HashMap<(u32, u32), u32>,
    /// Keyed by CC'; a BTreeMap so that finishing them runs in a fixed order.
    pending: BTreeMap<(u32, u32), Pending>,
    modified: bool,
    splits: u64,
    flips: u64,
    fresh: Vec<u32>,
    limits: Limits,
    stop: Option<StopReason>,
}

fn len2(v: &[Point], a: u32, b: u32) -> f64 {
    dist2(v[a as usize], v[b as usize])
}

impl Engine {
    fn new(mesh: &TriMesh, modified: bool, budget: Budget) -> Result<Engine> {
        let mut e = Engine {
            v: mesh.vertices.clone(),
            t: Vec::with_capacity(mesh.triangles.len() * 4),
            alive: Vec::new(),
            root: Vec::new(),
            by_edge: HashMap::new(),
            mid: HashMap::new(),
            pending: BTreeMap::new(),
            modified,
            splits: 0,
            flips: 0,
            fresh: Vec::new(),
            limits: Limits::new(budget),
            stop: None,
        };
        for (i, &tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|x| mesh.vertices.get(x as usize).copied());
            let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                return Err(Error::mesher(
                    "lsb",
                    format!("triangle {i} names a missing vertex"),
                ));
            };
            if orient2d(a, b, c) <= 0.0 {
                return Err(Error::mesher(
                    "lsb",
                    format!("triangle {i} is not counter-clockwise with positive area"),
                ));
            }
            for k in 0..3 {
                if e.by_edge.contains_key(&(tri[k], tri[(k + 1) % 3])) {
                    return Err(Error::mesher(
                        "lsb",
                        format!(
                            "edge {}-{} is used twice in one direction",
                            tri[k],
                            tri[(k + 1) % 3]
                        ),
                    ));
                }
            }
            e.add(tri, i as u32);
        }
        e.fresh.clear();
        Ok(e)
    }

    fn add(&mut self, tri: [u32; 3], root: u32) -> u32 {
        let id = self.t.len() as u32;
        for k in 0..3 {
            self.by_edge.insert((tri[k], tri[(k + 1) % 3]), id);
        }
        self.t.push(tri);
        self.alive.push(true);
        self.root.push(root);
        self.fresh.push(id);
        id
    }

    fn kill(&mut self, id: u32) {
        let tri = self.t[id as usize];
        for k in 0..3 {
            self.by_edge.remove(&(tri[k], tri[(k + 1) % 3]));
        }
        self.alive[id as usize] = false;
    }

    /// Rotates triangle `id` so that it reads (x, y, w) with x→y its edge `from`.
    fn rotated(&self, id: u32, from: u32) -> [u32; 3] {
        let [a, b, c] = self.t[id as usize];
        if a == from {
            [a, b, c]
        } else if b == from {
            [b, c, a]
        } else {
            [c, a, b]
        }
    }

    /// The longest side of triangle `id` as a directed edge; ties go to the smallest vertex
    /// pair so that every run makes the same choice.
    fn longest(&self, id: u32) -> (u32, u32) {
        let tri = self.t[id as usize];
        (0..3)
            .map(|k| (tri[k], tri[(k + 1) % 3]))
            .max_by(|&(a, b), &(c, d)| {
                len2(&self.v, a, b)
                    .total_cmp(&len2(&self.v, c, d))
                    .then_with(|| ekey(c, d).cmp(&ekey(a, b)))
            })
            .unwrap_or((tri[0], tri[1]))
    }

    /// True when x→y is a longest side of triangle `id` (ties count).
    fn is_a_longest(&self, id: u32, x: u32, y: u32) -> bool {
        let tri = self.t[id as usize];
        let l = len2(&self.v, x, y);
        (0..3).all(|k| len2(&self.v, tri[k], tri[(k + 1) % 3]) <= l)
    }

    fn area(&self, id: u32) -> f64 {
        let [a, b, c] = self.t[id as usize].map(|x| self.v[x as usize]);
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    }

    /// Splits edge ab at its midpoint in every triangle on it, after Rivara propagation has
    /// made it a longest side of each. `Ok(None)` when a budget stopped the refinement or the
    /// edge is no longer in the mesh (a flip during propagation removed it).
    fn split_edge(&mut self, a: u32, b: u32) -> Result<Option<u32>> {
        if self.stop.is_some() {
            return Ok(None);
        }
        // Each propagated split is along a strictly longer edge, so this terminates.
        loop {
            if let Some(&m) = self.mid.get(&ekey(a, b)) {
                return Ok(Some(m));
            }
            let mut propagated = false;
            for (x, y) in [(a, b), (b, a)] {
                if let Some(&id) = self.by_edge.get(&(x, y)) {
                    if !self.is_a_longest(id, x, y) {
                        let (p, q) = self.longest(id);
                        self.split_edge(p, q)?;
                        if self.stop.is_some() {
                            return Ok(None);
                        }
                        propagated = true;
                        break;
                    }
                }
            }
            if !propagated {
                break;
            }
        }
        if !self.by_edge.contains_key(&(a, b)) && !self.by_edge.contains_key(&(b, a)) {
            return Ok(None);
        }
        if let Some(reason) = self.limits.exceeded(self.splits, self.v.len() + 1) {
            self.stop = Some(reason);
            return Ok(None);
        }
        let (pa, pb) = (self.v[a as usize], self.v[b as usize]);
        let m = self.v.len() as u32;
        self.v.push([(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0]);
        let mut made = Vec::with_capacity(4);
        for (x, y) in [(a, b), (b, a)] {
            let Some(&id) = self.by_edge.get(&(x, y)) else {
                continue;
            };
            let [_, _, w] = self.rotated(id, x);
            let root = self.root[id as usize];
            if self.modified && self.condition2(x, y, w, m) {
                let (big, small) = if len2(&self.v, y, w) <= len2(&self.v, x, w) {
                    (x, y)
                } else {
                    (y, x)
                };
                self.pending.insert(ekey(w, m), [big, small, w, m]);
            }
            self.kill(id);
            for tri in [[x, m, w], [m, y, w]] {
                if orient2d(
                    self.v[tri[0] as usize],
                    self.v[tri[1] as usize],
                    self.v[tri[2] as usize],
                ) <= 0.0
                {
                    return Err(Error::mesher(
                        "lsb",
                        "a rounded midpoint produced an inverted triangle (the mesh is too thin for f64)",
                    ));
                }
                made.push(self.add(tri, root));
            }
        }
        self.mid.insert(ekey(a, b), m);
        self.splits += 1;
        if self.modified {
            for id in made {
                let tri = self.t[id as usize];
                for k in 0..3 {
                    let key = ekey(tri[k], tri[(k + 1) % 3]);
                    if self.pending.contains_key(&key) {
                        self.try_flip(key);
                    }
                }
            }
        }
        Ok(Some(m))
    }

    /// Condition (2) for triangle (x, y, w) bisected along its longest side xy at m:
    /// with C = w and B the end of xy nearer to C, |BC| ≥ |CC'| ≥ |BC'|. Squared lengths in
    /// f64: the test picks between two valid splits, it decides no topology.
    fn condition2(&self, x: u32, y: u32, w: u32, m: u32) -> bool {
        let p = |i: u32| self.v[i as usize];
        condition2_points(p(x), p(y), p(w), p(m))
    }

    /// Rule 4.1: once both children of a (2)-triangle are bisected, flip CC' to A'B'.
    fn try_flip(&mut self, key: (u32, u32)) -> bool {
        let Some(&[a, b, c, cp]) = self.pending.get(&key) else {
            return false;
        };
        let (Some(&bp), Some(&ap)) = (self.mid.get(&ekey(a, c)), self.mid.get(&ekey(b, c))) else {
            return false;
        };
        let (Some(&t1), Some(&t2)) = (self.by_edge.get(&(c, cp)), self.by_edge.get(&(cp, c)))
        else {
            // CC' itself was split (a tie in the longest side): the quaternary is gone.
            self.pending.remove(&key);
            return false;
        };
        let [x, y, p] = self.rotated(t1, c);
        let [_, _, q] = self.rotated(t2, cp);
        let ok_pair = (p == ap && q == bp) || (p == bp && q == ap);
        let new = [[x, q, p], [q, y, p]];
        let convex = new.iter().all(|t| {
            orient2d(
                self.v[t[0] as usize],
                self.v[t[1] as usize],
                self.v[t[2] as usize],
            ) > 0.0
        });
        // Both midpoints exist, so the state around CC' can only get finer: decide now.
        self.pending.remove(&key);
        if !ok_pair || !convex || self.root[t1 as usize] != self.root[t2 as usize] {
            return false;
        }
        let root = self.root[t1 as usize];
        self.kill(t1);
        self.kill(t2);
        for tri in new {
            self.add(tri, root);
        }
        self.flips += 1;
        true
    }

    /// Definition 3.2 for one pending quaternary: bisects the children not yet bisected, then
    /// flips.
    fn finish_quaternary(&mut self, key: (u32, u32)) -> Result<()> {
        let Some(&[a, b, c, cp]) = self.pending.get(&key) else {
            return Ok(());
        };
        if !self.pending_alive([a, b, c, cp]) {
            self.pending.remove(&key);
            return Ok(());
        }
        for (s, child) in [(a, [a, cp, c]), (b, [cp, b, c])] {
            if self.stop.is_some() {
                return Ok(());
            }
            if self.mid.contains_key(&ekey(s, c)) {
                continue;
            }
            let exists = [(child[0], child[1]), (child[1], child[0])]
                .iter()
                .any(|e| {
                    self.by_edge
                        .get(e)
                        .is_some_and(|&id| self.t[id as usize].contains(&child[2]))
                });
            if !exists {
                continue;
            }
            self.split_edge(s, c)?;
        }
        if self.pending.contains_key(&key) && self.stop.is_none() {
            // The flip did not happen (a child was cut differently): leave it bisected.
            self.pending.remove(&key);
        }
        Ok(())
    }

    /// True while the two triangles on CC' are the children of the recorded (2)-triangle ABC,
    /// or their bisections along AC and BC. A flip elsewhere (of the parent's own quaternary)
    /// can remove a child; the record is then dead and must not drive further splits.
    fn pending_alive(&self, [a, b, c, cp]: Pending) -> bool {
        let (Some(&t1), Some(&t2)) = (self.by_edge.get(&(c, cp)), self.by_edge.get(&(cp, c)))
        else {
            return false;
        };
        let p = self.rotated(t1, c)[2];
        let q = self.rotated(t2, cp)[2];
        let side = |s: u32, x: u32| x == s || self.mid.get(&ekey(s, c)) == Some(&x);
        (side(a, p) && side(b, q)) || (side(a, q) && side(b, p))
    }

    /// One level of uniform refinement: every triangle alive at the start is split once by
    /// Definition 3.2 (into four when (2) holds and the rule is modified, else bisected). A
    /// start triangle that Rivara propagation already bisected is completed to its four at
    /// its turn. Triangles made during the level and bisected by propagation are left to
    /// rule 4.1: completing them too would split edges shorter than the longest, which can
    /// cascade to ever smaller triangles (propagation is well-founded only towards longer
    /// edges), so a conforming mesh cannot in general stay inside the family T(A, B, C).
    fn uniform_level(&mut self) -> Result<()> {
        let start: Vec<u32> = (0..self.t.len() as u32)
            .filter(|&i| self.alive[i as usize])
            .collect();
        for id in start {
            if self.stop.is_some() {
                return Ok(());
            }
            if self.alive[id as usize] {
                let (a, b) = self.longest(id);
                let Some(m) = self.split_edge(a, b)? else {
                    // Stopped by the budget, or a flip during propagation took the edge away.
                    continue;
                };
                let [_, _, w] = self.rotated_any(id, a, b);
                if self.modified {
                    self.finish_quaternary(ekey(w, m))?;
                }
            } else if self.modified {
                let tri = self.t[id as usize];
                for k in 0..3 {
                    let (x, y, w) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    let Some(&m) = self.mid.get(&ekey(x, y)) else {
                        continue;
                    };
                    let key = ekey(w, m);
                    let mine = self
                        .pending
                        .get(&key)
                        .is_some_and(|r| r[2] == w && ekey(r[0], r[1]) == ekey(x, y) && r[3] == m);
                    if mine {
                        self.finish_quaternary(key)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The vertex of (dead or alive) triangle `id` opposite edge ab, as [a, b, w].
    fn rotated_any(&self, id: u32, a: u32, b: u32) -> [u32; 3] {
        let tri = self.t[id as usize];
        let w = tri
            .iter()
            .copied()
            .find(|&x| x != a && x != b)
            .unwrap_or(tri[2]);
        [a, b, w]
    }

    /// Sec. 4: splits the longest edge first until every triangle meets `target`.
    fn adaptive(&mut self, target: Target) -> Result<()> {
        let needs = |e: &Engine, id: u32| match target {
            Target::MaxEdge(l) => {
                let (a, b) = e.longest(id);
                len2(&e.v, a, b) > l * l
            }
            Target::MaxArea(area) => e.area(id) > area,
            Target::AreaAndEdge { area, edge } => {
                let (a, b) = e.longest(id);
                len2(&e.v, a, b) > edge * edge || e.area(id) > area
            }
        };
        // Keys: squared length (non-negative f64 bits order as the numbers do), then the
        // smaller vertex pair first among equals, for a fixed order.
        let mut heap: BinaryHeap<(u64, Reverse<(u32, u32)>)> = BinaryHeap::new();
        let push = |e: &Engine, heap: &mut BinaryHeap<_>, id: u32| {
            if e.alive[id as usize] && needs(e, id) {
                let (a, b) = e.longest(id);
                heap.push((len2(&e.v, a, b).to_bits(), Reverse(ekey(a, b))));
            }
        };
        for id in 0..self.t.len() as u32 {
            push(self, &mut heap, id);
        }
        self.fresh.clear();
        while let Some((_, Reverse((a, b)))) = heap.pop() {
            if self.stop.is_some() {
                break;
            }
            let wanted = [(a, b), (b, a)].iter().any(|&(x, y)| {
                self.by_edge
                    .get(&(x, y))
                    .is_some_and(|&id| self.is_a_longest(id, x, y) && needs(self, id))
            });
            if !wanted {
                continue;
            }
            self.split_edge(a, b)?;
            let fresh = std::mem::take(&mut self.fresh);
            for id in fresh {
                push(self, &mut heap, id);
            }
        }
        Ok(())
    }

    fn chain(&self, a: u32, b: u32, out: &mut Vec<u32>) {
        match self.mid.get(&ekey(a, b)) {
            Some(&m) => {
                self.chain(a, m, out);
                self.chain(m, b, out);
            }
            None => out.push(b),
        }
    }

    fn into_run(self, initial: TriMesh, segments: &[[u32; 2]], target: Option<Target>) -> LsbRun {
        let mut triangles = Vec::new();
        let mut parents = Vec::new();
        for (id, tri) in self.t.iter().enumerate() {
            if self.alive[id] {
                triangles.push(*tri);
                parents.push(self.root[id]);
            }
        }
        let chains = segments
            .iter()
            .map(|s| {
                let mut c = vec![s[0]];
                self.chain(s[0], s[1], &mut c);
                c
            })
            .collect();
        let mesh = TriMesh {
            vertices: self.v,
            triangles,
        };
        let ratio = lsb_descent_check(&initial, &mesh, &parents);
        LsbRun {
            run: MeshRun {
                mesh,
                complete: self.stop.is_none(),
                stop_reason: self.stop,
                steps: self.splits,
                elapsed: self.limits.elapsed(),
            },
            initial,
            parents,
            chains,
            quaternary_splits: self.flips,
            min_descent_ratio: ratio,
            target,
        }
    }
}

/// Splits one triangle by Definition 3.2 (or 2.1 when `plain`), without regard to its
/// neighbours: the step that generates the family T(A, B, C) of Definition 3.3.
fn split_alone(t: [Point; 3], plain: bool) -> Vec<[Point; 3]> {
    let k = (0..3)
        .max_by(|&i, &j| dist2(t[i], t[(i + 1) % 3]).total_cmp(&dist2(t[j], t[(j + 1) % 3])))
        .unwrap_or(0);
    let (x, y, w) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
    let mid = |p: Point, q: Point| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
    let m = mid(x, y);
    if !plain && condition2_points(x, y, w, m) {
        let (mx, my) = (mid(y, w), mid(w, x));
        vec![[x, m, my], [m, y, mx], [my, mx, w], [m, mx, my]]
    } else {
        vec![[x, m, w], [m, y, w]]
    }
}

/// Condition (2) on coordinates; see `Engine::condition2`.
fn condition2_points(x: Point, y: Point, w: Point, m: Point) -> bool {
    let bc = dist2(x, w).min(dist2(y, w));
    let cc = dist2(w, m);
    bc >= cc && cc >= dist2(x, y) / 4.0
}

/// The family T(A, B, C) of Definition 3.3 to depth `levels`, for every triangle of `initial`
/// independently (no conformity): the set Theorem 3.4 speaks about. Returned as a triangle
/// soup (three vertices per triangle) with, for every triangle, its initial triangle.
pub fn family(initial: &TriMesh, levels: u32, plain: bool) -> (TriMesh, Vec<u32>) {
    let mut soup = TriMesh::default();
    let mut parents = Vec::new();
    for t in 0..initial.triangles.len() {
        for tri in family_of(initial.corners(t), levels, plain) {
            let base = soup.vertices.len() as u32;
            soup.vertices.extend(tri);
            soup.triangles.push([base, base + 1, base + 2]);
            parents.push(t as u32);
        }
    }
    (soup, parents)
}

/// The family T(A, B, C) of triangle `root`, `levels` splits deep: every triangle each split
/// of `split_alone` makes, level by level.
fn family_of(root: [Point; 3], levels: u32, plain: bool) -> Vec<[Point; 3]> {
    let mut gen = vec![root];
    for _ in 0..levels {
        gen = gen
            .into_iter()
            .flat_map(|x| split_alone(x, plain))
            .collect();
    }
    gen
}

/// Theorem 3.4's quantity over the family T(A, B, C) of every triangle of `initial`, `levels`
/// deep, without building the soup: the smallest ratio of a descendant's smallest angle to its
/// ancestor's. Memory is one triangle's family (at most 4^levels triangles), so it runs on a
/// million-triangle triangulation too. Infinity when `initial` has no triangles.
pub fn family_min_ratio(initial: &TriMesh, levels: u32, plain: bool) -> f64 {
    let mut ratio = f64::INFINITY;
    for t in 0..initial.triangles.len() {
        let root = initial.corners(t);
        let base = smallest_angle(root);
        for tri in family_of(root, levels, plain) {
            ratio = ratio.min(smallest_angle(tri) / base);
        }
    }
    ratio
}

impl Lsb {
    /// Refines `mesh` uniformly: `levels` times, every triangle is split once (Definition 3.2
    /// for the modified rule, with Rivara propagation keeping the mesh conforming).
    pub fn refine_uniform(&self, mesh: &TriMesh, levels: u32, budget: Budget) -> Result<LsbRun> {
        let mut e = Engine::new(mesh, !self.plain, budget)?;
        for _ in 0..levels {
            e.uniform_level()?;
            if e.stop.is_some() {
                break;
            }
        }
        Ok(e.into_run(mesh.clone(), &[], None))
    }

    /// Refines `mesh` adaptively (Sec. 4, longest edge first, rule 4.1) until `target` holds.
    /// `segments` (vertex pairs that are edges of `mesh`) are reported back as chains.
    pub fn refine_to(
        &self,
        mesh: &TriMesh,
        segments: &[[u32; 2]],
        target: Target,
        budget: Budget,
    ) -> Result<LsbRun> {
        let mut e = Engine::new(mesh, !self.plain, budget)?;
        e.adaptive(target)?;
        Ok(e.into_run(mesh.clone(), segments, Some(target)))
    }

    /// The target `params` asks for: `max_area` and the input regions' area limits (the
    /// smallest of them, everywhere: `Pslg::smallest_area_limit`) and `max_edge`, or, when
    /// neither is given, every edge below 1/20 of the diagonal of the domain's bounding box.
    pub fn target(input: &Pslg, params: &Params) -> Result<Target> {
        input.validate_input()?;
        let (_, max_edge) = params.size_limits()?;
        let area = match input.smallest_area_limit(params.max_area) {
            Some(a) if !(a.is_finite() && a > 0.0) => {
                return Err(Error::Usage(format!(
                    "max-area must be a positive finite number, not {a}"
                )))
            }
            area => area,
        };
        Ok(match (area, max_edge) {
            (Some(area), Some(edge)) => Target::AreaAndEdge { area, edge },
            (Some(a), None) => Target::MaxArea(a),
            (None, Some(l)) => Target::MaxEdge(l),
            (None, None) => {
                let d = domain(input);
                let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for p in &d.points {
                    for k in 0..2 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                Target::MaxEdge(((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt() / 20.0)
            }
        })
    }

    /// The initial triangulation: the constrained Delaunay triangulation of the domain (a PSLG,
    /// or a point set in its bounding hexagon), without the triangles outside it or in holes
    /// ([`super::domain_cdt`]). Returns the mesh and the domain's segments renumbered to its
    /// vertices.
    pub fn initial(input: &Pslg) -> Result<(TriMesh, Vec<[u32; 2]>)> {
        super::domain_cdt(input, "lsb")
    }

    /// Meshes `input`: its initial triangulation refined adaptively to `Lsb::target`.
    pub fn refine(&self, input: &Pslg, params: &Params) -> Result<LsbRun> {
        let start = std::time::Instant::now();
        // Before anything fits a hexagon to the points: NaN would never fit.
        input.validate_input()?;
        let target = Lsb::target(input, params)?;
        let (initial, segments) = Lsb::initial(input)?;
        let mut budget = params.budget;
        if let Some(t) = budget.max_time.as_mut() {
            *t = t.saturating_sub(start.elapsed());
        }
        let mut run = self.refine_to(&initial, &segments, target, budget)?;
        run.run.elapsed = start.elapsed();
        Ok(run)
    }
}

impl Mesher for Lsb {
    fn name(&self) -> &'static str {
        if self.plain {
            "lsb-plain"
        } else {
            "lsb"
        }
    }

    fn version(&self) -> String {
        format!("hexmesh {}", env!("CARGO_PKG_VERSION"))
    }

    fn settings(&self, params: &Params) -> String {
        let rule = if self.plain {
            "plain longest-side bisection (Def. 2.1)"
        } else {
            "modified longest-side bisection (Def. 3.2, rule 4.1)"
        };
        let target = match (params.max_area, params.max_edge) {
            (Some(a), Some(l)) => format!("until every triangle's area <= {a} and edge <= {l}"),
            (Some(a), None) => format!("until every triangle's area <= {a}"),
            (None, Some(l)) => format!("until every edge <= {l}"),
            (None, None) => {
                "until every edge <= bounding-box diagonal / 20 (no max-area given)".into()
            }
        };
        let ignored = if params.min_angle.is_some() {
            "; min-angle ignored (the bound is 2/3 of the initial triangulation's)"
        } else {
            ""
        };
        format!(
            "{rule}, Rivara propagation, longest-edge heap, {target}; initial CDT of the domain (point sets in their bounding hexagon){ignored}"
        )
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        // Paper 003: plain bisection and the adaptive refinement with rule 4.1 keep half the
        // smallest angle of the initial triangle (Sec. 4); 2/3 needs every quaternary split
        // completed, which only uniform refinement does (Theorem 3.4).
        Bounds::descent(self.name(), LSB_ADAPTIVE_RATIO)
            .with_size_limits(params.max_area, params.max_edge)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        params.refuse_switches(self.name())?;
        Ok(self.refine(input, params)?.run)
    }
}
