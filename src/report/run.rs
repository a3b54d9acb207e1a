//! Running the cases: every mesher on every dataset, each meshing call in a child process of
//! our binary (`isolate`), checked by `quality` against the bounds its mesher promises
//! (`Mesher::promise`), and the paper's max-angle protocol (Sec. 8) for the references.
//! A failure becomes a row with its `err`; nothing here stops the report but a usage error
//! or an unwritable output directory.

use std::path::Path;

use super::case::run_case;
use super::plot::{self, AngleSeries, ScalingSeries};
use super::progress::Progress;
use super::readme::{self, Artifacts, Picture, RunFacts};
use super::row::{one_line, write_csv, Row, COLUMNS, NOT_RUN};
use super::table1::{self, paper_row, MaxAngleRow, MAX_ANGLE_COLUMNS};
use super::{clear_generated, ReportOptions, REFERENCES, REFERENCE_MIN_ANGLE};
use crate::error::{Error, Result};
use crate::io::{write_svg, SvgOptions};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Mesher;
use crate::{datasets, isolate, maxangle, registry};

/// The smallest plane-* dataset in the scaling plot (plane-1k).
const SCALING_FROM_POINTS: u64 = 1000;

/// The datasets drawn in the manner of the paper's Fig. 15 (its four rows).
const PICTURED: &[&str] = &["close-pair", "line-100", "plane-100", "imr"];

/// Runs the whole report and writes `opts.out` (see the module comment of `report`).
pub fn run_report(opts: &ReportOptions) -> Result<()> {
    check_options(opts)?;
    let names = dataset_names(opts);
    // Resolve every name before anything runs or is deleted: a typo is a usage error, not
    // an hour of work followed by a row per case.
    let mut inputs: Vec<(String, Pslg)> = Vec::with_capacity(names.len());
    for n in &names {
        inputs.push((n.clone(), datasets::by_name(n)?));
    }
    let examples: Vec<datasets::PslgExample> = example_names(opts)
        .iter()
        .filter_map(|n| datasets::pslg_example(n))
        .collect();
    let meshers = resolve_meshers(&opts.meshers)?;
    let segment_meshers = super::pslg::segment_meshers(&meshers);
    let exe = isolate::find_exe()?;
    plot::ensure_font()?;
    clear_generated(&opts.out)?;

    let references: Vec<&dyn Mesher> = meshers
        .iter()
        .map(|m| m.as_ref())
        .filter(|m| REFERENCES.contains(&m.name()))
        .collect();
    let table_inputs: Vec<&(String, Pslg)> = inputs
        .iter()
        .filter(|(n, _)| opts.max_angle && paper_row(n).is_some())
        .collect();
    // The studies of one mesher (lsb's descent, Saalfeld's two methods, counts over seeds) are
    // about the paper's datasets; the scaling series only adds points to the scaling plot.
    let small_inputs: Vec<(String, Pslg)> = inputs
        .iter()
        .filter(|(n, _)| !datasets::SCALING.contains(&n.as_str()))
        .cloned()
        .collect();
    let with_lsb = meshers.iter().any(|m| m.name() == "lsb");
    let lsb_steps = if with_lsb { 2 * small_inputs.len() } else { 0 };
    let with_saalfeld = meshers.iter().any(|m| m.name() == "saalfeld");
    let saalfeld_steps = if with_saalfeld { small_inputs.len() } else { 0 };
    let seed_steps = small_inputs
        .iter()
        .filter(|(n, _)| opts.max_angle && datasets::default_seed(n).is_some())
        .count()
        * meshers
            .iter()
            .filter(|m| super::seeds::COUNTED.contains(&m.name()))
            .count()
        * super::seeds::SEEDS as usize;
    let total = (inputs.len() * meshers.len()
        + examples.len() * segment_meshers.len()
        + table_inputs.len() * references.len()
        + lsb_steps
        + saalfeld_steps
        + seed_steps) as u64;
    let mut progress = Progress::new(total);
    let mut rows: Vec<Row> = Vec::new();
    let mut art = Artifacts::default();
    let results_csv = opts.out.join("results.csv");

    for (name, input) in &inputs {
        let mut series = Vec::new();
        // The scaling series is timed once: a run of plane-100k takes up to a minute and more.
        let runs = if datasets::SCALING.contains(&name.as_str()) {
            1
        } else {
            opts.runs
        };
        for m in &meshers {
            progress.start(&format!("{name} × {}", m.name()));
            let outcome = run_case(
                &exe,
                m.as_ref(),
                (name, input),
                runs,
                opts.timeout,
                opts.triangle_switches.as_deref(),
            );
            progress.finish_step(&summary(&outcome.row));
            if let Some(h) = &outcome.histogram {
                series.push(AngleSeries {
                    mesher: m.name().to_string(),
                    histogram: h.clone(),
                    bounds: outcome.bounds.clone(),
                    range: outcome.verdict.as_ref().and_then(|v| {
                        let m = &v.metrics;
                        Some((m.min_angle?.value, m.max_angle?.value))
                    }),
                });
            }
            if PICTURED.contains(&name.as_str()) {
                if let Some(mesh) = &outcome.mesh {
                    match picture(&opts.out, name, m.name(), input, mesh) {
                        Ok(p) => art.pictures.push(p),
                        Err(e) => art
                            .problems
                            .push(format!("picture of {name} × {}: {e}", m.name())),
                    }
                }
            }
            rows.push(outcome.row);
            // Rewritten after every case, so an interrupted report keeps what it measured.
            write_csv(&results_csv, COLUMNS, &rows)?;
        }
        if !series.is_empty() {
            let stem = format!("angles-{name}");
            let title = format!(
                "angles of {name}: fraction of all angles per 1° bin (log scale), one panel per \
                 mesher, dashed = promised bounds"
            );
            match plot::angle_plot(&opts.out, &stem, &title, &series) {
                Ok(_) => {
                    art.angle_plots.push((name.clone(), stem));
                    art.angle_notes
                        .push((name.clone(), plot::angle_notes(&series)));
                }
                Err(e) => art.problems.push(format!("angle plot of {name}: {e}")),
            }
        }
    }

    write_csv(&results_csv, COLUMNS, &rows)?;

    let mut max_angles = Vec::new();
    for (name, input) in &table_inputs {
        for m in &references {
            progress.start(&format!("max angle: {name} × {}", m.name()));
            let row = run_max_angle(&exe, *m, name, input, opts);
            progress.finish_step(&format!(
                "max angle: {name} × {}: {}",
                m.name(),
                match row.angle {
                    Some(a) => format!("{a:.2}°"),
                    None if !row.err.is_empty() => one_line(&row.err),
                    None => format!("none; {}", one_line(&row.next_failure)),
                }
            ));
            max_angles.push(row);
        }
    }
    write_csv(
        &opts.out.join("maxangle.csv"),
        MAX_ANGLE_COLUMNS,
        &max_angles,
    )?;

    let series = scaling_series(&rows, &meshers);
    if series.iter().any(|s| s.samples.len() >= 2) {
        match plot::scaling_plot(&opts.out, "scaling", &series) {
            Ok(_) => art.scaling = Some("scaling".to_string()),
            Err(e) => art.problems.push(format!("scaling plot: {e}")),
        }
    }

    let mesher_names: Vec<String> = meshers.iter().map(|m| m.name().to_string()).collect();
    // Counts over seeds belong to Table 1 and are skipped with it (`--no-max-angle`).
    let seed_datasets: Vec<String> = if opts.max_angle {
        small_inputs.iter().map(|(n, _)| n.clone()).collect()
    } else {
        Vec::new()
    };
    let seed_rows = progress.labelled(|step| {
        super::seeds::seed_rows(&exe, &seed_datasets, &mesher_names, opts.timeout, step)
    });
    write_csv(
        &opts.out.join("seeds.csv"),
        super::seeds::SEED_COLUMNS,
        &seed_rows,
    )?;
    let mut table = table1::render(
        &rows,
        &max_angles,
        &mesher_names,
        REFERENCES,
        REFERENCE_MIN_ANGLE,
    );
    table.push_str(&super::seeds::render(&seed_rows));
    write_text(&opts.out.join("table1.md"), &table)?;
    let facts = RunFacts {
        runs: opts.runs,
        timeout_s: opts.timeout.as_secs_f64(),
        references: references.iter().map(|m| m.name().to_string()).collect(),
        reference_request: REFERENCE_MIN_ANGLE,
        max_angle_step: opts.max_angle_step,
        max_angle_timeout_s: opts.max_angle_timeout.as_secs_f64(),
    };
    let with_pslg = !examples.is_empty() && !segment_meshers.is_empty();
    art.pslg = with_pslg;
    let mut readme_text = readme::render(&rows, &max_angles, &art, &facts);
    if with_lsb {
        let lsb_rows =
            progress.labelled(|step| super::lsb::lsb_rows(&exe, &small_inputs, opts.timeout, step));
        write_csv(
            &opts.out.join("lsb.csv"),
            super::lsb::LSB_COLUMNS,
            &lsb_rows,
        )?;
        readme_text.push_str(&super::lsb::render(&lsb_rows));
    }
    if with_saalfeld {
        let saalfeld_rows = progress.labelled(|step| {
            super::saalfeld::saalfeld_rows(&exe, &small_inputs, &rows, opts.timeout, step)
        });
        write_csv(
            &opts.out.join("saalfeld.csv"),
            super::saalfeld::SAALFELD_COLUMNS,
            &saalfeld_rows,
        )?;
        readme_text.push_str(&super::saalfeld::render(&saalfeld_rows));
    }
    if with_pslg {
        let (pslg_rows, pslg_meshes) = progress.labelled(|step| {
            super::pslg::pslg_rows(
                &exe,
                &examples,
                &segment_meshers,
                (opts.runs, opts.timeout),
                opts.triangle_switches.as_deref(),
                step,
            )
        });
        write_csv(
            &opts.out.join("pslg.csv"),
            super::pslg::PSLG_COLUMNS,
            &pslg_rows,
        )?;
        let mut pictures = Vec::new();
        for (name, mesher, mesh) in &pslg_meshes {
            let Some(e) = examples.iter().find(|e| e.name == *name) else {
                continue;
            };
            match picture(&opts.out, name, mesher, &e.pslg, mesh) {
                Ok(p) => pictures.push(p),
                Err(e) => progress.note(&format!("picture of {name} × {mesher}: {e}")),
            }
        }
        readme_text.push_str(&super::pslg::render(&examples, &pslg_rows, &pictures));
    }
    write_text(&opts.out.join("README.md"), &readme_text)?;
    progress.note(&format!(
        "report written to {} ({} rows)",
        opts.out.display(),
        rows.len()
    ));
    progress.finish();
    Ok(())
}

fn check_options(opts: &ReportOptions) -> Result<()> {
    if opts.runs == 0 {
        return Err(Error::Usage("--runs must be at least 1".into()));
    }
    if opts.timeout.is_zero() || opts.max_angle_timeout.is_zero() {
        return Err(Error::Usage("timeouts must be longer than zero".into()));
    }
    if !(opts.max_angle_step.is_finite() && opts.max_angle_step > 0.0) {
        return Err(Error::Usage(format!(
            "the max-angle step {} must be a positive number of degrees",
            opts.max_angle_step
        )));
    }
    if let Some(switches) = &opts.triangle_switches {
        // Checked as the triangle rows will send them, beside the report's own angle.
        let params = super::case_params("triangle")
            .0
            .with_switches(switches.as_str());
        crate::reference::triangle::user_switches(&params).map_err(|e| match e {
            Error::Usage(m) => Error::Usage(format!(
                "{m} (the report asks triangle for {}°)",
                super::REFERENCE_MIN_ANGLE
            )),
            other => other,
        })?;
    }
    Ok(())
}

/// The datasets of `results.csv` in the order given (PSLG examples left out), `SMALL` and
/// `SCALING_IN_REPORT` when none are given, with all of `SCALING` appended when asked; a name
/// given twice runs once.
fn dataset_names(opts: &ReportOptions) -> Vec<String> {
    let mut names: Vec<String> = if opts.datasets.is_empty() {
        datasets::SMALL
            .iter()
            .chain(datasets::SCALING_IN_REPORT)
            .map(|s| s.to_string())
            .collect()
    } else {
        opts.datasets
            .iter()
            .filter(|n| !datasets::PSLG_EXAMPLES.contains(&n.as_str()))
            .cloned()
            .collect()
    };
    if opts.scaling {
        names.extend(datasets::SCALING.iter().map(|s| s.to_string()));
    }
    let mut seen = Vec::new();
    names.retain(|n| {
        let new = !seen.contains(n);
        seen.push(n.clone());
        new
    });
    names
}

/// The PSLG examples of `pslg.csv`: every one when no dataset is given, else those named, in
/// the order of `PSLG_EXAMPLES`.
fn example_names(opts: &ReportOptions) -> Vec<&'static str> {
    datasets::PSLG_EXAMPLES
        .iter()
        .copied()
        .filter(|e| opts.datasets.is_empty() || opts.datasets.iter().any(|n| n == e))
        .collect()
}

fn resolve_meshers(names: &[String]) -> Result<Vec<Box<dyn Mesher>>> {
    if names.is_empty() {
        return Ok(registry::meshers());
    }
    let mut out: Vec<Box<dyn Mesher>> = Vec::new();
    for n in names {
        if !out.iter().any(|m| m.name() == n) {
            out.push(registry::mesher(n)?);
        }
    }
    Ok(out)
}

fn summary(r: &Row) -> String {
    let mut s = format!("{} × {}: ", r.dataset, r.mesher);
    match (r.triangles, r.min_angle, r.max_angle) {
        (Some(t), Some(lo), Some(hi)) => {
            s.push_str(&format!("{t} triangles, angles {lo:.2}°–{hi:.2}°"));
        }
        _ => s.push_str("no mesh"),
    }
    if let Some(t) = r.time_median_s {
        s.push_str(&format!(", {t:.4} s"));
    }
    if r.bounds_ok == Some(false) {
        s.push_str(", BOUNDS FAIL");
    }
    if !r.err.is_empty() {
        s.push_str(&format!(" [{}]", one_line(&r.err)));
    }
    s
}

fn run_max_angle(
    exe: &Path,
    mesher: &dyn Mesher,
    dataset: &str,
    input: &Pslg,
    opts: &ReportOptions,
) -> MaxAngleRow {
    let mut row = MaxAngleRow {
        dataset: dataset.to_string(),
        mesher: mesher.name().to_string(),
        step: opts.max_angle_step,
        start: opts.max_angle_start,
        angle: None,
        triangles: None,
        time_s: None,
        next_failure: String::new(),
        settings: String::new(),
        err: String::new(),
    };
    if input.has_segments() && !mesher.supports_segments() {
        row.err = NOT_RUN.into();
        return row;
    }
    match maxangle::max_angle(
        exe,
        mesher.name(),
        input,
        opts.max_angle_step,
        opts.max_angle_timeout,
        opts.max_angle_start,
    ) {
        Ok(m) => {
            row.angle = m.angle;
            if m.angle.is_some() {
                row.triangles = Some(m.triangles as u64);
                row.time_s = Some(m.seconds);
            }
            row.next_failure = one_line(&format!("{:.2}°: {}", m.failed_at, m.failure));
            row.settings = one_line(&m.settings);
        }
        Err(e) => row.err = one_line(&e.to_string()),
    }
    row
}

/// Time and triangles against input points for the plane-* family from plane-1k up, one series
/// per mesher: the runs that finished (within the time limit and their own budgets). plane-100
/// is left out: at 100 points a run's fixed costs (process start, the bounding hexagon) weigh
/// as much as its points and bend the fitted exponent.
fn scaling_series(rows: &[Row], meshers: &[Box<dyn Mesher>]) -> Vec<ScalingSeries> {
    meshers
        .iter()
        .map(|m| ScalingSeries {
            mesher: m.name().to_string(),
            samples: rows
                .iter()
                .filter(|r| {
                    r.mesher == m.name()
                        && r.dataset.starts_with("plane-")
                        && r.points >= SCALING_FROM_POINTS
                        && r.complete
                })
                .filter_map(|r| Some((r.points as f64, r.time_median_s?, r.triangles? as f64)))
                .collect(),
        })
        .filter(|s| !s.samples.is_empty())
        .collect()
}

/// Where the detail is, for the zoomed picture: the two close points, an end of the line.
fn zoom_window(dataset: &str, input: &Pslg) -> Option<([f64; 4], &'static str)> {
    match dataset {
        "close-pair" => {
            let (c, r) = crate::geom::min_enclosing_circle(&input.points);
            let h = 2.5 * r.max(f64::MIN_POSITIVE);
            Some((
                [c[0] - h, c[1] - h, c[0] + h, c[1] + h],
                "the two close points",
            ))
        }
        "line-100" => {
            let end = input
                .points
                .iter()
                .copied()
                .min_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])))?;
            let h = 0.05;
            Some((
                [end[0] - h, end[1] - h, end[0] + h, end[1] + h],
                "the end of the line at the origin",
            ))
        }
        "imr" => {
            // The R's bowl and counter, the finest detail: the input points around the hole
            // seed, framed with a small margin.
            let seed = *input.holes.first()?;
            let near: Vec<[f64; 2]> = input
                .points
                .iter()
                .copied()
                .filter(|p| crate::geom::dist(*p, seed) < 0.45)
                .collect();
            let lo = near
                .iter()
                .fold(seed, |a, p| [a[0].min(p[0]), a[1].min(p[1])]);
            let hi = near
                .iter()
                .fold(seed, |a, p| [a[0].max(p[0]), a[1].max(p[1])]);
            let pad = 0.04 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
            Some((
                [lo[0] - pad, lo[1] - pad, hi[0] + pad, hi[1] + pad],
                "the bowl and counter of the R",
            ))
        }
        _ => None,
    }
}

fn picture(
    out: &Path,
    dataset: &str,
    mesher: &str,
    input: &Pslg,
    mesh: &TriMesh,
) -> Result<Picture> {
    let file = format!("mesh-{dataset}-{mesher}.svg");
    let zoom = zoom_window(dataset, input);
    let opts = SvgOptions {
        width: 800.0,
        title: Some(format!(
            "{mesher} on {dataset}: {} triangles{}",
            mesh.triangles.len(),
            if zoom.is_some() {
                " (dashed frame: the zoomed detail)"
            } else {
                ""
            }
        )),
        highlight: input.points.clone(),
        zoom: None,
        frames: zoom.iter().map(|(w, _)| *w).collect(),
    };
    write_svg(&out.join(&file), mesh, &opts)?;
    let mut pic = Picture {
        dataset: dataset.to_string(),
        mesher: mesher.to_string(),
        file,
        zoom_file: None,
        zoom_note: String::new(),
    };
    if let Some((window, note)) = zoom {
        let zoom_file = format!("mesh-{dataset}-{mesher}-zoom.svg");
        let zopts = SvgOptions {
            width: 500.0,
            title: Some(format!("{mesher} on {dataset}: {note}")),
            zoom: Some(window),
            frames: Vec::new(),
            ..opts
        };
        write_svg(&out.join(&zoom_file), mesh, &zopts)?;
        pic.zoom_file = Some(zoom_file);
        pic.zoom_note = note.to_string();
    }
    Ok(pic)
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.to_path_buf(),
        source: e,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inside(w: [f64; 4], p: [f64; 2]) -> bool {
        w[0] < p[0] && p[0] < w[2] && w[1] < p[1] && p[1] < w[3]
    }

    #[test]
    fn close_pair_zoom_frames_both_points_tightly() {
        let input = datasets::by_name("close-pair").unwrap();
        let (w, _) = zoom_window("close-pair", &input).unwrap();
        assert!(input.points.iter().all(|&p| inside(w, p)));
        // Both points must stay far apart on the picture: the window is a few d_min wide.
        assert!(w[2] - w[0] < 0.2, "{w:?}");
    }

    #[test]
    fn line_zoom_shows_the_end_at_the_origin_only() {
        let input = datasets::by_name("line-100").unwrap();
        let (w, _) = zoom_window("line-100", &input).unwrap();
        let first = input
            .points
            .iter()
            .copied()
            .min_by(|a, b| a[0].total_cmp(&b[0]))
            .unwrap();
        assert!(inside(w, first));
        assert!(!inside(w, [1.0, 0.37]));
    }

    #[test]
    fn imr_zoom_is_centred_on_the_r_counter_and_plane_has_none() {
        let imr = datasets::by_name("imr").unwrap();
        let (w, _) = zoom_window("imr", &imr).unwrap();
        assert!(inside(w, imr.holes[0]));
        // The whole bowl: its rightmost point (above the leg) is in the frame, the M is not.
        let right = imr
            .points
            .iter()
            .copied()
            .filter(|p| p[1] > 0.5)
            .max_by(|a, b| a[0].total_cmp(&b[0]))
            .unwrap();
        assert!(inside(w, right), "{w:?} {right:?}");
        assert!(w[0] > 1.5, "{w:?}");
        let plane = datasets::by_name("plane-100").unwrap();
        assert!(zoom_window("plane-100", &plane).is_none());
    }

    #[test]
    fn report_triangle_switches_are_checked_beside_the_reports_own_angle() {
        let with = |s: &str| ReportOptions {
            triangle_switches: Some(s.to_string()),
            ..ReportOptions::default()
        };
        assert!(check_options(&with("Da0.5")).is_ok());
        for bad in ["q25", "j"] {
            match check_options(&with(bad)) {
                Err(Error::Usage(m)) => assert!(m.contains(bad) && m.contains("30"), "{m}"),
                other => panic!("{bad}: {other:?}"),
            }
        }
    }

    #[test]
    fn dataset_list_defaults_to_small_adds_scaling_and_drops_repeats() {
        let mut opts = ReportOptions::default();
        let mut default: Vec<&str> = datasets::SMALL.to_vec();
        default.extend(["plane-10k", "plane-100k"]);
        assert_eq!(dataset_names(&opts), default);
        opts.scaling = true;
        default.push("plane-1m");
        assert_eq!(dataset_names(&opts), default);
        opts.scaling = false;
        opts.datasets = vec!["imr".into(), "plane-1k".into(), "imr".into()];
        opts.scaling = true;
        let mut want = vec!["imr", "plane-1k"];
        want.extend(datasets::SCALING);
        assert_eq!(dataset_names(&opts), want);
    }

    #[test]
    fn pslg_examples_go_to_their_own_table_all_by_default_else_as_named() {
        let mut opts = ReportOptions::default();
        assert_eq!(example_names(&opts), datasets::PSLG_EXAMPLES);
        opts.datasets = vec!["pslg-slit".into(), "imr".into(), "pslg-holes".into()];
        assert_eq!(example_names(&opts), ["pslg-holes", "pslg-slit"]);
        assert_eq!(dataset_names(&opts), ["imr"]);
        opts.datasets = vec!["plane-100".into()];
        assert!(example_names(&opts).is_empty());
    }
}
