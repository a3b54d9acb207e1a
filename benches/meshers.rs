//! Criterion benches: every registered mesher on the paper's dataset families (paper 000,
//! Sec. 8, Table 1), in-process, as a second opinion on `hexmesh report`'s isolated timings
//! (METHODOLOGY.md). One group per mesher × family; inputs are generated outside the timed
//! closure, and the meshers get the same parameters as in the report (references 30°, ours
//! their defaults). Sample sizes are small so that `cargo bench` finishes in minutes.
//! (paper 000 Sec. 8 times the meshing alone: so does the closure here.)

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use hexmesh::report::case_params;
use hexmesh::{datasets, registry, Pslg};

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

/// Families and their members, smallest first; plane-2k and the scaling series are left to
/// `hexmesh report --scaling`, since one hexagon mesh of them takes seconds.
const FAMILIES: &[(&str, &[&str])] = &[
    ("close-pair", &["close-pair"]),
    ("line", &["line-100"]),
    ("plane", &["plane-100", "plane-1k"]),
    ("imr", &["imr"]),
];

fn meshers(c: &mut Criterion) {
    hexmesh::configure_allocator();
    let inputs: Vec<(&str, Vec<(&str, Pslg)>)> = FAMILIES
        .iter()
        .map(|(family, names)| {
            let sets = names
                .iter()
                .filter_map(|n| match datasets::by_name(n) {
                    Ok(p) => Some((*n, p)),
                    Err(e) => {
                        eprintln!("skipping dataset {n}: {e}");
                        None
                    }
                })
                .collect();
            (*family, sets)
        })
        .collect();
    for mesher in registry::meshers() {
        let (params, _) = case_params(mesher.name());
        for (family, sets) in &inputs {
            let mut group = c.benchmark_group(format!("{}:{family}", mesher.name()));
            group
                .sample_size(10)
                .warm_up_time(Duration::from_millis(300))
                .measurement_time(Duration::from_secs(2));
            for (name, input) in sets {
                if input.has_segments() && !mesher.supports_segments() {
                    continue;
                }
                // One untimed call first: a mesher that fails on this input is reported and
                // skipped rather than timed failing.
                if let Err(e) = mesher.mesh(input, &params) {
                    eprintln!("skipping {} on {name}: {e}", mesher.name());
                    continue;
                }
                group.bench_with_input(BenchmarkId::from_parameter(name), input, |b, input| {
                    b.iter(|| black_box(mesher.mesh(black_box(input), &params)))
                });
            }
            group.finish();
        }
    }
}

/// Criterion draws its HTML plots with plotters, whose text needs a registered font (the
/// `ab_glyph` feature this crate turns on): the report's DejaVu Sans, or no plots without it.
fn config() -> Criterion {
    match hexmesh::report::plot::ensure_font() {
        Ok(()) => Criterion::default(),
        Err(e) => {
            eprintln!("criterion plots off: {e}");
            Criterion::default().without_plots()
        }
    }
}

criterion_group! {
    name = benches;
    config = config();
    targets = meshers
}
criterion_main!(benches);
