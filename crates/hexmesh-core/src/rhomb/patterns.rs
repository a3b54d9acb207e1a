//! Triangulating the leaves (paper 001, Sec. 4 steps 10 and 12) and the centring patches.
//!
//! Each rhomb is cut along its short diagonal into two equilateral halves. A half with one
//! splitting point on its sides is joined from that point to the opposite corner (two 30-60-90
//! triangles, step 10(c)); a half with both sides split gets the diagonal's midpoint as well and
//! becomes four equilateral triangles, leaving the other half one splitting point (step 10(d)).
//! A third split side cannot occur: the tree splits such rhombs. Halves outside the bounding
//! hexagon (Sec. 4 step 9) and halves covered by a patch are skipped.

use super::centring::{Kind, Patch};
use super::lattice::{half_corners, half_in_hexagon, hexnorm, key, Cell, Frame, VKey};
use super::tree::{KeyMap, KeySet, Tree};
use crate::geom::Point;
use crate::mesh::TriMesh;

/// Builds the output: the input points first (vertex i is input point i, bit-exact), then the
/// lattice vertices in order of first use.
struct Builder<'a> {
    frame: &'a Frame,
    vertices: Vec<Point>,
    index: KeyMap<VKey, u32>,
    triangles: Vec<[u32; 3]>,
}

impl Builder<'_> {
    fn lattice(&mut self, k: VKey) -> u32 {
        if let Some(&v) = self.index.get(&k) {
            return v;
        }
        let v = self.vertices.len() as u32;
        self.vertices.push(self.frame.point(k));
        self.index.insert(k, v);
        v
    }

    /// A triangle of level-`level` lattice vertices, counter-clockwise.
    fn lattice_triangle(&mut self, level: u8, t: [(i64, i64); 3]) {
        let tri = t.map(|(i, j)| self.lattice(key(level, i, j)));
        self.triangles.push(tri);
    }
}

/// The triangulation of the tree's leaves and the patches. `points` are the input points; they
/// are output only when `patches` carries them.
pub fn triangulate(tree: &Tree, frame: &Frame, points: &[Point], patches: &[Patch]) -> TriMesh {
    let mut b = Builder {
        frame,
        vertices: Vec::new(),
        index: KeyMap::default(),
        triangles: Vec::new(),
    };
    if !patches.is_empty() {
        b.vertices.extend_from_slice(points);
    }
    // A point that is a boundary lattice vertex bit for bit stands for that vertex.
    for patch in patches.iter().filter(|p| p.kind == Kind::Vertex) {
        let (i, j) = patch.centre;
        b.index.insert(key(patch.level, i, j), patch.point);
    }
    let covered: KeySet<(Cell, u8)> = patches.iter().flat_map(Patch::halves).collect();
    for c in tree.leaves() {
        for half in 0..2u8 {
            if !covered.contains(&(c, half)) {
                leaf_half(&mut b, tree, c, half);
            }
        }
    }
    for patch in patches {
        match patch.kind {
            Kind::Moved => moved_triangles(&mut b, patch),
            Kind::Melted => melted_triangles(&mut b, patch),
            Kind::Vertex => {}
        }
    }
    TriMesh {
        vertices: b.vertices,
        triangles: b.triangles,
    }
}

/// One half of a leaf: 0 is (i,j),(i+1,j),(i,j+1) with sides bottom and left; 1 is
/// (i+1,j),(i+1,j+1),(i,j+1) with sides right and top. The diagonal closes both.
fn leaf_half(b: &mut Builder, tree: &Tree, c: Cell, half: u8) {
    if !half_in_hexagon(c, half) {
        return;
    }
    let corners = half_corners(c, half);
    let split = tree.hanging(c, half);
    // Work one level finer, where the side midpoints are lattice vertices.
    let l = c.level + 1;
    let v = corners.map(|(a, bb)| (2 * a, 2 * bb));
    let mid = |e: usize| {
        let (p, q) = (v[e], v[(e + 1) % 3]);
        ((p.0 + q.0) / 2, (p.1 + q.1) / 2)
    };
    match split.iter().filter(|&&s| s).count() {
        0 => b.lattice_triangle(l, v),
        1 => {
            let e = split.iter().position(|&s| s).unwrap_or(0);
            let m = mid(e);
            let (p, q, r) = (v[e], v[(e + 1) % 3], v[(e + 2) % 3]);
            b.lattice_triangle(l, [p, m, r]);
            b.lattice_triangle(l, [m, q, r]);
        }
        _ => {
            let (m0, m1, m2) = (mid(0), mid(1), mid(2));
            b.lattice_triangle(l, [v[0], m0, m2]);
            b.lattice_triangle(l, [m0, v[1], m1]);
            b.lattice_triangle(l, [m2, m1, v[2]]);
            b.lattice_triangle(l, [m0, m1, m2]);
        }
    }
}

/// A moved vertex (Sec. 5.5): its six level-k triangles with p in m's place.
fn moved_triangles(b: &mut Builder, patch: &Patch) {
    for (c, half) in patch.halves() {
        let tri = half_corners(c, half).map(|(i, j)| {
            if (i, j) == patch.centre {
                patch.point
            } else {
                b.lattice(key(c.level, i, j))
            }
        });
        b.triangles.push(tri);
    }
}

/// The patch of Sec. 5.4/5.5 in its melted form: 24 triangles of side L = 2l around m, the six
/// at m taking the input point in m's place, and each outer edge split at its midpoint (a
/// level-k vertex of the rhombs around the patch).
fn melted_triangles(b: &mut Builder, patch: &Patch) {
    let (mi, mj) = patch.centre;
    let k = patch.level;
    let at = |x: i64, y: i64| (mi + 2 * x, mj + 2 * y);
    let on_rim = |(i, j): (i64, i64)| hexnorm(i - mi, j - mj) == patch.radius();
    let radius = patch.radius() / 2;
    for y in -radius..radius {
        for x in -radius..radius {
            for t in [
                [(x, y), (x + 1, y), (x, y + 1)],
                [(x + 1, y), (x + 1, y + 1), (x, y + 1)],
            ] {
                if t.iter().any(|&(a, bb)| hexnorm(a, bb) > radius) {
                    continue;
                }
                if let Some(c) = t.iter().position(|&q| q == (0, 0)) {
                    let p = patch.point;
                    let next = at(t[(c + 1) % 3].0, t[(c + 1) % 3].1);
                    let prev = at(t[(c + 2) % 3].0, t[(c + 2) % 3].1);
                    let (vn, vp) = (
                        b.lattice(key(k, next.0, next.1)),
                        b.lattice(key(k, prev.0, prev.1)),
                    );
                    b.triangles.push([p, vn, vp]);
                    continue;
                }
                let v = t.map(|(a, bb)| at(a, bb));
                let rim_edge = (0..3).find(|&e| {
                    let (p, q) = (v[e], v[(e + 1) % 3]);
                    on_rim(p) && on_rim(q) && on_rim(((p.0 + q.0) / 2, (p.1 + q.1) / 2))
                });
                match rim_edge {
                    None => b.lattice_triangle(k, v),
                    Some(e) => {
                        let (p, q, r) = (v[e], v[(e + 1) % 3], v[(e + 2) % 3]);
                        let m = ((p.0 + q.0) / 2, (p.1 + q.1) / 2);
                        b.lattice_triangle(k, [p, m, r]);
                        b.lattice_triangle(k, [m, q, r]);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::angle_deg;
    use crate::geom::Hexagon;
    use crate::rhomb::tree::index_at;

    fn sorted_angles(m: &TriMesh, t: usize) -> [f64; 3] {
        let c = m.corners(t);
        let mut a = [0, 1, 2].map(|k| angle_deg(c[k], c[(k + 1) % 3], c[(k + 2) % 3]));
        a.sort_by(f64::total_cmp);
        a
    }

    #[test]
    fn every_leaf_pattern_is_equilateral_or_30_60_90() {
        let mut tree = Tree::new(vec![], 0);
        // A graded tree: split towards one spot so that every pattern of step 10 occurs.
        let mut c = Cell::ROOT;
        for _ in 0..6 {
            tree.split(c).unwrap();
            let l = c.level + 1;
            c = Cell::new(l, index_at(0.37, l), index_at(0.55, l));
        }
        let frame = Frame::new(Hexagon::new([0.0, 0.0], 1.0));
        let mesh = triangulate(&tree, &frame, &[], &[]);
        let (mut equilateral, mut right) = (0, 0);
        for t in 0..mesh.triangles.len() {
            let a = sorted_angles(&mesh, t);
            let near = |x: [f64; 3]| (0..3).all(|k| (a[k] - x[k]).abs() < 1e-9);
            if near([60.0, 60.0, 60.0]) {
                equilateral += 1;
            } else if near([30.0, 60.0, 90.0]) {
                right += 1;
            } else {
                panic!("triangle {t} has angles {a:?}");
            }
        }
        assert!(equilateral > 0 && right > 0);
        let area: f64 = mesh.area();
        assert!((area - 1.5 * 3f64.sqrt()).abs() < 1e-12);
    }
}
