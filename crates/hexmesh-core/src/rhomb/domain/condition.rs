//! Sec. 4 step 3, the corner condition of paper 001 Sec. 3: the leaf B holding a single point
//! or a corner of at most 60°, and its first neighbours, have one size; for a corner above
//! 60°, B and its first, second and third neighbours do. Larger rhombs around B are split;
//! when a rhomb around B is already finer, B itself is split (it is the larger one), and the
//! test starts again at the point's new leaf.
//!
//! The k-th neighbours of B (rhombs at distance k − 1, Sec. 3) are, for rhombs of B's size,
//! the cells (i + di, j + dj) with max(|di|, |dj|) = k: the rule asks the square of
//! `Class::reach` cells around B. Cells outside the root rhomb are virtual and ask nothing.
//!
//! Splitting for one point can break the condition of a point near it (the regions of two
//! corners overlap when their leaves are at most six rhombs apart), so the points are swept
//! until a whole sweep splits nothing. Every split is towards the finer of two sizes already
//! present, so the sweeps end.

use crate::rhomb::lattice::Cell;
use crate::rhomb::tree::{Cover, Guard, Stop, Tree};

/// The rhomb whose split brings point `p`'s leaf and the square of `reach` cells around it
/// closer to one size, or `None` when they have it.
fn to_split(tree: &Tree, p: u32, reach: i64) -> Option<Cell> {
    let b = tree.locate(p);
    for dj in -reach..=reach {
        for di in -reach..=reach {
            match tree.cover(b.offset(di, dj)) {
                Cover::Leaf(l) if l.level < b.level => return Some(l),
                Cover::Split => return Some(b),
                _ => {}
            }
        }
    }
    None
}

/// Splits until every `(point, reach)` meets the corner condition.
pub fn ensure(tree: &mut Tree, points: &[(u32, i64)], guard: &Guard) -> Result<(), Stop> {
    loop {
        let mut split = false;
        for &(p, reach) in points {
            while let Some(c) = to_split(tree, p, reach) {
                guard.check(tree)?;
                tree.split(c)?;
                split = true;
            }
        }
        if !split {
            return Ok(());
        }
    }
}

/// Whether `(point, reach)` meets the corner condition in `tree`.
#[cfg(test)]
pub fn holds(tree: &Tree, p: u32, reach: i64) -> bool {
    to_split(tree, p, reach).is_none()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesher::Budget;

    #[test]
    fn a_point_beside_a_deep_split_gets_neighbours_of_its_size() {
        // Two points, one of them split deep by hand: the other's leaf is coarse.
        let mut tree = Tree::new(vec![[0.30, 0.30], [0.36, 0.30]], 0);
        let mut c = Cell::ROOT;
        for _ in 0..7 {
            tree.split(c).unwrap();
            let l = c.level + 1;
            c = Cell::new(
                l,
                crate::rhomb::tree::index_at(0.36, l),
                crate::rhomb::tree::index_at(0.30, l),
            );
        }
        assert!(!holds(&tree, 0, 3));
        let guard = Guard::new(Budget::default());
        ensure(&mut tree, &[(0, 3), (1, 1)], &guard).unwrap();
        assert!(holds(&tree, 0, 3) && holds(&tree, 1, 1));
        // The deep split forced point 0's rhomb down to level 7 as well.
        assert_eq!(tree.locate(0).level, 7);
        assert_eq!(tree.locate(1).level, 7);
    }
}
