//! A neighbourhood of changed hexagons, for work proportional to what changes (paper 000
//! Sec. 8 names the O(n²) refinement loop of its prototype as the obstacle; Sec. 1 and 9 the
//! incremental insertion of points).
//!
//! After a first complete pass, the extended refinement only changes the subdivision around
//! a few hexagons (the ones a rule or the self-check subdivided, the ring cells that flipped,
//! the hexagons that received an added point). Classes and relocated centres (Sec. 5.1, 5.4)
//! depend on cells at most a few lattice steps away, so the triangles that can change lie
//! within a fixed lattice distance of a changed cell, at every level. A `Region` holds, for
//! every level, the cells within that distance of the ancestors of the changed cells, and
//! answers whether a lattice triangle of the dual recursion (`dual`) or a leaf may be
//! affected; everything else is known not to have changed.

use std::sync::Arc;

use crate::hex::lattice::{FxHashMap, FxHashSet, Key, KeyBytes};
use crate::hex::subdivision::{Cell, Hierarchy};

/// How far (in cells of their own level) the class, the relocated centre and the triangles
/// of a cell reach: fins and the fixed hexagons beyond them (2), the 2-ring of an occupied
/// hexagon (2), the top neighbour and consecutive runs of MOVED_CENTER_3 hexagons (2), and
/// the triangles around a relocated centre (1); 2 more cover the rounding of ancestors.
pub const REACH: i64 = 8;

/// The cells near a set of changed cells, level by level.
#[derive(Debug, Clone, Default)]
pub struct Region {
    /// The lattice distance of each cell within the widest reach built to the nearest anchor
    /// of its level; shared by the narrower views of `within`. Kept by 8 × 8 blocks: the
    /// search below walks the lattice, and the checks ask about cells in the dual's order.
    dist: Arc<KeyBytes>,
    /// The cells within this distance belong to the region.
    reach: u8,
    /// Two levels below the finest changed cell, plus one: below it nothing changed.
    depth: u8,
}

impl Region {
    /// The cells within `reach` of the ancestors, at every level, of `changed`, and of the
    /// cells up to two levels finer (a subdivision creates children).
    pub fn around(changed: &[Key], reach: i64) -> Region {
        let reach = reach.clamp(0, KeyBytes::NONE as i64 - 1) as u8;
        let mut anchors: FxHashMap<u8, FxHashSet<(i64, i64)>> = FxHashMap::default();
        let mut depth = 0;
        for &c in changed {
            // Two levels finer than the changed cell: its children, and the leaves beside
            // them, which balancing keeps within one level of them.
            let finest = c.central_child().central_child();
            depth = depth.max(finest.k + 1);
            for k in 0..=finest.k {
                let s = finest.k - k;
                anchors
                    .entry(k)
                    .or_default()
                    .insert((finest.i.div_euclid(1 << s), finest.j.div_euclid(1 << s)));
            }
        }
        let mut levels: Vec<u8> = anchors.keys().copied().collect();
        levels.sort_unstable();
        // The distance of every cell within `reach` of the anchors, level by level, by a
        // breadth-first search over the six lattice directions: each cell is visited once,
        // where the discs of anchors a few cells apart (the finer levels, where adjacent
        // changed cells give anchors 2^s apart) overlapped many times.
        let mut dist = KeyBytes::default();
        for k in levels {
            let mut cells: Vec<(i64, i64)> = anchors[&k].iter().copied().collect();
            cells.sort_unstable();
            let mut frontier: Vec<Key> = Vec::with_capacity(cells.len());
            for (i, j) in cells {
                let key = Key::new(k, i, j);
                if dist.insert_new(key, 0) {
                    frontier.push(key);
                }
            }
            for step in 1..=reach {
                let mut next = Vec::with_capacity(frontier.len() * 2);
                for c in &frontier {
                    for d in 0..6 {
                        let n = c.neighbor(d);
                        if dist.insert_new(n, step) {
                            next.push(n);
                        }
                    }
                }
                frontier = next;
            }
        }
        Region {
            dist: Arc::new(dist),
            reach,
            depth,
        }
    }

    /// The same region with a smaller reach (at most this one's), sharing its distances.
    pub fn within(&self, reach: i64) -> Region {
        Region {
            dist: Arc::clone(&self.dist),
            reach: reach.clamp(0, self.reach as i64) as u8,
            depth: self.depth,
        }
    }

    /// True when `key` lies within the region at its own level.
    pub fn contains(&self, key: Key) -> bool {
        key.k < self.depth && self.dist.get(&key).is_some_and(|d| d <= self.reach)
    }

    /// True when a lattice triangle of the dual recursion may hold changed triangles: one of
    /// its cells is in the region at its level.
    pub fn touches(&self, tri: &[Key; 3]) -> bool {
        tri.iter().any(|&c| self.contains(c))
    }

    /// The cells of the region, over all levels, in no particular order.
    pub fn cells(&self) -> impl Iterator<Item = Key> + '_ {
        self.dist
            .iter()
            .filter(|&(k, d)| d <= self.reach && k.k < self.depth)
            .map(|(k, _)| k)
    }

    /// The number of cells held, over all levels (a measure of the work done).
    pub fn len(&self) -> usize {
        self.dist.iter().filter(|&(_, d)| d <= self.reach).count()
    }

    /// Whether the region holds no cell.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The full leaves of `h` inside `region`, sorted: the descent of `Hierarchy::leaves`, pruned
/// to subdivided cells in the region (a leaf in the region has its parent there too, since
/// the region holds the ancestors of its cells with a margin).
pub fn full_leaves_in(h: &Hierarchy, region: &Region) -> Vec<Key> {
    let mut out = Vec::new();
    let mut seen: FxHashSet<Key> = FxHashSet::default();
    let mut stack = vec![Key::ROOT];
    while let Some(key) = stack.pop() {
        if !h.is_subdivided(key) {
            continue;
        }
        for c in key.children() {
            if !region.contains(c) {
                continue;
            }
            match h.cell(c) {
                Cell::Full { subdivided: true } if seen.insert(c) => stack.push(c),
                Cell::Full { subdivided: false } if c.inside() => out.push(c),
                _ => {}
            }
        }
    }
    if !h.is_subdivided(Key::ROOT) {
        out.push(Key::ROOT);
    }
    out.sort_unstable();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_region_holds_the_ancestors_of_a_changed_cell_at_every_level_with_their_discs() {
        let changed = Key::new(5, 13, -7);
        let r = Region::around(&[changed], 2);
        assert!(r.contains(changed));
        assert!(r.contains(changed.central_child()));
        assert!(r.contains(Key::new(5, 15, -7)));
        assert!(
            !r.contains(Key::new(5, 16, -7)),
            "outside the disc of radius 2"
        );
        assert!(r.contains(Key::new(0, 0, 0)));
        assert!(r.contains(Key::new(3, 3, -2)));
        assert!(r.contains(Key::new(7, 52, -28)));
        assert!(
            !r.contains(Key::new(8, 104, -56)),
            "three levels below the changed cell"
        );
    }

    #[test]
    fn a_narrower_view_holds_the_cells_of_a_region_built_with_that_reach() {
        let changed = [Key::new(4, 3, -2), Key::new(4, 4, -2), Key::new(6, 1, 9)];
        let wide = Region::around(&changed, 7);
        for reach in [0, 2, 5, 7] {
            let view = wide.within(reach);
            let built = Region::around(&changed, reach);
            assert_eq!(view.len(), built.len(), "reach {reach}");
            for k in 0..9u8 {
                for i in -40..40 {
                    for j in -40..40 {
                        let key = Key::new(k, i, j);
                        assert_eq!(view.contains(key), built.contains(key), "{key:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_cells_of_a_view_are_the_cells_it_contains() {
        let changed = [Key::new(4, 3, -2), Key::new(6, 1, 9)];
        let wide = Region::around(&changed, 5);
        let view = wide.within(2);
        let cells: Vec<Key> = view.cells().collect();
        assert_eq!(cells.len(), view.len());
        assert!(cells.iter().all(|&c| view.contains(c)));
        assert!(wide.cells().filter(|&c| !view.contains(c)).count() > 0);
    }

    #[test]
    fn an_empty_region_touches_nothing() {
        let r = Region::around(&[], REACH);
        assert!(r.is_empty());
        assert!(!r.touches(&[Key::ROOT, Key::ROOT.neighbor(0), Key::ROOT.neighbor(1)]));
    }
}
