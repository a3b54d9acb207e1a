//! The descent bound of longest-side bisection (paper 003): every triangle of a refinement
//! keeps at least a fraction r of the smallest angle of the initial triangle it lies in —
//! r = 2/3 for the family T(A, B, C) of Theorem 3.4 (uniform modified refinement), r = 1/2 for
//! plain bisection and for the adaptive refinement with rule 4.1 (the paper's Sec. 4: "both
//! discussed mesh refinement methods can locally lead to α/2 smallest angles").
//!
//! The ancestor of each output triangle is found here, independently of the mesher's own
//! bookkeeping: its centroid is located among the initial triangles with exact orientation
//! signs (a uniform grid of the initial triangles' bounding boxes keeps this near linear).

use crate::geom::angle_deg;
use crate::geom::{orient2d, Point};
use crate::mesh::TriMesh;

/// The smallest angle of a triangle given by its corners, in degrees.
fn smallest_angle(c: [Point; 3]) -> f64 {
    angle_deg(c[0], c[1], c[2])
        .min(angle_deg(c[1], c[2], c[0]))
        .min(angle_deg(c[2], c[0], c[1]))
}

/// What `descent` measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Descent {
    /// For every output triangle, the initial triangle its centroid lies in (the one with the
    /// smallest minimum angle when the centroid lies on an edge shared by several).
    pub parents: Vec<Option<u32>>,
    /// The smallest ratio (output triangle's smallest angle) / (its ancestor's), with the
    /// output triangle where it occurs; `None` when no triangle was located.
    pub min_ratio: Option<(f64, usize)>,
    /// The smallest margin θ − r·α in degrees over the located triangles, for the fraction
    /// `r` asked for, with its triangle: negative means the bound fails there.
    pub min_margin: Option<(f64, usize)>,
    /// The first output triangle whose centroid lies in no initial triangle.
    pub first_unlocated: Option<usize>,
}

/// Locates every triangle of `refined` in `initial` and measures the descent bound with
/// fraction `r` (see the module comment).
pub fn descent(initial: &TriMesh, refined: &TriMesh, r: f64) -> Descent {
    let base: Vec<f64> = (0..initial.triangles.len())
        .map(|t| smallest_angle(initial.corners(t)))
        .collect();
    let grid = Grid::new(initial);
    let mut out = Descent {
        parents: Vec::with_capacity(refined.triangles.len()),
        min_ratio: None,
        min_margin: None,
        first_unlocated: None,
    };
    for t in 0..refined.triangles.len() {
        let c = refined.corners(t);
        let g = [
            (c[0][0] + c[1][0] + c[2][0]) / 3.0,
            (c[0][1] + c[1][1] + c[2][1]) / 3.0,
        ];
        let parent = grid
            .candidates(g)
            .filter(|&p| {
                let [a, b, d] = initial.corners(p as usize);
                orient2d(a, b, g) >= 0.0 && orient2d(b, d, g) >= 0.0 && orient2d(d, a, g) >= 0.0
            })
            .min_by(|&p, &q| {
                base[p as usize]
                    .total_cmp(&base[q as usize])
                    .then(p.cmp(&q))
            });
        out.parents.push(parent);
        let Some(p) = parent else {
            out.first_unlocated.get_or_insert(t);
            continue;
        };
        let (theta, alpha) = (smallest_angle(c), base[p as usize]);
        let ratio = theta / alpha;
        if out.min_ratio.is_none_or(|(m, _)| ratio < m) {
            out.min_ratio = Some((ratio, t));
        }
        let margin = theta - r * alpha;
        if out.min_margin.is_none_or(|(m, _)| margin < m) {
            out.min_margin = Some((margin, t));
        }
    }
    out
}

/// A uniform grid over the initial triangles' bounding box; each cell lists the triangles
/// whose bounding boxes meet it.
struct Grid {
    lo: Point,
    cell: [f64; 2],
    n: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl Grid {
    fn new(mesh: &TriMesh) -> Grid {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for v in &mesh.vertices {
            for k in 0..2 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        let side = (mesh.triangles.len() as f64)
            .sqrt()
            .ceil()
            .clamp(1.0, 2048.0) as usize;
        let n = [side, side];
        let cell = [0, 1].map(|k| {
            let w = (hi[k] - lo[k]) / side as f64;
            if w > 0.0 && w.is_finite() {
                w
            } else {
                1.0
            }
        });
        let mut grid = Grid {
            lo,
            cell,
            n,
            cells: vec![Vec::new(); n[0] * n[1]],
        };
        for t in 0..mesh.triangles.len() {
            let c = mesh.corners(t);
            let (mut a, mut b) = (c[0], c[0]);
            for p in &c[1..] {
                for k in 0..2 {
                    a[k] = a[k].min(p[k]);
                    b[k] = b[k].max(p[k]);
                }
            }
            let (i0, j0) = grid.index(a);
            let (i1, j1) = grid.index(b);
            for i in i0..=i1 {
                for j in j0..=j1 {
                    grid.cells[i * grid.n[1] + j].push(t as u32);
                }
            }
        }
        grid
    }

    /// The cell of `p`, clamped to the grid.
    fn index(&self, p: Point) -> (usize, usize) {
        let at = |k: usize| {
            let x = ((p[k] - self.lo[k]) / self.cell[k]).floor();
            if x.is_nan() || x < 0.0 {
                0
            } else {
                (x as usize).min(self.n[k] - 1)
            }
        };
        (at(0), at(1))
    }

    fn candidates(&self, p: Point) -> impl Iterator<Item = u32> + '_ {
        let (i, j) = self.index(p);
        self.cells[i * self.n[1] + j].iter().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bisected_right_triangle_keeps_its_angles_and_names_its_parent() {
        let initial = TriMesh {
            vertices: vec![[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0]],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
        };
        // Triangle 0 bisected at (1, 1); triangle 1 kept.
        let refined = TriMesh {
            vertices: vec![[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0], [1.0, 1.0]],
            triangles: vec![[0, 1, 4], [0, 4, 2], [1, 3, 2]],
        };
        let d = descent(&initial, &refined, 0.5);
        assert_eq!(d.parents, vec![Some(0), Some(0), Some(1)]);
        assert_eq!(d.first_unlocated, None);
        let (ratio, _) = d.min_ratio.unwrap();
        assert!((ratio - 1.0).abs() < 1e-12, "{ratio}");
        let (margin, _) = d.min_margin.unwrap();
        assert!((margin - 22.5).abs() < 1e-9, "{margin}");
    }

    #[test]
    fn a_sliver_inside_a_fat_triangle_fails_the_half_angle_bound_there() {
        let h = 3f64.sqrt() / 2.0;
        let initial = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.5, h]],
            triangles: vec![[0, 1, 2]],
        };
        // The equilateral triangle cut by a point near its base: a 2.3° angle at the base.
        let refined = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.5, h], [0.5, 0.02]],
            triangles: vec![[0, 1, 3], [1, 2, 3], [2, 0, 3]],
        };
        let d = descent(&initial, &refined, 0.5);
        let (margin, t) = d.min_margin.unwrap();
        assert!(margin < -20.0, "{margin}");
        assert_eq!(t, 0);
        assert!(d.min_ratio.unwrap().0 < 0.05);
    }

    #[test]
    fn a_triangle_outside_the_initial_mesh_is_unlocated() {
        let initial = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        let refined = TriMesh {
            vertices: vec![[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]],
            triangles: vec![[0, 1, 2]],
        };
        let d = descent(&initial, &refined, 0.5);
        assert_eq!(d.parents, vec![None]);
        assert_eq!(d.first_unlocated, Some(0));
        assert_eq!(d.min_ratio, None);
    }
}
