//! The few statistics the report needs: median/min/max of repeated timings (METHODOLOGY.md)
//! and the exponent of a power law fitted on log-log axes, for the scaling plot (the paper's
//! Sec. 8 reads its O(n²) off such timings).

use std::time::Duration;

/// Median, minimum and maximum of the timed runs of one case, in seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

impl Timing {
    /// `None` for no runs. An even count takes the mean of the two middle runs.
    pub fn of(times: &[Duration]) -> Option<Timing> {
        let mut s: Vec<f64> = times.iter().map(Duration::as_secs_f64).collect();
        if s.is_empty() {
            return None;
        }
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let median = if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        };
        Some(Timing {
            median,
            min: s[0],
            max: s[n - 1],
        })
    }
}

/// The exponent b of y ≈ a·x^b by least squares on (ln x, ln y). Points with x or y not
/// positive cannot be on a log axis and are skipped; fewer than two distinct x give `None`.
pub fn power_law_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    Some(sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        let ms = |v: &[u64]| {
            v.iter()
                .map(|&m| Duration::from_millis(m))
                .collect::<Vec<_>>()
        };
        let t = Timing::of(&ms(&[30, 10, 20])).unwrap();
        assert_eq!((t.median, t.min, t.max), (0.02, 0.01, 0.03));
        let t = Timing::of(&ms(&[40, 10, 20, 30])).unwrap();
        assert!((t.median - 0.025).abs() < 1e-15);
        assert_eq!(Timing::of(&[]), None);
    }

    #[test]
    fn exponent_of_an_exact_quadratic_is_two() {
        let pts: Vec<(f64, f64)> = [100.0, 1e3, 1e4, 1e5]
            .iter()
            .map(|&x| (x, 3e-7 * x * x))
            .collect();
        let b = power_law_exponent(&pts).unwrap();
        assert!((b - 2.0).abs() < 1e-12, "{b}");
    }

    #[test]
    fn exponent_needs_two_distinct_positive_points() {
        assert_eq!(power_law_exponent(&[(10.0, 1.0)]), None);
        assert_eq!(power_law_exponent(&[(10.0, 1.0), (10.0, 2.0)]), None);
        assert_eq!(power_law_exponent(&[(10.0, 1.0), (0.0, 2.0)]), None);
    }
}
