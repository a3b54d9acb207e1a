//! Explains the edges of a `hex` mesh that fall below the shortest-edge bound of paper 000
//! Sec. 6.3 (√7/(12√3)·d_min): for each endpoint, the leaf hexagon holding it, its class and
//! level, and the nearest input point. A debugging aid for fuzz failures:
//! `cargo run --release --example hex_explain FILE.node`.

use hexmesh::geom::dist;
use hexmesh::hex::classify::{classify, rings};
use hexmesh::hex::extended::mesh_extended;
use hexmesh::quality::{bounds::HEX, closest_pair};
use hexmesh::Params;

fn main() {
    let path = std::env::args().nth(1).expect("a .node file");
    let input = hexmesh::io::read_input(std::path::Path::new(&path)).expect("reads");
    let run = mesh_extended(&input, &Params::default()).expect("meshes");
    let h = &run.hierarchy;
    let r = rings(h);
    let cp = closest_pair(&input.points).expect("two points");
    let l_min = cp.distance * HEX.min_edge_over_dmin;
    println!(
        "d_min {} (points {} and {}), l_min {l_min}, {} triangles, stats {:?}",
        cp.distance,
        cp.first,
        cp.second,
        run.mesh.triangles.len(),
        run.stats
    );
    let mesh = &run.mesh;
    let mut seen = std::collections::BTreeSet::new();
    for tri in &mesh.triangles {
        for e in 0..3 {
            let (a, b) = (tri[e].min(tri[(e + 1) % 3]), tri[e].max(tri[(e + 1) % 3]));
            let len = dist(mesh.vertices[a as usize], mesh.vertices[b as usize]);
            if len < l_min && seen.insert((a, b)) {
                println!("edge {a}-{b}: length {len} = {} d_min", len / cp.distance);
                for v in [a, b] {
                    let p = mesh.vertices[v as usize];
                    let leaf = h.leaf_of(p);
                    let class = if h.is_full_leaf(leaf) {
                        format!("{:?}", classify(h, &r, leaf).0)
                    } else {
                        format!("{:?}", h.cell(leaf))
                    };
                    let (near, d) = input
                        .points
                        .iter()
                        .enumerate()
                        .map(|(i, q)| (i, dist(*q, p)))
                        .min_by(|x, y| x.1.total_cmp(&y.1))
                        .expect("points");
                    let radius = h.lattice.radius(leaf.k);
                    let offset = {
                        let c = h.lattice.center(leaf);
                        [(p[0] - c[0]) / radius, (p[1] - c[1]) / radius]
                    };
                    println!(
                        "  vertex {v} {p:?}: input {}, leaf {leaf:?} r {radius:e} {class}, offset/r {offset:?}; nearest input {near} at {} r, role {:?}",
                        (v as usize) < input.points.len(),
                        d / radius,
                        r.roles.get(&leaf)
                    );
                }
            }
        }
    }
}
