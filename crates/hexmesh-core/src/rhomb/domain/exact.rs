//! Exact signs of small polynomials in f64 inputs (ours, for the angle tests of paper 001
//! Sec. 3 and 5.6–5.8, which compare an input corner with 30°, 60° and 150°: degree-4
//! polynomials that `robust`'s fixed predicates do not cover).
//!
//! Values are Shewchuk's expansions: sums of f64 components, nonoverlapping and in increasing
//! magnitude, built with error-free sums (two-sum) and products (fused multiply-add), so the
//! sign is the sign of the largest nonzero component. Exact as long as no product overflows
//! or underflows: callers scale their inputs by a power of two first (`Exact::scaled`).

/// An exact value: the sum of its components.
#[derive(Debug, Clone, PartialEq)]
pub struct Exact(Vec<f64>);

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    (x, (a - av) + (b - bv))
}

fn two_product(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    (x, a.mul_add(b, -x))
}

impl Exact {
    /// The exact difference a − b.
    pub fn diff(a: f64, b: f64) -> Exact {
        let (x, y) = two_sum(a, -b);
        Exact(vec![y, x])
    }

    /// The exact value v.
    pub fn of(v: f64) -> Exact {
        Exact(vec![v])
    }

    /// Adds one f64 exactly (Shewchuk's Grow-Expansion).
    fn grow(&mut self, b: f64) {
        let mut q = b;
        for h in self.0.iter_mut() {
            let (x, y) = two_sum(q, *h);
            *h = y;
            q = x;
        }
        self.0.push(q);
        self.0.retain(|&c| c != 0.0);
    }

    /// self + other.
    pub fn add(&self, other: &Exact) -> Exact {
        let mut out = self.clone();
        for &c in &other.0 {
            out.grow(c);
        }
        out
    }

    /// −self.
    pub fn neg(&self) -> Exact {
        Exact(self.0.iter().map(|c| -c).collect())
    }

    /// self − other.
    pub fn sub(&self, other: &Exact) -> Exact {
        self.add(&other.neg())
    }

    /// self · other.
    pub fn mul(&self, other: &Exact) -> Exact {
        let mut out = Exact(Vec::new());
        for &a in &self.0 {
            for &b in &other.0 {
                let (x, y) = two_product(a, b);
                out.grow(y);
                out.grow(x);
            }
        }
        out
    }

    /// self · 2^k (exact while no component under- or overflows).
    pub fn scaled(&self, k: i32) -> Exact {
        Exact(self.0.iter().map(|&c| crate::geom::scale2(c, k)).collect())
    }

    /// The largest component's magnitude (0 for zero).
    pub fn magnitude(&self) -> f64 {
        self.0.last().map_or(0.0, |c| c.abs())
    }

    /// −1, 0 or 1: the sign of the exact value.
    pub fn sign(&self) -> i32 {
        match self.0.last() {
            Some(&c) if c > 0.0 => 1,
            Some(&c) if c < 0.0 => -1,
            _ => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_difference_below_the_rounding_of_its_terms_keeps_its_sign() {
        // (1 + 2^-52) − 1 − 2^-52 is zero; a + b − c for tiny b is not, though f64 says so.
        let a = Exact::diff(1.0 + f64::EPSILON, 1.0);
        assert_eq!(a.sub(&Exact::of(f64::EPSILON)).sign(), 0);
        let big = Exact::of(1e16).add(&Exact::of(1.0)).sub(&Exact::of(1e16));
        assert_eq!(big.sign(), 1);
        assert_eq!(1e16 + 1.0 - 1e16, 0.0);
    }

    #[test]
    fn products_are_exact_where_f64_rounds() {
        // (1 + 2^-30)² − 1 − 2^-29 = 2^-60 > 0, lost in f64.
        let x = Exact::of(1.0).add(&Exact::of(2f64.powi(-30)));
        let sq = x.mul(&x);
        let rest = sq.sub(&Exact::of(1.0)).sub(&Exact::of(2f64.powi(-29)));
        assert_eq!(rest.sign(), 1);
        assert_eq!(rest.magnitude(), 2f64.powi(-60));
        assert_eq!(Exact::of(3.0).scaled(-1).magnitude(), 1.5);
    }
}
