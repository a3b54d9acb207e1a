//! Crowdedness on a domain (paper 001 Sec. 3, used by Sec. 4 step 2): a rhomb B is crowded
//! when the rhomb B' of x times its size centred at B holds two foreign elements (elements
//! with no common point), x = 7 when B' holds a polygon corner and 5 otherwise.
//!
//! Elements: every point of the domain (polygon corners, the extra corners of triangles,
//! single points) and every polygon side. A point is foreign to every other point and to the
//! sides not ending at it; two sides are foreign unless they share an end. So a corner with
//! its two sides is never crowded, nor are the two sides of a sharp corner near each other
//! (they share the corner): Sec. 5.6 handles them, not splitting.
//!
//! Which elements meet a window is decided in the lattice coordinates of `Frame::locate`,
//! rounded: it only decides how far rhombs are split, and no sign of the mesh depends on it.
//!
//! Departure (ours): the paper also asks for a path between the two elements inside B' and
//! the domain; it is not tested, so elements facing each other across a hole or across the
//! outside (two letters of `imr`) separate each other too. This splits more, never less.

use super::input::Domain;
use crate::rhomb::lattice::Cell;
use crate::rhomb::tree::Elements;

/// Half the width, in rhombs beyond the cell, of the windows x = 5 and x = 7.
const HALF_5: i64 = 2;
const HALF_7: i64 = 3;

/// A set of pairwise non-foreign elements of polygons has at most four members (the three
/// sides and one corner of a triangle; the footnote's extra corner leaves fewer): a longer
/// list is crowded without looking at pairs.
const MOST_NON_FOREIGN: usize = 4;

/// The elements of a domain: element e < `points` is domain point e, the others polygon
/// sides, in polygon and side order.
pub struct DomainElements {
    coords: Vec<[f64; 2]>,
    /// Whether each point is a polygon corner (not a single point).
    corner: Vec<bool>,
    sides: Vec<[u32; 2]>,
}

impl DomainElements {
    /// The elements of `domain`, with `coords` its points' lattice coordinates.
    pub fn new(domain: &Domain, coords: Vec<[f64; 2]>) -> DomainElements {
        let mut corner = vec![false; domain.points.len()];
        let mut sides = Vec::new();
        for poly in &domain.polygons {
            let n = poly.corners.len();
            for k in 0..n {
                corner[poly.corners[k] as usize] = true;
                sides.push([poly.corners[k], poly.corners[(k + 1) % n]]);
            }
        }
        DomainElements {
            coords,
            corner,
            sides,
        }
    }

    /// How many elements there are (points, then sides).
    pub fn count(&self) -> u32 {
        (self.coords.len() + self.sides.len()) as u32
    }

    /// The domain points side `e` joins, or `None` when element `e` is a point.
    pub fn side(&self, e: u32) -> Option<[u32; 2]> {
        (e as usize)
            .checked_sub(self.coords.len())
            .map(|k| self.sides[k])
    }

    /// True when elements a and b have no common point.
    pub fn foreign(&self, a: u32, b: u32) -> bool {
        match (self.side(a), self.side(b)) {
            (None, None) => a != b,
            (None, Some(s)) => !s.contains(&a),
            (Some(s), None) => !s.contains(&b),
            (Some(s), Some(t)) => !s.iter().any(|v| t.contains(v)),
        }
    }

    /// Whether element `e` meets the window of `half` rhombs around `cell` (closed).
    fn in_window(&self, e: u32, cell: Cell, half: i64) -> bool {
        let n = (1i64 << cell.level) as f64;
        let lo = [(cell.i - half) as f64 / n, (cell.j - half) as f64 / n];
        let hi = [
            (cell.i + half + 1) as f64 / n,
            (cell.j + half + 1) as f64 / n,
        ];
        match self.side(e) {
            None => {
                let p = self.coords[e as usize];
                (0..2).all(|a| lo[a] <= p[a] && p[a] <= hi[a])
            }
            Some([a, b]) => {
                segment_meets_box(self.coords[a as usize], self.coords[b as usize], lo, hi)
            }
        }
    }
}

impl Elements for DomainElements {
    fn meets(&self, e: u32, cell: Cell) -> bool {
        self.in_window(e, cell, HALF_7)
    }

    fn crowded(&self, cell: Cell, list: &[u32]) -> bool {
        let has_corner = list
            .iter()
            .any(|&e| self.side(e).is_none() && self.corner[e as usize]);
        let window: Vec<u32> = if has_corner {
            list.to_vec()
        } else {
            list.iter()
                .copied()
                .filter(|&e| self.in_window(e, cell, HALF_5))
                .collect()
        };
        if window.len() > MOST_NON_FOREIGN {
            return true;
        }
        window
            .iter()
            .enumerate()
            .any(|(k, &a)| window[k + 1..].iter().any(|&b| self.foreign(a, b)))
    }
}

/// Whether segment ab meets the closed box [lo, hi] (Liang–Barsky clipping).
fn segment_meets_box(a: [f64; 2], b: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..2 {
        let d = b[axis] - a[axis];
        if d == 0.0 {
            if a[axis] < lo[axis] || a[axis] > hi[axis] {
                return false;
            }
            continue;
        }
        let (mut enter, mut leave) = ((lo[axis] - a[axis]) / d, (hi[axis] - a[axis]) / d);
        if enter > leave {
            std::mem::swap(&mut enter, &mut leave);
        }
        t0 = t0.max(enter);
        t1 = t1.min(leave);
        if t0 > t1 {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::super::input::Polygon;
    use super::*;

    /// A domain in lattice coordinates directly (the identity frame).
    fn domain(points: &[[f64; 2]], loops: &[&[u32]]) -> DomainElements {
        let d = Domain {
            points: points.to_vec(),
            polygons: loops
                .iter()
                .map(|l| Polygon {
                    corners: l.to_vec(),
                    sides: (0..l.len() as u32).collect(),
                    outer: true,
                })
                .collect(),
            singles: Vec::new(),
        };
        DomainElements::new(&d, points.to_vec())
    }

    const SQUARE: [[f64; 2]; 4] = [[0.3, 0.3], [0.7, 0.3], [0.7, 0.7], [0.3, 0.7]];

    #[test]
    fn sides_sharing_a_corner_are_not_foreign_and_opposite_sides_are() {
        let e = domain(&SQUARE, &[&[0, 1, 2, 3]]);
        // Elements: points 0..4, sides 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0).
        assert_eq!(e.count(), 8);
        assert!(!e.foreign(4, 5) && !e.foreign(4, 7) && e.foreign(4, 6));
        assert!(!e.foreign(0, 4) && !e.foreign(0, 7) && e.foreign(0, 5));
        assert!(e.foreign(0, 1) && !e.foreign(2, 2));
    }

    #[test]
    fn a_corner_alone_with_its_sides_is_not_crowded_and_the_far_corner_crowds_it() {
        let e = domain(&SQUARE, &[&[0, 1, 2, 3]]);
        // Level 6 cells are 1/64 wide: the cell at corner 0 sees only it and sides 4, 7.
        let at_corner = Cell::new(6, 19, 19);
        let list: Vec<u32> = (0..8).filter(|&x| e.meets(x, at_corner)).collect();
        assert_eq!(list, vec![0, 4, 7]);
        assert!(!e.crowded(at_corner, &list));
        // At level 2 (cells 1/4 wide) the 7-window of the cell at the corner holds the whole
        // square: crowded.
        let coarse = Cell::new(2, 1, 1);
        let list: Vec<u32> = (0..8).filter(|&x| e.meets(x, coarse)).collect();
        assert_eq!(list.len(), 8);
        assert!(e.crowded(coarse, &list));
    }

    #[test]
    fn without_a_corner_the_window_is_five_rhombs_wide() {
        let e = domain(&SQUARE, &[&[0, 1, 2, 3]]);
        // Level 5 (rhombs 1/32 wide): the cell at t-index 12 (t from 0.375) has the bottom
        // side (t = 0.3) 2.4 rhombs below it, inside its 7-window but not its 5-window.
        let c = Cell::new(5, 16, 12);
        assert!(e.in_window(4, c, HALF_7));
        assert!(!e.in_window(4, c, HALF_5));
        let list: Vec<u32> = (0..8).filter(|&x| e.meets(x, c)).collect();
        assert_eq!(list, vec![4]);
        assert!(!e.crowded(c, &list));
    }

    #[test]
    fn segment_box_clipping_sees_crossings_and_misses() {
        let (lo, hi) = ([0.0, 0.0], [1.0, 1.0]);
        assert!(segment_meets_box([-1.0, 0.5], [2.0, 0.5], lo, hi));
        assert!(segment_meets_box([0.5, 0.5], [0.6, 0.6], lo, hi));
        assert!(!segment_meets_box([-1.0, 0.5], [0.5, 2.0], lo, hi));
        assert!(segment_meets_box([-1.0, 0.2], [1.0, 1.2], lo, hi));
        assert!(!segment_meets_box([2.0, -1.0], [2.0, 3.0], lo, hi));
    }
}
