//! One case of the report: a mesher on one input, meshed `runs` times in child processes of
//! our binary (`isolate`), timed, and its first mesh checked by `quality::verdict` against
//! the bounds its mesher promises, as one `Row`. The tables of datasets (`run`) and of PSLG
//! examples (`pslg`) both run their cases here.

use std::path::Path;
use std::time::Duration;

use super::case_params;
use super::row::{one_line, Row, NOT_RUN};
use super::stats::Timing;
use crate::isolate;
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher};
use crate::quality;

/// What one case leaves behind besides its row.
pub(super) struct Outcome {
    pub(super) row: Row,
    pub(super) histogram: Option<Vec<u64>>,
    pub(super) bounds: Vec<f64>,
    pub(super) mesh: Option<TriMesh>,
    /// The verdict on the mesh, when there was one to judge (its violations by kind, the
    /// near-segment and interior figures apart).
    pub(super) verdict: Option<quality::Verdict>,
}

/// Meshes `input` with `mesher` `runs` times, each in a child of `exe` killed after
/// `timeout`, and checks the first mesh against what the mesher promises for the parameters
/// of the run (`Mesher::promise`: for a reference, the minimum angle it was asked for).
/// `triangle_switches` go to the `triangle` mesher alone (`Params::switches`).
pub(super) fn run_case(
    exe: &Path,
    mesher: &dyn Mesher,
    (dataset, input): (&str, &Pslg),
    runs: usize,
    timeout: Duration,
    triangle_switches: Option<&str>,
) -> Outcome {
    let name = mesher.name();
    let mut row = Row::empty(dataset, input.points.len(), name, &mesher.version());
    let (mut params, asked) = case_params(name);
    if name == "triangle" {
        params.switches = triangle_switches.map(str::to_string);
    }
    row.params = asked;
    row.settings = one_line(&mesher.settings(&params));
    let mut outcome = Outcome {
        row,
        histogram: None,
        bounds: Vec::new(),
        mesh: None,
        verdict: None,
    };
    if input.has_segments() && !mesher.supports_segments() {
        outcome.row.err = NOT_RUN.into();
        return outcome;
    }

    let mut times: Vec<Duration> = Vec::new();
    let mut peak: Option<u64> = None;
    let mut first: Option<MeshRun> = None;
    let mut errors: Vec<String> = Vec::new();
    for _ in 0..runs {
        match isolate::run_isolated(exe, name, input, &params, timeout) {
            Err(e) => {
                errors.push(e.to_string());
                break;
            }
            Ok(iso) => {
                peak = Some(peak.unwrap_or(0).max(iso.peak_rss_bytes));
                let run = iso.run;
                if !run.complete {
                    errors.push(format!(
                        "stopped early: {}",
                        run.stop_reason
                            .as_ref()
                            .map_or("no reason given".into(), ToString::to_string)
                    ));
                    if first.is_none() {
                        first = Some(run);
                    }
                    break;
                }
                times.push(run.elapsed);
                match &first {
                    None => first = Some(run),
                    Some(f) if f.mesh != run.mesh => {
                        errors.push("the mesh differs from the first run's".into());
                    }
                    Some(_) => {}
                }
            }
        }
    }
    let row = &mut outcome.row;
    row.complete = errors.is_empty() && first.as_ref().is_some_and(|r| r.complete);
    row.err = one_line(&errors.join("; "));
    row.runs = times.len() as u64;
    if let Some(t) = Timing::of(&times) {
        row.time_median_s = Some(t.median);
        row.time_min_s = Some(t.min);
        row.time_max_s = Some(t.max);
    }
    row.peak_rss_mb = peak.map(|b| b as f64 / (1024.0 * 1024.0));

    let Some(run) = first else {
        return outcome;
    };
    if run.mesh.triangles.is_empty() {
        // A mesher that finishes without a triangle has failed, even if it says complete.
        if row.err.is_empty() {
            row.err = "the mesh has no triangles".into();
        }
        return outcome;
    }
    let bounds = mesher.promise(&params);
    // Messages number as the files `hexmesh datasets` and `hexmesh mesh` write: from 1.
    let verdict =
        quality::verdict(&run.mesh, Some(input), Some(&bounds)).numbered(quality::Numbering::FILES);
    let m = &verdict.metrics;
    row.vertices = Some(m.vertices as u64);
    row.steiner_points = Some(m.vertices.saturating_sub(row.points as usize) as u64);
    row.triangles = Some(m.triangles as u64);
    row.covered_area = Some(m.covered_area);
    row.min_angle = m.min_angle.as_ref().map(|w| w.value);
    row.max_angle = m.max_angle.as_ref().map(|w| w.value);
    row.radius_ratio_max = m.radius_ratio_max.as_ref().map(|w| w.value);
    row.edge_ratio_max = m.edge_ratio_max.as_ref().map(|w| w.value);
    row.shortest_edge = m.shortest_edge.as_ref().map(|w| w.value);
    row.d_min = m.d_min;
    row.shortest_over_dmin = m.shortest_edge_over_d_min;
    row.delaunay_exact_violations = Some(m.delaunay_violations as u64);
    row.delaunay_tol_violations = Some(m.delaunay_tolerance_violations as u64);
    if let Some(split) = &verdict.split {
        row.interior_min_angle = split.interior.min_angle.as_ref().map(|w| w.value);
        row.interior_max_angle = split.interior.max_angle.as_ref().map(|w| w.value);
    }
    row.valid = Some(verdict.violations.len() as u64);
    row.problem = first_problem(&verdict);
    row.bounds_ok = Some(verdict.passed());
    outcome.bounds = bounds
        .min_angle
        .into_iter()
        .chain(bounds.max_angle)
        .collect();
    outcome.histogram = Some(verdict.metrics.angle_histogram.clone());
    outcome.mesh = Some(run.mesh);
    outcome.verdict = Some(verdict);
    outcome
}

/// The first validity violation, else the first failed check, in one line.
pub(crate) fn first_problem(v: &quality::Verdict) -> String {
    if let Some(first) = v.violations.first() {
        let more = v.violations.len() - 1;
        let tail = if more > 0 {
            format!(" (and {more} more)")
        } else {
            String::new()
        };
        return one_line(&format!("{}{tail}", first.describe(v.numbering)));
    }
    v.checks
        .iter()
        .find(|c| c.status == quality::Status::Fail)
        .map_or_else(String::new, |c| {
            let value = c
                .value
                .map_or_else(|| "none".to_string(), |x| format!("{x}"));
            let note = c
                .note
                .as_ref()
                .map_or_else(String::new, |n| format!(" ({n})"));
            one_line(&format!(
                "{} = {value}, must be {} {}{note}",
                c.what, c.relation, c.limit
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_problem_names_a_failed_bound_with_its_limit() {
        // A 30°-60°-90° triangle breaks hex's 43.9° bound; a 45°-45°-90° one keeps it.
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [3f64.sqrt(), 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        let b = crate::registry::bounds("hex").unwrap();
        let v = quality::verdict(&mesh, None, Some(&b));
        let p = first_problem(&v);
        assert!(p.starts_with("min angle (deg) = 30"), "{p}");
        assert!(p.contains("must be ≥ 43.89"), "{p}");
        let ok = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        assert_eq!(first_problem(&quality::verdict(&ok, None, Some(&b))), "");
    }
}
