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

/// Groups the edges of the usable triangles, deterministically (in order of their vertices,
/// then of the triangles using them; no hash order).
pub(crate) fn topology(mesh: &TriMesh) -> Topology {
    let n = mesh.vertices.len();
    let usable: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|t| {
            t.iter().all(|&v| (v as usize) < n) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
        })
        .collect();
    // The edges bucketed by their lower vertex (a counting sort: one pass to count, one to
    // place), as (higher vertex, triangle << 1 | forward), forward when the triangle goes
    // lower → higher. A bucket is filled in triangle order and a usable triangle has an edge
    // once, so sorting each (small) bucket stably by the higher vertex orders the edges by
    // (lower, higher, triangle): the order of sorting them all, without a sort of three
    // entries a triangle (at 12 million triangles, about 4 s and 0.8 GB that way).
    let edges_of = |t: usize| {
        let tri = mesh.triangles[t];
        (0..3).map(move |k| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            (
                a.min(b) as usize,
                a.max(b),
                ((t as u64) << 1) | u64::from(a < b),
            )
        })
    };
    let usable_triangles = || (0..mesh.triangles.len()).filter(|&t| usable[t]);
    let mut start = vec![0usize; n + 1];
    for (lo, _, _) in usable_triangles().flat_map(edges_of) {
        start[lo + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut buckets: Vec<(u32, u64)> = vec![(0, 0); start[n]];
    for (lo, hi, use_) in usable_triangles().flat_map(edges_of) {
        buckets[fill[lo]] = (hi, use_);
        fill[lo] += 1;
    }
    drop(fill);
    let mut topo = Topology {
        usable,
        boundary: Vec::new(),
        interior: Vec::new(),
        overused: Vec::new(),
        same_direction: Vec::new(),
    };
    for lo in 0..n {
        let bucket = &mut buckets[start[lo]..start[lo + 1]];
        bucket.sort_by_key(|e| e.0);
        let lo = lo as u32;
        for group in bucket.chunk_by(|a, b| a.0 == b.0) {
            let hi = group[0].0;
            let triangle = |e: &(u32, u64)| (e.1 >> 1) as usize;
            let directed = |e: &(u32, u64)| if e.1 & 1 == 1 { (lo, hi) } else { (hi, lo) };
            match group.len() {
                1 => {
                    let (from, to) = directed(&group[0]);
                    topo.boundary.push(DirectedEdge {
                        from,
                        to,
                        triangle: triangle(&group[0]),
                    });
                }
                2 => {
                    let (u, v) = directed(&group[0]);
                    let (t1, t2) = (triangle(&group[0]), triangle(&group[1]));
                    if group[0].1 & 1 == group[1].1 & 1 {
                        topo.same_direction.push((u, v, t1, t2));
                    } else {
                        topo.interior.push((u, v, t1, t2));
                    }
                }
                _ => topo
                    .overused
                    .push((lo, hi, group.iter().map(triangle).collect())),
            }
        }
    }
    topo.boundary.sort_unstable();
    topo
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift::XorShift;

    /// The edge structure by sorting every edge by (lower, higher, triangle, forward): what
    /// `topology` computes without the sort.
    fn by_sorting(mesh: &TriMesh, usable: &[bool]) -> Topology {
        let mut edges: Vec<(u32, u32, usize, bool)> = Vec::new();
        for (t, tri) in mesh
            .triangles
            .iter()
            .enumerate()
            .filter(|(t, _)| usable[*t])
        {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                edges.push((a.min(b), a.max(b), t, a < b));
            }
        }
        edges.sort_unstable();
        let mut topo = Topology {
            usable: usable.to_vec(),
            boundary: Vec::new(),
            interior: Vec::new(),
            overused: Vec::new(),
            same_direction: Vec::new(),
        };
        for group in edges.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
            let (lo, hi) = (group[0].0, group[0].1);
            let directed = |e: &(u32, u32, usize, bool)| if e.3 { (lo, hi) } else { (hi, lo) };
            match group {
                [e] => {
                    let (from, to) = directed(e);
                    topo.boundary.push(DirectedEdge {
                        from,
                        to,
                        triangle: e.2,
                    });
                }
                [e, f] if e.3 == f.3 => {
                    topo.same_direction
                        .push((directed(e).0, directed(e).1, e.2, f.2))
                }
                [e, f] => topo.interior.push((directed(e).0, directed(e).1, e.2, f.2)),
                _ => topo
                    .overused
                    .push((lo, hi, group.iter().map(|e| e.2).collect())),
            }
        }
        topo.boundary.sort_unstable();
        topo
    }

    #[test]
    fn the_bucketed_edges_are_those_of_sorting_every_edge() {
        let mut x = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = |m: u64| x.below(m) as u32;
        let mut kinds = [0usize; 4];
        for case in 0..300 {
            // Few vertices, so that edges are shared, shared the same way and overused; an
            // index one past the end and repeated corners make unusable triangles.
            let n = 3 + case % 9;
            let mesh = TriMesh {
                vertices: vec![[0.0, 0.0]; n],
                triangles: (0..1 + case % 23)
                    .map(|_| [0; 3].map(|_| next(n as u64 + 1)))
                    .collect(),
            };
            let got = topology(&mesh);
            let want = by_sorting(&mesh, &got.usable);
            assert_eq!(got.boundary, want.boundary, "case {case}");
            assert_eq!(got.interior, want.interior, "case {case}");
            assert_eq!(got.overused, want.overused, "case {case}");
            assert_eq!(got.same_direction, want.same_direction, "case {case}");
            for (k, len) in [
                got.boundary.len(),
                got.interior.len(),
                got.overused.len(),
                got.same_direction.len(),
            ]
            .into_iter()
            .enumerate()
            {
                kinds[k] += len;
            }
        }
        assert!(
            kinds.iter().all(|&k| k > 0),
            "every kind of edge met: {kinds:?}"
        );
    }
}
