//! `hex` and `hex-simple` split long lists of work over threads (`Params::threads`): the
//! mesh must be the same bytes whatever the count.

use std::num::NonZeroUsize;

use hexmesh::{Mesher, Params, Pslg, TriMesh};

/// The vertices' bits and the triangles of `mesher` on `input` with `threads` threads.
fn mesh_bits(mesher: &dyn Mesher, input: &Pslg, threads: usize) -> (Vec<[u64; 2]>, Vec<[u32; 3]>) {
    let params = Params::default().with_threads(NonZeroUsize::new(threads).unwrap());
    let run = mesher.mesh(input, &params).expect("meshes");
    assert!(run.complete);
    let TriMesh {
        vertices,
        triangles,
    } = run.mesh;
    (
        vertices.iter().map(|p| p.map(f64::to_bits)).collect(),
        triangles,
    )
}

/// Points clustered at three scales (MOVED_CENTER_3 patches, contested ring cells, dropped
/// centres) beside a uniform part, from a fixed xorshift sequence.
fn clustered(n: usize) -> Pslg {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let points = (0..n)
        .map(|i| {
            let s = [1.0, 0.03, 0.001][i % 3];
            [0.2 + next() * s, 0.7 - next() * s]
        })
        .collect();
    Pslg::from_points(points)
}

#[test]
fn one_two_and_three_threads_make_the_same_bytes() {
    // plane-10k: its contested ring cells are settled in stages of up to 510 cells to
    // search, over threads from 256 (`settle_contested`).
    let cases = [
        ("hex", "plane-10k"),
        ("hex", "clustered"),
        ("hex-simple", "plane-10k"),
    ];
    for (mesher, name) in cases {
        let input = match name {
            "clustered" => clustered(3000),
            _ => hexmesh::datasets::by_name(name).expect("dataset"),
        };
        let m = hexmesh::mesher(mesher).expect("registered");
        let one = mesh_bits(m.as_ref(), &input, 1);
        // Large enough that every split applies: the dual is split from 65,536 full leaves
        // (about 131,000 triangles) on, the rules' blocks and the relocations' leaves from
        // fewer.
        assert!(one.1.len() > 140_000, "{mesher} on {name}: {}", one.1.len());
        for threads in [2, 3] {
            assert!(
                mesh_bits(m.as_ref(), &input, threads) == one,
                "{mesher} on {name}: {threads} threads differ from one"
            );
        }
    }
}
