//! The segments inserted into the dual (ours, in place of paper Sec. 7.3/7.4's added
//! triangles). The paper keeps the dual's topology and adds triangles in the gap between two
//! projected centres. Here every dual triangle with a corner in a crossed hexagon is removed,
//! and the cavity is triangulated again as a constrained Delaunay triangulation (`fill`) of its
//! boundary, the input points in it and the projected centres, with the segment pieces between
//! consecutive projected centres as constraints. This is valid and conforming in every
//! configuration (acute input angles, hexagons crossed twice, projections outside the
//! hexagon), where the paper's construction degenerates (its Fig. 14, right: nearly collinear
//! segments give degenerate triangles).
//!
//! Dual triangles that meet a segment without a corner in a crossed hexagon (relocated
//! centres, level transitions) join the cavity (`grow_cavity`). Input points never move: a
//! crossed hexagon holding an input point keeps its point. An input point outside the region
//! the segments bound (or inside a hole) is refused: it could not be a vertex of the mesh.

use std::collections::BTreeMap;

use super::band::{Band, Effort};
use super::domain::carve;
use super::fill::fill_cavity;
use super::project::projected_centres;
use super::{leaf_of_vertex, polygon_meets_segment, PslgStats};
use crate::error::{Error, InputError};
use crate::geom::Point;
use crate::hex::lattice::{FxHashSet, Key};
use crate::hex::subdivision::Hierarchy;
use crate::mesh::{Pslg, TriMesh};

/// The mesh with the segments inserted, before compaction is undone: vertex keys and marks.
pub(super) struct Built {
    /// The mesh, compacted: the input points first and in order, unused vertices dropped.
    pub mesh: TriMesh,
    /// The leaf hexagon of each vertex (projected centres: the hexagon they came from).
    pub keys: Vec<Key>,
    /// For each vertex, true when it lies on an input segment.
    pub on_segment: Vec<bool>,
    /// For each triangle, true when it is not a triangle of the hexagon dual.
    pub cavity: Vec<bool>,
    /// Triangles touching a segment that break the near-segment bounds and that no edit of
    /// the band repaired.
    pub stuck: Vec<usize>,
}

/// How many points `band` may insert per triangle of the mesh it improves (its budget).
const BAND_BUDGET_PER_TRIANGLE: u64 = 2;

/// A triangle's corners in a canonical rotation (smallest index first).
fn canonical(t: [u32; 3]) -> [u32; 3] {
    let m = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
    [t[m], t[(m + 1) % 3], t[(m + 2) % 3]]
}

/// Removes the dual triangles with a corner in a crossed hexagon, and fills the cavity with a
/// constrained Delaunay triangulation of its boundary, its input points and the projected
/// centres, the segment pieces as constraints (module docs); then removes what lies outside
/// the domain and drops unused vertices.
pub(super) fn insert_segments(
    h: &Hierarchy,
    input: &Pslg,
    segments: &[[Point; 2]],
    crossed: &BTreeMap<Key, Vec<u32>>,
    (dual, dual_keys): (TriMesh, Vec<Key>),
    effort: Effort,
    stats: &mut PslgStats,
) -> std::result::Result<Built, Error> {
    let n_input = input.points.len();
    let mut vertices = dual.vertices;
    let mut keys: Vec<Key> = dual_keys.iter().map(|&k| leaf_of_vertex(h, k)).collect();
    let mut on: Vec<Vec<u32>> = vec![Vec::new(); vertices.len()];
    for (s, seg) in input.segments.iter().enumerate() {
        for &v in seg {
            on[v as usize].push(s as u32);
        }
    }
    let in_crossed: Vec<bool> = keys.iter().map(|k| crossed.contains_key(k)).collect();

    // Sec. 7.3 and 7.4: the projected centres kept on each segment, in order along it.
    let projected = projected_centres(h, segments, crossed, &keys, &vertices, stats);
    let mut chains: Vec<Vec<u32>> = Vec::with_capacity(segments.len());
    for (s, kept) in projected.into_iter().enumerate() {
        let [ia, ib] = input.segments[s];
        let mut chain = vec![ia];
        for rec in kept {
            let v = vertices.len() as u32;
            vertices.push(rec.point);
            keys.push(rec.key);
            on.push(vec![s as u32]);
            chain.push(v);
            stats.projected += 1;
        }
        chain.push(ib);
        chains.push(chain);
    }
    let n_all = vertices.len();
    let is_new = |v: u32| v as usize >= in_crossed.len();
    // Vertices on the dual's outer boundary stay: without them the cavity would be open.
    let mut on_hull = vec![false; in_crossed.len()];
    {
        let mut directed: FxHashSet<(u32, u32)> = FxHashSet::default();
        for tri in &dual.triangles {
            for e in 0..3 {
                directed.insert((tri[e], tri[(e + 1) % 3]));
            }
        }
        for &(u, v) in &directed {
            if !directed.contains(&(v, u)) {
                on_hull[u as usize] = true;
                on_hull[v as usize] = true;
            }
        }
    }
    // A dual vertex in a crossed hexagon goes, unless it is an input point or on the hull.
    let dropped = |v: u32| {
        !is_new(v) && in_crossed[v as usize] && (v as usize) >= n_input && !on_hull[v as usize]
    };

    let mut removed = vec![false; dual.triangles.len()];
    for (t, tri) in dual.triangles.iter().enumerate() {
        removed[t] = tri.iter().any(|&v| !is_new(v) && in_crossed[v as usize]);
    }
    grow_cavity(&vertices, &dual.triangles, segments, &mut removed);
    // Cavity boundary: directed edges of removed triangles whose reverse is not one.
    let mut removed_edges: FxHashSet<(u32, u32)> = FxHashSet::default();
    for (t, tri) in dual.triangles.iter().enumerate() {
        if removed[t] {
            for e in 0..3 {
                removed_edges.insert((tri[e], tri[(e + 1) % 3]));
            }
        }
    }
    let mut boundary: Vec<(u32, u32)> = removed_edges
        .iter()
        .copied()
        .filter(|&(u, v)| !removed_edges.contains(&(v, u)))
        .collect();
    boundary.sort_unstable();

    let mut cavity_points: Vec<u32> = dual
        .triangles
        .iter()
        .enumerate()
        .filter(|&(t, _)| removed[t])
        .flat_map(|(_, tri)| tri.iter().copied())
        .filter(|&v| !dropped(v))
        .collect();
    cavity_points.extend((in_crossed.len() as u32)..(n_all as u32));
    cavity_points.sort_unstable();
    cavity_points.dedup();

    let mut triangles: Vec<[u32; 3]> = dual
        .triangles
        .iter()
        .enumerate()
        .filter(|&(t, _)| !removed[t])
        .map(|(_, tri)| *tri)
        .collect();
    let n_kept = triangles.len();
    if !cavity_points.is_empty() {
        let (filled, extra_on) = fill_cavity(&vertices, &cavity_points, &boundary, &chains, input)?;
        for (v, s) in extra_on {
            if !on[v as usize].contains(&s) {
                on[v as usize].push(s);
            }
        }
        triangles.extend(filled);
    }

    let on_segment_edge =
        |u: u32, v: u32| on[u as usize].iter().any(|s| on[v as usize].contains(s));
    let keep = carve(&vertices, &triangles, input, on_segment_edge)?;
    let dual_set: FxHashSet<[u32; 3]> = triangles[..n_kept].iter().map(|&t| canonical(t)).collect();
    let triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(t, _)| t)
        .collect();

    // Quality along the segments (`band`): the constrained Delaunay triangulation, improved
    // by points on the segments.
    let mut band = Band::new(segments, vertices, on, triangles, n_input).with_effort(effort);
    band.make_delaunay();
    let left = band.improve(BAND_BUDGET_PER_TRIANGLE * band.tris.len() as u64 + 1000);
    stats.band_inserted += band.inserted;
    stats.band_removed += band.deleted;
    stats.band_moved += band.moved;
    stats.band_flips += band.flips;
    for &v in &band.origin[keys.len()..] {
        keys.push(keys[v as usize]);
    }
    stats.band_left += left.len() as u64;
    let mut position = vec![usize::MAX; band.tris.len()];
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for (t, slot) in position.iter_mut().enumerate() {
        if band.alive[t] {
            *slot = triangles.len();
            triangles.push(band.tris[t]);
        }
    }
    let stuck: Vec<usize> = left
        .iter()
        .filter(|&&t| {
            band.tris[t as usize]
                .iter()
                .any(|&v| !band.segs[v as usize].is_empty())
        })
        .map(|&t| position[t as usize])
        .collect();
    // A triangle off the segments the band could not repair is left as it is: the driver's
    // self-check finds it and subdivides the hexagons around it (`drive`). (It used to be
    // flipped towards the segment, giving up the empty-circle property at that edge, which the
    // constrained Delaunay promise does not allow.)
    let (vertices, on) = (band.verts, band.segs);
    let n_all = vertices.len();
    let cavity: Vec<bool> = triangles
        .iter()
        .map(|&t| !dual_set.contains(&canonical(t)))
        .collect();

    // Compact, keeping the input points first and in order.
    let mut used = vec![false; n_all];
    for tri in &triangles {
        for &v in tri {
            used[v as usize] = true;
        }
    }
    if let Some(i) = (0..n_input).find(|&i| !used[i]) {
        return Err(Error::input(InputError::PointOutsideDomain { point: i }));
    }
    let mut map = vec![u32::MAX; n_all];
    let mut out_vertices = Vec::new();
    let mut out_keys = Vec::new();
    let mut out_on = Vec::new();
    for v in 0..n_all {
        if used[v] {
            map[v] = out_vertices.len() as u32;
            out_vertices.push(vertices[v]);
            out_keys.push(keys[v]);
            out_on.push(!on[v].is_empty());
        }
    }
    let mesh = TriMesh {
        vertices: out_vertices,
        triangles: triangles
            .iter()
            .map(|t| t.map(|v| map[v as usize]))
            .collect(),
    };
    Ok(Built {
        mesh,
        keys: out_keys,
        on_segment: out_on,
        cavity,
        stuck,
    })
}

/// Adds to the cavity every dual triangle that meets a segment (exact) although none of its
/// corners lies in a crossed hexagon: relocated centres (Sec. 5.4) and level transitions let a
/// dual triangle reach beyond its three hexagons. Such a triangle touches the cavity, so the
/// search spreads from the cavity over triangles sharing a corner with it.
fn grow_cavity(
    vertices: &[Point],
    triangles: &[[u32; 3]],
    segments: &[[Point; 2]],
    removed: &mut [bool],
) {
    if segments.is_empty() {
        return;
    }
    // A uniform grid of segment bounding boxes.
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in segments.iter().flatten() {
        for d in 0..2 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let side = ((segments.len() as f64).sqrt().ceil() as usize).clamp(1, 256);
    let size = [
        ((hi[0] - lo[0]) / side as f64).max(f64::MIN_POSITIVE),
        ((hi[1] - lo[1]) / side as f64).max(f64::MIN_POSITIVE),
    ];
    let cell = |x: f64, d: usize| -> usize {
        let k = ((x - lo[d]) / size[d]).floor();
        if k.is_nan() || k < 0.0 {
            0
        } else {
            (k as usize).min(side - 1)
        }
    };
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); side * side];
    for (s, [a, b]) in segments.iter().enumerate() {
        for i in cell(a[0].min(b[0]), 0)..=cell(a[0].max(b[0]), 0) {
            for j in cell(a[1].min(b[1]), 1)..=cell(a[1].max(b[1]), 1) {
                grid[i * side + j].push(s);
            }
        }
    }
    let meets = |t: usize| {
        let c = triangles[t].map(|v| vertices[v as usize]);
        let (mut tlo, mut thi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &c {
            for d in 0..2 {
                tlo[d] = tlo[d].min(p[d]);
                thi[d] = thi[d].max(p[d]);
            }
        }
        if thi[0] < lo[0] || thi[1] < lo[1] || tlo[0] > hi[0] || tlo[1] > hi[1] {
            return false;
        }
        for i in cell(tlo[0], 0)..=cell(thi[0], 0) {
            for j in cell(tlo[1], 1)..=cell(thi[1], 1) {
                for &s in &grid[i * side + j] {
                    let [a, b] = segments[s];
                    if polygon_meets_segment(&c, a, b) {
                        return true;
                    }
                }
            }
        }
        false
    };
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); vertices.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            around[v as usize].push(t);
        }
    }
    let mut queued = removed.to_vec();
    let mut stack: Vec<usize> = (0..triangles.len()).filter(|&t| removed[t]).collect();
    while let Some(t) = stack.pop() {
        for &v in &triangles[t] {
            for &u in &around[v as usize] {
                if queued[u] {
                    continue;
                }
                queued[u] = true;
                if meets(u) {
                    removed[u] = true;
                    stack.push(u);
                }
            }
        }
    }
}
