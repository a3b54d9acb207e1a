//! The fixed-seed shuffle behind Welzl's minimum enclosing circle (`geom::min_enclosing_circle`),
//! written out so that the meshing library needs no random-number crate.
//!
//! The circle Welzl's algorithm returns depends, in its last bits, on the order it visits the
//! points (which support points it finds first, and in which order it passes them to the
//! circumcentre). The fitted hexagon, and so every mesh of a point set without a given
//! hexagon, depends on those bits. This module reproduces, bit for bit, the order the first
//! versions of the library obtained from `rand` 0.10 (`SliceRandom::shuffle` driven by
//! `rand_pcg::Pcg64::seed_from_u64`), so meshes did not change when the dependency left:
//!
//! - the generator is PCG XSL-RR 128/64: a 128-bit linear congruential state, each output the
//!   xor of its two halves rotated by its top six bits;
//! - a 64-bit seed is stretched into the generator's 32-byte seed by PCG-32 steps, four bytes
//!   a step; the first 16 bytes are the state, the last 16 (made odd) the increment;
//! - the shuffle is Durstenfeld's Fisher–Yates from the front: element i is swapped with a
//!   uniform index in [0, i]. Indices are drawn in batches: one 32-bit draw below
//!   (n+1)(n+2)…(n+k), the largest such product that fits, is split into k indices by
//!   successive remainders;
//! - a draw below `bound` is the high half of a 32×32-bit product of a 32-bit output (the low
//!   half of a 64-bit one) and `bound`; when the low half lies in the last `2^32 mod bound`
//!   values, a second output's high half is added to it and a carry, if any, rounds up.
//!
//! The harness's tests compare it with `rand` on thousands of slices.

/// The 128-bit multiplier of the PCG XSL-RR 128/64 generator.
const PCG_MULTIPLIER: u128 = 0x2360_ED05_1FC6_5DA4_4385_DF64_9FCC_F645;

/// PCG XSL-RR 128/64 (module docs).
struct Pcg128 {
    state: u128,
    increment: u128,
}

impl Pcg128 {
    /// The generator from a 64-bit seed (module docs).
    fn from_seed_u64(mut seed: u64) -> Pcg128 {
        let mut bytes = [0u8; 32];
        for chunk in bytes.chunks_exact_mut(4) {
            seed = seed
                .wrapping_mul(0x5851_F42D_4C95_7F2D)
                .wrapping_add(0xA176_54E4_6FBE_17F3);
            let mixed = (((seed >> 18) ^ seed) >> 27) as u32;
            chunk.copy_from_slice(&mixed.rotate_right((seed >> 59) as u32).to_le_bytes());
        }
        let word = |k: usize| {
            u128::from_le_bytes(bytes[16 * k..16 * (k + 1)].try_into().expect("16 bytes"))
        };
        let mut g = Pcg128 {
            state: word(0),
            increment: word(1) | 1,
        };
        g.state = g.state.wrapping_add(g.increment);
        g.step();
        g
    }

    fn step(&mut self) {
        self.state = self
            .state
            .wrapping_mul(PCG_MULTIPLIER)
            .wrapping_add(self.increment);
    }

    fn next_u64(&mut self) -> u64 {
        self.step();
        let folded = ((self.state >> 64) as u64) ^ (self.state as u64);
        folded.rotate_right((self.state >> 122) as u32)
    }

    fn next_u32(&mut self) -> u32 {
        self.next_u64() as u32
    }

    /// A draw in [0, bound), bound > 0 (module docs).
    fn below(&mut self, bound: u32) -> u32 {
        let wide = u64::from(self.next_u32()) * u64::from(bound);
        let (high, low) = ((wide >> 32) as u32, wide as u32);
        if low > bound.wrapping_neg() {
            let extra = ((u64::from(self.next_u32()) * u64::from(bound)) >> 32) as u32;
            return high + u32::from(low.checked_add(extra).is_none());
        }
        high
    }
}

/// The largest product (m)(m+1)…(m+k−1) that fits in 32 bits, and k.
fn batch(m: u32) -> (u32, u32) {
    let mut product = m;
    let mut next = m + 1;
    while let Some(p) = product.checked_mul(next) {
        product = p;
        next += 1;
    }
    (product, next - m)
}

/// Shuffles `items` in the order seeded by `seed` (module docs). Slices of 2^32 − 1 items or
/// more are beyond the 32-bit batches: each index is then one 64-bit draw scaled to [0, i].
pub(crate) fn shuffle<T>(items: &mut [T], seed: u64) {
    if items.len() <= 1 {
        return;
    }
    let mut g = Pcg128::from_seed_u64(seed);
    if items.len() >= u32::MAX as usize {
        for i in 1..items.len() {
            let index = (u128::from(g.next_u64()) * (i as u128 + 1)) >> 64;
            items.swap(i, index as usize);
        }
        return;
    }
    // Index 0 is always swapped with itself: the batches start at n = 0 with nothing left.
    let mut n: u32 = 0;
    let (mut chunk, mut left) = (0u32, 1u32);
    for i in 0..items.len() {
        let next = n + 1;
        if left == 0 {
            let (bound, count) = batch(next);
            chunk = g.below(bound);
            left = count;
        }
        left -= 1;
        let index = if left == 0 {
            chunk
        } else {
            let r = chunk % next;
            chunk /= next;
            r
        };
        items.swap(i, index as usize);
        n = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_order_is_rands_shuffle_seeded_through_pcg64_bit_for_bit() {
        use rand::seq::SliceRandom;
        use rand::SeedableRng;
        for (len, seed) in (0..600usize).map(|k| (k, k as u64 * 0x9E37_79B9)).chain([
            (1000, 0x0068_6578_6d65_7368),
            (4097, 1),
            (100_000, 0x0068_6578_6d65_7368),
        ]) {
            let mut ours: Vec<usize> = (0..len).collect();
            let mut theirs = ours.clone();
            shuffle(&mut ours, seed);
            theirs.shuffle(&mut rand_pcg::Pcg64::seed_from_u64(seed));
            assert_eq!(ours, theirs, "length {len}, seed {seed}");
        }
    }

    #[test]
    fn every_order_of_three_items_occurs() {
        let mut seen = std::collections::BTreeSet::new();
        for seed in 0..200 {
            let mut v = [0, 1, 2];
            shuffle(&mut v, seed);
            seen.insert(v);
        }
        assert_eq!(seen.len(), 6);
    }

    #[test]
    fn a_shuffle_is_a_permutation_and_the_same_every_time() {
        let mut a: Vec<u32> = (0..1000).collect();
        let mut b = a.clone();
        shuffle(&mut a, 7);
        shuffle(&mut b, 7);
        assert_eq!(a, b);
        assert_ne!(a, (0..1000).collect::<Vec<_>>());
        a.sort_unstable();
        assert_eq!(a, (0..1000).collect::<Vec<_>>());
    }

    #[test]
    fn the_largest_batch_for_two_is_twelve_factors() {
        // 2·3·…·13 = 13!/1 = 6 227 020 800 > 2^32, 2·…·12 = 479 001 600 fits.
        assert_eq!(batch(2), (479_001_600, 11));
    }
}
