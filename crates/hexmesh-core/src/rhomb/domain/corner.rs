//! The corners of the polygons by interior angle α (paper 001 Sec. 3, the corner condition;
//! Sec. 5.6–5.8 treat each class): α ≤ 60° (cut off, 5.6), 60° < α ≤ 150° (shifted rows, 5.7)
//! and α > 150° (centred like a single point, 5.8). The promise exempts a corner sharper than
//! 30°, whose one triangle is the whole corner.
//!
//! Every comparison is an exact sign (`exact`): with u the vector to the next corner and w the
//! vector to the previous one, the domain on the left, α is the counter-clockwise angle from u
//! to w, so sin α has the sign of cross = u × w and cos α of dot = u · w, and
//! α ≤ 60° ⇔ cross > 0, dot > 0, cross² ≤ 3·dot²; α < 30° ⇔ cross > 0, dot > 0,
//! 3·cross² < dot²; α ≤ 150° ⇔ cross > 0 and (dot ≥ 0 or 3·cross² ≥ dot²).

use super::exact::Exact;
use super::input::Polygon;
use crate::geom::Point;

/// Which rule of Sec. 5.6–5.8 meshes a corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// α ≤ 60° (Sec. 5.6); `sharp`: α < 30°, the corner is one whole triangle angle.
    Acute { sharp: bool },
    /// 60° < α ≤ 150° (Sec. 5.7).
    Middle,
    /// α > 150°, reflex corners included (Sec. 5.8).
    Obtuse,
}

impl Class {
    /// How far (in rhombs) the corner condition of Sec. 3 keeps the rhombs around the
    /// corner's rhomb of its size: first neighbours for α ≤ 60° (and single points), first
    /// to third neighbours otherwise.
    pub fn reach(self) -> i64 {
        match self {
            Class::Acute { .. } => 1,
            Class::Middle | Class::Obtuse => 3,
        }
    }
}

/// The class of corner `c` with neighbours `prev` and `next`, the domain on the left of
/// prev → c → next.
pub fn classify(prev: Point, c: Point, next: Point) -> Class {
    let (ux, uy) = (Exact::diff(next[0], c[0]), Exact::diff(next[1], c[1]));
    let (wx, wy) = (Exact::diff(prev[0], c[0]), Exact::diff(prev[1], c[1]));
    // One power of two brings the largest difference near 1, so that the degree-4 products
    // neither overflow nor (for sides of comparable length) underflow.
    let largest = [&ux, &uy, &wx, &wy]
        .iter()
        .map(|e| e.magnitude())
        .fold(0.0, f64::max);
    let k = -crate::geom::exponent(largest);
    let [ux, uy, wx, wy] = [ux, uy, wx, wy].map(|e| e.scaled(k));
    let cross = ux.mul(&wy).sub(&uy.mul(&wx));
    let dot = ux.mul(&wx).add(&uy.mul(&wy));
    let (c2, d2) = (cross.mul(&cross), dot.mul(&dot));
    let three = Exact::of(3.0);
    let (s, d) = (cross.sign(), dot.sign());
    if s > 0 && d > 0 && c2.sub(&three.mul(&d2)).sign() <= 0 {
        let sharp = three.mul(&c2).sub(&d2).sign() < 0;
        Class::Acute { sharp }
    } else if s > 0 && (d >= 0 || three.mul(&c2).sub(&d2).sign() >= 0) {
        Class::Middle
    } else {
        Class::Obtuse
    }
}

/// The class of every corner of `poly`, in corner order.
pub fn classes(points: &[Point], poly: &Polygon) -> Vec<Class> {
    let n = poly.corners.len();
    let at = |k: usize| points[poly.corners[k % n] as usize];
    (0..n)
        .map(|k| classify(at(k + n - 1), at(k), at(k + 1)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corner at the origin between the +x axis (next) and the direction `deg` (prev).
    fn corner(deg: f64) -> Class {
        let r = deg.to_radians();
        classify([r.cos(), r.sin()], [0.0, 0.0], [1.0, 0.0])
    }

    #[test]
    fn corners_fall_into_the_classes_of_their_angles() {
        assert_eq!(corner(5.0), Class::Acute { sharp: true });
        assert_eq!(corner(45.0), Class::Acute { sharp: false });
        assert_eq!(corner(90.0), Class::Middle);
        assert_eq!(corner(149.0), Class::Middle);
        assert_eq!(corner(151.0), Class::Obtuse);
        assert_eq!(corner(270.0), Class::Obtuse);
        // Straight on: a flat corner (the extra corner of a triangle's side).
        assert_eq!(classify([-1.0, 0.0], [0.0, 0.0], [1.0, 0.0]), Class::Obtuse);
        assert_eq!(corner(45.0).reach(), 1);
        assert_eq!(corner(90.0).reach(), 3);
    }

    #[test]
    fn the_class_boundaries_are_decided_exactly() {
        // Exactly 60° and 30° need irrational coordinates; tan α = cross/dot rational near
        // them decides on the right side by a hair: (1, 1.7320508) is just below 60°.
        let below = classify([1.0, 1.732_050_8], [0.0, 0.0], [1.0, 0.0]);
        let above = classify([1.0, 1.732_050_81], [0.0, 0.0], [1.0, 0.0]);
        assert_eq!(below, Class::Acute { sharp: false });
        assert_eq!(above, Class::Middle);
        // 3·cross² = dot² holds for no f64 pair; (1.7320508, 1) is just under 30°.
        assert_eq!(
            classify([1.732_050_8, 1.0], [0.0, 0.0], [1.0, 0.0]),
            Class::Acute { sharp: false }
        );
        assert_eq!(
            classify([1.732_050_81, 1.0], [0.0, 0.0], [1.0, 0.0]),
            Class::Acute { sharp: true }
        );
        // Near 150° (cross 1, dot −√3): just inside, just outside, and inside.
        assert_eq!(
            classify([-1.732_050_8, 1.0], [0.0, 0.0], [1.0, 0.0]),
            Class::Middle
        );
        assert_eq!(
            classify([-1.732_050_81, 1.0], [0.0, 0.0], [1.0, 0.0]),
            Class::Obtuse
        );
        assert_eq!(
            classify([-1.732_05, 1.0], [0.0, 0.0], [1.0, 0.0]),
            Class::Middle
        );
    }

    #[test]
    fn far_from_the_origin_the_class_is_the_same() {
        // A 59.99° corner at 1e12 with unit sides: the differences are exact, the products not
        // in f64, and the class stays.
        let r = 59.99f64.to_radians();
        let c = [1e12, -3e11];
        let prev = [c[0] + r.cos(), c[1] + r.sin()];
        assert_eq!(
            classify(prev, c, [c[0] + 1.0, c[1]]),
            classify([prev[0] - c[0], prev[1] - c[1]], [0.0, 0.0], [1.0, 0.0])
        );
    }
}
