//! Criterion bench of the hexagonal meshers on uniform unit-square point sets of 1k, 10k and
//! 100k points (seeded PCG), to show the O(output) refinement loop: the paper's proof of concept
//! was O(n²) (paper 000 Sec. 8). Input generation stays outside the timed call.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use hexmesh::hex::HexSimple;
use hexmesh::{Mesher, Params, Point, Pslg};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn plane(n: usize) -> Pslg {
    let mut rng = Pcg64::seed_from_u64(0x0070_6c61_6e65 + n as u64);
    let pts: Vec<Point> = (0..n)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    Pslg::from_points(pts)
}

fn bench_hex(c: &mut Criterion) {
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

// Plots need a system font that a fresh machine may lack; the medians are what this bench is for.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = bench_hex
}
criterion_main!(benches);
