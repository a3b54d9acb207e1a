//! The edge structure of a mesh, which every later check reads: each undirected edge of the
//! usable triangles classified by how many triangles use it and in which directions.

use crate::mesh::TriMesh;

/// The edge structure of the usable triangles (indices in range, three distinct corners).
pub(crate) struct Topology {
    /// Triangles with in-range, distinct corners.
    pub usable: Vec<bool>,
    /// Edges used by exactly one triangle, directed as that triangle traverses them.
    pub boundary: Vec<DirectedEdge>,
    /// Edges shared by two triangles in opposite directions: (u, v, t1, t2), t1 traverses u→v.
    pub interior: Vec<(u32, u32, usize, usize)>,
    /// Edges used three or more times: (lo, hi, triangles).
    pub overused: Vec<(u32, u32, Vec<usize>)>,
    /// Edges two triangles traverse in the same direction: (u, v, t1, t2).
    pub same_direction: Vec<(u32, u32, usize, usize)>,
}

/// An edge used by one triangle only, as that triangle traverses it (the triangle on its
/// left when the triangle is counter-clockwise). Sorted by `from`, then `to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct DirectedEdge {
    /// The vertex the edge leaves.
    pub from: u32,
    /// The vertex the edge reaches.
    pub to: u32,
    /// The triangle using it.
    pub triangle: usize,
}

/// Groups the edges of the usable triangles, deterministically (sorted, no hash order).
pub(crate) fn topology(mesh: &TriMesh) -> Topology {
    let n = mesh.vertices.len();
    let usable: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|t| {
            t.iter().all(|&v| (v as usize) < n) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
        })
        .collect();
    // (lo, hi, triangle, forward): forward when the triangle goes lo→hi.
    let mut edges: Vec<(u32, u32, usize, bool)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !usable[t] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), t, a < b));
        }
    }
    edges.sort_unstable();
    let mut topo = Topology {
        usable,
        boundary: Vec::new(),
        interior: Vec::new(),
        overused: Vec::new(),
        same_direction: Vec::new(),
    };
    let mut i = 0;
    while i < edges.len() {
        let (lo, hi, _, _) = edges[i];
        let mut j = i;
        while j < edges.len() && edges[j].0 == lo && edges[j].1 == hi {
            j += 1;
        }
        let group = &edges[i..j];
        let directed = |e: &(u32, u32, usize, bool)| if e.3 { (lo, hi) } else { (hi, lo) };
        match group.len() {
            1 => {
                let (from, to) = directed(&group[0]);
                topo.boundary.push(DirectedEdge {
                    from,
                    to,
                    triangle: group[0].2,
                });
            }
            2 => {
                let (u, v) = directed(&group[0]);
                if group[0].3 == group[1].3 {
                    topo.same_direction.push((u, v, group[0].2, group[1].2));
                } else {
                    topo.interior.push((u, v, group[0].2, group[1].2));
                }
            }
            _ => topo
                .overused
                .push((lo, hi, group.iter().map(|e| e.2).collect())),
        }
        i = j;
    }
    topo.boundary.sort_unstable();
    topo
}
