//! Criterion group `hex-vs`: `hex`, `hex-simple` and `triangle` side by side on plane-10k and
//! plane-100k, in one run, with each mesher's own output triangles as the throughput, so that
//! criterion prints triangles per second and the ratio of two meshers' costs per triangle is
//! read from one sitting (times on this project's virtual machines drift between sittings;
//! METHODOLOGY.md). The meshers get the report's parameters (`report::case_params`: ours
//! their defaults, Triangle 30°), the inputs are generated outside the timed call, and one
//! untimed call first counts the triangles.
//!
//! `hex` and `hex-simple` run twice, on one thread (`hex/1t`: the single-thread cost the
//! ratio to `hex-simple/1t` is about) and on all the machine's threads (`hex/2t` on 2 cores;
//! the mesh is the same bytes); `triangle` runs on one.
//!
//! `cargo bench --bench hex_vs` (about 20 minutes on 2 cores, most of it `hex` on plane-100k:
//! ten samples of one run each); `cargo bench --bench hex_vs -- plane-10k` for the small set
//! alone, `-- /1t` for the single-thread runs alone.
//!
//! `cargo test --all-targets` (`make test`) runs each bench once to see that it works; there the
//! group takes plane-10k alone, since plane-100k would add two minutes of `hex` to the tests
//! without testing anything plane-10k does not.

use std::hint::black_box;
use std::num::NonZeroUsize;
use std::time::Duration;

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use hexmesh::report::case_params;
use hexmesh::{datasets, registry};

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

const MESHERS: [&str; 3] = ["hex", "hex-simple", "triangle"];
const DATASETS: [&str; 2] = ["plane-10k", "plane-100k"];

fn hex_vs(c: &mut Criterion) {
    hexmesh::configure_allocator();
    let mut group = c.benchmark_group("hex-vs");
    // Runs of seconds each: one run a sample, ten samples (criterion's least).
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_millis(1))
        .measurement_time(Duration::from_secs(1));
    // cargo passes `--bench` to a bench target under `cargo bench` and not under `cargo test`.
    let benching = std::env::args().any(|a| a == "--bench");
    let datasets = if benching {
        &DATASETS[..]
    } else {
        &DATASETS[..1]
    };
    for &name in datasets {
        let input = datasets::by_name(name).expect("a scaling dataset");
        for mesher_name in MESHERS {
            let mesher = registry::mesher(mesher_name).expect("a registered mesher");
            let (params, _) = case_params(mesher_name);
            let all = params.thread_count();
            let counts: &[usize] = match (mesher_name, all) {
                ("triangle", _) | (_, 1) => &[1],
                _ => &[1, all],
            };
            for &threads in counts {
                let params = params
                    .clone()
                    .with_threads(NonZeroUsize::new(threads).expect("at least one"));
                let triangles = match mesher.mesh(&input, &params) {
                    Ok(run) => run.mesh.triangles.len(),
                    Err(e) => {
                        eprintln!("skipping {mesher_name} on {name}: {e}");
                        continue;
                    }
                };
                group.throughput(Throughput::Elements(triangles as u64));
                let id = BenchmarkId::new(format!("{mesher_name}/{threads}t"), name);
                group.bench_with_input(id, &input, |b, input| {
                    b.iter(|| black_box(mesher.mesh(black_box(input), &params)))
                });
            }
        }
    }
    group.finish();
}

// Plots need a system font that a fresh machine may lack; the medians are what this bench is for.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = hex_vs
}
criterion_main!(benches);
