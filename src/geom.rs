//! Small geometric primitives shared by every module: exact orientation and incircle signs
//! (Shewchuk's adaptive predicates through the `robust` crate), the flat-topped hexagon,
//! and the minimum enclosing circle (Welzl 1991, "Smallest enclosing disks").

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_pcg::Pcg64;

/// A point in the plane.
pub type Point = [f64; 2];

/// Exact sign of the orientation of (a, b, c): > 0 counter-clockwise, < 0 clockwise, 0 collinear.
/// The magnitude is twice the signed area when the computation is exact.
pub fn orient2d(a: Point, b: Point, c: Point) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Exact incircle sign: > 0 when `d` lies strictly inside the circle through the
/// counter-clockwise triangle (a, b, c), 0 when cocircular, < 0 outside.
pub fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
    robust::incircle(coord(a), coord(b), coord(c), coord(d))
}

fn coord(p: Point) -> robust::Coord<f64> {
    robust::Coord { x: p[0], y: p[1] }
}

/// Squared Euclidean distance.
pub fn dist2(a: Point, b: Point) -> f64 {
    let dx = a[0] - b[0];
    let dy = a[1] - b[1];
    dx * dx + dy * dy
}

/// Euclidean distance.
pub fn dist(a: Point, b: Point) -> f64 {
    dist2(a, b).sqrt()
}

/// A regular, flat-topped hexagon: corners at 0°, 60°, …, 300° from the centre
/// (DESIGN.md "One way to see the hexagon hierarchy").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hexagon {
    pub center: Point,
    /// Distance from the centre to a corner (equal to the edge length).
    pub circumradius: f64,
}

impl Hexagon {
    /// The hexagon whose inscribed circle has radius `inradius`.
    pub fn with_inradius(center: Point, inradius: f64) -> Hexagon {
        Hexagon {
            center,
            circumradius: inradius * 2.0 / 3f64.sqrt(),
        }
    }

    /// Distance from the centre to the middle of an edge.
    pub fn inradius(&self) -> f64 {
        self.circumradius * 3f64.sqrt() / 2.0
    }

    /// The six corners, counter-clockwise, starting at angle 0.
    pub fn corners(&self) -> [Point; 6] {
        let r = self.circumradius;
        let h = r * 3f64.sqrt() / 2.0;
        let [cx, cy] = self.center;
        [
            [cx + r, cy],
            [cx + r / 2.0, cy + h],
            [cx - r / 2.0, cy + h],
            [cx - r, cy],
            [cx - r / 2.0, cy - h],
            [cx + r / 2.0, cy - h],
        ]
    }

    /// Area: 3√3/2 · r².
    pub fn area(&self) -> f64 {
        1.5 * 3f64.sqrt() * self.circumradius * self.circumradius
    }

    /// The bounding hexagon DESIGN.md prescribes for a point set: its inscribed circle is the
    /// minimum enclosing circle of the points, enlarged by a relative 1e-9 (and further, if
    /// rounding left any point outside a corner test).
    pub fn fitted(points: &[Point]) -> Hexagon {
        let (center, radius) = min_enclosing_circle(points);
        // A single point (or all points equal) has radius 0: fall back to a unit-size hexagon
        // scaled to the coordinates so that the hexagon is not degenerate.
        let base = if radius > 0.0 {
            radius
        } else {
            center[0].abs().max(center[1].abs()).max(1.0) * 1e-3
        };
        let mut hex = Hexagon::with_inradius(center, base * (1.0 + 1e-9));
        // Rounding can leave a point on the boundary; a few relative 1e-9 steps settle it.
        // Non-finite points (which `Pslg::check` refuses) are never inside: skip them rather
        // than loop.
        let finite = |p: &&Point| p[0].is_finite() && p[1].is_finite();
        for _ in 0..64 {
            if points
                .iter()
                .filter(finite)
                .all(|&p| hex.contains_strictly(p))
            {
                break;
            }
            hex.circumradius *= 1.0 + 1e-9;
        }
        hex
    }

    /// True when `p` lies strictly inside the hexagon (exact orientation tests).
    pub fn contains_strictly(&self, p: Point) -> bool {
        let c = self.corners();
        (0..6).all(|i| orient2d(c[i], c[(i + 1) % 6], p) > 0.0)
    }
}

/// Minimum enclosing circle (centre, radius) of the finite points of a set by Welzl's randomized incremental
/// algorithm, with a fixed-seed shuffle so the result is the same on every run. Empty input
/// gives the origin with radius 0.
pub fn min_enclosing_circle(points: &[Point]) -> (Point, f64) {
    // Non-finite points (refused by `Pslg::check`) have no place in a circle: skip them.
    let mut pts: Vec<Point> = points
        .iter()
        .copied()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    if pts.is_empty() {
        return ([0.0, 0.0], 0.0);
    }
    pts.shuffle(&mut Pcg64::seed_from_u64(0x0068_6578_6d65_7368));
    let inside = |c: Point, r2: f64, p: Point| dist2(c, p) <= r2 * (1.0 + 1e-12);
    let mut c = pts[0];
    let mut r2 = 0.0;
    for i in 1..pts.len() {
        if inside(c, r2, pts[i]) {
            continue;
        }
        c = pts[i];
        r2 = 0.0;
        for j in 0..i {
            if inside(c, r2, pts[j]) {
                continue;
            }
            c = midpoint(pts[i], pts[j]);
            r2 = dist2(c, pts[i]);
            for k in 0..j {
                if inside(c, r2, pts[k]) {
                    continue;
                }
                match circumcenter(pts[i], pts[j], pts[k]) {
                    Some(cc) => {
                        c = cc;
                        r2 = dist2(cc, pts[i]);
                    }
                    None => {
                        // Collinear triple: the circle on the two farthest points.
                        let pairs = [(pts[i], pts[j]), (pts[i], pts[k]), (pts[j], pts[k])];
                        let (a, b) = pairs
                            .into_iter()
                            .max_by(|x, y| dist2(x.0, x.1).total_cmp(&dist2(y.0, y.1)))
                            .expect("three pairs");
                        c = midpoint(a, b);
                        r2 = dist2(c, a);
                    }
                }
            }
        }
    }
    // Make sure every point is inside despite rounding.
    let r2 = pts.iter().map(|&p| dist2(c, p)).fold(r2, f64::max);
    (c, r2.sqrt())
}

fn midpoint(a: Point, b: Point) -> Point {
    [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
}

/// Circumcentre of a triangle, `None` when the three points are collinear.
pub fn circumcenter(a: Point, b: Point, c: Point) -> Option<Point> {
    if orient2d(a, b, c) == 0.0 {
        return None;
    }
    let bx = b[0] - a[0];
    let by = b[1] - a[1];
    let cx = c[0] - a[0];
    let cy = c[1] - a[1];
    let d = 2.0 * (bx * cy - by * cx);
    let b2 = bx * bx + by * by;
    let c2 = cx * cx + cy * cy;
    Some([
        a[0] + (cy * b2 - by * c2) / d,
        a[1] + (bx * c2 - cx * b2) / d,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enclosing_circle_of_a_square_has_its_diagonal_as_diameter() {
        let (c, r) = min_enclosing_circle(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert!((c[0] - 0.5).abs() < 1e-12 && (c[1] - 0.5).abs() < 1e-12);
        assert!((r - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn enclosing_circle_ignores_interior_points() {
        let mut pts = vec![[-1.0, 0.0], [1.0, 0.0]];
        pts.extend((0..50).map(|i| [0.01 * i as f64 - 0.25, 0.1]));
        let (c, r) = min_enclosing_circle(&pts);
        assert!(c[0].abs() < 1e-12 && c[1].abs() < 1e-12);
        assert!((r - 1.0).abs() < 1e-12);
    }

    #[test]
    fn fitting_a_hexagon_to_non_finite_points_returns() {
        let hex = Hexagon::fitted(&[[0.0, 0.0], [f64::NAN, 1.0], [1.0, f64::INFINITY]]);
        assert!(hex.contains_strictly([0.0, 0.0]));
        assert!(hex.circumradius.is_finite() && hex.circumradius > 0.0);
    }

    #[test]
    fn fitted_hexagon_contains_every_point_strictly() {
        let pts = [[0.0, 0.0], [1.0, 0.37], [0.5, 0.185], [0.25, 0.0925]];
        let hex = Hexagon::fitted(&pts);
        assert!(pts.iter().all(|&p| hex.contains_strictly(p)));
        let (_, r) = min_enclosing_circle(&pts);
        assert!((hex.inradius() - r).abs() <= r * 1e-8);
    }
}
