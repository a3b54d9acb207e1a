//! What `hex` does with a domain: the levels of the hexagons after the refinement rules alone
//! (in units of the domain's d_min, `quality::feature_gap`), then the final mesh's levels and
//! the run's counts (rounds, subdivisions, the near-segment repair's edits). A debugging aid
//! for domain fuzz failures: `cargo run --release --example pslg_stats FILE.poly`.

use std::collections::BTreeMap;

fn levels(h: &hexmesh::hex::subdivision::Hierarchy) -> BTreeMap<u8, usize> {
    let mut by_level = BTreeMap::new();
    for (k, _) in h.leaves() {
        *by_level.entry(k.k).or_insert(0usize) += 1;
    }
    by_level
}

fn main() {
    let path = std::env::args().nth(1).expect("a .poly file");
    let input = hexmesh::io::read_input(std::path::Path::new(&path)).expect("reads");
    let params = hexmesh::Params::default();
    let (h, stopped) = hexmesh::hex::pslg::refine_pslg(&input, &params).expect("refines");
    let gap = hexmesh::quality::feature_gap(&input).expect("two features");
    println!(
        "d_min {} (point {} to {:?})",
        gap.distance, gap.point, gap.other
    );
    println!("after the rules (stopped: {stopped:?}):");
    for (k, n) in levels(&h) {
        let r = h.lattice.radius(k);
        println!(
            "  level {k}: {n} leaves, radius {r} = {} d_min",
            r / gap.distance
        );
    }
    let run = hexmesh::hex::pslg::mesh_pslg(&input, &params).expect("meshes");
    println!(
        "final: {} triangles, leaves by level {:?}\n{:?}",
        run.mesh.triangles.len(),
        levels(&run.hierarchy),
        run.stats
    );
}
