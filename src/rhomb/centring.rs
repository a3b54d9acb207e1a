//! Centring single points (paper 001, Sec. 4 step 5, Sec. 5.4–5.5 and Fig. 11).
//!
//! The paper moves the corner b nearest to p onto p when p is centred, and otherwise melts
//! four rhombs into one of side 2l "offset by half" so that p is centred in it (the Claim of
//! Sec. 5.4: dist > 0.6485 l' > 0.6 l'). We always take the melted form: with l the side of
//! p's leaf, the patch is the hexagon of side 2L (L = 2l) of a lattice of spacing L centred at m,
//! the level-k lattice vertex nearest to p. Then |p − m| ≤ l/√3 = 0.2887 L, inside the disc of
//! radius (√3 − 1)/2·L = 0.366 L where all six triangles (p, A_i, A_{i+1}) keep every angle in
//! [30°, 90°] (the nearest bound is the 90° at p: p must stay off the disc on A_iA_{i+1}).
//! The outer ring of the patch (the paper's melted first and second neighbours) stays equilateral
//! and is joined to the level-k rhombs around it by midpoints on its outer edges, giving
//! 30-60-90 triangles as in pattern 10(c).
//!
//! Departures, all by refining more (which is always safe): the patch's zone (its rhombs and
//! every rhomb touching it) must be level-k leaves inside the hexagon; a coarser rhomb there is
//! split, a finer one splits p's leaf instead, and two zones that meet split both points' leaves.
//! These replace the paper's corner condition (Sec. 3) and protection (Sec. 4 step 5), whose
//! missing figure leaves the size of the protected area open.

use std::collections::{BTreeMap, BTreeSet};

use super::lattice::{hexnorm, Cell};
use super::tree::{Cover, Guard, Stop, Tree};

/// Circumradius of the patch in level-k steps (side 2L, L = 2l).
pub const PATCH_RADIUS: i64 = 4;

/// One input point and the patch that carries it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Patch {
    pub point: u32,
    pub level: u8,
    /// The level-k lattice vertex m the patch is centred at.
    pub centre: (i64, i64),
}

impl Patch {
    /// The level-k rhombs inside or touching the closed patch, in a fixed order.
    pub fn zone(&self) -> Vec<Cell> {
        let (mi, mj) = self.centre;
        let r = PATCH_RADIUS;
        let mut cells = Vec::new();
        for j in mj - r - 1..=mj + r {
            for i in mi - r - 1..=mi + r {
                let touches = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .iter()
                    .any(|&(a, b)| hexnorm(i + a - mi, j + b - mj) <= r);
                if touches {
                    cells.push(Cell::new(self.level, i, j));
                }
            }
        }
        cells
    }

    /// The halves (0 lower, 1 upper) of level-k rhombs that lie inside the patch.
    pub fn halves(&self) -> Vec<(Cell, u8)> {
        let (mi, mj) = self.centre;
        let inside = |i: i64, j: i64| hexnorm(i - mi, j - mj) <= PATCH_RADIUS;
        self.zone()
            .into_iter()
            .flat_map(|c| {
                let (i, j) = (c.i, c.j);
                let lower = inside(i, j) && inside(i + 1, j) && inside(i, j + 1);
                let upper = inside(i + 1, j) && inside(i + 1, j + 1) && inside(i, j + 1);
                [(lower, (c, 0u8)), (upper, (c, 1u8))]
            })
            .filter(|&(keep, _)| keep)
            .map(|(_, h)| h)
            .collect()
    }
}

/// The level-k lattice vertex nearest to root-normalised coordinates (s, t), by the lattice
/// metric |a·e1 + b·e2|² = a² + ab + b².
pub fn nearest_vertex(st: [f64; 2], level: u8) -> (i64, i64) {
    let n = (1i64 << level) as f64;
    let (x, y) = (st[0] * n, st[1] * n);
    let (i0, j0) = (x.floor() as i64, y.floor() as i64);
    let mut best = (i0, j0);
    let mut best_d = f64::INFINITY;
    for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let (dx, dy) = (x - (i0 + a) as f64, y - (j0 + b) as f64);
        let d = dx * dx + dx * dy + dy * dy;
        if d < best_d {
            best_d = d;
            best = (i0 + a, j0 + b);
        }
    }
    best
}

/// Refines the tree until every point has a patch whose zone is made of level-k leaves inside
/// the hexagon and meets no other zone; returns the patches in point order.
pub fn centre_points(tree: &mut Tree, points: u32, guard: &Guard) -> Result<Vec<Patch>, Stop> {
    loop {
        guard.check(tree)?;
        let mut to_split: BTreeSet<Cell> = BTreeSet::new();
        let mut patches = Vec::with_capacity(points as usize);
        for p in 0..points {
            let leaf = tree.locate(p);
            let patch = Patch {
                point: p,
                level: leaf.level,
                centre: nearest_vertex(tree.coords(p), leaf.level),
            };
            for c in patch.zone() {
                if !c.in_hexagon() {
                    to_split.insert(leaf);
                    break;
                }
                match tree.cover(c) {
                    Cover::Leaf(l) if l == c => {}
                    Cover::Leaf(coarser) => {
                        to_split.insert(coarser);
                    }
                    Cover::Split | Cover::Outside => {
                        to_split.insert(leaf);
                        break;
                    }
                }
            }
            patches.push(patch);
        }
        if to_split.is_empty() {
            let mut claims: BTreeMap<Cell, u32> = BTreeMap::new();
            for patch in &patches {
                for c in patch.zone() {
                    if let Some(other) = claims.insert(c, patch.point) {
                        if other != patch.point {
                            to_split.insert(tree.locate(other));
                            to_split.insert(tree.locate(patch.point));
                        }
                    }
                }
            }
            if to_split.is_empty() {
                return Ok(patches);
            }
        }
        for c in to_split {
            tree.split(c)?;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_patch_is_96_level_k_triangles_in_its_zone() {
        let p = Patch {
            point: 0,
            level: 6,
            centre: (20, 30),
        };
        assert_eq!(p.halves().len(), 96);
        let zone: BTreeSet<Cell> = p.zone().into_iter().collect();
        assert!(p.halves().iter().all(|(c, _)| zone.contains(c)));
    }

    #[test]
    fn nearest_vertex_is_within_the_lattice_voronoi_radius() {
        for k in 0..200 {
            let st = [
                0.3 + (k as f64 * 0.618).fract() / 64.0,
                0.4 + (k as f64 * 0.414).fract() / 64.0,
            ];
            let (i, j) = nearest_vertex(st, 6);
            let (dx, dy) = (st[0] * 64.0 - i as f64, st[1] * 64.0 - j as f64);
            let d = (dx * dx + dx * dy + dy * dy).sqrt();
            assert!(d <= 1.0 / 3f64.sqrt() + 1e-12, "{d}");
        }
    }
}
