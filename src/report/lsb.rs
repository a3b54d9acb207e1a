//! Paper 003's angle bounds measured on the datasets (Stamm, Eidenbenz & Pajarola, Theorem 3.4):
//! the family T(A,B,C) of every initial Delaunay triangle refined `FAMILY_LEVELS` deep keeps 2/3
//! of its smallest angle (1/2 under plain bisection); the conforming, heap-driven refinement
//! keeps 1/2 (the paper's Sec. 4), and its measured minimum ratio is shown beside the bounds.
//! The family is measured in the report's process one initial triangle at a time (memory of one
//! family); the adaptive meshes are made like every other case, in a child process with the
//! report's timeout (`lsb`, `lsb-plain`), and measured by the checker (`quality::descent`).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use serde::Serialize;

use super::row::one_line;
use crate::isolate;
use crate::mesh::Pslg;
use crate::mesher::Params;
use crate::quality::{descent, LSB_ADAPTIVE_RATIO, LSB_FAMILY_RATIO};
use crate::refine::{family_min_ratio, Lsb};

/// Depth of the uniform family: 4^3 = 64 descendants of every initial triangle.
pub const FAMILY_LEVELS: u32 = 3;

/// The columns of `lsb.csv`.
pub const LSB_COLUMNS: &[&str] = &[
    "dataset",
    "variant",
    "bound",
    "family_min_ratio",
    "adaptive_bound",
    "adaptive_min_ratio",
    "adaptive_triangles",
    "err",
];

/// One dataset × variant (modified or plain bisection).
#[derive(Debug, Clone, Serialize)]
pub struct LsbRow {
    pub dataset: String,
    /// `modified` (the mesher `lsb`) or `plain` (`lsb-plain`).
    pub variant: &'static str,
    /// The ratio Theorem 3.4 (or plain bisection's 1/2) promises for the family.
    pub bound: f64,
    /// Smallest ratio over the uniform family, `FAMILY_LEVELS` deep.
    pub family_min_ratio: Option<f64>,
    /// The ratio the adaptive refinement promises (`verify --bounds lsb`): 1/2.
    pub adaptive_bound: f64,
    /// Smallest ratio over the conforming refinement the mesher outputs with default
    /// parameters, each triangle against the initial triangle its centroid lies in.
    pub adaptive_min_ratio: Option<f64>,
    pub adaptive_triangles: Option<u64>,
    pub err: String,
}

/// The variants measured: (variant, mesher name, plain bisection, family bound).
const VARIANTS: [(&str, &str, bool, f64); 2] = [
    ("modified", "lsb", false, LSB_FAMILY_RATIO),
    ("plain", "lsb-plain", true, LSB_ADAPTIVE_RATIO),
];

/// Measures both variants on every input; the adaptive meshes are made by `exe` in a child
/// process each, killed after `timeout`. `progress` hears the label of each step.
pub fn lsb_rows(
    exe: &Path,
    inputs: &[(String, Pslg)],
    timeout: Duration,
    mut progress: impl FnMut(&str),
) -> Vec<LsbRow> {
    let mut rows = Vec::new();
    for (name, input) in inputs {
        let initial = Lsb::initial(input);
        for (variant, mesher, plain, bound) in VARIANTS {
            progress(&format!("{name} × {mesher}: Theorem 3.4"));
            let mut row = LsbRow {
                dataset: name.clone(),
                variant,
                bound,
                family_min_ratio: None,
                adaptive_bound: LSB_ADAPTIVE_RATIO,
                adaptive_min_ratio: None,
                adaptive_triangles: None,
                err: String::new(),
            };
            let initial = match &initial {
                Ok((initial, _)) => initial,
                Err(e) => {
                    row.err = one_line(&e.to_string());
                    rows.push(row);
                    continue;
                }
            };
            row.family_min_ratio = Some(family_min_ratio(initial, FAMILY_LEVELS, plain));
            match isolate::run_isolated(exe, mesher, input, &Params::default(), timeout) {
                Ok(iso) if iso.run.complete => {
                    let mesh = &iso.run.mesh;
                    let d = descent(initial, mesh, LSB_ADAPTIVE_RATIO);
                    row.adaptive_triangles = Some(mesh.triangles.len() as u64);
                    row.adaptive_min_ratio = d.min_ratio.map(|(r, _)| r);
                    if let Some(t) = d.first_unlocated {
                        row.err = format!(
                            "triangle {} (numbered from 1) lies outside the initial triangulation",
                            t + 1
                        );
                    }
                }
                Ok(iso) => {
                    row.err = one_line(&format!(
                        "{mesher} stopped early: {}",
                        iso.run
                            .stop_reason
                            .as_ref()
                            .map_or("no reason given".into(), ToString::to_string)
                    ))
                }
                Err(e) => row.err = one_line(&format!("{mesher}: {e}")),
            }
            rows.push(row);
        }
    }
    rows
}

/// The README section: the family's minimum against its bound, and the adaptive minimum
/// against the bound `verify --bounds lsb` checks.
pub fn render(rows: &[LsbRow]) -> String {
    let mut md = String::from(
        "\n## Longest-side bisection (paper 003)\n\n\
         Theorem 3.4: every triangle of the family T(A,B,C) of a triangle keeps at least 2/3 of \
         its smallest angle under the modified bisection (1/2 under plain bisection). The \
         family column refines every initial Delaunay triangle of the dataset uniformly, \
         3 levels deep, and gives the smallest ratio of a descendant's smallest angle to its \
         ancestor's. The adaptive column is what the mesher outputs (`lsb` for modified, \
         `lsb-plain` for plain: conforming, longest-edge heap, rule 4.1, default target), each \
         triangle measured against the initial triangle it lies in; the paper (Sec. 4) gives \
         the adaptive refinement 1/2 only (\"both discussed mesh refinement methods can \
         locally lead to α/2 smallest angles\"), and that is what `verify --bounds lsb` \
         checks. Data: `lsb.csv`.\n\n\
         | dataset | variant | family bound | family min ratio | adaptive bound | adaptive min ratio | adaptive triangles |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: |\n",
    );
    let ratio = |r: Option<f64>| r.map_or_else(|| "—".to_string(), |v| format!("{v:.4}"));
    for r in rows {
        let _ = writeln!(
            md,
            "| `{}` | {} | {:.4} | {} | {:.4} | {} | {} |",
            r.dataset,
            r.variant,
            r.bound,
            ratio(r.family_min_ratio),
            r.adaptive_bound,
            ratio(r.adaptive_min_ratio),
            r.adaptive_triangles
                .map_or_else(|| "—".to_string(), |t| t.to_string()),
        );
    }
    for r in rows.iter().filter(|r| !r.err.is_empty()) {
        let _ = writeln!(md, "\n- `{}` ({}): {}", r.dataset, r.variant, r.err);
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_section_sets_each_ratio_beside_its_bound_and_names_failures() {
        let row = |variant, bound, family, adaptive, err: &str| LsbRow {
            dataset: "imr".into(),
            variant,
            bound,
            family_min_ratio: family,
            adaptive_bound: LSB_ADAPTIVE_RATIO,
            adaptive_min_ratio: adaptive,
            adaptive_triangles: adaptive.map(|_| 607),
            err: err.into(),
        };
        let md = render(&[
            row(
                "modified",
                LSB_FAMILY_RATIO,
                Some(0.97858),
                Some(0.97858),
                "",
            ),
            row(
                "plain",
                0.5,
                Some(0.5885),
                None,
                "lsb-plain: timeout after 60s",
            ),
        ]);
        assert!(
            md.contains("| `imr` | modified | 0.6667 | 0.9786 | 0.5000 | 0.9786 | 607 |"),
            "{md}"
        );
        assert!(
            md.contains("| `imr` | plain | 0.5000 | 0.5885 | 0.5000 | — | — |"),
            "{md}"
        );
        assert!(
            md.contains("- `imr` (plain): lsb-plain: timeout after 60s"),
            "{md}"
        );
    }

    #[test]
    fn the_streamed_family_ratio_equals_the_soups() {
        let input = crate::datasets::by_name("imr").expect("dataset");
        let (initial, _) = Lsb::initial(&input).expect("initial");
        for plain in [false, true] {
            let (soup, parents) = crate::refine::family(&initial, 3, plain);
            let whole = crate::refine::lsb_descent_check(&initial, &soup, &parents);
            let streamed = family_min_ratio(&initial, 3, plain);
            assert!((whole - streamed).abs() < 1e-12, "{whole} {streamed}");
        }
    }
}
