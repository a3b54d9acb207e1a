//! Times the extended hexagonal mesher (`hex`) on one dataset: `cargo run --release --example
//! hex_time [dataset] [runs] [stats]`. A profiling aid; the measured figures live in
//! benches/hex.rs. With a third argument it also prints the mesher's counters
//! (`ExtendedStats`: rounds, triangles checked, repairs) from one more, untimed run.

use hexmesh::hex::extended::{mesh_extended, Hex};
use hexmesh::{Mesher, Params};

// The `hexmesh` command's allocator, set up as it sets it, so that these times are its.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

fn main() {
    hexmesh::configure_allocator();
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "plane-2k".to_string());
    let runs: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(3);
    let stats = args.next().is_some();
    let input = hexmesh::datasets::by_name(&name).expect("a dataset");
    for _ in 0..runs {
        let t = std::time::Instant::now();
        let run = Hex.mesh(&input, &Params::default()).expect("meshes");
        println!(
            "{name}: {} triangles in {:.3} s",
            run.mesh.triangles.len(),
            t.elapsed().as_secs_f64()
        );
    }
    if stats {
        let run = mesh_extended(&input, &Params::default()).expect("meshes");
        println!("{:#?}", run.stats);
    }
}
