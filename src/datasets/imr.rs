//! The `imr` dataset: the letters I, M and R as closed polygonal outlines, the PSLG of the
//! paper's Table 1 and the last row of Fig. 15 (Sußner & Greiner 2009, Sec. 8), where "the
//! level-of-detail increases from letter I to letter R".
//!
//! The paper does not publish its outlines, so these are this project's own: I is a serifed
//! bar (12 vertices), M has straight strokes and a flat notch (14), R has a bowl whose outer
//! edge is a sampled circular arc (40 chords) and whose counter is a hole bounded by a second
//! arc (30 chords) with a hole seed inside. The domain is the union of the three letters;
//! there is no enclosing box, so a mesher must remove what lies outside the outer loops.

use crate::geom::Point;
use crate::mesh::Pslg;

/// Height of every letter; letters stand on y = 0.
pub const HEIGHT: f64 = 1.0;

/// Left edges of I, M and R: each letter is drawn in its own frame and shifted right by this.
const OFFSET_I: f64 = 0.0;
const OFFSET_M: f64 = 0.7;
const OFFSET_R: f64 = 1.8;

/// Centre of the R bowl's arcs (in the R frame) and their radii.
const BOWL_CENTER: Point = [0.42, 0.725];
const BOWL_OUTER: f64 = 0.275;
const BOWL_INNER: f64 = 0.125;
/// The outer arc starts where the leg's outer edge meets the bowl, −68° from the bowl's
/// centre, and runs counter-clockwise to the top of the letter at 90°.
const OUTER_ARC_FROM_DEG: f64 = -68.0;
const OUTER_ARC_CHORDS: usize = 40;
const INNER_ARC_CHORDS: usize = 30;

/// The I: a bar with serifs at top and bottom, counter-clockwise.
const LETTER_I: [Point; 12] = [
    [0.0, 0.0],
    [0.5, 0.0],
    [0.5, 0.15],
    [0.33, 0.15],
    [0.33, 0.85],
    [0.5, 0.85],
    [0.5, 1.0],
    [0.0, 1.0],
    [0.0, 0.85],
    [0.17, 0.85],
    [0.17, 0.15],
    [0.0, 0.15],
];

/// The M: two stems joined by a V whose notch is flat, counter-clockwise. The outer and
/// inner edges of each diagonal stroke are 0.3 apart vertically, so they never meet.
const LETTER_M: [Point; 14] = [
    [0.0, 0.0],
    [0.16, 0.0],
    [0.16, 0.68],
    [0.38, 0.18],
    [0.52, 0.18],
    [0.74, 0.68],
    [0.74, 0.0],
    [0.9, 0.0],
    [0.9, 1.0],
    [0.74, 1.0],
    [0.49, 0.38],
    [0.41, 0.38],
    [0.16, 1.0],
    [0.0, 1.0],
];

/// The PSLG: three outer loops (I, M, R) and the R's counter, each counter-clockwise, points
/// in loop order, and one hole seed inside the counter.
pub fn letters() -> Pslg {
    let mut pslg = Pslg::default();
    push_loop(&mut pslg, &shifted(&LETTER_I, OFFSET_I));
    push_loop(&mut pslg, &shifted(&LETTER_M, OFFSET_M));
    push_loop(&mut pslg, &shifted(&r_outline(), OFFSET_R));
    push_loop(&mut pslg, &shifted(&r_counter(), OFFSET_R));
    // The middle of the counter, between its straight left side and its arc.
    pslg.holes.push([OFFSET_R + 0.30, BOWL_CENTER[1]]);
    pslg
}

/// The R's outer loop in its own frame: stem, bowl bottom, leg, the outer arc of the bowl,
/// the top bar.
fn r_outline() -> Vec<Point> {
    let mut loop_ = vec![
        [0.0, 0.0],
        [0.18, 0.0],
        [0.18, 0.45],
        [0.34, 0.45],
        [0.56, 0.0],
        [0.76, 0.0],
    ];
    // The arc's last sample would be the top of the letter up to rounding: put it there
    // exactly, so that the top bar is horizontal.
    loop_.extend(arc(BOWL_OUTER, OUTER_ARC_FROM_DEG, 90.0, OUTER_ARC_CHORDS));
    loop_.pop();
    loop_.push([BOWL_CENTER[0], BOWL_CENTER[1] + BOWL_OUTER]);
    loop_.push([0.0, HEIGHT]);
    loop_
}

/// The counter of the R's bowl in its own frame: a straight left side on the stem and a
/// half circle of radius `BOWL_INNER`, counter-clockwise.
fn r_counter() -> Vec<Point> {
    let bottom = BOWL_CENTER[1] - BOWL_INNER;
    let top = BOWL_CENTER[1] + BOWL_INNER;
    let mut loop_ = vec![[0.18, bottom], [BOWL_CENTER[0], bottom]];
    let half = arc(BOWL_INNER, -90.0, 90.0, INNER_ARC_CHORDS);
    // Both ends of the half circle are placed exactly, like the straight sides they join.
    loop_.extend_from_slice(&half[1..half.len() - 1]);
    loop_.push([BOWL_CENTER[0], top]);
    loop_.push([0.18, top]);
    loop_
}

/// `chords + 1` points on the circle of radius `radius` about `BOWL_CENTER`, from angle
/// `from_deg` to `to_deg` (degrees, counter-clockwise), equally spaced in angle.
fn arc(radius: f64, from_deg: f64, to_deg: f64, chords: usize) -> Vec<Point> {
    (0..=chords)
        .map(|k| {
            let deg = from_deg + (to_deg - from_deg) * k as f64 / chords as f64;
            let (c, s) = cos_sin(deg * (std::f64::consts::PI / 180.0));
            [BOWL_CENTER[0] + radius * c, BOWL_CENTER[1] + radius * s]
        })
        .collect()
}

/// cos and sin by their Taylor series. The platform's `sin`/`cos` are not correctly rounded
/// and differ between C libraries; this uses only IEEE-754 additions, multiplications and
/// divisions, so every machine gets the same bits (the committed hashes depend on it). For
/// |x| ≤ π the terms fall below 2^-80 of the largest long before the 60th, and the absolute
/// error is a few ulps of 1, far below anything a mesher can see on a letter of height 1.
pub(super) fn cos_sin(x: f64) -> (f64, f64) {
    let (mut cos, mut sin) = (1.0, 0.0);
    let mut term = 1.0;
    for k in 1..60 {
        term *= x / k as f64;
        match k % 4 {
            1 => sin += term,
            2 => cos -= term,
            3 => sin -= term,
            _ => cos += term,
        }
    }
    (cos, sin)
}

fn shifted(points: &[Point], dx: f64) -> Vec<Point> {
    points.iter().map(|p| [p[0] + dx, p[1]]).collect()
}

/// Appends a closed loop: its points, and a segment from each to the next, the last back to
/// the first.
pub(super) fn push_loop(pslg: &mut Pslg, points: &[Point]) {
    let base = pslg.points.len() as u32;
    let n = points.len() as u32;
    pslg.points.extend_from_slice(points);
    pslg.segments
        .extend((0..n).map(|i| [base + i, base + (i + 1) % n]));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taylor_cos_sin_agree_with_the_platform_to_rounding() {
        for k in -180..=180 {
            let x = k as f64 * std::f64::consts::PI / 180.0;
            let (c, s) = cos_sin(x);
            assert!((c - x.cos()).abs() < 1e-15, "cos {k}°");
            assert!((s - x.sin()).abs() < 1e-15, "sin {k}°");
        }
    }

    #[test]
    fn arc_samples_lie_on_their_circle() {
        for p in arc(BOWL_OUTER, OUTER_ARC_FROM_DEG, 90.0, OUTER_ARC_CHORDS) {
            let r = ((p[0] - BOWL_CENTER[0]).powi(2) + (p[1] - BOWL_CENTER[1]).powi(2)).sqrt();
            assert!((r - BOWL_OUTER).abs() < 1e-15);
        }
    }

    #[test]
    fn letters_have_the_promised_level_of_detail() {
        assert_eq!(LETTER_I.len(), 12);
        assert_eq!(LETTER_M.len(), 14);
        // 6 straight corners, 40 chords of arc (41 points), the top-left corner.
        assert_eq!(r_outline().len(), 6 + OUTER_ARC_CHORDS + 1 + 1);
        // 2 bottom corners, 29 inner arc points, 2 top corners.
        assert_eq!(r_counter().len(), 2 + (INNER_ARC_CHORDS - 1) + 2);
    }

    #[test]
    fn the_r_top_bar_and_counter_sides_are_exactly_horizontal() {
        let outline = r_outline();
        let n = outline.len();
        assert_eq!(outline[n - 2][1], HEIGHT);
        assert_eq!(outline[n - 1][1], HEIGHT);
        let counter = r_counter();
        let m = counter.len();
        assert_eq!(counter[0][1], counter[1][1]);
        assert_eq!(counter[m - 2][1], counter[m - 1][1]);
    }
}
