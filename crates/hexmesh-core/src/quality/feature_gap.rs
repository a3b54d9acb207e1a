//! d_min of an input with segments: the smallest distance between two input features that
//! share no point, that is two input points, or a point and a segment that does not end at
//! it (nor pass through it: a point on a segment, within the conformity check's tolerance,
//! splits it). Two segments that share no endpoint come nearest at an endpoint of one of them (they
//! do not cross: `Pslg::check` refuses that), so point–segment distances cover them. Without
//! segments it is the closest pair of points, paper 000's d_min (Sec. 6.3).
//!
//! Ours: the paper states its shortest-edge bound in the closest pair of points, and on a
//! domain a point may lie nearer to a segment, or two segments nearer to each other, than any
//! two points do. The mesh has to resolve that gap too, so the bound is stated in it (a
//! domain whose segments come 0.002 apart while its points lie 0.1 apart has edges of about
//! 0.002 between them, whatever the mesher).
//!
//! The point–segment distances below the closest pair's are found through a uniform grid: each
//! segment is registered in the cells of points sampled along it at most one cell apart, and
//! each point looks at the 5 × 5 cells around its own, which hold every segment that passes
//! within one cell of it.

use std::collections::HashMap;

use super::closest_pair::closest_pair;
use crate::geom::{dist, scale2, scale_exponent, scale_point, Point};
use crate::mesh::Pslg;

/// The other feature of the closest pair of features.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Feature {
    /// An input point (0-based index).
    Point(usize),
    /// An input segment (0-based index) that does not end at the point.
    Segment(usize),
}

/// The closest pair of input features that share no point.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FeatureGap {
    /// An input point of the pair (0-based).
    pub point: usize,
    /// The other feature.
    pub other: Feature,
    /// Their distance: d_min.
    pub distance: f64,
}

/// The distance from `p` to the segment ab, computed on the three points scaled by one power
/// of two (exact) so that it neither overflows nor underflows.
pub(crate) fn point_segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let k = scale_exponent(&[p[0], p[1], a[0], a[1], b[0], b[1]]);
    let (p, a, b) = (scale_point(p, -k), scale_point(a, -k), scale_point(b, -k));
    let d = [b[0] - a[0], b[1] - a[1]];
    let w = [p[0] - a[0], p[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        ((w[0] * d[0] + w[1] * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    scale2(dist(p, [a[0] + t * d[0], a[1] + t * d[1]]), k)
}

/// The distance from `p` to the segment ab, or `None` when `p` lies on it within the
/// conformity check's 2^-40 of the segment's coordinate scale (`validate`): such a point
/// splits the segment, and the two share it.
fn gap_to_segment(p: Point, a: Point, b: Point) -> Option<f64> {
    let d = point_segment_distance(p, a, b);
    let scale = [a[0], a[1], b[0], b[1]]
        .iter()
        .fold(crate::geom::dist_scaled(a, b), |m, c| m.max(c.abs()));
    (d > scale * (-40f64).exp2()).then_some(d)
}

/// The closest pair of features of `input` (module docs); `None` for fewer than two points or
/// a coordinate that is not finite. Ties go to the pair of two points, then to the smallest
/// point and segment indices, so the answer does not depend on anything but the input.
pub fn feature_gap(input: &Pslg) -> Option<FeatureGap> {
    let pair = closest_pair(&input.points)?;
    let mut best = FeatureGap {
        point: pair.first,
        other: Feature::Point(pair.second),
        distance: pair.distance,
    };
    let segments: Vec<(usize, [usize; 2])> = input
        .segments
        .iter()
        .enumerate()
        .map(|(s, seg)| (s, [seg[0] as usize, seg[1] as usize]))
        .filter(|(_, [a, b])| *a < input.points.len() && *b < input.points.len())
        .collect();
    if segments.is_empty() || best.distance == 0.0 {
        return Some(best);
    }
    let points = &input.points;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for d in 0..2 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let total: f64 = segments
        .iter()
        .map(|&(_, [a, b])| crate::geom::dist_scaled(points[a], points[b]))
        .sum();
    // Only distances below the closest pair's matter, so a cell need not be smaller; it is
    // no smaller than a 2048th of the span nor than what keeps the samples along the segments
    // within four per input item. The 1 % keeps rounding of the cell indices inside the margin.
    let items = (points.len() + segments.len()) as f64;
    let cell = best.distance.max(span / 2048.0).max(total / (4.0 * items)) * 1.01;
    if !cell.is_finite() || cell <= 0.0 {
        return Some(best);
    }
    let index = |p: Point| {
        [
            ((p[0] - lo[0]) / cell).floor() as i64,
            ((p[1] - lo[1]) / cell).floor() as i64,
        ]
    };
    let mut grid: HashMap<[i64; 2], Vec<u32>> = HashMap::new();
    for &(s, [a, b]) in &segments {
        let (pa, pb) = (points[a], points[b]);
        let major = (pb[0] - pa[0]).abs().max((pb[1] - pa[1]).abs());
        let steps = (major / cell).ceil().max(1.0) as usize;
        let mut last = None;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let q = [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
            let c = index(q);
            if last != Some(c) {
                let list = grid.entry(c).or_default();
                if list.last() != Some(&(s as u32)) {
                    list.push(s as u32);
                }
                last = Some(c);
            }
        }
    }
    for (i, &p) in points.iter().enumerate() {
        let [cx, cy] = index(p);
        let mut near: Vec<u32> = Vec::new();
        for dx in -2..=2 {
            for dy in -2..=2 {
                if let Some(list) = grid.get(&[cx + dx, cy + dy]) {
                    near.extend_from_slice(list);
                }
            }
        }
        near.sort_unstable();
        near.dedup();
        for s in near {
            let [a, b] = segments[s as usize].1;
            if a == i || b == i {
                continue;
            }
            let Some(d) = gap_to_segment(p, points[a], points[b]) else {
                continue;
            };
            if d < best.distance {
                best = FeatureGap {
                    point: i,
                    other: Feature::Segment(segments[s as usize].0),
                    distance: d,
                };
            }
        }
    }
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn domain(points: Vec<Point>, segments: Vec<[u32; 2]>) -> Pslg {
        Pslg {
            points,
            segments,
            ..Pslg::default()
        }
    }

    #[test]
    fn a_point_near_a_segment_sets_d_min_below_the_closest_pair() {
        // A unit square and a point 0.01 inside its bottom side.
        let input = domain(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.4, 0.01]],
            vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        );
        let gap = feature_gap(&input).expect("five points");
        assert_eq!(gap.point, 4);
        assert_eq!(gap.other, Feature::Segment(0));
        assert!((gap.distance - 0.01).abs() < 1e-15, "{}", gap.distance);
    }

    #[test]
    fn two_segments_close_at_an_endpoint_set_d_min() {
        // Two long segments 0.002 apart at the end of one of them; points 1 apart or more.
        let input = domain(
            vec![[0.0, 0.0], [10.0, 0.0], [5.0, 0.002], [5.0, 3.0]],
            vec![[0, 1], [2, 3]],
        );
        let gap = feature_gap(&input).expect("four points");
        assert_eq!((gap.point, gap.other), (2, Feature::Segment(0)));
        assert!((gap.distance - 0.002).abs() < 1e-15, "{}", gap.distance);
    }

    #[test]
    fn a_segment_does_not_count_against_its_own_endpoints_and_a_point_set_keeps_its_pair() {
        let square = domain(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        );
        let gap = feature_gap(&square).expect("four points");
        assert_eq!(gap.other, Feature::Point(gap.point + 1));
        assert_eq!(gap.distance, 1.0);
        let points = Pslg::from_points(vec![[0.0, 0.0], [3.0, 4.0], [3.0, 4.5]]);
        let gap = feature_gap(&points).expect("three points");
        assert_eq!(
            (gap.point, gap.other, gap.distance),
            (1, Feature::Point(2), 0.5)
        );
    }

    #[test]
    fn the_grid_finds_what_every_pair_finds() {
        // A zigzag of 200 segments with points placed near them: the grid answer is the
        // minimum over every point and segment.
        let mut points: Vec<Point> = (0..201)
            .map(|i| [i as f64 * 0.05, if i % 2 == 0 { 0.0 } else { 0.3 }])
            .collect();
        let segments: Vec<[u32; 2]> = (0..200).map(|i| [i, i + 1]).collect();
        for k in 0..50 {
            let x = 0.013 + k as f64 * 0.197;
            points.push([x, 0.15 + 0.001 * (k % 7) as f64]);
        }
        let input = domain(points.clone(), segments.clone());
        let mut brute = closest_pair(&points).expect("pair").distance;
        for (i, &p) in points.iter().enumerate() {
            for s in &segments {
                let (a, b) = (s[0] as usize, s[1] as usize);
                if a != i && b != i {
                    if let Some(d) = gap_to_segment(p, points[a], points[b]) {
                        brute = brute.min(d);
                    }
                }
            }
        }
        assert_eq!(feature_gap(&input).expect("gap").distance, brute);
    }

    #[test]
    fn a_point_on_a_segment_splits_it_and_does_not_count_as_a_gap() {
        // The midpoint of the bottom side lies on it (an input vertex of its chain).
        let input = domain(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.0]],
            vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        );
        let gap = feature_gap(&input).expect("five points");
        assert_eq!((gap.other, gap.distance), (Feature::Point(4), 0.5));
    }

    #[test]
    fn huge_and_tiny_coordinates_neither_overflow_nor_underflow() {
        for scale in [1e-300, 1e300] {
            let input = domain(
                vec![[0.0, 0.0], [scale, 0.0], [0.5 * scale, 0.01 * scale]],
                vec![[0, 1]],
            );
            let gap = feature_gap(&input).expect("three points");
            assert_eq!(gap.other, Feature::Segment(0));
            assert!(
                (gap.distance / scale - 0.01).abs() < 1e-12,
                "{}",
                gap.distance
            );
        }
    }
}
