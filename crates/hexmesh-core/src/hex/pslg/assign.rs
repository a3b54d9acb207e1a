//! Segments assigned to hexagons, paper Sec. 7.1: a segment belongs to every leaf whose
//! closed constructed hexagon it meets, decided exactly (`hexagon_meets_segment`: `orient2d`
//! against the lattice's bit-shared corners). A segment that only touches a hexagon's edge or
//! corner is assigned to it too, so a segment on the common edge of two hexagons belongs to
//! both. A semi-hexagon is tested as the half of its cell inside its owner (four of the cell's
//! corners). `crossed_cells` computes the assignment from the hierarchy; the rule loop keeps
//! it up to date after every batch of splits and joins (`Assignment`), re-assigning only the
//! cells the batch changed, as the paper does at each split and join, and gets the same sets.

use std::collections::BTreeMap;

use crate::geom::{orient2d, Point};
use crate::hex::key::Parents;
use crate::hex::lattice::{FxHashMap, FxHashSet, Key};
use crate::hex::subdivision::{Cell, Hierarchy};

/// True when the closed convex hexagon with counter-clockwise `corners` and the closed segment
/// ab share a point. Exact: no hexagon edge has both a and b strictly outside it, and the line
/// ab does not have all six corners strictly on one side (separating axes of two convex sets).
pub fn hexagon_meets_segment(corners: &[Point; 6], a: Point, b: Point) -> bool {
    polygon_meets_segment(corners, a, b)
}

/// `hexagon_meets_segment` for any closed convex polygon with counter-clockwise corners.
pub fn polygon_meets_segment(corners: &[Point], a: Point, b: Point) -> bool {
    let n = corners.len();
    for m in 0..n {
        let (p, q) = (corners[m], corners[(m + 1) % n]);
        if orient2d(p, q, a) < 0.0 && orient2d(p, q, b) < 0.0 {
            return false;
        }
    }
    let sides: Vec<f64> = corners.iter().map(|&c| orient2d(a, b, c)).collect();
    !(sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0))
}

/// The leaves (full unsubdivided hexagons and semi-hexagons) each segment meets, with the
/// indices of the segments meeting them, sorted: the assignment of Sec. 7.1 by the rule of the
/// module docs, found by descending from the root through the hexagons the segment meets.
pub fn crossed_cells(h: &Hierarchy, segments: &[[Point; 2]]) -> BTreeMap<Key, Vec<u32>> {
    let mut out: BTreeMap<Key, Vec<u32>> = BTreeMap::new();
    for (s, &[a, b]) in segments.iter().enumerate() {
        let mut stack = vec![Key::ROOT];
        let mut seen: FxHashSet<Key> = FxHashSet::default();
        while let Some(key) = stack.pop() {
            if !key.inside() || !seen.insert(key) {
                continue;
            }
            let corners = h.lattice.corners(key);
            if !hexagon_meets_segment(&corners, a, b) {
                continue;
            }
            let cell = h.cell(key);
            // A semi-hexagon is the half of its cell inside its owner: the four corners of the
            // cell in the owner's closed hexagon (the two on the long edge are corners of both).
            if let Cell::Semi { owner, .. } = cell {
                let half: Vec<Point> = corners
                    .into_iter()
                    .filter(|&c| h.closed_contains(owner, c))
                    .collect();
                if !polygon_meets_segment(&half, a, b) {
                    continue;
                }
            }
            match cell {
                Cell::Full { subdivided: true } => stack.extend(key.children()),
                Cell::Full { subdivided: false } | Cell::Semi { .. } => {
                    out.entry(key).or_default().push(s as u32)
                }
                _ => {}
            }
        }
    }
    for v in out.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    out
}

/// The assignment of `crossed_cells`, kept up to date across batches of subdivisions
/// (`update`) at a cost of the cells each batch changed, not of every crossed cell: the rule
/// loop of Sec. 7.2 runs a round per batch, and recomputing the whole assignment each round
/// made it quadratic in the length of the segments' band (fixture
/// tests/fixtures/hex/pslg-spade-issue96-box-hang.poly: a wave of subdivisions one cell a
/// round along the box's sides, tens of thousands of rounds).
///
/// It follows the descent of `crossed_cells`: a segment reaches a cell from a parent it meets
/// that is subdivided and inside the bounding hexagon (from the owner alone for a
/// semi-hexagon), and is assigned to the cell when it also meets the cell's closed hexagon
/// (for a semi-hexagon, its half inside the owner). Subdividing a hexagon changes the cell of
/// the hexagon itself and of its seven children only (`Hierarchy::cell` reads the subdivided
/// flags of a cell and its parents), so those are the cells `update` re-assigns. A full cell
/// stays full while the rules run (they only subdivide), so the segments reaching it are
/// kept (`reaching`).
pub(super) struct Assignment<'a> {
    segments: &'a [[Point; 2]],
    /// For full cells: the segments that reach the cell and meet its closed hexagon.
    reaching: FxHashMap<Key, Vec<u32>>,
    /// The assignment: every leaf with the segments it is assigned, as `crossed_cells` gives.
    crossed: BTreeMap<Key, Vec<u32>>,
}

impl<'a> Assignment<'a> {
    /// The assignment of `segments` in `h` now.
    pub(super) fn new(h: &Hierarchy, segments: &'a [[Point; 2]]) -> Assignment<'a> {
        let mut a = Assignment {
            segments,
            reaching: FxHashMap::default(),
            crossed: BTreeMap::new(),
        };
        let mut stack = vec![Key::ROOT];
        let mut seen: FxHashSet<Key> = FxHashSet::default();
        while let Some(key) = stack.pop() {
            if !seen.insert(key) {
                continue;
            }
            if h.cell(key) == (Cell::Full { subdivided: true })
                && !a.full_reaching(h, key).is_empty()
            {
                stack.extend(key.children());
            } else {
                a.assign(h, key);
            }
        }
        a
    }

    /// The leaves crossed by segments, with the segments crossing each, sorted.
    pub(super) fn crossed(&self) -> &BTreeMap<Key, Vec<u32>> {
        &self.crossed
    }

    /// The assignment, taken out.
    pub(super) fn into_crossed(self) -> BTreeMap<Key, Vec<u32>> {
        self.crossed
    }

    /// Re-assigns the cells that subdividing each of `subdivided` (the batch's log) changed:
    /// the hexagon, no longer a leaf, and its children.
    pub(super) fn update(&mut self, h: &Hierarchy, subdivided: &[Key]) {
        for &key in subdivided {
            self.crossed.remove(&key);
            for child in key.children() {
                self.assign(h, child);
            }
        }
    }

    /// Sets `key`'s entry of the assignment from the hierarchy now: the segments assigned to
    /// it when it is a leaf, none otherwise.
    fn assign(&mut self, h: &Hierarchy, key: Key) {
        self.crossed.remove(&key);
        if !key.inside() {
            return;
        }
        let segments = match h.cell(key) {
            Cell::Full { subdivided: false } => self.full_reaching(h, key).clone(),
            Cell::Semi { owner, .. } if owner.inside() && h.is_subdivided(owner) => {
                let corners = h.lattice.corners(key);
                let half: Vec<Point> = corners
                    .into_iter()
                    .filter(|&c| h.closed_contains(owner, c))
                    .collect();
                let segments = self.segments;
                self.full_reaching(h, owner)
                    .iter()
                    .copied()
                    .filter(|&s| {
                        let [a, b] = segments[s as usize];
                        hexagon_meets_segment(&corners, a, b) && polygon_meets_segment(&half, a, b)
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        if !segments.is_empty() {
            self.crossed.insert(key, segments);
        }
    }

    /// The segments reaching the full cell `key` that meet its closed hexagon, ascending.
    fn full_reaching(&mut self, h: &Hierarchy, key: Key) -> &Vec<u32> {
        if !self.reaching.contains_key(&key) {
            // Parents first, iteratively: a chain of missing ancestors can be long.
            let mut pending = vec![key];
            while let Some(&k) = pending.last() {
                let parents: Vec<Key> = match k.parents() {
                    Parents::None => Vec::new(),
                    Parents::Central(p) => vec![p],
                    Parents::Edge(a, b) => vec![a, b],
                };
                let through: Vec<Key> = parents
                    .into_iter()
                    .filter(|&p| p.inside() && h.is_subdivided(p))
                    .collect();
                if let Some(&missing) = through.iter().find(|p| !self.reaching.contains_key(p)) {
                    pending.push(missing);
                    continue;
                }
                pending.pop();
                let candidates: Vec<u32> = if k == Key::ROOT {
                    (0..self.segments.len() as u32).collect()
                } else {
                    let mut c: Vec<u32> = through
                        .iter()
                        .flat_map(|p| self.reaching[p].iter().copied())
                        .collect();
                    c.sort_unstable();
                    c.dedup();
                    c
                };
                let corners = h.lattice.corners(k);
                let met: Vec<u32> = candidates
                    .into_iter()
                    .filter(|&s| {
                        let [a, b] = self.segments[s as usize];
                        hexagon_meets_segment(&corners, a, b)
                    })
                    .collect();
                self.reaching.insert(k, met);
            }
        }
        &self.reaching[&key]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_hexagon() -> [Point; 6] {
        std::array::from_fn(|m| {
            let a = (60.0 * m as f64).to_radians();
            [a.cos(), a.sin()]
        })
    }

    #[test]
    fn a_segment_through_the_hexagon_meets_it() {
        let c = unit_hexagon();
        assert!(hexagon_meets_segment(&c, [-2.0, 0.1], [2.0, -0.1]));
        assert!(hexagon_meets_segment(&c, [0.0, 0.0], [0.1, 0.1]));
    }

    #[test]
    fn a_segment_beside_the_hexagon_does_not_meet_it() {
        let c = unit_hexagon();
        assert!(!hexagon_meets_segment(&c, [-2.0, 1.0], [2.0, 1.0]));
        assert!(!hexagon_meets_segment(&c, [1.5, -3.0], [1.5, 3.0]));
        // The line meets the hexagon, the segment stops short of it.
        assert!(!hexagon_meets_segment(&c, [-3.0, 0.0], [-1.5, 0.0]));
    }

    #[test]
    fn a_segment_touching_a_corner_or_lying_on_an_edge_meets_the_closed_hexagon() {
        let c = unit_hexagon();
        assert!(hexagon_meets_segment(&c, [1.0, 0.0], [2.0, 0.0]));
        assert!(hexagon_meets_segment(&c, c[1], c[2]));
        assert!(hexagon_meets_segment(&c, [-2.0, c[1][1]], [2.0, c[1][1]]));
    }
}
