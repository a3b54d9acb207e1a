//! Prints a digest of the `hex` mesh of each point-set dataset and of fuzz cases, so that a
//! change meant to keep the output (a speed-up) can be checked to give the same bytes:
//! `cargo run --release --example hex_digest [cases]`.

use std::hash::{Hash, Hasher};

use hexmesh::hex::extended::Hex;
use hexmesh::{Mesher, Params, Pslg};

// The `hexmesh` command's allocator, set up as it sets it: the digests are its output's.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

fn digest(input: &Pslg) -> String {
    match Hex.mesh(input, &Params::default()) {
        Ok(run) => {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            for v in &run.mesh.vertices {
                v[0].to_bits().hash(&mut h);
                v[1].to_bits().hash(&mut h);
            }
            run.mesh.triangles.hash(&mut h);
            format!("{} {:016x}", run.mesh.triangles.len(), h.finish())
        }
        Err(e) => format!("error {e}"),
    }
}

fn main() {
    hexmesh::configure_allocator();
    let cases: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(300);
    for name in ["close-pair", "line-100", "plane-100", "plane-1k", "imr"] {
        let input = hexmesh::datasets::by_name(name).expect("a dataset");
        println!("{name}: {}", digest(&input));
    }
    for case in 0..cases {
        let (family, input) = hexmesh::fuzz::generate_case(20261123, case);
        println!("case {case} {family}: {}", digest(&input));
    }
}
