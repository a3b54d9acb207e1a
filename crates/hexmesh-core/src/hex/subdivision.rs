//! The adaptive hexagon hierarchy of paper 000 Sec. 3: split a full hexagon into a half-size
//! hexagon and six semi-hexagons, join two semi-hexagons that meet at their long edges into a
//! full hexagon (3.1), split counters (3.2, derived in `Key::split_counter`), and the balancing
//! rule (3.3): the level difference of adjacent (semi-)hexagons never exceeds one.
//!
//! The state is the set of subdivided hexagons; whether a lattice cell is a full hexagon, a
//! semi-hexagon (a fin of its unsubdivided parent) or not yet present follows from its parents
//! (`Key::parents`): an edge child is a full hexagon when both hexagons sharing its edge are
//! subdivided, and a semi-hexagon when only one is. Cells whose centre lies outside the
//! bounding hexagon count as subdivided, which makes the boundary semi-hexagons virtual full
//! hexagons (Fig. 1).
//!
//! Point location rule: a point belongs to the cell reached by descending from the root. Inside
//! a subdivided hexagon it goes to the child cell (central or edge) whose constructed hexagon
//! contains it, tested exactly with `orient2d` on the bit-shared constructed corners (closed
//! cells); a point on the boundary of several children goes to the one with the smallest
//! (i, j) in lexicographic order. An edge child that is a semi-hexagon only receives points
//! through its subdivided parent, so the half owned by the other parent is never assigned to it.

use std::time::Instant;

use crate::error::InputError;
use crate::geom::{orient2d, Point};
use crate::hex::lattice::{FxHashMap, Key, KeySet, Lattice, Parents, MAX_LEVEL};
use crate::mesher::{Budget, Params, StopReason};

/// What a lattice cell is in the current subdivision.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cell {
    /// The centre lies outside the bounding hexagon.
    Outside,
    /// Covered by a coarser hexagon: no hexagon of this cell exists.
    Absent,
    /// A semi-hexagon: the half of the cell inside `owner` (subdivided, or outside), which is a
    /// fin of `fin_of`, the unsubdivided full hexagon across its long edge.
    Semi {
        /// The subdivided (or outside) parent holding the half.
        owner: Key,
        /// The unsubdivided parent it is a fin of.
        fin_of: Key,
    },
    /// A full hexagon (possibly a virtual one on the boundary).
    Full {
        /// Whether it is subdivided (not a leaf).
        subdivided: bool,
    },
}

/// Why the refinement stopped before it was done.
#[derive(Debug, Clone, PartialEq)]
pub enum Stop {
    /// A budget ran out.
    Budget(StopReason),
    /// The points are too close together for the lattice: f64 cannot place the hexagons
    /// they need within the rounding allowance, or they need more than `MAX_LEVEL` levels
    /// (`InputError::Rounding`, naming the two points).
    Precision(InputError),
}

/// The hexagon hierarchy with the input points distributed over its leaves.
#[derive(Debug, Clone)]
pub struct Hierarchy {
    /// The lattice of the bounding hexagon, which places every cell.
    pub lattice: Lattice,
    /// The input points; point i (0-based) is vertex i of the relocated dual.
    pub points: Vec<Point>,
    subdivided: KeySet,
    /// Input points per leaf (full unsubdivided hexagon or semi-hexagon); only occupied leaves.
    occupants: FxHashMap<Key, Vec<u32>>,
    /// The keys of `occupants`, as a block set: the rules ask whether a cell is occupied for
    /// every cell around each subdivision, and most are not, which a block set answers
    /// from the words it has just read where the table of lists misses the cache.
    occupied: KeySet,
    /// Cells whose rules must be re-examined.
    pub(crate) work: Vec<Key>,
    /// Hexagons subdivided since the log was last cleared (the extended rules re-examine the
    /// cells around them).
    pub(crate) log: Vec<Key>,
    /// Subdivisions so far (the mesher's steps).
    pub steps: u64,
    /// Full hexagons that are leaves, inside the bounding hexagon (about the dual's vertices).
    pub full_leaves: usize,
    budget: Budget,
    start: Instant,
    /// The largest rounding allowance (degrees) a finished mesh may use (`set_max_rounding`).
    max_rounding: f64,
    /// The threads long lists of independent work are split over (`set_threads`, `parallel`).
    threads: usize,
    /// The deepest level a hexagon has reached.
    deepest: u8,
    /// The level every full leaf reaches to keep the size limits (`hex::size`); 0 for none.
    size_level: u8,
    /// Hexagons that started or stopped being occupied, while `track_occupancy` is on (the
    /// extended rules bring their rings up to date from it).
    occupancy_changes: Option<Vec<Key>>,
}

impl Hierarchy {
    /// The root hexagon alone, holding every point. The caller has checked that each point lies
    /// strictly inside `lattice.root()`.
    pub fn new(lattice: Lattice, points: Vec<Point>, budget: Budget) -> Hierarchy {
        let mut occupants =
            FxHashMap::with_capacity_and_hasher(points.len() + 1, Default::default());
        let mut occupied = KeySet::default();
        if !points.is_empty() {
            occupants.insert(Key::ROOT, (0..points.len() as u32).collect());
            occupied.insert(Key::ROOT);
        }
        // About seven subdivisions per point on uniform sets: reserving spares the rehashing of
        // tables that outgrow the caches.
        let expected = 8 * points.len() + 64;
        Hierarchy {
            max_rounding: crate::quality::rounding::DEFAULT_MAX_ROUNDING_DEG,
            threads: Params::default().thread_count(),
            deepest: 0,
            size_level: 0,
            occupancy_changes: None,
            lattice,
            points,
            subdivided: KeySet::with_capacity(expected),
            occupants,
            occupied,
            work: Vec::new(),
            log: Vec::new(),
            steps: 0,
            full_leaves: 1,
            budget,
            start: Instant::now(),
        }
    }

    /// A hierarchy for a part of the points (a tile, `extended::tiles`): the root alone over
    /// `points`, with this one's lattice, budget and its clock (the time budget counts from
    /// the whole run's start), rounding allowance and size level, on one thread.
    pub(crate) fn part(&self, points: Vec<Point>) -> Hierarchy {
        let mut h = Hierarchy::new(self.lattice, points, self.budget);
        h.start = self.start;
        h.max_rounding = self.max_rounding;
        h.size_level = self.size_level;
        h.threads = 1;
        h
    }

    /// The subdivided hexagons, given up (a part's result, `part`).
    pub(crate) fn into_subdivided(self) -> KeySet {
        self.subdivided
    }

    /// Adds the subdivided hexagons of other hierarchies over the same lattice (parts of the
    /// points, `part`) to this one, unrefined or not, and gives each point the leaf the
    /// descent from the root finds for it. Each set given is a state some run of
    /// subdivisions reached, and a union of such states is one too: a subdivided hexagon's
    /// ancestors and the parents its neighbours need to be full (the balancing of Sec. 3.3)
    /// are in its own set, and a subdivision elsewhere makes no full cell a semi-hexagon.
    /// The steps count the hexagons added.
    pub(crate) fn absorb(&mut self, sets: impl IntoIterator<Item = KeySet>) {
        for set in sets {
            for key in set.iter() {
                if self.subdivided.insert(key) {
                    self.steps += 1;
                    self.deepest = self.deepest.max(key.k + 1);
                }
            }
        }
        self.occupants.clear();
        self.occupied = KeySet::default();
        // Each point's leaf is found over the threads (a descent of the levels each, a
        // quarter of a second for plane-100k's points on one thread), then entered in order.
        let me = &*self;
        let mut leaves = vec![Key::ROOT; me.points.len()];
        crate::hex::parallel::fill_in_parallel(me.threads, &mut leaves, 4096, |i| {
            me.leaf_of(me.points[i])
        });
        for (i, leaf) in leaves.into_iter().enumerate() {
            self.occupants.entry(leaf).or_default().push(i as u32);
            self.occupied.insert(leaf);
        }
        self.full_leaves = self.count_full_leaves();
    }

    /// How many full leaves `full_leaves_iter` gives, counted over the threads.
    fn count_full_leaves(&self) -> usize {
        let counts = self.in_subdivided_runs(|keys| {
            keys.map(|key| self.full_children(key).count())
                .sum::<usize>()
        });
        counts.iter().sum::<usize>() + usize::from(!self.subdivided.contains(&Key::ROOT))
    }

    /// `f` on runs of the subdivided hexagons, in the order of the subdivided set's
    /// iteration, over the hierarchy's threads (runs of its blocks, from 1,024 blocks on);
    /// the results in order.
    fn in_subdivided_runs<R: Send>(
        &self,
        f: impl Fn(&mut dyn Iterator<Item = Key>) -> R + Sync,
    ) -> Vec<R> {
        let blocks: Vec<(Key, u64)> = self.subdivided.blocks().collect();
        crate::hex::parallel::in_parallel_from(self.threads, &blocks, 1024, |run| {
            f(&mut run.iter().flat_map(|&(b, w)| KeySet::keys_in_block(b, w)))
        })
    }

    /// True when the hexagon of `key` is subdivided, counting cells outside the root as
    /// subdivided (they never constrain anything inside).
    pub fn is_subdivided_or_outside(&self, key: Key) -> bool {
        !key.inside() || self.subdivided.contains(&key)
    }

    /// True when the hexagon of `key` is subdivided (never for a cell outside the root).
    pub fn is_subdivided(&self, key: Key) -> bool {
        self.subdivided.contains(&key)
    }

    /// Whether `key` is subdivided, and the directions (bit d: `DIRS[d]`) in which its
    /// same-level neighbour is, inside the bounding hexagon or not.
    pub fn subdivided_neighbourhood(&self, key: Key) -> (bool, u8) {
        let m = self.subdivided.neighbourhood(key);
        (m & 0x40 != 0, m & 0x3f)
    }

    /// Which of the cells `key + offsets[n]` are subdivided, as bit n (`KeySet::mask_at`: the
    /// offsets stay within 8 cells of `key` along each axis).
    pub fn subdivided_at(&self, key: Key, offsets: &[(i64, i64)]) -> u32 {
        self.subdivided.mask_at(key, offsets)
    }

    /// For the 8 × 8 block of cells `block` (`KeySet` layout): which of them are subdivided,
    /// and which have a subdivided neighbour (inside the bounding hexagon: only cells inside
    /// are ever subdivided), as two words (`KeySet::block_and_beside`).
    pub fn subdivided_block(&self, block: Key) -> (u64, u64) {
        self.subdivided.block_and_beside(block)
    }

    /// The subdivided hexagons, sorted.
    pub fn subdivided_sorted(&self) -> Vec<Key> {
        let mut v: Vec<Key> = self.subdivided.iter().collect();
        v.sort_unstable_by_key(|k| k.packed());
        v
    }

    /// The input points assigned to a leaf.
    pub fn occupants(&self, key: Key) -> &[u32] {
        self.occupants.get(&key).map_or(&[], |v| v.as_slice())
    }

    /// The occupied leaves, in no particular order.
    pub fn occupied_unordered(&self) -> impl Iterator<Item = Key> + '_ {
        self.occupants.keys().copied()
    }

    /// The occupied leaves, sorted.
    pub fn occupied_sorted(&self) -> Vec<Key> {
        let mut v: Vec<Key> = self.occupants.keys().copied().collect();
        v.sort_unstable_by_key(|k| k.packed());
        v
    }

    /// True when the leaf `key` holds at least one input point.
    pub fn is_occupied(&self, key: Key) -> bool {
        self.occupied.contains(&key)
    }

    /// Appends point `p` to the input points and assigns it to `leaf` (which must be the leaf
    /// `leaf_of(p)` names). Returns its index.
    pub fn add_point(&mut self, leaf: Key, p: Point) -> u32 {
        let id = self.points.len() as u32;
        self.points.push(p);
        self.occupants.entry(leaf).or_default().push(id);
        self.occupied.insert(leaf);
        if let Some(log) = &mut self.occupancy_changes {
            log.push(leaf);
        }
        id
    }

    /// Starts (or restarts, forgetting what was logged) the log of hexagons whose occupancy
    /// changes (`take_occupancy_changes`).
    pub(crate) fn track_occupancy(&mut self) {
        self.occupancy_changes = Some(Vec::new());
    }

    /// The hexagons that started or stopped being occupied since tracking began or since the
    /// last call (in any order, with repeats); empty when tracking is off.
    pub(crate) fn take_occupancy_changes(&mut self) -> Vec<Key> {
        self.occupancy_changes
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    /// What the cell `key` currently is.
    pub fn cell(&self, key: Key) -> Cell {
        if !key.inside() {
            return Cell::Outside;
        }
        let full = |me: &Self| Cell::Full {
            subdivided: me.subdivided.contains(&key),
        };
        match key.parents() {
            Parents::None => full(self),
            Parents::Central(p) => {
                if self.subdivided.contains(&p) {
                    full(self)
                } else {
                    Cell::Absent
                }
            }
            Parents::Edge(a, b) => match (
                self.is_subdivided_or_outside(a),
                self.is_subdivided_or_outside(b),
            ) {
                (true, true) => full(self),
                (true, false) => Cell::Semi {
                    owner: a,
                    fin_of: b,
                },
                (false, true) => Cell::Semi {
                    owner: b,
                    fin_of: a,
                },
                (false, false) => Cell::Absent,
            },
        }
    }

    /// True when `key` is a full hexagon that is not subdivided.
    pub fn is_full_leaf(&self, key: Key) -> bool {
        self.cell(key) == Cell::Full { subdivided: false }
    }

    /// Makes the cell `key` a full hexagon (or leaves it alone if outside or already full):
    /// a semi-hexagon is joined by subdividing the hexagon it is a fin of; an absent cell
    /// first needs its parents (Sec. 3.3, Fig. 2).
    pub fn ensure_full(&mut self, key: Key) -> Result<(), Stop> {
        match self.cell(key) {
            Cell::Outside | Cell::Full { .. } => Ok(()),
            Cell::Semi { fin_of, .. } => self.subdivide(fin_of),
            Cell::Absent => match key.parents() {
                Parents::None => Ok(()),
                Parents::Central(p) => {
                    self.ensure_full(p)?;
                    self.subdivide(p)
                }
                Parents::Edge(a, b) => {
                    for p in [a, b] {
                        if !self.is_subdivided_or_outside(p) {
                            self.ensure_full(p)?;
                            self.subdivide(p)?;
                        }
                    }
                    Ok(())
                }
            },
        }
    }

    /// Splits the full hexagon `key` (Sec. 3.1). Balancing first (Sec. 3.3): every neighbour
    /// is made a full hexagon, since a semi-hexagon beside the new semi-hexagons would differ
    /// from them by two levels. Semi-hexagons of the new children that meet a subdivided
    /// neighbour's semi-hexagon are joined implicitly (the cell becomes full). The points of
    /// `key` move to its children.
    pub fn subdivide(&mut self, key: Key) -> Result<(), Stop> {
        if self.subdivided.contains(&key) || !key.inside() {
            return Ok(());
        }
        self.check_budget(key)?;
        for d in 0..6 {
            self.ensure_full(key.neighbor(d))?;
        }
        if self.subdivided.contains(&key) {
            return Ok(());
        }
        debug_assert_eq!(self.cell(key), Cell::Full { subdivided: false });
        self.subdivided.insert(key);
        self.steps += 1;
        self.deepest = self.deepest.max(key.k + 1);
        self.log.push(key);
        // The central child replaces `key` as a leaf; each edge child that is now full joined.
        for d in 0..6 {
            let child = key.edge_child(d);
            if child.inside() && self.is_subdivided_or_outside(key.neighbor(d)) {
                self.full_leaves += 1;
            }
        }
        if let Some(pts) = self.occupants.remove(&key) {
            self.occupied.remove(&key);
            for p in pts {
                let child = self.locate_child(key, self.points[p as usize]);
                self.occupants.entry(child).or_default().push(p);
                self.occupied.insert(child);
                if let Some(log) = &mut self.occupancy_changes {
                    log.push(child);
                }
            }
            if let Some(log) = &mut self.occupancy_changes {
                log.push(key);
            }
        }
        self.schedule_around(key);
        Ok(())
    }

    /// Makes the subdivided hexagon `top` and its six subdivided neighbours leaves again: the
    /// local coarsening into a blossom of Sec. 5.3 (`blossom::can_form` has checked that the
    /// 37 cells of the next level around `top` are unoccupied full leaves and that nothing
    /// finer lies next to them, so balancing (Sec. 3.3) still holds). The 37 full leaves
    /// become 7.
    pub(crate) fn merge_blossom(&mut self, top: Key) {
        debug_assert!(self.is_subdivided(top));
        self.subdivided.remove(&top);
        for d in 0..6 {
            let n = top.neighbor(d);
            debug_assert!(self.is_subdivided(n));
            self.subdivided.remove(&n);
        }
        self.full_leaves -= 30;
    }

    /// Queues the cells whose rules may have changed: the seven children, the ring of cells of
    /// the next level around them, and the neighbours of `key`.
    fn schedule_around(&mut self, key: Key) {
        let c = key.central_child();
        for di in -2i64..=2 {
            for dj in -2i64..=2 {
                if (di + dj).abs() <= 2 {
                    self.work.push(Key::new(c.k, c.i + di, c.j + dj));
                }
            }
        }
        for d in 0..6 {
            self.work.push(key.neighbor(d));
        }
    }

    /// Sets the largest rounding allowance, in degrees, that a finished mesh may use
    /// (`quality::rounding`); refinement stops, naming the points, where hexagons would be
    /// so small that rounding alone may move an angle by `ROUNDING_GUARD` times that.
    pub fn set_max_rounding(&mut self, degrees: f64) {
        self.max_rounding = degrees;
    }

    /// Sets how many threads the long lists of independent work (the extended rules, the
    /// relocations, the dual) are split over; at least one. The results do not depend on it.
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads.max(1);
    }

    /// The threads of `set_threads` (by default as many as the machine has).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// How far rounding may move an angle of the dual triangles between the hexagons of
    /// level `k` around `key` (degrees): every vertex within a few radii of the hexagon's
    /// centre c moves by at most δ = 2^-50·(max(|cx|, |cy|) + 2·r_k), and the dual's edges
    /// there are at least r_k/2 long (moved centres; Sec. 5.4), so an angle moves by at most
    /// 4·δ/(r_k/2) radians (`quality::rounding`).
    pub fn rounding_at(&self, key: Key) -> f64 {
        let c = self.lattice.center(key);
        let r = self.lattice.radius(key.k);
        let delta =
            crate::quality::rounding::ROUNDING_UNIT * (c[0].abs().max(c[1].abs()) + 2.0 * r);
        (8.0 * delta / r).to_degrees()
    }

    /// The refusal of an input whose points near `key` are too close together for f64: the
    /// closest pair of input points in the hexagon of `key` (or, when it holds fewer than
    /// two, of the whole input) with their distance, and the allowance `needed` (degrees).
    pub fn too_fine(&self, key: Key, needed: f64) -> InputError {
        let mut inside: Vec<u32> = Vec::new();
        let mut stack = vec![key];
        // The points of the hexagon's leaves, through its subdivided descendants.
        while let Some(k) = stack.pop() {
            inside.extend_from_slice(self.occupants(k));
            if self.is_subdivided(k) {
                stack.extend(k.children().into_iter().filter(|c| c.inside()));
            }
        }
        let ids: Vec<u32> = if inside.len() >= 2 {
            inside
        } else {
            (0..self.points.len() as u32).collect()
        };
        let pts: Vec<Point> = ids.iter().map(|&i| self.points[i as usize]).collect();
        let (first, second, distance) = match crate::quality::closest_pair(&pts) {
            Some(c) => {
                let (a, b) = (ids[c.first] as usize, ids[c.second] as usize);
                (a.min(b), a.max(b), c.distance)
            }
            None => (0, 0, 0.0),
        };
        InputError::Rounding {
            first,
            second,
            distance,
            needed,
            allowed: self.max_rounding,
        }
    }

    /// Sets the level every full leaf must reach to keep the size limits (`hex::size`, which
    /// subdivides to it; blossoms are not formed coarser).
    pub fn set_size_level(&mut self, level: u8) {
        self.size_level = level;
    }

    /// The level every full leaf must reach to keep the size limits; 0 for none.
    pub fn size_level(&self) -> u8 {
        self.size_level
    }

    /// The budget the refinement keeps.
    pub fn budget(&self) -> Budget {
        self.budget
    }

    /// The deepest level a hexagon has reached.
    pub fn deepest(&self) -> u8 {
        self.deepest
    }

    /// The time budget, checked now: for callers that do much work between subdivisions
    /// (the extended rules), where the check every 256 steps comes too late.
    pub fn check_time(&self) -> Result<(), Stop> {
        match self.budget.max_time {
            Some(max) if self.start.elapsed() > max => Err(Stop::Budget(StopReason::Time(max))),
            _ => Ok(()),
        }
    }

    fn check_budget(&self, key: Key) -> Result<(), Stop> {
        if key.k + 1 > MAX_LEVEL {
            return Err(Stop::Precision(self.too_fine(key, f64::INFINITY)));
        }
        let needed = self.rounding_at(key.central_child());
        if needed > ROUNDING_GUARD * self.max_rounding {
            return Err(Stop::Precision(self.too_fine(key, needed)));
        }
        if let Some(max) = self.budget.max_steps {
            if self.steps >= max {
                return Err(Stop::Budget(StopReason::Steps(max)));
            }
        }
        if let Some(max) = self.budget.max_vertices {
            if self.full_leaves >= max {
                return Err(Stop::Budget(StopReason::Vertices(max)));
            }
        }
        if let Some(max) = self.budget.max_time {
            if self.steps % 256 == 0 && self.start.elapsed() > max {
                return Err(Stop::Budget(StopReason::Time(max)));
            }
        }
        Ok(())
    }

    /// The child cell of the subdivided hexagon `parent` that `p` belongs to (module docs).
    pub fn locate_child(&self, parent: Key, p: Point) -> Key {
        // Children outside the bounding hexagon never hold points: a point that rounding puts
        // just inside the constructed root edge still belongs to the boundary cell there.
        let mut children = parent.children().to_vec();
        children.retain(|c| c.inside());
        let guess = self.lattice.nearest(parent.k + 1, p);
        if children.contains(&guess) && self.strictly_inside(guess, p) {
            return guess;
        }
        let mut best: Option<Key> = None;
        for &c in &children {
            if self.closed_contains(c, p) && best.is_none_or(|b| (c.i, c.j) < (b.i, b.j)) {
                best = Some(c);
            }
        }
        // Rounding of the constructed corners can leave a sliver of the parent outside every
        // constructed child; the nearest centre decides there (ties to the lower (i, j)).
        best.unwrap_or_else(|| {
            let mut v = children;
            v.sort_by(|a, b| {
                let da = crate::geom::dist2(self.lattice.center(*a), p);
                let db = crate::geom::dist2(self.lattice.center(*b), p);
                da.total_cmp(&db).then((a.i, a.j).cmp(&(b.i, b.j)))
            });
            v[0]
        })
    }

    fn strictly_inside(&self, key: Key, p: Point) -> bool {
        let c = self.lattice.corners(key);
        (0..6).all(|m| orient2d(c[m], c[(m + 1) % 6], p) > 0.0)
    }

    /// True when `p` lies in the closed constructed hexagon of cell `key` (exact).
    pub fn closed_contains(&self, key: Key, p: Point) -> bool {
        let c = self.lattice.corners(key);
        (0..6).all(|m| orient2d(c[m], c[(m + 1) % 6], p) >= 0.0)
    }

    /// The leaf of the dual vertex with canonical key `key`: the end of its chain of
    /// central children (the cells with the same centre, one per level).
    pub fn leaf_of_vertex(&self, key: Key) -> Key {
        let mut k = key;
        while self.is_subdivided(k) {
            k = k.central_child();
        }
        k
    }

    /// The leaf holding `p`, by the descent of the module docs. Used by tests and pictures.
    pub fn leaf_of(&self, p: Point) -> Key {
        let mut key = Key::ROOT;
        while self.subdivided.contains(&key) {
            key = self.locate_child(key, p);
            if !matches!(self.cell(key), Cell::Full { .. }) {
                break;
            }
        }
        key
    }

    /// The full unsubdivided hexagons inside the root, in no particular order (the order of
    /// the subdivided set): for callers whose result does not depend on it.
    pub fn full_leaves_unordered(&self) -> Vec<Key> {
        self.full_leaves_where(|_| true)
    }

    /// The keys of `full_leaves_unordered`, one at a time (no list of them all).
    pub fn full_leaves_iter(&self) -> impl Iterator<Item = Key> + '_ {
        let children = self
            .subdivided
            .iter()
            .flat_map(move |key| self.full_children(key));
        let root = (!self.subdivided.contains(&Key::ROOT)).then_some(Key::ROOT);
        children.chain(root)
    }

    /// The full leaves for which `keep` holds, in the order of `full_leaves_iter`, found over
    /// the hierarchy's threads in runs of the subdivided set's blocks (at plane-100k, 5.6 M
    /// leaves took a quarter of a second on one thread).
    pub fn full_leaves_where(&self, keep: impl Fn(Key) -> bool + Sync) -> Vec<Key> {
        let parts = self.in_subdivided_runs(|keys| {
            keys.flat_map(|key| self.full_children(key))
                .filter(|&c| keep(c))
                .collect::<Vec<Key>>()
        });
        let mut out = Vec::with_capacity(parts.iter().map(Vec::len).sum::<usize>() + 1);
        for part in parts {
            out.extend(part);
        }
        if !self.subdivided.contains(&Key::ROOT) && keep(Key::ROOT) {
            out.push(Key::ROOT);
        }
        out
    }

    /// The children of the subdivided hexagon `key` that are full leaves, each named by one
    /// parent: its central child unless subdivided, and each edge child inside the root that
    /// is a full hexagon (the neighbour across the edge subdivided too, or outside) and not
    /// subdivided, named by the parent of the two with the lower packed key.
    fn full_children(&self, key: Key) -> impl Iterator<Item = Key> + '_ {
        let c = key.central_child();
        let central = (!self.subdivided.contains(&c)).then_some(c);
        let edges = (0..6).filter_map(move |d| {
            let e = key.edge_child(d);
            if !e.inside() {
                return None;
            }
            let n = key.neighbor(d);
            (self.is_subdivided_or_outside(n)
                && (!n.inside() || key.packed() < n.packed())
                && !self.subdivided.contains(&e))
            .then_some(e)
        });
        central.into_iter().chain(edges)
    }

    /// The full leaves that are central children (of a subdivided hexagon), in the order of
    /// `full_leaves_iter`: one look-up per subdivided hexagon, where `full_leaves_iter` also
    /// finds the edge children.
    pub fn central_leaves_iter(&self) -> impl Iterator<Item = Key> + '_ {
        self.subdivided
            .iter()
            .map(Key::central_child)
            .filter(move |c| !self.subdivided.contains(c))
    }

    /// Every leaf inside the root: full unsubdivided hexagons and semi-hexagons, sorted.
    ///
    /// Every subdivided hexagon is a full hexagon (`check_invariants`), so the leaves are the
    /// children of subdivided hexagons that are full and unsubdivided, and the semi-hexagons
    /// they own: one pass over the subdivided set, no descent from the root.
    pub fn leaves(&self) -> Vec<(Key, Cell)> {
        let mut out = Vec::with_capacity(self.full_leaves + self.subdivided.len());
        for key in self.subdivided.iter() {
            // The central child is full; it is a leaf unless subdivided.
            let c = key.central_child();
            if !self.subdivided.contains(&c) {
                out.push((c, Cell::Full { subdivided: false }));
            }
            for d in 0..6 {
                let e = key.edge_child(d);
                if !e.inside() {
                    continue;
                }
                let n = key.neighbor(d);
                if !self.is_subdivided_or_outside(n) {
                    // A semi-hexagon owned by `key`, a fin of `n`.
                    out.push((
                        e,
                        Cell::Semi {
                            owner: key,
                            fin_of: n,
                        },
                    ));
                } else if (!n.inside() || key.packed() < n.packed())
                    && !self.subdivided.contains(&e)
                {
                    // A full leaf between two subdivided hexagons, listed by one of them.
                    out.push((e, Cell::Full { subdivided: false }));
                }
            }
        }
        if !self.subdivided.contains(&Key::ROOT) {
            out.push((Key::ROOT, self.cell(Key::ROOT)));
        }
        out.sort_unstable_by_key(|e| e.0.packed());
        debug_assert!(out.windows(2).all(|w| w[0].0 != w[1].0));
        debug_assert!(out.iter().all(|&(k, c)| self.cell(k) == c));
        out
    }
}

impl Hierarchy {
    /// Checks the structural invariants every state keeps (a sanity check for tests and the
    /// fuzzer): each subdivided hexagon is a full hexagon whose neighbours inside the bounding
    /// hexagon are full (the balancing rule of Sec. 3.3), and each point is held by the leaf
    /// the point-location rule gives it. Returns the first violation.
    pub fn check_invariants(&self) -> Result<(), String> {
        for key in self.subdivided_sorted() {
            if !matches!(self.cell(key), Cell::Full { .. }) {
                return Err(format!("subdivided {key:?} is not a full hexagon"));
            }
            for d in 0..6 {
                let n = key.neighbor(d);
                if !matches!(self.cell(n), Cell::Full { .. } | Cell::Outside) {
                    return Err(format!(
                        "subdivided {key:?} has neighbour {n:?} that is {:?}",
                        self.cell(n)
                    ));
                }
            }
        }
        for key in self.occupied_sorted() {
            for &p in self.occupants(key) {
                let leaf = self.leaf_of(self.points[p as usize]);
                if leaf != key {
                    return Err(format!("point {p} is held by {key:?}, located in {leaf:?}"));
                }
            }
        }
        Ok(())
    }

    /// Checks the end state of the simple refinement (Sec. 4.1): every occupied hexagon is a
    /// full hexagon holding one point, surrounded by full, unsubdivided, unoccupied hexagons.
    pub fn check_refined(&self) -> Result<(), String> {
        for key in self.occupied_sorted() {
            if !self.is_full_leaf(key) {
                return Err(format!("occupied {key:?} is {:?}", self.cell(key)));
            }
            if self.occupants(key).len() != 1 {
                return Err(format!(
                    "{key:?} holds {} points",
                    self.occupants(key).len()
                ));
            }
            for d in 0..6 {
                let n = key.neighbor(d);
                if !n.inside() {
                    continue;
                }
                if !self.is_full_leaf(n) || self.is_occupied(n) {
                    return Err(format!(
                        "occupied {key:?} has neighbour {n:?}: {:?}, occupied {}",
                        self.cell(n),
                        self.is_occupied(n)
                    ));
                }
            }
        }
        Ok(())
    }
}

/// How many times the largest allowed rounding (`Hierarchy::set_max_rounding`) the worst case
/// of `Hierarchy::rounding_at` may reach before refinement stops. The worst case adds up
/// every vertex's largest move in the worst direction; the angles of a finished mesh, which
/// decide (`quality::rounding::check_angles`), move far less, so the guard only stops descents
/// that could not end in a mesh.
pub const ROUNDING_GUARD: f64 = 64.0;
