//! A fixed xorshift64 sequence (Marsaglia's shifts 13, 7, 17) from which unit tests draw their
//! inputs, so that each test sees the same cases on every run without a random-number crate.

/// The generator: its state is its last output.
pub(crate) struct XorShift(u64);

impl XorShift {
    /// The sequence after `seed` (not zero: zero stays zero).
    pub(crate) fn new(seed: u64) -> XorShift {
        XorShift(seed)
    }

    /// The next value.
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// The next value reduced below `m` (by remainder: close enough to uniform for tests).
    pub(crate) fn below(&mut self, m: u64) -> u64 {
        self.next() % m
    }
}
