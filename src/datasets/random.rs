//! The random point sets of the paper's benchmark (Sußner & Greiner 2009, Sec. 8, Table 1):
//! points on one straight segment and points in the unit square.
//!
//! Bit-for-bit reproducible: the generator is PCG-XSL-RR 128/64 (`rand_pcg::Pcg64`, O'Neill's
//! `pcg64`) built from an explicit state and PCG's default stream, and coordinates are made
//! here from the top 53 bits of each 64-bit output, so nothing depends on how a rand version
//! seeds or turns words into floats.

use std::collections::HashSet;

use rand::Rng;
use rand_pcg::Pcg64;

use crate::geom::Point;

/// PCG's default stream (increment selector), as published with the reference implementation.
const PCG_DEFAULT_STREAM: u128 = 0x0a02_bdbf_7bb3_c0a7_ac28_fa16_a64a_bf96;

/// 2^-53: one unit in the last place of a number in [0.5, 1).
const TWO_POW_MINUS_53: f64 = 1.0 / 9_007_199_254_740_992.0;

/// The direction of the segment `line-100` lies on: from (0, 0) to (1, 0.37).
pub const LINE_END: Point = [1.0, 0.37];

/// A uniform double in [0, 1): the top 53 bits of one output word, times 2^-53. Every value
/// k·2^-53 is exact in f64, so the product involves no rounding.
struct UnitStream {
    rng: Pcg64,
}

impl UnitStream {
    fn new(seed: u64) -> UnitStream {
        UnitStream {
            rng: Pcg64::new(u128::from(seed), PCG_DEFAULT_STREAM),
        }
    }

    fn next(&mut self) -> f64 {
        (self.rng.next_u64() >> 11) as f64 * TWO_POW_MINUS_53
    }
}

/// `count` distinct points t·(1, 0.37), t uniform in [0, 1). A repeated t is rejected and
/// drawn again, so the output depends only on the seed.
pub fn on_line(count: usize, seed: u64) -> Vec<Point> {
    let mut stream = UnitStream::new(seed);
    let mut seen = HashSet::with_capacity(count);
    let mut points = Vec::with_capacity(count);
    while points.len() < count {
        let t = stream.next();
        // Distinct t give distinct x, hence distinct points; the set is only asked
        // membership, so its iteration order never reaches the output.
        if seen.insert(t.to_bits()) {
            points.push([t * LINE_END[0], t * LINE_END[1]]);
        }
    }
    points
}

/// `count` distinct points uniform in the unit square [0, 1)², x drawn before y. A repeated
/// point is rejected and drawn again.
pub fn in_unit_square(count: usize, seed: u64) -> Vec<Point> {
    let mut stream = UnitStream::new(seed);
    let mut seen = HashSet::with_capacity(count);
    let mut points = Vec::with_capacity(count);
    while points.len() < count {
        let p = [stream.next(), stream.next()];
        if seen.insert([p[0].to_bits(), p[1].to_bits()]) {
            points.push(p);
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg64_matches_the_official_reference_words() {
        // The first outputs of pcg64 for state 42, stream 54, from PCG's official C test
        // suite: if the generator changed, every committed dataset hash would change with it.
        let mut rng = Pcg64::new(42, 54);
        let words: Vec<u64> = (0..6).map(|_| rng.next_u64()).collect();
        assert_eq!(
            words,
            [
                0x86b1da1d72062b68,
                0x1304aa46c9853d39,
                0xa3670e9e0dd50358,
                0xf9090e529a7dae00,
                0xc85b9fd837996f2c,
                0x606121f8e3919196
            ]
        );
    }

    #[test]
    fn unit_values_are_in_the_half_open_unit_interval() {
        let mut s = UnitStream::new(7);
        for _ in 0..10_000 {
            let u = s.next();
            assert!((0.0..1.0).contains(&u), "{u}");
        }
    }

    #[test]
    fn a_repeated_draw_is_redrawn() {
        let a = on_line(500, 3);
        let mut bits: Vec<u64> = a.iter().map(|p| p[0].to_bits()).collect();
        bits.sort_unstable();
        bits.dedup();
        assert_eq!(bits.len(), 500);
    }

    #[test]
    fn the_same_seed_gives_the_same_points_and_another_seed_others() {
        assert_eq!(in_unit_square(50, 9), in_unit_square(50, 9));
        assert_ne!(in_unit_square(50, 9), in_unit_square(50, 10));
    }
}
