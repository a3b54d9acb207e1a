//! Paper 003's angle bounds measured on the datasets (Stamm, Eidenbenz & Pajarola, Theorem 3.4):
//! the family T(A,B,C) of every initial Delaunay triangle refined `FAMILY_LEVELS` deep keeps 2/3
//! of its smallest angle (1/2 under plain bisection); the conforming, heap-driven refinement
//! has no such theorem, so its minimum ratio is measured and shown beside the bounds.

use std::fmt::Write as _;

use serde::Serialize;

use crate::mesh::Pslg;
use crate::mesher::Params;
use crate::refine::{family, lsb_descent_check, Lsb};

/// Depth of the uniform family: 4^3 = 64 descendants of every initial triangle.
pub const FAMILY_LEVELS: u32 = 3;

/// The columns of `lsb.csv`.
pub const LSB_COLUMNS: &[&str] = &[
    "dataset",
    "variant",
    "bound",
    "family_min_ratio",
    "adaptive_min_ratio",
    "adaptive_triangles",
    "quaternary_splits",
    "err",
];

/// One dataset × variant (modified or plain bisection).
#[derive(Debug, Clone, Serialize)]
pub struct LsbRow {
    pub dataset: String,
    pub variant: &'static str,
    /// The ratio Theorem 3.4 (or plain bisection's 1/2) promises for the family.
    pub bound: f64,
    /// Smallest ratio over the uniform family, `FAMILY_LEVELS` deep.
    pub family_min_ratio: Option<f64>,
    /// Smallest ratio over the conforming refinement `lsb` outputs with default parameters.
    pub adaptive_min_ratio: Option<f64>,
    pub adaptive_triangles: Option<u64>,
    pub quaternary_splits: Option<u64>,
    pub err: String,
}

/// Measures both variants on every input.
pub fn lsb_rows(inputs: &[(String, Pslg)]) -> Vec<LsbRow> {
    let mut rows = Vec::new();
    for (name, input) in inputs {
        for (variant, plain, bound) in [("modified", false, 2.0 / 3.0), ("plain", true, 0.5)] {
            let mut row = LsbRow {
                dataset: name.clone(),
                variant,
                bound,
                family_min_ratio: None,
                adaptive_min_ratio: None,
                adaptive_triangles: None,
                quaternary_splits: None,
                err: String::new(),
            };
            match Lsb::initial(input) {
                Ok((initial, _)) => {
                    let (soup, parents) = family(&initial, FAMILY_LEVELS, plain);
                    row.family_min_ratio = Some(lsb_descent_check(&initial, &soup, &parents));
                }
                Err(e) => row.err = e.to_string(),
            }
            match (Lsb { plain }).refine(input, &Params::default()) {
                Ok(run) => {
                    row.adaptive_min_ratio = Some(run.min_descent_ratio);
                    row.adaptive_triangles = Some(run.run.mesh.triangles.len() as u64);
                    row.quaternary_splits = Some(run.quaternary_splits);
                }
                Err(e) if row.err.is_empty() => row.err = e.to_string(),
                Err(_) => {}
            }
            rows.push(row);
        }
    }
    rows
}

/// The README section: the family's minimum against its bound, and the adaptive minimum.
pub fn render(rows: &[LsbRow]) -> String {
    let mut md = String::from(
        "\n## Longest-side bisection (paper 003)\n\n\
         Theorem 3.4: every triangle of the family T(A,B,C) of a triangle keeps at least 2/3 of \
         its smallest angle under the modified bisection (1/2 under plain bisection). The \
         family column refines every initial Delaunay triangle of the dataset uniformly, \
         3 levels deep, and gives the smallest ratio of a descendant's smallest angle to its \
         ancestor's; the adaptive column is what `lsb` outputs (conforming, longest-edge heap, \
         default target), for which the paper proves no bound. Data: `lsb.csv`.\n\n\
         | dataset | variant | bound | family min ratio | adaptive min ratio | adaptive triangles | quaternary splits |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: |\n",
    );
    let ratio = |r: Option<f64>| r.map_or_else(|| "—".to_string(), |v| format!("{v:.4}"));
    for r in rows {
        let _ = writeln!(
            md,
            "| `{}` | {} | {:.4} | {} | {} | {} | {} |",
            r.dataset,
            r.variant,
            r.bound,
            ratio(r.family_min_ratio),
            ratio(r.adaptive_min_ratio),
            r.adaptive_triangles
                .map_or_else(|| "—".to_string(), |t| t.to_string()),
            r.quaternary_splits
                .map_or_else(|| "—".to_string(), |t| t.to_string()),
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_family_meets_theorem_3_4_on_a_small_dataset() {
        let input = crate::datasets::by_name("plane-100").expect("dataset");
        let rows = lsb_rows(&[("plane-100".to_string(), input)]);
        assert_eq!(rows.len(), 2);
        for r in &rows {
            assert!(r.err.is_empty(), "{}", r.err);
            let family = r.family_min_ratio.expect("measured");
            assert!(family >= r.bound - 1e-9, "{} {family}", r.variant);
            assert!(r.adaptive_min_ratio.is_some_and(|a| a > 0.0));
        }
        let md = render(&rows);
        assert!(md.contains("| `plane-100` | modified | 0.6667 |"), "{md}");
    }
}
