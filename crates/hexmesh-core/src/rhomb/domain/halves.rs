//! The tree operation of paper 001 Sec. 5.1: a leaf rhomb is halved along its short diagonal
//! into two equilateral triangles, and a half is cut into four triangles of half the side,
//! without splitting the rhomb itself. The quad-tree keeps its leaves; the cut halves are kept
//! beside it, and `covering` answers which triangle of the resulting mesh covers a small
//! triangle of the lattice: a leaf's half, or a quarter of a cut half.
//!
//! Triangles are unit triangles of a level's lattice: half 0 or half 1 of a cell
//! (`lattice::half_corners`).

use super::super::lattice::{half_corners, Cell};
use super::super::tree::{Cover, KeySet, Tree};

/// A unit triangle of the level-`cell.level` lattice: half `half` of `cell`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Tri {
    pub cell: Cell,
    pub half: u8,
}

impl Tri {
    /// The unit triangle of level `level` holding the level-`fine` unit triangle with corners
    /// `corners` (`fine` ≥ `level`): the one holding its centroid, which lies inside a unit
    /// triangle of every coarser level.
    pub fn holding(level: u8, fine: u8, corners: [(i64, i64); 3]) -> Tri {
        let d = 3i64 << (fine - level);
        let sx: i64 = corners.iter().map(|c| c.0).sum();
        let sy: i64 = corners.iter().map(|c| c.1).sum();
        let (x, rx) = (sx.div_euclid(d), sx.rem_euclid(d));
        let (y, ry) = (sy.div_euclid(d), sy.rem_euclid(d));
        Tri {
            cell: Cell::new(level, x, y),
            half: u8::from(rx + ry >= d),
        }
    }

    /// Whether the level-`fine` lattice vertex p is one of this triangle's corners.
    pub fn has_corner(&self, fine: u8, p: (i64, i64)) -> bool {
        let shift = fine - self.cell.level;
        let mask = (1i64 << shift) - 1;
        if p.0 & mask != 0 || p.1 & mask != 0 {
            return false;
        }
        half_corners(self.cell, self.half).contains(&(p.0 >> shift, p.1 >> shift))
    }
}

/// The leaf halves cut into four (Sec. 5.1).
#[derive(Debug, Default)]
pub struct Halves {
    cut: KeySet<(Cell, u8)>,
}

impl Halves {
    /// Cuts half `half` of leaf `c` into four; false when it was cut already.
    pub fn cut(&mut self, c: Cell, half: u8) -> bool {
        self.cut.insert((c, half))
    }

    /// How many halves are cut.
    pub fn len(&self) -> usize {
        self.cut.len()
    }

    /// The triangle of the mesh (leaf halves, quarters of cut halves) covering the level-`fine`
    /// unit triangle with corners `corners`, or `None` when the tree is split finer than
    /// `fine` there or it lies outside the root.
    pub fn covering(&self, tree: &Tree, fine: u8, corners: [(i64, i64); 3]) -> Option<Tri> {
        let small = Tri::holding(fine, fine, corners);
        let Cover::Leaf(leaf) = tree.cover(small.cell) else {
            return None;
        };
        let half = Tri::holding(leaf.level, fine, corners);
        if self.cut.contains(&(half.cell, half.half)) {
            Some(Tri::holding(leaf.level + 1, fine, corners))
        } else {
            Some(half)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fine_triangle_is_held_by_the_coarse_half_its_centroid_lies_in() {
        // Level-2 unit triangle (1,0),(1,1),(0,1), the middle quarter of half 0 of level-1
        // cell (0,0), lies in that half, and (2,1),(2,2),(1,2) in its half 1, across the
        // short diagonal.
        let lower = Tri::holding(1, 2, [(1, 0), (1, 1), (0, 1)]);
        assert_eq!(
            lower,
            Tri {
                cell: Cell::new(1, 0, 0),
                half: 0
            }
        );
        let upper = Tri::holding(1, 2, [(2, 1), (2, 2), (1, 2)]);
        assert_eq!(
            upper,
            Tri {
                cell: Cell::new(1, 0, 0),
                half: 1
            }
        );
        // At its own level a unit triangle holds itself; negative coordinates floor.
        let t = Tri::holding(3, 3, [(-1, -1), (0, -1), (-1, 0)]);
        assert_eq!(
            t,
            Tri {
                cell: Cell::new(3, -1, -1),
                half: 0
            }
        );
        assert!(upper.has_corner(2, (2, 2)) && upper.has_corner(3, (4, 4)));
        assert!(!upper.has_corner(2, (1, 1)) && !upper.has_corner(3, (3, 2)));
    }

    #[test]
    fn a_cut_half_is_covered_by_quarters_and_the_other_half_stays_whole() {
        let mut tree = Tree::new(vec![], 0);
        tree.split(Cell::ROOT).unwrap();
        let leaf = Cell::new(1, 0, 0);
        let mut halves = Halves::default();
        // Level-3 triangles, one in each half of the leaf.
        let in_lower = [(0, 0), (1, 0), (0, 1)];
        let in_upper = [(3, 3), (4, 3), (3, 4)];
        assert_eq!(
            halves.covering(&tree, 3, in_lower),
            Some(Tri {
                cell: leaf,
                half: 0
            })
        );
        assert!(halves.cut(leaf, 0));
        assert!(!halves.cut(leaf, 0));
        assert_eq!(halves.len(), 1);
        assert_eq!(
            halves.covering(&tree, 3, in_lower),
            Some(Tri {
                cell: Cell::new(2, 0, 0),
                half: 0
            })
        );
        assert_eq!(
            halves.covering(&tree, 3, in_upper),
            Some(Tri {
                cell: leaf,
                half: 1
            })
        );
        // Outside the root nothing covers.
        assert_eq!(halves.covering(&tree, 3, [(-1, 0), (0, 0), (-1, 1)]), None);
    }
}
