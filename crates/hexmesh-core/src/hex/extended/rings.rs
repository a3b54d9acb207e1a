//! The rings of occupied hexagons (paper 000, Sußner & Greiner 2009, Sec. 5.1) as the
//! self-check leaves them: which contested cells moved after all, where the local searches
//! placed cells, which OCCUPIED_2 rings shifted towards their second corner (`RingState`, our
//! departures from Sec. 5.4, module docs of `extended`); and the ring cache, which brings
//! the rings up to date only around hexagons whose occupancy changed (engineering, not in
//! the paper).

use super::undo::Undo;
use crate::geom::Point;
use crate::hex::classify::{rings, Rings, Role};
use crate::hex::lattice::{FxHashMap, FxHashSet, Key};
use crate::hex::region::Region;
use crate::hex::subdivision::Hierarchy;

/// What the self-check decided about ring cells, beyond their class: kept so that a later
/// extraction (after a local check, or an incremental insertion) places them the same way.
#[derive(Debug, Clone, Default)]
pub struct RingState {
    /// Contested ring cells whose centre moves after all, because keeping it fixed spoiled a
    /// triangle; each cell flips at most once, so the verification still terminates.
    pub flipped: FxHashSet<Key>,
    /// Vertices (by canonical key) that `settle_contested` placed, with their place.
    pub placed: FxHashMap<Key, Point>,
    /// OCCUPIED_2 hexagons whose moved 1-ring shifts towards the corner second nearest to
    /// the point (`switch_corner`); each switches at most once.
    pub second_corner: FxHashSet<Key>,
}

impl RingState {
    /// Forgets the places of cells near `changed`: their class or their neighbours changed.
    /// A vertex is judged by its leaf, the level its triangles are checked at: its canonical
    /// key can be many levels coarser, where a region reaches much farther.
    pub(super) fn forget_near(&mut self, h: &Hierarchy, changed: &[Key]) {
        if self.placed.is_empty() || changed.is_empty() {
            return;
        }
        let near = Region::around(changed, 3);
        // From the region's cells when it is the smaller (a few subdivisions late in a large
        // run), so that forgetting costs what changed, not a pass over every place.
        let cells: Vec<Key> = near.cells().collect();
        if cells.len() < self.placed.len() {
            for c in cells {
                let k = c.canonical();
                if self.placed.contains_key(&k) && h.leaf_of_vertex(k) == c {
                    self.placed.remove(&k);
                }
            }
        } else {
            self.placed
                .retain(|k, _| !near.contains(h.leaf_of_vertex(*k)));
        }
    }
}

pub(super) fn apply_placed(moved: &mut FxHashMap<Key, Point>, state: &RingState) {
    let mut placed: Vec<(Key, Point)> = state.placed.iter().map(|(k, p)| (*k, *p)).collect();
    placed.sort_by_key(|e| e.0);
    moved.extend(placed);
}

/// The rings of `h` with the decisions of `state`: the moved 1-rings of the hexagons in
/// `second_corner` shifted towards their second corner, then the contested cells in
/// `flipped` given their moved role.
pub(super) fn rings_with_flips(h: &Hierarchy, state: &RingState) -> Rings {
    let mut r = rings(h);
    apply_flips(h, &mut r, state, &mut Undo::default());
    r
}

/// Gives the rings `r` the decisions of `state` in place, logging in `undo` what they
/// replace.
pub(super) fn apply_flips(h: &Hierarchy, r: &mut Rings, state: &RingState, undo: &mut Undo) {
    let mut owners: Vec<Key> = state.second_corner.iter().copied().collect();
    owners.sort_unstable();
    for owner in owners {
        switch_corner(h, r, owner, undo);
    }
    let mut keys: Vec<Key> = state.flipped.iter().copied().collect();
    keys.sort_unstable();
    for key in keys {
        flip(r, key, undo);
    }
}

/// The contested cell `key` takes its moved role.
pub(super) fn flip(r: &mut Rings, key: Key, undo: &mut Undo) {
    if let Some(&alt) = r.contested.get(&key) {
        undo.set(r, false, key, alt);
    }
}

/// Departure from Sec. 5.4 (a last resort before a subdivision): the moved 1-ring of the
/// OCCUPIED_2 hexagon `owner` shifts by half the vector to the corner second nearest to its
/// point. A point near the border of two corners' regions lies in the region Fig. 8 allows
/// for both, and when a cell of the ring is held fixed by another point's 2-ring (three
/// hexagons apart), the shift towards the nearest corner can pull the ring cell beside it
/// too far from the fixed one (38.8° on fixture hex-second-corner-*), where the other
/// corner keeps every angle; a subdivision there would go below the r_min of Sec. 6.3.
pub(super) fn switch_corner(h: &Hierarchy, r: &mut Rings, owner: Key, undo: &mut Undo) {
    let Some(&p) = h.occupants(owner).first().map(|&i| &h.points[i as usize]) else {
        return;
    };
    let shift = crate::hex::classify::ring_shift_ranked(h, owner, p, 1);
    for d in 0..6 {
        let cell = owner.neighbor(d);
        for contested in [false, true] {
            let map = if contested { &r.contested } else { &r.roles };
            if let Some(&Role::Moved { owner: o, .. }) = map.get(&cell) {
                if o == owner {
                    undo.set(r, contested, cell, Role::Moved { owner, shift });
                }
            }
        }
    }
}

/// The rings of the occupied hexagons, brought up to date only around the hexagons whose
/// occupancy changed (the hierarchy logs them): the rule loop asks for them after every
/// batch of subdivisions, and most batches (fins spreading outwards) do not touch an
/// occupied hexagon. No pass over all occupied hexagons per batch.
#[derive(Default)]
pub(super) struct RingCache {
    rings: Option<Rings>,
}

impl RingCache {
    /// A cache holding the rings `r` of the hierarchy as it stands, whose occupancy changes
    /// are tracked from when `r` was made (`Hierarchy::track_occupancy`).
    pub(super) fn holding(r: Rings) -> RingCache {
        RingCache { rings: Some(r) }
    }

    pub(super) fn get(&mut self, h: &mut Hierarchy) -> &Rings {
        match &mut self.rings {
            Some(r) => {
                let changed = h.take_occupancy_changes();
                if !changed.is_empty() {
                    // Only the cells near hexagons that changed are claimed again.
                    r.update_changed(h, changed);
                    debug_assert!(same_rings(r, &rings(h)), "incremental rings differ");
                }
            }
            None => {
                h.track_occupancy();
                self.rings = Some(rings(h));
            }
        }
        self.rings.get_or_insert_with(|| rings(h))
    }

    /// The up-to-date rings, taken out of the cache until `put` gives them back unchanged.
    pub(super) fn take(&mut self, h: &mut Hierarchy) -> Rings {
        self.get(h);
        self.rings.take().expect("`get` fills the cache")
    }

    pub(super) fn put(&mut self, r: Rings) {
        self.rings = Some(r);
    }
}

/// True when two ring sets give every cell the same role, contest, class and conflicts.
pub(super) fn same_rings(a: &Rings, b: &Rings) -> bool {
    let roles = |x: &FxHashMap<Key, Role>, y: &FxHashMap<Key, Role>| {
        x.len() == y.len() && x.iter().all(|(k, v)| y.get(k) == Some(v))
    };
    roles(&a.roles, &b.roles)
        && roles(&a.contested, &b.contested)
        && a.occupied == b.occupied
        && a.conflicts == b.conflicts
}
