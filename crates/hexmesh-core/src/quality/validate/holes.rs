//! Hole seeds: no triangle may cover a hole seed of the input.

use super::Violation;
use crate::geom::{orient2d_scaled, Point};
use crate::mesh::{Pslg, TriMesh};

/// A hole seed inside (or on an edge of) a triangle means the mesher meshed the hole; seeds
/// on an input segment decide nothing and are skipped. Triangles are matched to the seeds in
/// their x-range, found by binary search in the seeds sorted by x.
pub(super) fn holes_covered(
    mesh: &TriMesh,
    geometric: &[bool],
    input: &Pslg,
    out: &mut Vec<Violation>,
) {
    let on_segment = |q: Point| {
        input.segments.iter().any(|s| {
            match (
                input.points.get(s[0] as usize),
                input.points.get(s[1] as usize),
            ) {
                (Some(&a), Some(&b)) => {
                    orient2d_scaled(a, b, q) == 0.0
                        && q[0] >= a[0].min(b[0])
                        && q[0] <= a[0].max(b[0])
                        && q[1] >= a[1].min(b[1])
                        && q[1] <= a[1].max(b[1])
                }
                _ => false,
            }
        })
    };
    let mut seeds: Vec<(usize, Point)> = input
        .holes
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, h)| h[0].is_finite() && h[1].is_finite() && !on_segment(*h))
        .collect();
    if seeds.is_empty() {
        return;
    }
    seeds.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.0.cmp(&b.0)));
    let mut first: Vec<Option<usize>> = vec![None; input.holes.len()];
    for (t, &g) in geometric.iter().enumerate() {
        if !g {
            continue;
        }
        let [a, b, c] = mesh.corners(t);
        let (lo, hi) = (a[0].min(b[0]).min(c[0]), a[0].max(b[0]).max(c[0]));
        let start = seeds.partition_point(|s| s.1[0] < lo);
        for &(h, q) in seeds[start..].iter().take_while(|s| s.1[0] <= hi) {
            let inside = orient2d_scaled(a, b, q) >= 0.0
                && orient2d_scaled(b, c, q) >= 0.0
                && orient2d_scaled(c, a, q) >= 0.0
                && orient2d_scaled(a, b, c) > 0.0;
            if inside && first[h].is_none() {
                first[h] = Some(t);
            }
        }
    }
    for (hole, t) in first.iter().enumerate() {
        if let Some(triangle) = *t {
            out.push(Violation::HoleCovered {
                hole,
                point: input.holes[hole],
                triangle,
            });
        }
    }
}
