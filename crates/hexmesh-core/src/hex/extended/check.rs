//! The self-check of the finished dual: our departure from paper 000 (Sußner & Greiner
//! 2009). Its Sec. 6.1 admits that the angle bounds were checked on "almost all
//! configurations"; here every triangle of the dual is measured against them
//! (`breaks_bounds`, with what rounding of its corners explains) and every pair against the
//! exact empty-circle test, and the offending triangles are named for a repair
//! (`offending_leaves`). A pair only rounding made non-Delaunay (the cocircular quadruples of
//! Sec. 6.4 in real arithmetic) is flipped once the mesh is done (`settle_rounding`).

use crate::error::{Error, Result};
use crate::geom::angle_deg;
use crate::geom::{incircle, orient2d, Point};
use crate::hex::lattice::Key;
use crate::hex::parallel::{ranges_in_parallel, PARALLEL_MIN};
use crate::hex::subdivision::Hierarchy;
use crate::mesh::TriMesh;
use crate::quality::rounding;
use crate::quality::HEX;

/// True when an angle of `t` lies beyond [α, 90°] by more than the self-check's slack plus
/// what placing its corners explains (`rounding::placement_allowance`: one rounding of each
/// coordinate): a configuration the rules must fix, not rounding's doing. Where rounding is
/// a few ulps of unit coordinates this is the plain slack; at coordinates far larger than the
/// hexagons (a set translated to 1e7) it grows with the rounding there. It grants a quarter
/// of what the checks allow: the whole allowance let rules through whose exact angles break
/// the bound (0.05° below α around a pair 1e-11 of its coordinates apart), and the input
/// was then refused for the rounding those angles seemed to use.
pub(crate) fn breaks_bounds(t: &[Point; 3]) -> bool {
    (0..3).any(|m| {
        let (a, b, c) = (t[m], t[(m + 1) % 3], t[(m + 2) % 3]);
        let beyond = rounding::beyond(angle_deg(a, b, c), HEX.min_angle, HEX.max_angle);
        beyond > HEX.self_check_slack + rounding::placement_allowance(a, b, c)
    })
}

/// A triangle of the dual that breaks the angle bounds or the exact empty-circle test.
pub(super) struct BadTriangle {
    /// Its index in the checked mesh.
    pub(super) triangle: usize,
    /// The leaf hexagons of its three vertices.
    pub(super) vertices: [Key; 3],
    /// The coarsest of them, the one to subdivide.
    pub(super) coarsest: Key,
}

/// The triangles that break the angle bounds or the exact empty-circle test.
pub(super) fn offending_leaves(
    h: &Hierarchy,
    mesh: &TriMesh,
    keys: &[Key],
    rounding_pairs: &mut u64,
) -> Vec<BadTriangle> {
    let filter = HEX.angle_filter();
    // Triangle by triangle, over the hierarchy's threads in ranges, concatenated in order.
    let mut bad_tris: Vec<usize> =
        ranges_in_parallel(h.threads(), mesh.triangles.len(), PARALLEL_MIN, |range| {
            range
                .filter(|&t| {
                    let c = mesh.corners(t);
                    !filter.clearly_within(&c) && breaks_bounds(&c)
                })
                .collect::<Vec<_>>()
        })
        .concat();
    // A pair that only rounding made non-Delaunay is flipped once the mesh is finished
    // (`settle_rounding`), not refined.
    for (t, u) in delaunay_violations_over(mesh, h.threads()) {
        if rounding_made(mesh, t, u) {
            *rounding_pairs += 1;
        } else {
            bad_tris.push(t);
            bad_tris.push(u);
        }
    }
    bad_tris.sort_unstable();
    bad_tris.dedup();
    bad_tris
        .iter()
        .map(|&t| {
            let vertices = mesh.triangles[t].map(|v| h.leaf_of_vertex(keys[v as usize]));
            let coarsest = vertices
                .iter()
                .copied()
                .min_by_key(|k| (k.k, *k))
                .unwrap_or(Key::ROOT);
            BadTriangle {
                triangle: t,
                vertices,
                coarsest,
            }
        })
        .collect()
}

/// Pairs of triangles sharing an edge where the opposite vertex of one lies strictly inside
/// the circumcircle of the other (exact `incircle`).
pub fn delaunay_violations(mesh: &TriMesh) -> Vec<(usize, usize)> {
    delaunay_violations_over(mesh, 1)
}

/// `delaunay_violations` with the triangles tested over `threads` threads in ranges (the
/// pairs in the same order).
pub(super) fn delaunay_violations_over(mesh: &TriMesh, threads: usize) -> Vec<(usize, usize)> {
    // The triangles around each vertex (a counting sort), so that the other triangle of an
    // edge is found among the few around one of its ends: 12 bytes a triangle, where a list
    // of the edges with their triangles and opposite vertices took 36 (4 GB at plane-1m,
    // touched afresh at every complete check). Each pair of triangles sharing an edge is
    // tested once, from the smaller index; the exact test is symmetric (the opposite vertex of
    // one lies strictly inside the other's circumcircle exactly when the reverse holds).
    let n = mesh.vertices.len();
    // Counted one slot ahead, so that after the sums start[v + 1] is where v's triangles
    // begin, and after the fill where they end.
    let mut start = vec![0u32; n + 2];
    for tri in &mesh.triangles {
        for &v in tri {
            start[v as usize + 2] += 1;
        }
    }
    for v in 0..n {
        start[v + 2] += start[v + 1];
    }
    let mut star = vec![0u32; 3 * mesh.triangles.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            let at = &mut start[v as usize + 1];
            star[*at as usize] = t as u32;
            *at += 1;
        }
    }
    // Now v's triangles are star[start[v]..start[v + 1]].
    let around = |v: u32| &star[start[v as usize] as usize..start[v as usize + 1] as usize];
    ranges_in_parallel(threads, mesh.triangles.len(), PARALLEL_MIN, |range| {
        let mut out = Vec::new();
        for t in range {
            let tri = mesh.triangles[t];
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                for &u in around(a.min(b)) {
                    if u as usize <= t {
                        continue;
                    }
                    let other = mesh.triangles[u as usize];
                    if !other.contains(&a.max(b)) {
                        continue;
                    }
                    let Some(&opp) = other.iter().find(|&&w| w != a && w != b) else {
                        continue;
                    };
                    let [p, q, r] = mesh.corners(t);
                    if incircle(p, q, r, mesh.vertices[opp as usize]) > 0.0 {
                        out.push((t, u as usize));
                    }
                }
            }
        }
        out
    })
    .concat()
}

/// The pair (t, u) sharing an edge, as (p, q, w1, w2): t = (p, q, w1) and u = (q, p, w2), both
/// counter-clockwise, so that the quadrilateral is p, w2, q, w1.
pub(super) fn shared_edge(mesh: &TriMesh, t: usize, u: usize) -> Option<[u32; 4]> {
    let (a, b) = (mesh.triangles[t], mesh.triangles[u]);
    (0..3).find_map(|e| {
        let (p, q) = (a[e], a[(e + 1) % 3]);
        let w1 = a[(e + 2) % 3];
        (0..3)
            .find(|&f| b[f] == q && b[(f + 1) % 3] == p)
            .map(|f| [p, q, w1, b[(f + 2) % 3]])
    })
}

/// True when the exact empty-circle test fails on the pair (t, u) only by what rounding of
/// their corners explains, and the pair can be flipped (`flipped`): the two angles opposite
/// the shared edge sum to at most 180° plus the self-check's slack and their rounding
/// allowances (less the floor). Real arithmetic puts such a pair on a circle (the cocircular
/// quadruples of Sec. 6.4); the flip makes it Delaunay. A pair whose flip would break a
/// bound is blamed and refined, as any other.
pub(super) fn rounding_made(mesh: &TriMesh, t: usize, u: usize) -> bool {
    let Some([p, q, w1, w2]) = shared_edge(mesh, t, u) else {
        return false;
    };
    if flipped(mesh, [p, q, w1, w2]).is_none() {
        return false;
    }
    let v = |i: u32| mesh.vertices[i as usize];
    let (p, q, w1, w2) = (v(p), v(q), v(w1), v(w2));
    let excess = angle_deg(w1, p, q) + angle_deg(w2, q, p) - 180.0;
    excess <= HEX.self_check_slack
        || excess
            <= HEX.self_check_slack
                + rounding::angle_allowance(w1, p, q)
                + rounding::angle_allowance(w2, q, p)
                - 2.0 * rounding::ANGLE_FLOOR_DEG
}

/// The two triangles of the other diagonal of the quadrilateral p, w2, q, w1 of a shared edge
/// (`shared_edge`), when both are counter-clockwise and keep the angle bounds within the
/// self-check's slack (`breaks_bounds`).
pub(super) fn flipped(mesh: &TriMesh, [p, q, w1, w2]: [u32; 4]) -> Option<[[u32; 3]; 2]> {
    let new = [[p, w2, w1], [w2, q, w1]];
    let corners = new.map(|tri| tri.map(|i| mesh.vertices[i as usize]));
    corners
        .iter()
        .all(|c| orient2d(c[0], c[1], c[2]) > 0.0 && !breaks_bounds(c))
        .then_some(new)
}

/// Rounds of flips `settle_rounding` makes before it gives up.
pub(super) const FLIP_ROUNDS: usize = 64;

/// Makes a finished mesh exactly Delaunay where rounding alone spoiled it (Sec. 6.4; README
/// "Checks"), when the self-check let such pairs pass (`rounding_pairs`, counted by
/// `offending_leaves`; with none there is nothing to flip): each pair the exact empty-circle
/// test rejects is flipped to its other diagonal (`flipped`: the self-check let it pass only
/// when that keeps the bounds); flips repeat until none is needed. A pair left over is a
/// defect of the mesher, reported as such: no mesh with a non-Delaunay edge is handed out.
/// Then the angles are held to `max_rounding` (`quality::rounding::check_angles`).
pub fn settle_rounding(
    mesh: &mut TriMesh,
    points: &[Point],
    rounding_pairs: u64,
    max_rounding: f64,
    threads: usize,
) -> Result<()> {
    if rounding_pairs > 0 {
        flip_rounding_pairs(mesh);
        if let Some(&(t, u)) = delaunay_violations(mesh).first() {
            return Err(Error::mesher(
                "hex",
                format!(
                    "internal error: triangles {t} and {u} are not Delaunay after the flips of \
                     the pairs rounding made non-Delaunay"
                ),
            ));
        }
    }
    rounding::check_angles_over(
        mesh,
        points,
        (HEX.min_angle, HEX.max_angle),
        max_rounding,
        "hex",
        threads,
    )
}

/// The flips of `settle_rounding`, at most `FLIP_ROUNDS` rounds of them.
pub(super) fn flip_rounding_pairs(mesh: &mut TriMesh) {
    for _ in 0..FLIP_ROUNDS {
        let pairs = delaunay_violations(mesh);
        let mut touched = vec![false; mesh.triangles.len()];
        let mut any = false;
        for (t, u) in pairs {
            if touched[t] || touched[u] {
                continue;
            }
            if let Some(new) = shared_edge(mesh, t, u).and_then(|e| flipped(mesh, e)) {
                mesh.triangles[t] = new[0];
                mesh.triangles[u] = new[1];
                touched[t] = true;
                touched[u] = true;
                any = true;
            }
        }
        if !any {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delaunay_violations_are_the_pairs_a_test_of_every_two_triangles_finds() {
        // A row of rhombi (0,0) (2,-h) (4,0) (2,h), each split along its long diagonal (not
        // Delaunay when h < 2) or its short one, with fans of triangles between them so that
        // vertices have several triangles around them; every triangle counter-clockwise.
        let mut vertices: Vec<Point> = Vec::new();
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        for r in 0..12u32 {
            let x = 5.0 * r as f64;
            let h = [0.5, 1.5, 2.5][r as usize % 3];
            let base = vertices.len() as u32;
            vertices.extend([[x, 0.0], [x + 2.0, -h], [x + 4.0, 0.0], [x + 2.0, h]]);
            let [a, b, c, d] = [base, base + 1, base + 2, base + 3];
            if r % 2 == 0 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
            if r > 0 {
                // The previous rhombus's right corner, top and bottom joined to this one.
                let (pb, pc, pd) = (base - 3, base - 2, base - 1);
                triangles.extend([[pc, b, a], [pc, a, d], [pb, b, pc], [pd, pc, d]]);
            }
        }
        let mesh = TriMesh {
            vertices,
            triangles,
        };
        let mut found = delaunay_violations(&mesh);
        found.sort_unstable();
        let mut want = Vec::new();
        for t in 0..mesh.triangles.len() {
            for u in t + 1..mesh.triangles.len() {
                let (x, y) = (mesh.triangles[t], mesh.triangles[u]);
                let shared = x.iter().filter(|v| y.contains(v)).count();
                if shared != 2 {
                    continue;
                }
                let opp = *y.iter().find(|v| !x.contains(v)).expect("a third vertex");
                let [p, q, r] = mesh.corners(t);
                if incircle(p, q, r, mesh.vertices[opp as usize]) > 0.0 {
                    want.push((t, u));
                }
            }
        }
        assert!(!want.is_empty(), "the fixture has non-Delaunay pairs");
        assert_eq!(found, want);
    }
}
