//! d_min, the smallest distance between two input points: the quantity the paper's
//! shortest-edge bound √7/(12√3)·d_min is stated in (Sußner & Greiner 2009, Sec. 6.3).
//! A plane sweep in x with the active strip ordered by y (Shamos–Hoey style), O(n log n).
//! Squared distances are compared as `geom::Dist2` (mantissa and exponent apart), which
//! neither underflows nor overflows at any coordinates (at 1e-150, plain squares of
//! distances are subnormal or zero) and orders like the plain squares wherever those are exact.

use std::collections::BTreeSet;
use std::ops::Bound::Included;

use crate::geom::{Dist2, Point};

/// The closest pair of a point set: indices (first < second) and their distance.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ClosestPair {
    /// The smaller 0-based index.
    pub first: usize,
    /// The larger 0-based index.
    pub second: usize,
    /// Their Euclidean distance, d_min.
    pub distance: f64,
}

/// A u64 whose unsigned order is the numeric order of finite f64 values (sign bit flipped
/// for positives, all bits for negatives); -0.0 is folded into 0.0 first.
fn ordered(x: f64) -> u64 {
    let b = (x + 0.0).to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | (1 << 63)
    }
}

/// The closest pair of `points`, `None` for fewer than two points or when a coordinate is
/// not finite. Ties are broken towards the smallest (first, second) indices, so the answer
/// does not depend on the input order beyond the indices.
pub fn closest_pair(points: &[Point]) -> Option<ClosestPair> {
    if points.len() < 2
        || points
            .iter()
            .any(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return None;
    }
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a][0]
            .total_cmp(&points[b][0])
            .then(points[a][1].total_cmp(&points[b][1]))
            .then(a.cmp(&b))
    });
    let better = |d2: Dist2, pair: (usize, usize), best: &(Dist2, (usize, usize))| {
        d2 < best.0 || (d2 == best.0 && pair < best.1)
    };
    let mut best = (Dist2::INFINITY, (usize::MAX, usize::MAX));
    // The strip holds the points with x within the best distance of the sweep line.
    let mut strip: BTreeSet<(u64, usize)> = BTreeSet::new();
    let mut tail = 0;
    for &i in &order {
        let p = points[i];
        // Widened a little so that rounding of the window never drops a tie.
        let d = best.0.sqrt() * (1.0 + 1e-9);
        while tail < order.len() && points[order[tail]][0] < p[0] - d {
            strip.remove(&(ordered(points[order[tail]][1]), order[tail]));
            tail += 1;
        }
        let lo = (ordered(p[1] - d), 0);
        let hi = (ordered(p[1] + d), usize::MAX);
        for &(_, j) in strip.range((Included(lo), Included(hi))) {
            let d2 = Dist2::between(p, points[j]);
            let pair = (i.min(j), i.max(j));
            if better(d2, pair, &best) {
                best = (d2, pair);
            }
        }
        strip.insert((ordered(p[1]), i));
    }
    let (first, second) = best.1;
    Some(ClosestPair {
        first,
        second,
        distance: best.0.sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_close_pair_dataset_has_d_min_two_hundredths() {
        let pts = [[1.0, 0.0], [-0.01, 0.0], [0.5, 0.8], [0.01, 0.0]];
        let c = closest_pair(&pts).expect("four points");
        assert_eq!((c.first, c.second), (1, 3));
        assert!((c.distance - 0.02).abs() < 1e-15);
    }

    #[test]
    fn duplicate_points_give_zero_and_a_single_point_gives_none() {
        let c = closest_pair(&[[0.0, 0.0], [3.0, 1.0], [-0.0, 0.0]]).expect("three points");
        assert_eq!((c.first, c.second, c.distance), (0, 2, 0.0));
        assert_eq!(closest_pair(&[[1.0, 2.0]]), None);
    }

    #[test]
    fn ordered_keys_sort_like_the_numbers() {
        let xs = [-3.5, -1e-300, -0.0, 0.0, 1e-300, 2.0, 1e300];
        for w in xs.windows(2) {
            assert!(ordered(w[0]) <= ordered(w[1]), "{} vs {}", w[0], w[1]);
        }
        assert_eq!(ordered(-0.0), ordered(0.0));
    }
}
