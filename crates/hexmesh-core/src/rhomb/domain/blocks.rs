//! Which inner points lie within a front corner's reach (ours, engineering of `fill`'s
//! windows): the inner chain in runs with their bounding boxes.

use super::input::bbox;
use crate::geom::{dist, Point};

/// The inner chain in runs of `Blocks::RUN` points, each with its bounding box, so that a
/// window's search (the points within a front corner's reach, among 1,201 around its foot)
/// skips the runs that lie out of reach: it measured every point, a fifth of a fill on a
/// large domain.
pub struct Blocks {
    boxes: Vec<[f64; 4]>,
}

impl Blocks {
    const RUN: usize = 16;

    pub fn new(inner: &[Point]) -> Blocks {
        let boxes = inner.chunks(Self::RUN).map(bbox).collect();
        Blocks { boxes }
    }

    /// The first and last index in `range` whose point lies within `reach` of `p`
    /// (`dist(p, q) <= reach`, as measured point by point). A run is skipped only when its
    /// box is farther than `reach` along an axis by more than the rounding of `dist` (a
    /// relative 1e-9): no point of it can pass then, since the differences and their squares
    /// are rounded monotonically.
    pub fn within(
        &self,
        inner: &[Point],
        p: Point,
        reach: f64,
        range: std::ops::RangeInclusive<usize>,
    ) -> Option<(usize, usize)> {
        let far = reach * (1.0 + 1e-9);
        let (lo, hi) = (*range.start(), *range.end());
        let mut found: Option<(usize, usize)> = None;
        for b in lo / Self::RUN..=hi / Self::RUN {
            let [x0, y0, x1, y1] = self.boxes[b];
            let gap = (x0 - p[0]).max(p[0] - x1).max(y0 - p[1]).max(p[1] - y1);
            if gap > far || gap.is_nan() {
                continue;
            }
            let from = (b * Self::RUN).max(lo);
            let to = ((b + 1) * Self::RUN - 1).min(hi);
            for x in (from..=to).filter(|&x| dist(p, inner[x]) <= reach) {
                found = Some(found.map_or((x, x), |f| (f.0, x)));
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain that winds back on itself: a spiral of 2,000 points with a jitter.
    fn spiral() -> Vec<Point> {
        (0..2000)
            .map(|k| {
                let t = k as f64 * 0.05;
                let r = 1.0 + 0.01 * k as f64 + 0.003 * ((k * 7919) % 13) as f64;
                [r * t.cos(), r * t.sin()]
            })
            .collect()
    }

    #[test]
    fn the_runs_find_the_first_and_last_point_in_reach_as_measuring_every_point_does() {
        let inner = spiral();
        let blocks = Blocks::new(&inner);
        let mut found = 0;
        for (c, reach) in [
            ([0.0, 0.0], 1.5),
            ([3.0, -2.0], 0.8),
            ([10.0, 10.0], 0.3),
            ([-5.0, 1.0], 4.0),
        ] {
            for lo in (0..inner.len()).step_by(97) {
                let hi = (lo + 1200).min(inner.len() - 1);
                let near: Vec<usize> = (lo..=hi).filter(|&x| dist(c, inner[x]) <= reach).collect();
                let want = near.first().map(|&f| (f, *near.last().expect("one")));
                assert_eq!(
                    blocks.within(&inner, c, reach, lo..=hi),
                    want,
                    "{c:?} {reach} {lo}"
                );
                found += usize::from(want.is_some());
            }
        }
        // Both outcomes were met.
        assert!(found > 10 && found < 80, "{found}");
    }

    #[test]
    fn a_point_exactly_at_the_reach_is_in_it() {
        let inner: Vec<Point> = (0..40).map(|k| [k as f64, 0.0]).collect();
        let blocks = Blocks::new(&inner);
        assert_eq!(
            blocks.within(&inner, [20.0, 0.0], 3.0, 0..=39),
            Some((17, 23))
        );
        assert_eq!(blocks.within(&inner, [20.0, 5.0], 3.0, 0..=39), None);
    }
}
