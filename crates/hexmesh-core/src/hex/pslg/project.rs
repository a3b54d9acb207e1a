//! Projected centres, paper Sec. 7.3 and 7.4: the centre of each crossed hexagon is projected
//! onto each segment crossing it along the hexagon axis with the largest angle to the segment,
//! and kept when the projection lies in the hexagon and strictly inside the segment (7.3); a
//! hexagon crossed by two segments gets one projected centre on each (7.4).
//!
//! Omission rules: a projected centre farther than the hexagon's radius r from the hexagon's
//! (moved) centre is not used (7.4). Ours on top: a projected centre closer than r/2 to the
//! previous point kept on the segment (or to the segment's end) is omitted too, so that no
//! segment piece is short.

use std::collections::BTreeMap;

use super::PslgStats;
use crate::geom::{dist, Point};
use crate::hex::lattice::{FxHashMap, Key};
use crate::hex::subdivision::Hierarchy;

/// A projected centre (Sec. 7.3): its parameter along the segment, position and hexagon.
#[derive(Debug, Clone, Copy)]
pub(super) struct Record {
    /// The parameter along the segment ab: the centre lies at a + t·(b − a), 0 < t < 1.
    pub t: f64,
    /// The projected centre.
    pub point: Point,
    /// The hexagon whose centre was projected.
    pub key: Key,
}

/// The three axes of a flat-topped hexagon, orthogonal to its edges (paper Fig. 13).
fn axes() -> [Point; 3] {
    let s = 3f64.sqrt() / 2.0;
    [[s, 0.5], [0.0, 1.0], [-s, 0.5]]
}

/// The cross product of two vectors (z component).
fn cross(a: Point, b: Point) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The vector a − b.
fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}

/// The centre of hexagon `key` projected onto segment ab along the axis with the largest angle
/// to it (Sec. 7.3), when that point lies in the hexagon and strictly inside the segment: the
/// parameter t along ab and the point a + t·(b − a).
fn project(h: &Hierarchy, key: Key, a: Point, b: Point) -> Option<(f64, Point)> {
    let c = h.lattice.center(key);
    let r = h.lattice.radius(key.k);
    let d = sub(b, a);
    let axis = axes()
        .into_iter()
        .max_by(|x, y| cross(*x, d).abs().total_cmp(&cross(*y, d).abs()))?;
    let denom = cross(d, axis);
    if denom == 0.0 {
        return None;
    }
    let t = cross(sub(c, a), axis) / denom;
    if !(t > 0.0 && t < 1.0) {
        return None;
    }
    let q = [a[0] + t * d[0], a[1] + t * d[1]];
    let inradius = r * 3f64.sqrt() / 2.0;
    let off = sub(q, c);
    let inside = axes()
        .iter()
        .all(|ax| (off[0] * ax[0] + off[1] * ax[1]).abs() <= inradius);
    inside.then_some((t, q))
}

/// The projected centres kept on each segment (indexed like `segments`), sorted along it from
/// its first endpoint. `keys` and `vertices` are the dual's vertices: a crossed hexagon with a
/// dual vertex has its (moved) centre there. Hexagons holding an input point keep their point
/// and project nothing. Counts the omitted centres in `stats.omitted`.
pub(super) fn projected_centres(
    h: &Hierarchy,
    segments: &[[Point; 2]],
    crossed: &BTreeMap<Key, Vec<u32>>,
    keys: &[Key],
    vertices: &[Point],
    stats: &mut PslgStats,
) -> Vec<Vec<Record>> {
    let vertex_of: FxHashMap<Key, u32> = keys
        .iter()
        .enumerate()
        .map(|(v, &k)| (k, v as u32))
        .collect();

    // Sec. 7.3: projected centres per segment, sorted by the distance from its start.
    let mut records: Vec<Vec<Record>> = vec![Vec::new(); segments.len()];
    for (&key, set) in crossed {
        if h.is_occupied(key) {
            continue;
        }
        let moved = vertex_of.get(&key).map(|&v| vertices[v as usize]);
        let r = h.lattice.radius(key.k);
        for &s in set {
            let [a, b] = segments[s as usize];
            let Some((t, point)) = project(h, key, a, b) else {
                stats.omitted += 1;
                continue;
            };
            // Sec. 7.4's omission rule: farther than r from the moved centre.
            if moved.is_some_and(|m| dist(m, point) > r) {
                stats.omitted += 1;
                continue;
            }
            records[s as usize].push(Record { t, point, key });
        }
    }
    // Ours: no projected centre closer than r/2 to the previous kept point or to the end.
    let mut out: Vec<Vec<Record>> = Vec::with_capacity(segments.len());
    for (s, recs) in records.iter_mut().enumerate() {
        recs.sort_by(|x, y| x.t.total_cmp(&y.t).then(x.key.cmp(&y.key)));
        let [a, b] = segments[s];
        let mut kept: Vec<Record> = Vec::new();
        let mut last = a;
        for rec in recs.iter() {
            let r = h.lattice.radius(rec.key.k);
            if dist(last, rec.point) < r / 2.0 || dist(rec.point, b) < r / 2.0 {
                stats.omitted += 1;
                continue;
            }
            last = rec.point;
            kept.push(*rec);
        }
        out.push(kept);
    }
    out
}
