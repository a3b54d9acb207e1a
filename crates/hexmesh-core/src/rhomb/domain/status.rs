//! Which tree corners lie in the domain (groundwork of paper 001 Sec. 4 step 9, "delete all
//! rhombs outside of the polygon", and of Sec. 2's cut of the tree edges crossing the
//! boundary), in time linear in the tree: a corner's status is passed along the sides of the
//! leaves, flipping at every crossing of the boundary, from a corner known to be outside (the
//! root rhomb's corner (0, 0), outside the bounding hexagon). Only the boundary sides in a
//! leaf's window list can cross its sides.
//!
//! Exact: every decision is an orientation sign of f64 positions. A boundary side ab crosses
//! the tree edge uw when a and b lie on different sides of the line uw, a vertex on the line
//! counting as on its left (the boundary's vertices pushed off the line, all the same way, so
//! that a side and its neighbour agree), and u, w on strictly different sides of the line ab.
//! The parity along uw is then the difference of the statuses of u and w for the pushed
//! boundary, which are theirs, since u and w are not on the boundary: a corner on a boundary
//! side (or at a boundary vertex) is `OnBoundary` and passes nothing on.
//!
//! Open: a corner cut off from the start by `OnBoundary` corners (the boundary running along
//! tree edges all round a region, which needs input corners at lattice positions bit for bit)
//! gets no status, and callers count it as not inside; a parity test over the polygons would
//! settle it.

use super::crowded::DomainElements;
use super::input::Domain;
use crate::geom::{orient2d, Point};
use crate::rhomb::lattice::{key, Frame, VKey};
use crate::rhomb::tree::{KeyMap, Tree};

/// Where a tree corner lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Inside,
    Outside,
    OnBoundary,
}

/// Whether boundary side ab crosses tree edge uw (module notes).
fn crosses(u: Point, w: Point, a: Point, b: Point) -> bool {
    let left = |x: Point| orient2d(u, w, x) >= 0.0;
    let (ou, ow) = (orient2d(a, b, u), orient2d(a, b, w));
    left(a) != left(b) && ((ou > 0.0 && ow < 0.0) || (ou < 0.0 && ow > 0.0))
}

/// Whether `p` lies on the closed segment ab.
fn on_side(p: Point, a: Point, b: Point) -> bool {
    orient2d(a, b, p) == 0.0
        && p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// The status of every corner of every leaf, by its global key.
pub fn statuses(domain: &Domain, tree: &Tree, frame: &Frame) -> KeyMap<VKey, Status> {
    let elements = DomainElements::new(domain, vec![[0.0; 2]; domain.points.len()]);
    let sides_of = |c| -> Vec<[Point; 2]> {
        tree.window(c)
            .iter()
            .filter_map(|&e| elements.side(e))
            .map(|s| s.map(|v| domain.points[v as usize]))
            .collect()
    };
    // The tree edges: each leaf's four sides, with the boundary sides that may cross them.
    let mut edges: KeyMap<VKey, Vec<(VKey, usize)>> = KeyMap::default();
    let mut near: Vec<Vec<[Point; 2]>> = Vec::new();
    let mut status: KeyMap<VKey, Status> = KeyMap::default();
    for c in tree.leaves() {
        let corners =
            [(0, 0), (1, 0), (1, 1), (0, 1)].map(|(di, dj)| key(c.level, c.i + di, c.j + dj));
        let list = near.len();
        near.push(sides_of(c));
        for (k, &u) in corners.iter().enumerate() {
            let w = corners[(k + 1) % 4];
            edges.entry(u).or_default().push((w, list));
            edges.entry(w).or_default().push((u, list));
            let p = frame.point(u);
            if near[list].iter().any(|&[a, b]| on_side(p, a, b)) {
                status.insert(u, Status::OnBoundary);
            }
        }
    }
    let start = key(1, 0, 0);
    let mut stack = vec![start];
    status.entry(start).or_insert(Status::Outside);
    while let Some(u) = stack.pop() {
        let su = status[&u];
        if su == Status::OnBoundary {
            continue;
        }
        let pu = frame.point(u);
        for &(w, list) in edges.get(&u).map_or(&[][..], Vec::as_slice) {
            if status.contains_key(&w) {
                continue;
            }
            let pw = frame.point(w);
            let flips = near[list]
                .iter()
                .filter(|&&[a, b]| crosses(pu, pw, a, b))
                .count();
            let sw = match (su, flips % 2) {
                (Status::Inside, 0) | (Status::Outside, 1) => Status::Inside,
                _ => Status::Outside,
            };
            status.insert(w, sw);
            stack.push(w);
        }
    }
    status
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_side_through_an_edge_end_or_along_it_does_not_cross_it() {
        let (u, w) = ([0.0, 0.0], [1.0, 0.0]);
        assert!(crosses(u, w, [0.5, -1.0], [0.5, 1.0]));
        assert!(!crosses(u, w, [1.5, -1.0], [1.5, 1.0]));
        // Touching from above at 0.5: both ends count as left, no crossing.
        assert!(!crosses(u, w, [0.5, 0.0], [0.7, 1.0]));
        // Passing through the line at a boundary vertex on it: one side ends there on the
        // left, the next leaves below: exactly one of the two crosses.
        let v = [0.5, 0.0];
        let n = [crosses(u, w, [0.3, 1.0], v), crosses(u, w, v, [0.7, -1.0])];
        assert_eq!(n.iter().filter(|&&x| x).count(), 1);
        // Along the edge: no crossing.
        assert!(!crosses(u, w, [0.2, 0.0], [0.8, 0.0]));
        assert!(on_side([0.5, 0.0], [0.2, 0.0], [0.8, 0.0]));
        assert!(!on_side([0.9, 0.0], [0.2, 0.0], [0.8, 0.0]));
    }
}
