//! The repair loop (`extend_and_verify`): the extended rules of paper 000 (Sußner & Greiner
//! 2009) Sec. 5.2 to a fixed point, the local coarsening of Sec. 5.3 once, the relocated dual
//! of Sec. 5.4, then our self-check and its repairs (settling, flips, corner switches,
//! polishing, subdivisions) until the dual meets every bound; the loop itself is our
//! departure (Sec. 6.1 checked the bounds on "almost all configurations"). Local checks and
//! the splice keep the work of a repair proportional to what it changes.

use super::check::{offending_leaves, BadTriangle};
use super::relocate::{chain_relocations, chain_triangles, relocated, relocations_of};
use super::rings::{apply_flips, apply_placed, flip, switch_corner, RingCache, RingState};
use super::rules::{around, extended_actions, Why};
use super::settle::{polish_rings, record_moves, settle_contested, Moves, SettleCells, SettlePass};
use super::splice::{keep_for_splice, whole_dual};
use super::undo::Undo;
use super::ExtendedStats;
use crate::error::Result;
use crate::hex::blossom;
use crate::hex::classify::{Class, Rings};
use crate::hex::dual::{self, Placement};
use crate::hex::lattice::{Key, KeySet};
use crate::hex::mc3::Patch;
use crate::hex::refine::drain;
use crate::hex::region::{full_leaves_in, Region, REACH};
use crate::hex::subdivision::{Cell, Hierarchy, Stop};
use crate::mesh::TriMesh;
use crate::progress::{self, Progress};

/// The extended rules on `candidates` to a fixed point, then the self-check of the dual,
/// repeated until the dual meets every bound. With `changed == None` the first check covers
/// the whole dual and, when it passes, that dual is returned; otherwise (and after any
/// repair) each check covers only the triangles near the cells changed since the previous
/// check (`region`), so that the work of a repair is proportional to what it changes, not
/// to how many other places are still being repaired. When every check has passed, one
/// more covers the triangles near every cell changed since the complete check, and the
/// whole dual is spliced from the complete one and that region's (`splice`); `None` says
/// that the whole dual passes but is still to be extracted (`final_dual`): there was no
/// complete check (incremental insertion), or the splice was refused. `state` keeps the
/// ring decisions of the self-check. The rings of `h` as it stands may come along (made
/// while its occupancy was tracked), else they are made at the first rules. `progress`
/// hears of the phases: the extended rules, the steps of the complete check, each local
/// check, each later round of rules, the splice of the final dual.
pub(crate) fn extend_and_verify(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    state: &mut RingState,
    (candidates, rings): (KeySet, Option<Rings>),
    changed: Option<Vec<Key>>,
    progress: Option<&Progress>,
) -> Result<Option<TriMesh>, Stop> {
    let mut repair = Repair::new(h, stats, state, candidates, changed);
    if let Some(r) = rings {
        repair.cache = RingCache::holding(r);
    }
    repair.progress = progress;
    repair.run()
}

/// The extended rules on `candidates` to a fixed point and nothing else: no coarsening, no
/// check (a tile's part of the run, `tiles`). The subdivisions the rules made are counted in
/// `stats`.
pub(crate) fn rules_to_fixed_point(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    candidates: KeySet,
) -> Result<(), Stop> {
    let mut state = RingState::default();
    let mut repair = Repair::new(h, stats, &mut state, candidates, None);
    repair.coarsened = true;
    repair.apply_rules()
}

/// What a local check of `extend_and_verify` covers.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scope {
    /// The cells changed since the last check.
    Fresh,
    /// Every cell changed since the complete check: the part of the dual `splice` takes.
    All,
}

/// How a round of checks ended.
enum Verdict {
    /// The whole dual passes (`None`: still to be extracted, see `extend_and_verify`).
    Passed(Option<TriMesh>),
    /// These triangles need a subdivision.
    Rejected(Vec<BadTriangle>),
}

/// The part of the dual one check covers, with what the check needs beside it.
struct Checked {
    mesh: TriMesh,
    /// The canonical key of each vertex of `mesh` (after `blame_fins`, the MOVED_CENTER_3
    /// hexagon of a fin vertex).
    keys: Vec<Key>,
    patch: Patch,
    /// Where `settle_contested` and `polish_rings` may move vertices (a vertex whose every
    /// triangle is in this part of the dual); `None`: anywhere (a complete check).
    movable: Option<Region>,
    /// The cells whose vertices `splice` takes from this part; `None` for a complete check.
    inner: Option<Region>,
    /// The vertex keys `blame_fins` replaced, for `splice`.
    blamed: Vec<(usize, Key)>,
}

/// The state of `extend_and_verify`, one method a step.
struct Repair<'a> {
    h: &'a mut Hierarchy,
    stats: &'a mut ExtendedStats,
    state: &'a mut RingState,
    cache: RingCache,
    /// The local coarsening of Sec. 5.3 has run.
    coarsened: bool,
    /// The shortest edge Sec. 6.3 promises, √7/(12√3)·d_min: placing a contested cell must
    /// not undercut it.
    l_min: f64,
    /// The cells the extended rules look at next.
    candidates: KeySet,
    /// `None` until the complete check fails (or from the start for incremental
    /// insertion): then every cell changed since, for the dual the splice takes.
    changed: Option<Vec<Key>>,
    /// The last complete dual that failed the check, with its vertex keys, once local
    /// repairs began: the whole dual they end with is spliced from it (`splice`).
    base: Option<(TriMesh, Vec<Key>)>,
    /// The cells changed since the last local check.
    fresh: Vec<Key>,
    /// The vertices of offending triangles left for later (`set_aside`).
    stuck: Vec<Key>,
    scope: Scope,
    /// Who hears of the phases (`extend_and_verify`); `None` for a tile.
    progress: Option<&'a Progress>,
    /// Local checks made so far, for `progress`.
    local_checks: u64,
}

impl<'a> Repair<'a> {
    fn new(
        h: &'a mut Hierarchy,
        stats: &'a mut ExtendedStats,
        state: &'a mut RingState,
        candidates: KeySet,
        changed: Option<Vec<Key>>,
    ) -> Repair<'a> {
        let l_min = crate::quality::closest_pair(&h.points).map_or(0.0, |c| {
            c.distance * crate::quality::HEX.min_edge_over_dmin * (1.0 + 1e-9)
        });
        if let Some(c) = &changed {
            state.forget_near(h, c);
        }
        let fresh = changed.clone().unwrap_or_default();
        Repair {
            h,
            stats,
            state,
            cache: RingCache::default(),
            coarsened: false,
            l_min,
            candidates,
            changed,
            base: None,
            fresh,
            stuck: Vec::new(),
            scope: Scope::Fresh,
            progress: None,
            local_checks: 0,
        }
    }

    /// Rounds of rules, then checks, then the subdivisions the checks ask for, until a
    /// check passes.
    fn run(mut self) -> Result<Option<TriMesh>, Stop> {
        let first_round = self.stats.rounds;
        loop {
            self.stats.rounds += 1;
            // The first round's rules are the bulk of the refinement; a later round's rules
            // follow the subdivisions the last check asked for.
            match self.stats.rounds - first_round {
                1 => progress::phase(self.progress, "extended rules"),
                n => progress::round(self.progress, "repair round", n - 1),
            }
            self.apply_rules()?;
            // The work list of the subdivisions is empty now but holds the room of its
            // longest batch (25 cells a subdivision: about 2 GB at plane-1m), which the
            // check does not need.
            self.h.work = Vec::new();
            // The rings with the decisions of `state`, changed in place and given back to
            // the cache (undone) before the next subdivisions.
            let mut r = self.cache.take(self.h);
            let mut undo = Undo::default();
            apply_flips(self.h, &mut r, self.state, &mut undo);
            let bad = match self.check(&mut r, &mut undo)? {
                Verdict::Passed(mesh) => return Ok(mesh),
                Verdict::Rejected(bad) => bad,
            };
            undo.restore(&mut r);
            self.cache.put(r);
            self.subdivide_rejected(bad)?;
        }
    }

    /// The extended rules of Sec. 5.2 on the candidates, to a fixed point, with the local
    /// coarsening of Sec. 5.3 once on the way.
    fn apply_rules(&mut self) -> Result<(), Stop> {
        loop {
            self.h.check_time()?;
            let r = self.cache.get(self.h);
            let actions = extended_actions(self.h, r, &self.candidates);
            if !actions.is_empty() {
                self.subdivide_for_rules(actions)?;
            } else if !self.coarsen_once() {
                return Ok(());
            }
        }
    }

    /// The final local coarsening of Sec. 5.3, once, on the first complete refinement: true
    /// when it formed blossoms, around which the rules then run again (they find nothing to
    /// do there, or undo a blossom, which is not formed again).
    fn coarsen_once(&mut self) -> bool {
        if self.changed.is_some() || self.coarsened {
            return false;
        }
        self.coarsened = true;
        // The rings are read in place (the coarsening changes the hierarchy, not the cache),
        // and the full leaves one at a time: at plane-100k a copy of the rings and a list of
        // the leaves were about 13 and 12 bytes an output triangle (the central ones listed
        // by `candidate_tops` are a fifth of them).
        let r = self.cache.get(self.h);
        let h = &*self.h;
        // Only central children can be the central child of a top.
        let tops = blossom::candidate_tops(h, r, h.central_leaves_iter());
        let merged = blossom::coarsen(self.h, r, &tops);
        self.stats.blossoms += merged.len() as u64 / 7;
        if merged.is_empty() {
            return false;
        }
        self.candidates = around(&merged);
        true
    }

    /// Makes the subdivisions (or full hexagons) the rules asked for.
    fn subdivide_for_rules(&mut self, actions: Vec<(Key, Why)>) -> Result<(), Stop> {
        let h = &mut *self.h;
        h.log.clear();
        for (key, why) in actions {
            let before = h.steps;
            match h.cell(key) {
                Cell::Full { subdivided: false } => h.subdivide(key)?,
                Cell::Semi { .. } | Cell::Absent => h.ensure_full(key)?,
                _ => {}
            }
            self.stats.rule_splits += h.steps - before;
            if why == Why::Mc3 {
                self.stats.mc3_splits += h.steps - before;
            }
        }
        drain(h)?;
        if let Some(c) = self.changed.as_mut() {
            c.extend_from_slice(&h.log);
            self.fresh.extend_from_slice(&h.log);
            self.state.forget_near(h, &h.log);
        }
        self.candidates = around(&h.log);
        Ok(())
    }

    /// Checks the dual (the whole of it first, then near the changes) until it passes or only
    /// subdivisions are left, trying first the repairs that need none.
    fn check(&mut self, r: &mut Rings, undo: &mut Undo) -> Result<Verdict, Stop> {
        let cells = if self.changed.is_none() {
            progress::phase(self.progress, "self-check: the dual");
            SettleCells::listed(self.h, r)
        } else {
            SettleCells::Lookup
        };
        loop {
            if let Some(verdict) = self.check_once(r, undo, &cells)? {
                return Ok(verdict);
            }
        }
    }

    /// One check of the dual (see `Scope`), with the repairs that need no subdivision:
    /// settling and polishing the ring cells, flipping contested cells to their moved role,
    /// switching OCCUPIED_2 rings to their second corner. `None`: check again (`scope` says
    /// where).
    fn check_once(
        &mut self,
        r: &mut Rings,
        undo: &mut Undo,
        cells: &SettleCells,
    ) -> Result<Option<Verdict>, Stop> {
        self.h.check_time()?;
        let full = self.changed.is_none();
        // The complete check is long (at plane-100k nearly half the run): its steps are
        // reported one by one; a local check is short, and counted.
        if !full {
            self.local_checks += 1;
            progress::round(self.progress, "local checks", self.local_checks);
        }
        let around_all = self.scope == Scope::All;
        let mut part = self.extract(r, around_all);
        if full {
            progress::phase(self.progress, "self-check: ring cells");
        }
        self.stats.checked_triangles += part.mesh.triangles.len() as u64;
        self.settle(r, cells, &mut part);
        part.blame_fins();
        if full {
            progress::phase(self.progress, "self-check: angles and circles");
        }
        let mut bad = offending_leaves(
            self.h,
            &part.mesh,
            &part.keys,
            &mut self.stats.rounding_pairs,
        );
        self.stats.mc3_rejected += bad
            .iter()
            .filter(|b| {
                b.vertices
                    .iter()
                    .any(|v| part.patch.chain_cells.contains(v))
            })
            .count() as u64;
        // Before any subdivision (which would go below the r_min of Sec. 6.3), let the
        // contested cells of the offending triangles take the moved role instead.
        let flips = vertices_where(&bad, |c| self.can_flip(r, c));
        // Next, the OCCUPIED_2 points of the offending triangles shift their moved 1-ring
        // towards their second corner (`switch_corner`).
        let switches = vertices_where(&bad, |c| self.can_switch(r, c));
        if !bad.is_empty() && flips.is_empty() && switches.is_empty() && self.stuck.is_empty() {
            bad = self.polish(r, &mut part, bad);
            if !bad.is_empty() {
                if full {
                    self.keep_as_base(&mut part);
                }
                return Ok(Some(Verdict::Rejected(bad)));
            }
        }
        if bad.is_empty() && self.stuck.is_empty() {
            if full || around_all || self.base.is_none() {
                return Ok(Some(Verdict::Passed(self.finish(part))));
            }
            // Every local check passed: the dual around all the changes once more, for the
            // splice (and checked again, since settling may move a vertex anew).
            self.scope = Scope::All;
            return Ok(None);
        }
        self.scope = Scope::Fresh;
        if flips.is_empty() && switches.is_empty() {
            self.recheck_stuck(&bad);
            return Ok(None);
        }
        // Only the offending triangles acted on are checked again at once; the others wait
        // (`stuck`) until nothing else is left to try, so that a repair needing many rounds
        // in one place does not re-examine every other place each round.
        let acted: Vec<bool> = bad
            .iter()
            .map(|b| {
                b.vertices.iter().any(|c| {
                    if flips.is_empty() {
                        self.can_switch(r, c)
                    } else {
                        self.can_flip(r, c)
                    }
                })
            })
            .collect();
        self.set_aside(&bad, &acted);
        if flips.is_empty() {
            self.switch_corners(r, undo, switches);
        } else {
            self.flip_cells(r, undo, flips);
        }
        if full {
            self.keep_as_base(&mut part);
        }
        Ok(None)
    }

    /// The part of the dual a check covers: the whole relocated dual for a complete check;
    /// for a local one, the triangles near the cells changed since the last check
    /// (`fresh`), or, for the dual the splice takes (`around_all`), near every cell changed
    /// since the complete check.
    fn extract(&mut self, r: &Rings, around_all: bool) -> Checked {
        let h = &*self.h;
        let Some(c) = &self.changed else {
            let (mut moved, patch, chains) = chain_relocations(h, r);
            apply_placed(&mut moved, self.state);
            let relocate = |k: Key| relocated(h, r, k);
            let later = |emit: &mut dyn FnMut([Key; 3])| chain_triangles(h, r, &chains, emit);
            let (mesh, keys) = dual::extract_relocated(h, (&moved, &relocate), &patch, &later);
            return Checked {
                mesh,
                keys,
                patch,
                movable: None,
                inner: None,
                blamed: Vec::new(),
            };
        };
        let centre = if around_all { &c[..] } else { &self.fresh[..] };
        // Relocations reach a little further than the triangles checked, so that every
        // vertex of a checked triangle has its final place.
        let wide = Region::around(centre, REACH + 3);
        self.fresh.clear();
        let (moved, patch) = relocations_of(h, r, full_leaves_in(h, &wide));
        let region = wide.within(REACH);
        let (mesh, keys) = dual::extract_region_patched(
            h,
            Placement::Relocated,
            (&self.state.placed, &moved),
            &patch,
            &region,
        );
        Checked {
            mesh,
            keys,
            patch,
            // Only vertices whose every triangle is in this part of the dual may be placed
            // by `settle_contested`.
            movable: Some(wide.within(REACH - 3)),
            // The vertices `splice` takes from this part of the dual.
            inner: Some(wide.within(REACH - 1)),
            blamed: Vec::new(),
        }
    }

    /// The two passes of `settle_contested` (contested cells, then their ring neighbours
    /// too), the places they end at kept in `state`.
    fn settle(&mut self, r: &Rings, cells: &SettleCells, part: &mut Checked) {
        let h = &*self.h;
        let movable = movable_in(h, &part.movable);
        let mut settled = Moves::default();
        for with_neighbours in [false, true] {
            let pass = SettlePass {
                rings: r,
                cells,
                with_neighbours,
            };
            let moves = settle_contested(h, &mut part.mesh, &part.keys, self.l_min, pass, &movable);
            self.stats.settled += moves.count;
            settled.from.extend(moves.from);
        }
        record_moves(&mut self.state.placed, settled, &part.mesh, &part.keys);
    }

    /// Before subdividing (which below r_min = d_min/(6√3) would break the shortest-edge
    /// bound of Sec. 6.3), polishes the ring cells of the rejected triangles `bad` with a
    /// finer local search (`polish_rings`); the triangles still rejected after it.
    fn polish(&mut self, r: &Rings, part: &mut Checked, bad: Vec<BadTriangle>) -> Vec<BadTriangle> {
        let h = &*self.h;
        let tris: Vec<usize> = bad.iter().map(|b| b.triangle).collect();
        // Its moves never add a bad triangle or a short edge, so they are kept even when
        // other triangles (elsewhere) still need a subdivision.
        let movable = movable_in(h, &part.movable);
        let moved = polish_rings(
            h,
            r,
            &mut part.mesh,
            &part.keys,
            &tris,
            self.l_min,
            &movable,
        );
        if moved.count == 0 {
            return bad;
        }
        self.stats.polished += moved.count;
        record_moves(&mut self.state.placed, moved, &part.mesh, &part.keys);
        offending_leaves(h, &part.mesh, &part.keys, &mut self.stats.rounding_pairs)
    }

    /// A contested cell not flipped yet.
    fn can_flip(&self, r: &Rings, c: &Key) -> bool {
        r.contested.contains_key(c) && !self.state.flipped.contains(c)
    }

    /// An OCCUPIED_2 hexagon whose ring has not switched to its second corner yet.
    fn can_switch(&self, r: &Rings, c: &Key) -> bool {
        r.occupied.get(c) == Some(&Class::Occupied2) && !self.state.second_corner.contains(c)
    }

    /// Notes the vertices of the offending triangles `bad` as changed, the ones a repair
    /// acts on (`acted`) to be checked again at once, the others to wait in `stuck`.
    fn set_aside(&mut self, bad: &[BadTriangle], acted: &[bool]) {
        let all = self.changed.get_or_insert_with(Vec::new);
        for (b, &acted) in bad.iter().zip(acted) {
            all.extend_from_slice(&b.vertices);
            let to = if acted {
                &mut self.fresh
            } else {
                &mut self.stuck
            };
            to.extend_from_slice(&b.vertices);
        }
    }

    /// The contested cells `flips` take their moved role; they are checked again, with the
    /// offending triangles they touch.
    fn flip_cells(&mut self, r: &mut Rings, undo: &mut Undo, flips: Vec<Key>) {
        for c in flips {
            flip(r, c, undo);
            self.state.flipped.insert(c);
            self.state.placed.remove(&c.canonical());
            self.fresh.push(c);
            self.changed.get_or_insert_with(Vec::new).push(c);
            self.stats.ring_flips += 1;
        }
    }

    /// The OCCUPIED_2 hexagons `switches` shift their moved 1-ring towards their second
    /// corner (`switch_corner`); they and their rings are checked again.
    fn switch_corners(&mut self, r: &mut Rings, undo: &mut Undo, switches: Vec<Key>) {
        for owner in switches {
            switch_corner(self.h, r, owner, undo);
            self.state.second_corner.insert(owner);
            self.state.forget_near(self.h, &[owner]);
            let ring = std::iter::once(owner).chain((0..6).map(|d| owner.neighbor(d)));
            self.fresh.extend(ring.clone());
            self.changed.get_or_insert_with(Vec::new).extend(ring);
            self.stats.corner_switches += 1;
        }
    }

    /// Nothing to try on the offending triangles `bad`, but the waiting ones (`stuck`) may
    /// still have a flip or a switch: they (and these) are checked again together.
    fn recheck_stuck(&mut self, bad: &[BadTriangle]) {
        // Reached only with triangles waiting: with none, `polish` would have returned the
        // rejected triangles or the check passed.
        debug_assert!(!self.stuck.is_empty());
        self.fresh.append(&mut self.stuck);
        let vertices = bad.iter().flat_map(|b| b.vertices.iter().copied());
        self.fresh.extend(vertices.clone());
        self.changed.get_or_insert_with(Vec::new).extend(vertices);
    }

    /// After a complete check that failed, when local repairs begin: its dual becomes the
    /// `base` the final one is spliced from (`keep_for_splice`).
    fn keep_as_base(&mut self, part: &mut Checked) {
        keep_for_splice(&mut self.base, &mut part.mesh, &mut part.keys, &part.blamed);
    }

    /// The whole dual once a check has passed (`whole_dual`).
    fn finish(&mut self, mut part: Checked) -> Option<TriMesh> {
        if part.inner.is_some() {
            progress::phase(self.progress, "final dual");
        }
        whole_dual(
            self.h,
            self.stats,
            self.base.take(),
            part.mesh,
            &mut part.keys,
            &part.blamed,
            part.inner.as_ref(),
        )
    }

    /// Subdivides the coarsest hexagon of each rejected triangle. A rejected triangle breaks
    /// a bound by more than rounding explains (`breaks_bounds`), so subdividing is the repair
    /// at any level; the hierarchy's guard (`check_budget`) stops descents that rounding
    /// would spoil.
    fn subdivide_rejected(&mut self, bad: Vec<BadTriangle>) -> Result<(), Stop> {
        let mut bad: Vec<Key> = bad.into_iter().map(|b| b.coarsest).collect();
        bad.sort();
        bad.dedup();
        let h = &mut *self.h;
        h.log.clear();
        for key in bad {
            let before = h.steps;
            h.subdivide(key)?;
            self.stats.verify_splits += h.steps - before;
        }
        drain(h)?;
        self.state.forget_near(h, &h.log);
        self.changed
            .get_or_insert_with(Vec::new)
            .extend_from_slice(&h.log);
        self.fresh.extend_from_slice(&h.log);
        self.scope = Scope::Fresh;
        self.candidates = around(&h.log);
        Ok(())
    }
}

impl Checked {
    /// A triangle at a fin vertex is blamed on the MOVED_CENTER_3 hexagon of the fin:
    /// its vertex key is replaced by the hexagon's (`blamed` keeps the keys replaced, for
    /// `splice`).
    fn blame_fins(&mut self) {
        for (v, k) in self.keys.iter_mut().enumerate() {
            if let Some(&owner) = self.patch.fin_owner.get(k) {
                self.blamed.push((v, *k));
                *k = owner;
            }
        }
    }
}

/// Whether the vertex with canonical key `k` may be moved by the local searches: anywhere
/// without a region, else when its leaf lies in `region`.
fn movable_in<'b>(h: &'b Hierarchy, region: &'b Option<Region>) -> impl Fn(Key) -> bool + 'b {
    move |k| {
        region
            .as_ref()
            .is_none_or(|m| m.contains(h.leaf_of_vertex(k)))
    }
}

/// The vertices of the triangles `bad` for which `keep` holds, sorted, without repeats.
fn vertices_where(bad: &[BadTriangle], keep: impl Fn(&Key) -> bool) -> Vec<Key> {
    let mut out: Vec<Key> = bad
        .iter()
        .flat_map(|b| b.vertices.iter().copied())
        .filter(|c| keep(c))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}
