//! The boundary of a mesh as loops: boundary edges that do not pair up at a vertex, the split
//! into loops (through the fan of triangles where loops touch), and the one-disc check.

use std::collections::HashMap;

use super::{DirectedEdge, Topology, Violation};
use crate::mesh::TriMesh;

/// A chain of boundary edges (indices into the boundary list), closed unless the boundary
/// is broken.
pub(crate) struct BoundaryLoop {
    /// The loop's edges in order, as indices into the boundary list.
    pub edges: Vec<usize>,
    /// True when the loop passes through a vertex shared with another loop or itself.
    pub pinched: bool,
}

/// Splits the boundary edges into loops. Where several loops meet at a vertex, the incoming
/// edge is continued by the outgoing edge of the same fan of triangles (found by rotating
/// around the vertex through shared edges), so that two discs touching at a corner give two
/// loops rather than one figure eight.
pub(crate) fn boundary_loops(
    mesh: &TriMesh,
    topo: &Topology,
    boundary: &[DirectedEdge],
    out: &mut Vec<Violation>,
) -> Vec<BoundaryLoop> {
    let verts = &mesh.vertices;
    let mut incoming: HashMap<u32, usize> = HashMap::new();
    let mut outgoing: HashMap<u32, usize> = HashMap::new();
    for e in boundary {
        *outgoing.entry(e.from).or_default() += 1;
        *incoming.entry(e.to).or_default() += 1;
    }
    let mut touched: Vec<u32> = incoming.keys().chain(outgoing.keys()).copied().collect();
    touched.sort_unstable();
    touched.dedup();
    for &v in &touched {
        let (i, o) = (
            incoming.get(&v).copied().unwrap_or(0),
            outgoing.get(&v).copied().unwrap_or(0),
        );
        if i != o {
            out.push(Violation::OpenBoundary {
                vertex: v as usize,
                point: verts[v as usize],
                incoming: i,
                outgoing: o,
            });
        }
    }

    // Directed edge -> triangle, for the fan walk; boundary is sorted by (from, to). Only a
    // vertex with several outgoing boundary edges needs the walk (below), and most meshes have
    // none: then the table of every interior edge is not built.
    let fans_to_walk = outgoing.values().any(|&o| o > 1);
    let mut directed: Vec<(u32, u32, usize)> = match fans_to_walk {
        true => topo
            .interior
            .iter()
            .flat_map(|&(u, v, t1, t2)| [(u, v, t1), (v, u, t2)])
            .collect(),
        false => Vec::new(),
    };
    directed.sort_unstable();
    let twin_triangle = |from: u32, to: u32| -> Option<usize> {
        directed
            .binary_search_by(|e| (e.0, e.1).cmp(&(from, to)))
            .ok()
            .map(|k| directed[k].2)
    };
    let boundary_index = |from: u32, to: u32| -> Option<usize> {
        let k = boundary.partition_point(|e| (e.from, e.to) < (from, to));
        (k < boundary.len() && boundary[k].from == from && boundary[k].to == to).then_some(k)
    };
    let next_corner = |t: usize, v: u32| -> Option<u32> {
        let tri = mesh.triangles[t];
        (0..3).find(|&k| tri[k] == v).map(|k| tri[(k + 1) % 3])
    };
    // The boundary edge leaving `v` in the fan that edge `e` (arriving at v) belongs to; `None`
    // also where v has at most one outgoing boundary edge, which the walk could only find
    // (or miss) and the scan below takes just the same.
    let fan_successor = |e: &DirectedEdge| -> Option<usize> {
        let v = e.to;
        if outgoing.get(&v).copied().unwrap_or(0) <= 1 {
            return None;
        }
        let mut t = e.triangle;
        // Each step is a bijection between the triangles at v (every directed interior
        // edge names one triangle), so the walk ends at a boundary edge or comes back.
        loop {
            let w = next_corner(t, v)?;
            if let Some(k) = boundary_index(v, w) {
                return Some(k);
            }
            t = twin_triangle(w, v)?;
            if t == e.triangle {
                return None;
            }
        }
    };

    let first_out = |v: u32| boundary.partition_point(|e| e.from < v);
    let mut used = vec![false; boundary.len()];
    let mut loops = Vec::new();
    for start in 0..boundary.len() {
        if used[start] {
            continue;
        }
        let mut edges = vec![start];
        used[start] = true;
        let mut cur = start;
        loop {
            let preferred = fan_successor(&boundary[cur]).filter(|&k| !used[k] || k == start);
            let next = preferred.or_else(|| {
                let v = boundary[cur].to;
                (first_out(v)..boundary.len())
                    .take_while(|&k| boundary[k].from == v)
                    .find(|&k| !used[k] || k == start)
            });
            match next {
                Some(k) if k == start => break,
                Some(k) => {
                    used[k] = true;
                    edges.push(k);
                    cur = k;
                }
                None => break,
            }
        }
        let pinched = edges
            .iter()
            .any(|&k| outgoing.get(&boundary[k].from).copied().unwrap_or(0) > 1);
        loops.push(BoundaryLoop { edges, pinched });
    }
    loops
}

/// The one-disc check, for meshes whose domain is a disc (point sets in their bounding
/// hexagon): one boundary loop, and no vertex where the boundary touches itself.
pub(super) fn one_disc(
    boundary: &[DirectedEdge],
    loops: &[BoundaryLoop],
    out: &mut Vec<Violation>,
) {
    // Several boundary edges leaving one vertex: the boundary touches itself there.
    let mut pinched_at: Vec<u32> = boundary
        .windows(2)
        .filter(|w| w[0].from == w[1].from)
        .map(|w| w[0].from)
        .collect();
    pinched_at.dedup();
    if loops.len() > 1 || !pinched_at.is_empty() {
        out.push(Violation::HoleInMesh {
            loops: loops.len(),
            first_vertices: loops.iter().map(|l| boundary[l.edges[0]].from).collect(),
            pinched_at,
        });
    }
}
