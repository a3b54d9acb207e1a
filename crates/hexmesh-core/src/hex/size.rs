//! Size control of `hex` and `hex-simple` (ours, not the paper's): a maximum triangle area
//! (`--max-area`, and the smallest area limit of an input's regions) and a maximum edge length
//! (`--max-edge`) are kept by subdividing every full leaf coarser than a level L before the
//! rules run again, so that the bounds of Sec. 4 and 6 hold as before: the rules only ever
//! subdivide further, and the local coarsening of Sec. 5.3 forms no blossom coarser than L
//! (`blossom::can_form`).
//!
//! # Which leaf size keeps the limits
//!
//! A hexagon of level k has circumradius r_k = r_0/2^k, and the centres of two adjacent cells
//! of level k lie s = √3·r_k apart (`lattice`). Every triangle of the dual (Sec. 4.2, `dual`)
//! is a lattice triangle of some level k: the centres A, B, C of three mutually adjacent full
//! hexagons of level k, or one of the two halves of such a triangle through the midpoint of AB.
//! At least one of A, B, C is then a full hexagon of level k that is not subdivided (were all
//! three subdivided, the triangle would be split into four of level k + 1), so once every full
//! leaf inside the bounding hexagon has level ≥ L, every triangle has level k ≥ L. A corner is
//! the centre of a level-k cell, except where it is moved:
//!
//! - `hex-simple`: only an input point replaces a centre, and it lies in the closed hexagon of
//!   the occupied leaf at the end of that cell's chain of central children (same centre,
//!   circumradius ≤ r_k). Occupied leaves are never adjacent (each has a ring of unoccupied
//!   ones, Sec. 4.1) and a dual edge joins adjacent hexagons, so a triangle has at most one
//!   input point, say P for A. The edge BC stays s = √3·r_k; P is at most √7·r_k from B or C
//!   (the farthest point of A's hexagon from B's centre is the corner across: 3r² + r² +
//!   2·√3r·r·cos 30° = 7r²); and P lies at most 3r_k/2 + r_k from the line BC (A is the height
//!   3r_k/2 of the equilateral triangle away, and the hexagon reaches r_k along that height, a
//!   corner direction). So every edge is at most √7·r_k and every area at most
//!   ½·√3r_k·(5/2)r_k = (5√3/4)·r_k². The halves are smaller (M, at level k + 1, moves at
//!   most r_k/2: edges ≤ 2r_k, areas ≤ ½·√3r_k·(5/4)r_k).
//! - `hex` (and its PSLG path away from the segments): the relocations of Sec. 5.4 move
//!   centres as well (ring cells by r/2, MOVED_CENTER_1/2 centres towards their fins, the
//!   MOVED_CENTER_3 stars rebuilt with fin vertices between C and C_N, MOVED_CENTER_4 tops by
//!   at most 2/5·√3·r), so we take every corner within r_k of its centre (an input point in
//!   its hexagon's circumcircle, every relocation ≤ r_k). Each edge is then at most
//!   s + 2r_k = (2 + √3)·r_k, and a triangle whose longest edge is e has area at most
//!   (√3/4)·e² (the third corner lies in the lens of the two discs of radius e around the
//!   ends of that edge, at most (√3/2)·e from it): (√3/4)·(2 + √3)²·r_k². The MOVED_CENTER_3
//!   stars are not lattice triangles, but their corners lie within K's star (fins at most
//!   0.6·√3·r_k from K's centre, towards a neighbour), and their edges are shorter than that.
//!
//! L is the smallest level with `EDGE·r_L ≤ max_edge` and `AREA·r_L² ≤ max_area` (`level`).
//! The bound for `hex` is loose (a regular triangle of level L has (3√3/4)·r_L², a fifth of
//! it), the price of not tracking each relocation; a finished mesh is still checked against
//! the limits (`check`), and a triangle beyond one is an internal error, never a silent one.
//!
//! Work: the subdivision runs level by level over the full leaves coarser than L (`refine`),
//! each split once, so it costs the hexagons it creates; the mesh has Θ(area / r_L²) triangles
//! anyway, so the mesher stays O(output).

use crate::error::{Error, Result};
use crate::hex::lattice::{Key, MAX_LEVEL};
use crate::hex::refine::drain;
use crate::hex::subdivision::{Hierarchy, Stop};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Params;

/// How large the triangles of level-k lattice triangles can get, in units of r_k: the longest
/// edge and the largest area (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Factors {
    /// Longest edge over r_k.
    pub edge: f64,
    /// Largest area over r_k².
    pub area: f64,
}

/// `hex-simple`'s factors: edges ≤ √7·r_k, areas ≤ (5√3/4)·r_k².
pub const SIMPLE: Factors = Factors {
    edge: 2.645_751_311_064_590_7,
    area: 2.165_063_509_461_097,
};

/// `hex`'s factors: edges ≤ (2 + √3)·r_k, areas ≤ (√3/4)·(2 + √3)²·r_k².
pub const EXTENDED: Factors = Factors {
    edge: 3.732_050_807_568_877,
    area: 6.031_088_913_245_535,
};

impl Factors {
    /// The factors of the mesher called `mesher` (`hex-simple`, else `hex`).
    pub fn of(mesher: &str) -> Factors {
        if mesher == "hex-simple" {
            SIMPLE
        } else {
            EXTENDED
        }
    }
}

/// The limits a call keeps: `--max-area` with the smallest area limit of the input's regions
/// folded in, and `--max-edge`. Refuses a limit that is not positive and finite.
pub fn limits(input: &Pslg, params: &Params) -> Result<(Option<f64>, Option<f64>)> {
    let (_, max_edge) = params.size_limits()?;
    let area = input.smallest_area_limit(params.max_area);
    if let Some(a) = area {
        if !(a > 0.0 && a.is_finite()) {
            return Err(Error::Usage(format!(
                "--max-area must be a positive finite number, not {a}"
            )));
        }
    }
    Ok((area, max_edge))
}

/// The coarsest level L whose triangles keep the limits, for a root of circumradius `r0`
/// (module docs); 0 without limits. Errors when L would exceed the lattice's depth.
pub fn level(
    r0: f64,
    (max_area, max_edge): (Option<f64>, Option<f64>),
    factors: Factors,
    mesher: &str,
) -> Result<u8> {
    let fits = |k: u8| {
        let r = r0 * 0.5f64.powi(i32::from(k));
        max_edge.is_none_or(|e| factors.edge * r <= e)
            && max_area.is_none_or(|a| factors.area * r * r <= a)
    };
    // Well below MAX_LEVEL: the points need the levels beneath.
    let deepest = MAX_LEVEL - 8;
    (0..=deepest).find(|&k| fits(k)).ok_or_else(|| {
        Error::mesher(
            mesher,
            format!(
                "the size limits (max-area {max_area:?}, max-edge {max_edge:?}) need hexagons \
                 finer than level {deepest} of a root of circumradius {r0}"
            ),
        )
    })
}

/// Subdivides every full leaf coarser than the hierarchy's size level
/// (`Hierarchy::size_level`), coarsest first, then applies rules 1–5 again to the cells
/// around the subdivisions (`refine::drain`). Run after the simple refinement: the rules that
/// follow (the extended ones, the PSLG ones, the self-checks) only subdivide further.
pub fn refine(h: &mut Hierarchy) -> Result<(), Stop> {
    let level = h.size_level();
    if level == 0 {
        return Ok(());
    }
    let mut by_level: Vec<Vec<Key>> = vec![Vec::new(); usize::from(level)];
    for key in h.full_leaves_iter() {
        if key.k < level {
            by_level[usize::from(key.k)].push(key);
        }
    }
    let mut next: Vec<Key> = Vec::new();
    for k in 0..level {
        let mut frontier = std::mem::take(&mut by_level[usize::from(k)]);
        frontier.append(&mut next);
        frontier.sort_unstable_by_key(|key| key.packed());
        frontier.dedup();
        // With every leaf coarser than k already split, splitting a level-k leaf creates
        // leaves of level k + 1 only: its children.
        for &key in &frontier {
            if h.is_full_leaf(key) && key.inside() {
                h.subdivide(key)?;
            }
        }
        if k + 1 < level {
            for &key in &frontier {
                next.extend(
                    key.children()
                        .into_iter()
                        .filter(|&c| c.inside() && h.is_full_leaf(c)),
                );
            }
        }
    }
    drain(h)
}

/// Checks a finished mesh against the limits: the first triangle beyond one, among those
/// `checked` admits, is an internal error of `mesher` (the module docs' bound failed).
pub fn check(
    mesh: &TriMesh,
    (max_area, max_edge): (Option<f64>, Option<f64>),
    mesher: &str,
    checked: impl Fn(usize) -> bool,
) -> Result<()> {
    if max_area.is_none() && max_edge.is_none() {
        return Ok(());
    }
    for t in (0..mesh.triangles.len()).filter(|&t| checked(t)) {
        let c = mesh.corners(t);
        let area = 0.5 * crate::geom::orient2d(c[0], c[1], c[2]);
        let edge = (0..3)
            .map(|e| crate::geom::dist(c[e], c[(e + 1) % 3]))
            .fold(0.0, f64::max);
        let over_area = max_area.is_some_and(|a| area > a);
        let over_edge = max_edge.is_some_and(|l| edge > l);
        if over_area || over_edge {
            return Err(Error::mesher(
                mesher,
                format!(
                    "internal error: triangle {} ({:?}, {:?}, {:?}) has area {area:e} and \
                     longest edge {edge:e}, beyond the limits (max-area {max_area:?}, max-edge \
                     {max_edge:?}) its hexagons were refined for",
                    t + 1,
                    c[0],
                    c[1],
                    c[2]
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_factors_match_their_formulas() {
        let s3 = 3f64.sqrt();
        assert!((SIMPLE.edge - 7f64.sqrt()).abs() < 1e-15);
        assert!((SIMPLE.area - 5.0 * s3 / 4.0).abs() < 1e-15);
        assert!((EXTENDED.edge - (2.0 + s3)).abs() < 1e-15);
        assert!((EXTENDED.area - s3 / 4.0 * (2.0 + s3).powi(2)).abs() < 1e-14);
    }

    #[test]
    fn the_level_is_the_coarsest_that_keeps_both_limits() {
        // r_k = 2^-k: level 3 has r = 1/8, edge (2 + √3)/8 = 0.4665, area 6.031/64 = 0.0942.
        let l = |a, e| level(1.0, (a, e), EXTENDED, "hex").unwrap();
        assert_eq!(l(None, None), 0);
        assert_eq!(l(None, Some(0.47)), 3);
        assert_eq!(l(None, Some(0.46)), 4);
        assert_eq!(l(Some(0.095), None), 3);
        assert_eq!(l(Some(0.094), None), 4);
        assert_eq!(l(Some(0.095), Some(0.46)), 4);
        assert!(level(1.0, (Some(1e-40), None), EXTENDED, "hex").is_err());
    }

    #[test]
    fn the_size_check_names_a_triangle_beyond_a_limit() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        assert!(check(&mesh, (Some(1.0), Some(2.3)), "hex", |_| true).is_ok());
        let e = check(&mesh, (Some(0.99), None), "hex", |_| true).unwrap_err();
        assert!(e.to_string().contains("triangle 1"), "{e}");
        assert!(check(&mesh, (None, Some(2.2)), "hex", |_| true).is_err());
        // A triangle left out (near a segment) is not checked.
        assert!(check(&mesh, (None, Some(2.2)), "hex", |_| false).is_ok());
    }
}
