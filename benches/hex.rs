//! Criterion bench of the hexagonal meshers on uniform unit-square point sets of 1k, 10k and
//! 100k points (seeded PCG), to show the O(output) refinement loop: the paper's proof of concept
//! was O(n²) (paper 000 Sec. 8). Input generation stays outside the timed call.
//!
//! The extended mesher `hex` runs on the paper's own plane-1k and plane-2k (Table 1: 30.4 s and
//! 123 s) and on plane-10k and plane-100k, with the output triangles as the throughput, so that
//! criterion prints the time per output triangle: flat when the work is O(output). plane-1m
//! (114 million triangles, about six minutes and 12 GB a run) joins them when the
//! environment sets `HEXMESH_BENCH_1M=1`: criterion's ten samples and a warm-up run then take
//! about 80 minutes (measured: 81 on a 2-core Xeon), so a plain `cargo bench` leaves it out.

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use hexmesh::hex::extended::Hex;
use hexmesh::hex::HexSimple;
use hexmesh::{Mesher, Params, Point, Pslg};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

fn plane(n: usize) -> Pslg {
    let mut rng = Pcg64::seed_from_u64(0x0070_6c61_6e65 + n as u64);
    let pts: Vec<Point> = (0..n)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    Pslg::from_points(pts)
}

fn bench_hex(c: &mut Criterion) {
    hexmesh::configure_allocator();
    let mut group = c.benchmark_group("hex-simple");
    group.sample_size(10);
    for n in [1_000usize, 10_000, 100_000] {
        let input = plane(n);
        group.bench_with_input(BenchmarkId::new("plane", n), &input, |b, input| {
            b.iter(|| {
                HexSimple
                    .mesh(input, &Params::default())
                    .expect("plane sets mesh")
            })
        });
    }
    group.finish();
}

fn bench_hex_extended(c: &mut Criterion) {
    hexmesh::configure_allocator();
    let mut group = c.benchmark_group("hex");
    group.sample_size(10);
    let mut names = vec!["plane-1k", "plane-2k", "plane-10k", "plane-100k"];
    if std::env::var("HEXMESH_BENCH_1M").is_ok_and(|v| v == "1") {
        names.push("plane-1m");
    }
    for name in names {
        if name == "plane-1m" {
            // One run a sample: the default linear sampling would ask for 55 runs.
            group.sampling_mode(SamplingMode::Flat);
        }
        let input = hexmesh::datasets::by_name(name).expect("a dataset");
        let triangles = Hex
            .mesh(&input, &Params::default())
            .expect("plane sets mesh")
            .mesh
            .triangles
            .len();
        group.throughput(Throughput::Elements(triangles as u64));
        group.bench_with_input(BenchmarkId::new("dataset", name), &input, |b, input| {
            b.iter(|| {
                Hex.mesh(input, &Params::default())
                    .expect("plane sets mesh")
            })
        });
    }
    group.finish();
}

// Plots need a system font that a fresh machine may lack; the medians are what this bench is for.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = bench_hex, bench_hex_extended
}
criterion_main!(benches);
