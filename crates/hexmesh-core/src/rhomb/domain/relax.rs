//! Near misses (ours, before step 16's melting and our erosion): where the best ladder
//! misses the bounds by a little at a front corner (or gets no further than it, within what
//! it reached), the corner is first moved a little within the lattice triangles it keeps,
//! and the fill tried again from each place. Erosion alone turns near misses into large
//! ones: in case 16 of the domain fuzz (seed 20261123) a miss of 0.27° at a notch of the
//! front beside a reflex corner became, two erosions later, a hole the ladder missed by 80°,
//! and forty erosions followed. Moving first meshes case 3 of that campaign (fixture
//! `fuzz-seed20261123-case3-holes.poly`: a miss of 1.7° after one erosion), not yet case
//! 16; and case 11, which met the bounds by erosion alone, now takes another path and
//! fails. It is a search, not a construction.
//!
//! The ladder is solved piece by piece in order and reports the first piece it cannot join,
//! so a move that mends the corner's piece shows as a failure further on, often by more:
//! such a move is kept (`elsewhere`), where comparing the margins had put the corner back
//! (on fuzz case 14, with an earlier form of the graded band, a move of 0.3 side mended a
//! miss of 3.3° and was undone for a later piece's 5.1°). A near miss whose moves mend it
//! does not count against the band's limit of moved corners; one whose moves do not, does.

use super::cut::{Prepared, Segments};
use crate::geom::{angle_deg, orient2d, Point};
use crate::mesh::TriMesh;
use crate::quality::feature_gap::point_segment_distance;

/// Misses smaller than this (degrees) are tried with the corner moved before it is eroded
/// (a failure with no ladder past the corner counts by the best margin it reached).
pub const NEAR_MISS: f64 = 5.0;

/// How far inside the bounds (degrees) a kept triangle's angles stay once its corner moves.
const KEEP: f64 = 1.0;

/// The places to try for lattice vertex `v`: on twelve directions at a tenth to three
/// tenths of its side, where every kept triangle at `v` stays counter-clockwise with its
/// angles in [31°, 89°] and `v` stays at least half as far from every segment as it was.
pub fn places(mesh: &TriMesh, prep: &Prepared, segments: &Segments, v: u32) -> Vec<Point> {
    let at: Vec<[u32; 3]> = prep
        .triangles_at(v)
        .filter(|&t| prep.is_kept(t))
        .map(|t| mesh.triangles[t])
        .collect();
    let p = prep.position(v);
    let side = prep.side(v);
    let clearance = |q: Point| -> f64 {
        let r = 4.0 * side;
        segments
            .near([q[0] - r, q[1] - r, q[0] + r, q[1] + r])
            .into_iter()
            .map(|s| {
                let [a, b] = segments.ends[s as usize];
                point_segment_distance(q, a, b)
            })
            .fold(r, f64::min)
    };
    let before = clearance(p);
    let mut out = Vec::new();
    for r in [0.1, 0.2, 0.3] {
        for k in 0..12 {
            let theta = (k as f64 * 30.0).to_radians();
            let q = [p[0] + r * side * theta.cos(), p[1] + r * side * theta.sin()];
            let in_bounds = at.iter().all(|tri| {
                let c = tri.map(|w| if w == v { q } else { prep.position(w) });
                orient2d(c[0], c[1], c[2]) > 0.0
                    && (0..3).all(|i| {
                        let a = angle_deg(c[(i + 1) % 3], c[i], c[(i + 2) % 3]);
                        (30.0 + KEEP..=90.0 - KEEP).contains(&a)
                    })
            });
            if in_bounds && clearance(q) >= 0.5 * before {
                out.push(q);
            }
        }
    }
    out
}

/// How far (in `v`'s lattice sides) a failure must lie from a moved corner `v` for the move to
/// count as mending `v`'s piece of the ladder.
const ELSEWHERE: f64 = 6.0;

/// Whether lattice vertex `w`, where a fill failed after `v` moved, lies beyond `ELSEWHERE`
/// of `v`'s sides from it, taken as beyond the pieces of the ladder that hold `v` (a piece
/// spans the front corners between two rungs, a side or two apart; a failing piece merged
/// with its neighbours spans a few more). A failure nearer, or at `v` itself, is the move's
/// own result and is compared by its margin.
pub fn elsewhere(prep: &Prepared, v: u32, w: u32) -> bool {
    let (p, q) = (prep.position(v), prep.position(w));
    w != v && crate::geom::dist(p, q) > ELSEWHERE * prep.side(v)
}
