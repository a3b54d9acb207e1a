//! The extended refinement (`hex`, paper 000 Sec. 5–6) under the fuzz campaign of
//! `hexmesh::fuzz`: every finished case must meet every Sec. 6 bound.

use std::time::{Duration, Instant};

mod mesh_support;

use hexmesh::fuzz::generate_case;
use hexmesh::hex::extended::Hex;
use hexmesh::mesher::Budget;
use hexmesh::{Mesher, Params};

/// Meshes cases `from..to` of `seed` and returns one line per failing or slow case.
fn explore(seed: u64, from: u64, to: u64, slow: Duration) -> Vec<String> {
    let bounds = hexmesh::registry::bounds("hex").expect("hex bounds");
    let params = Params::default().with_budget(Budget {
        max_time: Some(Duration::from_secs(5)),
        ..Budget::default()
    });
    let mut out = Vec::new();
    for case in from..to {
        let (family, input) = match std::env::var("HEX_FAMILIES7") {
            Ok(_) => {
                let f = hexmesh::fuzz::FAMILIES[(case % 7) as usize];
                (f, hexmesh::fuzz::generate_family_case(seed, case, f))
            }
            Err(_) => generate_case(seed, case),
        };
        let t = Instant::now();
        let run = Hex.mesh(&input, &params);
        let el = t.elapsed();
        let msg = match run {
            Err(e) => Some(format!("error {e}")),
            Ok(run) if !run.complete => Some(format!("incomplete {:?}", run.stop_reason)),
            Ok(run) => match mesh_support::inputs_first(&run.mesh, &input.points) {
                Err(e) => Some(e),
                Ok(()) => {
                    let v = hexmesh::quality::verdict(&run.mesh, Some(&input), Some(&bounds));
                    (!v.passed()).then(|| {
                        let fail = format!("{v}")
                            .lines()
                            .filter(|l| l.contains("FAIL"))
                            .map(|l| l.chars().take(60).collect::<String>())
                            .collect::<Vec<_>>()
                            .join("; ");
                        format!("{fail} [{}]", levels(&input))
                    })
                }
            },
        };
        if msg.is_some() && std::env::var_os("HEX_WRITE").is_some() {
            let _ = hexmesh::fuzz::write_failure(
                std::path::Path::new("fuzz-failures"),
                "hex",
                seed,
                case,
                family,
                &input,
            );
        }
        if msg.is_some() || el > slow {
            out.push(format!(
                "case {case} {family} n={} {el:?}: {}",
                input.points.len(),
                msg.unwrap_or_else(|| "slow".into())
            ));
        }
    }
    out
}

/// The finest leaf radius over d_min after the simple and after the extended refinement, with
/// the extended statistics: where the extra level comes from.
fn levels(input: &hexmesh::Pslg) -> String {
    let mut d_min = f64::INFINITY;
    for i in 0..input.points.len() {
        for j in 0..i {
            d_min = d_min.min(hexmesh::geom::dist(input.points[i], input.points[j]));
        }
    }
    let finest = |h: &hexmesh::hex::Hierarchy| {
        h.leaves()
            .iter()
            .map(|(k, _)| h.lattice.radius(k.k))
            .fold(f64::INFINITY, f64::min)
            / d_min
    };
    let (hs, _) = hexmesh::hex::mesh_with_hierarchy(input, &Params::default()).expect("simple");
    let ext = hexmesh::hex::extended::mesh_extended(input, &Params::default()).expect("ext");
    format!(
        "simple r/d {:.4}, extended r/d {:.4}, r_min/d {:.4}, {:?}",
        finest(&hs),
        finest(&ext.hierarchy),
        1.0 / (6.0 * 3f64.sqrt()),
        ext.stats
    )
}

#[test]
#[ignore = "exploration: HEX_SEED, HEX_FROM, HEX_TO"]
fn explore_hex_fuzz_cases() {
    let var = |n: &str, d: u64| {
        std::env::var(n)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let lines = explore(
        var("HEX_SEED", 7),
        var("HEX_FROM", 0),
        var("HEX_TO", 200),
        Duration::from_secs(1),
    );
    for l in &lines {
        eprintln!("{l}");
    }
    eprintln!("{} lines", lines.len());
}

/// A thousand seeded cases of all ten families (seed 20261123, at most 20 points each, so
/// that the test build takes about fifteen seconds), among them a hundred each of projected
/// map coordinates, near-duplicates down to 1e-11 of their coordinates and sets translated to
/// 1e7, meet every Sec. 6 bound up to the rounding allowance or are refused as too close for
/// f64, at most one in a thousand (the rounding contract's 0.1 %). Measured: none refused
/// since the self-check grants the rules only the rounding their placement makes (1 while it
/// granted the whole allowance; 120 of the nine families' thousand under the old fixed 1e-6°
/// slack).
#[test]
fn hex_meets_every_bound_on_a_thousand_fuzz_cases() {
    let t = Instant::now();
    let s = hexmesh::fuzz::fuzz_campaign_sized("hex", 0..1000, 20261123, 20, None, |_| {});
    eprintln!("{s:?}\n{:?}", t.elapsed());
    assert_eq!(s.cases, 1000);
    assert_eq!(s.failures, 0, "{:?}", s.first_failure);
    // Every angle kept its bounds up to its rounding allowance (the verdict:
    // no failures), and none used more than the default 0.01°.
    assert!(s.worst_min_angle >= hexmesh::quality::HEX.min_angle - 0.01);
    assert!(s.worst_max_angle <= 90.0 + 0.01);
    assert_eq!(*s.rounding_used.last().unwrap(), 0);
    // Every finished mesh is in a bin (the verdict reported its angle checks).
    assert_eq!(s.rounding_used.iter().sum::<u64>(), s.cases - s.refused);
    // Each radius ratio met 1.20787 up to its own allowance (the verdict, above); angles
    // within 0.01° of theirs move it by at most about 6e-4.
    assert!(
        s.worst_radius_ratio <= 1.20787 + 1e-3,
        "{}",
        s.worst_radius_ratio
    );
    assert!(s.worst_edge_over_d_min >= 7f64.sqrt() / (12.0 * 3f64.sqrt()));
    assert_eq!(s.max_delaunay_violations, 0);
    assert!(s.refused <= 1, "{} refused", s.refused);
}
