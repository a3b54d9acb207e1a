//! The moving conditions of paper 001 Sec. 5.1 (step 7): a tree corner p near the boundary
//! where rhombs of different sizes meet, or a splitting point, is made movable. The hexagon
//! side (a_j, a_{j+3}) through p, j the direction of the nearest boundary crossing (`near`),
//! cuts the hexagon around p into two parts; a part that cannot be triangulated into
//! triangles of one size is made so by cutting the larger rhomb's halves lying in it into
//! four (`halves`).
//!
//! Around p the mesh is read as six sectors: sector s is the small triangle (p, p + d_s,
//! p + d_{s+1}) of a lattice finer than every leaf at p, and it is covered by one triangle of
//! the mesh (a leaf half or a quarter of a cut half). The part of sectors j, j+1, j+2 and the
//! part of j+3, j+4, j+5 are *even* when their three covering triangles have one size and p
//! is a corner of each.
//!
//! Departure, chosen where the paper leaves it open: the paper measures the parts in the
//! hexagon of side l, the largest rhomb's side at p; at a splitting point that hexagon is not
//! made of triangles with corner p at all. Here each part is made even *at p*: its coarsest
//! leaf halves are cut until its three triangles have one size and corner p, which for a
//! corner of rhombs of two sizes is the paper's rule (the larger rhomb's halves in the part
//! are cut) and for a splitting point cuts the halves whose side p halves.

use super::super::tree::{Cover, Tree};
use super::halves::{Halves, Tri};
use super::near::DIRECTIONS;

/// How many levels below the coarsest leaf at a corner the sectors are read: leaves at a
/// corner are at most one level apart (balance) and a cut half adds one more.
pub const FINER: u8 = 3;

/// The six triangles of the mesh around level-`fine` lattice vertex p, by sector, or `None`
/// where the tree is finer than `fine` or p lies on the root's boundary.
pub fn sectors(tree: &Tree, halves: &Halves, fine: u8, p: (i64, i64)) -> Option<[Tri; 6]> {
    let mut out = [Tri {
        cell: super::super::lattice::Cell::ROOT,
        half: 0,
    }; 6];
    for (s, slot) in out.iter_mut().enumerate() {
        let (a, b) = (DIRECTIONS[s], DIRECTIONS[(s + 1) % 6]);
        let corners = [p, (p.0 + a.0, p.1 + a.1), (p.0 + b.0, p.1 + b.1)];
        *slot = halves.covering(tree, fine, corners)?;
    }
    Some(out)
}

/// Whether the triangles `tris` have one size and the level-`fine` vertex p as a corner.
pub fn even(tris: &[Tri], fine: u8, p: (i64, i64)) -> bool {
    tris.iter()
        .all(|t| t.cell.level == tris[0].cell.level && t.has_corner(fine, p))
}

/// The sectors of part `part` (0: j, j+1, j+2; 1: j+3, j+4, j+5) of the hexagon cut by the
/// side (a_j, a_{j+3}).
fn part(tris: &[Tri; 6], j: usize, part: usize) -> [Tri; 3] {
    [0, 1, 2].map(|k| tris[(j + 3 * part + k) % 6])
}

/// What step 7 did at a corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Both parts are even; `cut` leaf halves were cut into four to make them so.
    Movable { cut: usize },
    /// A part stays uneven: its coarsest triangle is a quarter already, or the sectors could
    /// not be read (the tree is finer than `fine` there, or p is on the root's boundary).
    /// Open case, left unresolved: halves cut at neighbouring corners can put triangles of
    /// three sizes around p (quarters of a cut half beside quarters of a cut smaller half),
    /// which the paper's rule, made for a corner of two rhomb sizes, does not reach. On imr
    /// one corner (level-10 vertex (815, 555)) ends so; splitting the leaf under the coarsest
    /// quarter in the tree proper would be the next thing to try.
    Stuck,
}

/// Enforces the moving condition at level-`fine` vertex p whose nearest boundary crossing is
/// on hexagon side j.
pub fn ensure(tree: &Tree, halves: &mut Halves, fine: u8, p: (i64, i64), j: usize) -> Outcome {
    let mut cut = 0;
    for side in 0..2 {
        loop {
            let Some(tris) = sectors(tree, halves, fine, p) else {
                return Outcome::Stuck;
            };
            let tris = part(&tris, j, side);
            if even(&tris, fine, p) {
                break;
            }
            let coarsest = tris.iter().map(|t| t.cell.level).min().unwrap_or(0);
            let mut any = false;
            for t in tris.iter().filter(|t| t.cell.level == coarsest) {
                // Only a leaf's half can be cut; a quarter is as fine as this goes.
                if tree.cover(t.cell) == Cover::Leaf(t.cell) && halves.cut(t.cell, t.half) {
                    cut += 1;
                    any = true;
                }
            }
            if !any {
                return Outcome::Stuck;
            }
        }
    }
    Outcome::Movable { cut }
}

#[cfg(test)]
mod tests {
    use super::super::super::lattice::Cell;
    use super::*;

    /// Level-2 leaves everywhere but cell (1, 1), split into level-3 leaves.
    fn two_sizes() -> Tree {
        let mut tree = Tree::new(vec![], 0);
        tree.split(Cell::ROOT).unwrap();
        for c in Cell::ROOT.children() {
            tree.split(c).unwrap();
        }
        tree.split(Cell::new(2, 1, 1)).unwrap();
        tree
    }

    #[test]
    fn at_a_corner_of_two_sizes_the_larger_halves_of_an_uneven_part_are_cut() {
        let tree = two_sizes();
        let fine = 2 + FINER;
        // p = (2, 2) of level 2: the 60° corner of the split cell (1, 1), which fills sector
        // 3 alone (between -e1 and -e2); the other five sectors are level-2 halves.
        let p = (2 << FINER, 2 << FINER);
        let mut halves = Halves::default();
        let before = sectors(&tree, &halves, fine, p).unwrap();
        let levels: Vec<u8> = before.iter().map(|t| t.cell.level).collect();
        assert_eq!(levels, vec![2, 2, 2, 3, 2, 2]);
        assert!(!even(&before, fine, p));
        // Nearest crossing on side 0: part 0, 1, 2 is even; part 3, 4, 5 is not, and both
        // halves of level-2 cell (2, 1) (sectors 4 and 5) are cut.
        assert_eq!(
            ensure(&tree, &mut halves, fine, p, 0),
            Outcome::Movable { cut: 2 }
        );
        assert_eq!(halves.len(), 2);
        let after = sectors(&tree, &halves, fine, p).unwrap();
        let levels: Vec<u8> = after.iter().map(|t| t.cell.level).collect();
        assert_eq!(levels, vec![2, 2, 2, 3, 3, 3]);
        assert!(even(&part(&after, 0, 0), fine, p) && even(&part(&after, 0, 1), fine, p));
        // Enforced again, nothing more is cut.
        assert_eq!(
            ensure(&tree, &mut halves, fine, p, 0),
            Outcome::Movable { cut: 0 }
        );
        // Nearest crossing on side 1: part 1, 2, 3 is uneven (both halves of cell (1, 2) are
        // cut), part 4, 5, 0 even.
        let mut other = Halves::default();
        assert_eq!(
            ensure(&tree, &mut other, fine, p, 1),
            Outcome::Movable { cut: 2 }
        );
        let levels: Vec<u8> = sectors(&tree, &other, fine, p)
            .unwrap()
            .iter()
            .map(|t| t.cell.level)
            .collect();
        assert_eq!(levels, vec![2, 3, 3, 3, 2, 2]);
    }

    #[test]
    fn a_part_whose_coarsest_triangle_is_a_quarter_is_stuck() {
        let tree = two_sizes();
        let fine = 2 + FINER;
        let p = (2 << FINER, 2 << FINER);
        let mut halves = Halves::default();
        // Sector 3's level-3 leaf half and sector 4's level-2 half cut beforehand: part 3, 4,
        // 5 holds triangles of levels 4, 3 and 2. Cutting sector 5's half leaves levels 4, 3,
        // 3, the level-3 ones quarters, which are not cut again.
        assert!(halves.cut(Cell::new(3, 3, 3), 1) && halves.cut(Cell::new(2, 2, 1), 0));
        let levels: Vec<u8> = sectors(&tree, &halves, fine, p)
            .unwrap()
            .iter()
            .map(|t| t.cell.level)
            .collect();
        assert_eq!(levels, vec![2, 2, 2, 4, 3, 2]);
        assert_eq!(ensure(&tree, &mut halves, fine, p, 0), Outcome::Stuck);
        assert_eq!(halves.len(), 3);
    }

    #[test]
    fn at_a_splitting_point_the_halves_it_halves_are_cut() {
        let tree = two_sizes();
        let fine = 3 + FINER;
        // Level-3 vertex (4, 3): right corner of the split cell's leaves, the midpoint of the
        // left side of level-2 cell (2, 1).
        let p = (4 << FINER, 3 << FINER);
        let mut halves = Halves::default();
        let before = sectors(&tree, &halves, fine, p).unwrap();
        // Side 1 (along e2) is the split side: left of it three level-3 leaves with corner
        // p, right of it three sectors of half 0 of (2, 1), p the midpoint of its side.
        assert!(even(&part(&before, 1, 0), fine, p));
        assert!(!even(&part(&before, 1, 1), fine, p));
        assert_eq!(
            before[0],
            Tri {
                cell: Cell::new(2, 2, 1),
                half: 0
            }
        );
        assert_eq!(
            ensure(&tree, &mut halves, fine, p, 1),
            Outcome::Movable { cut: 1 }
        );
        let after = sectors(&tree, &halves, fine, p).unwrap();
        assert!(even(&after, fine, p), "{after:?}");
        assert!(after.iter().all(|t| t.cell.level == 3), "{after:?}");
    }
}
