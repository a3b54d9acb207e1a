//! Triangle counts and times of the extended hexagonal mesher (`hex`, paper 000 Sec. 5) on the
//! point-set datasets, against paper 000 Table 1, with the subdivisions by cause
//! (`ExtendedStats`). Random sets: the canonical seed and the mean over ten seeds.
//!
//! `cargo run --release --example hex_counts [dataset ...]`

use hexmesh::hex::extended::mesh_extended;
use hexmesh::Params;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<&str> = if args.is_empty() {
        vec![
            "close-pair",
            "line-100",
            "plane-100",
            "plane-1k",
            "plane-2k",
        ]
    } else {
        args.iter().map(|s| s.as_str()).collect()
    };
    let paper = |n: &str| match n {
        "close-pair" => 684,
        "line-100" => 18_667,
        "plane-100" => 12_748,
        "plane-1k" => 127_729,
        "plane-2k" => 268_138,
        _ => 0,
    };
    for name in names {
        let input = match hexmesh::datasets::by_name(name) {
            Ok(i) => i,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        let t = std::time::Instant::now();
        let out = match mesh_extended(&input, &Params::default()) {
            Ok(o) => o,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        let elapsed = t.elapsed();
        let s = &out.stats;
        println!(
            "{name}: {} triangles (paper {}) in {:.3} s; splits: rules {} (MC3 {}), self-check {} (rejected triangles at MC3 chains {}), ring flips {}, rounds {}, blossoms {}",
            out.mesh.triangles.len(),
            paper(name),
            elapsed.as_secs_f64(),
            s.rule_splits,
            s.mc3_splits,
            s.verify_splits,
            s.mc3_rejected,
            s.ring_flips,
            s.rounds,
            s.blossoms
        );
        if let Some(seed) = hexmesh::datasets::default_seed(name) {
            let mut total = 0usize;
            let mut verify = 0u64;
            let mut rejected = 0u64;
            for t in 0..10 {
                let Ok(input) = hexmesh::datasets::random_with_seed(name, seed + t) else {
                    continue;
                };
                if let Ok(o) = mesh_extended(&input, &Params::default()) {
                    total += o.mesh.triangles.len();
                    verify += o.stats.verify_splits;
                    rejected += o.stats.mc3_rejected;
                }
            }
            println!(
                "{name}: mean over seeds {seed}..{}: {:.0} triangles, self-check splits {verify} (rejected at MC3 chains {rejected})",
                seed + 9,
                total as f64 / 10.0
            );
        }
    }
}
