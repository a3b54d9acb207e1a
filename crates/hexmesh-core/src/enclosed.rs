//! The region a PSLG's segments enclose, by Triangle's .poly semantics (Triangle 1.6
//! documentation, ".poly files" and the `-c` switch): the constrained Delaunay triangulation of
//! the points and segments ([`triangulate`]) minus the triangles reachable from its convex
//! hull's boundary without crossing a segment and those reachable from a hole seed
//! ([`carve`]).
//!
//! Every mesher that takes segments meshes this region, so an input is refused before any
//! of them runs (`Pslg::check`, through [`Pslg::check_enclosed`]) when the region is empty
//! (`InputError::NoEnclosedRegion`), when a segment lies outside it or in a hole
//! (`SegmentOutsideDomain`: Triangle drops such a segment without a word, and a mesh that
//! does is not conforming), or when a point on no segment does (`PointOutsideDomain`: it
//! cannot be a vertex of the mesh). [`Pslg::with_convex_hull`] adds the convex hull's edges
//! as segments (Triangle's `-c`), so that every mesher meshes the hull minus the holes. The
//! refinement meshers start from the same triangulation and carving (`refine::domain_cdt`).

use std::collections::{HashMap, HashSet};

use spade::{ConstrainedDelaunayTriangulation, InsertionError, Point2, Triangulation};

use crate::error::{InputError, Unenclosed};
use crate::geom::{orient2d, scale_exponent, scale_point, Point};
use crate::mesh::Pslg;

/// Undirected edge key: the smaller vertex first.
pub(crate) fn ekey(a: u32, b: u32) -> (u32, u32) {
    if a < b {
        (a, b)
    } else {
        (b, a)
    }
}

/// spade refuses coordinates of magnitude below 2^-142 (its exact predicates could underflow);
/// such a coordinate is indistinguishable from zero at any scale f64 can mesh.
pub(crate) fn to_spade(p: Point) -> Point2<f64> {
    spade::mitigate_underflow(Point2::new(p[0], p[1]))
}

/// Why spade could not triangulate a PSLG faithfully.
#[derive(Debug)]
pub(crate) enum CdtFailure {
    /// spade refused a vertex.
    Insertion(InsertionError),
    /// The segment between these two points conflicts with another segment.
    Conflict([usize; 2]),
    /// Two points coincide once tiny coordinates are flushed to zero.
    Coincide,
}

/// The counter-clockwise triangles of the constrained Delaunay triangulation of `points` with
/// the constraint edges `segments` (which must neither cross nor pass through a point, as
/// `Pslg::check` ensures), as indices into `points`.
pub(crate) fn triangulate(
    points: &[Point],
    segments: &[[u32; 2]],
) -> Result<Vec<[u32; 3]>, CdtFailure> {
    let pts: Vec<Point2<f64>> = points.iter().map(|&p| to_spade(p)).collect();
    let edges: Vec<[usize; 2]> = segments
        .iter()
        .map(|s| [s[0] as usize, s[1] as usize])
        .collect();
    let mut conflict = None;
    let cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(pts, edges, |e| {
        conflict.get_or_insert(e);
    })
    .map_err(CdtFailure::Insertion)?;
    if let Some(pair) = conflict {
        return Err(CdtFailure::Conflict(pair));
    }
    if cdt.num_vertices() != points.len() {
        return Err(CdtFailure::Coincide);
    }
    // spade's vertex handles count insertions from 0: the index is the input order.
    Ok(cdt
        .inner_faces()
        .map(|f| f.vertices().map(|v| v.fix().index() as u32))
        .collect())
}

/// Keeps the triangles inside the domain (Triangle's convention for `.poly` files): triangles
/// reachable from the convex hull without crossing a segment are outside, and so are those
/// reachable from a hole seed. `barriers` holds the segment edges as undirected keys.
/// The flood runs in index order, so the result does not depend on hash order.
pub(crate) fn carve(
    vertices: &[Point],
    triangles: &[[u32; 3]],
    barriers: &HashSet<(u32, u32)>,
    holes: &[Point],
) -> Vec<[u32; 3]> {
    let mut by_edge: HashMap<(u32, u32), usize> = HashMap::with_capacity(triangles.len() * 3);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            by_edge.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let mut outside = vec![false; triangles.len()];
    let mut stack: Vec<usize> = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if !by_edge.contains_key(&(b, a)) && !barriers.contains(&ekey(a, b)) && !outside[t] {
                outside[t] = true;
                stack.push(t);
            }
        }
    }
    for &h in holes {
        let hit = triangles.iter().position(|tri| {
            let [a, b, c] = tri.map(|v| vertices[v as usize]);
            orient2d(a, b, h) >= 0.0 && orient2d(b, c, h) >= 0.0 && orient2d(c, a, h) >= 0.0
        });
        if let Some(t) = hit {
            if !outside[t] {
                outside[t] = true;
                stack.push(t);
            }
        }
    }
    while let Some(t) = stack.pop() {
        let tri = triangles[t];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if barriers.contains(&ekey(a, b)) {
                continue;
            }
            if let Some(&n) = by_edge.get(&(b, a)) {
                if !outside[n] {
                    outside[n] = true;
                    stack.push(n);
                }
            }
        }
    }
    triangles
        .iter()
        .zip(&outside)
        .filter(|(_, &o)| !o)
        .map(|(t, _)| *t)
        .collect()
}

/// `points` scaled by the one power of two that brings the largest coordinate into [1, 2):
/// exact, so every orientation keeps its sign, and no coordinate of a PSLG that `Pslg::check`
/// accepts is flushed by [`to_spade`] unless it is below 2^-142 of the largest.
fn scaled(points: &[Point], k: i32) -> Vec<Point> {
    points.iter().map(|&p| scale_point(p, -k)).collect()
}

/// The input's scale exponent (`scale_exponent` of every point coordinate).
fn exponent_of(points: &[Point]) -> i32 {
    let coords: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
    scale_exponent(&coords)
}

/// The boundary of the convex hull of `points`, counter-clockwise from the lowest-leftmost
/// point, with every point that lies on it (a point in the middle of a hull edge splits it),
/// decided with exact orientations; `None` when all points lie on one line (no hull area).
fn hull_boundary(points: &[Point]) -> Option<Vec<u32>> {
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    order.sort_by(|&a, &b| {
        let (p, q) = (points[a as usize], points[b as usize]);
        p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
    });
    let turn = |a: u32, b: u32, c: u32| {
        orient2d(points[a as usize], points[b as usize], points[c as usize])
    };
    // Andrew's monotone chain keeping collinear points: pop only at a strict right turn.
    let chain = |seq: &mut dyn Iterator<Item = u32>| {
        let mut out: Vec<u32> = Vec::new();
        for v in seq {
            while out.len() >= 2 && turn(out[out.len() - 2], out[out.len() - 1], v) < 0.0 {
                out.pop();
            }
            out.push(v);
        }
        out
    };
    // The first and last in this order are distinct (no duplicate points) and on the hull:
    // every point lies on their line exactly when there is no hull area.
    let (&first, &last) = (order.first()?, order.last()?);
    if order.iter().all(|&v| turn(first, last, v) == 0.0) {
        return None;
    }
    let mut lower = chain(&mut order.iter().copied());
    let mut upper = chain(&mut order.iter().rev().copied());
    lower.pop();
    upper.pop();
    lower.extend(upper);
    Some(lower)
}

impl Pslg {
    /// This PSLG with the edges of its points' convex hull added as segments (Triangle's `-c`),
    /// so that the region to mesh is the hull minus the holes. Hull edges are split at every
    /// input point on the hull (exact orientations, collinear points included), a hull edge
    /// that is already a segment is not added twice, and the new segments come after the
    /// input's (marker 0 when the input has segment markers), so that every input segment
    /// keeps its index. A point set (no segments) comes back unchanged: its domain is its
    /// bounding hexagon, which holds the hull. So does a PSLG whose points all lie on one line,
    /// which has no hull area (`check` refuses it).
    pub fn with_convex_hull(&self) -> Pslg {
        let mut out = self.clone();
        if !self.has_segments() {
            return out;
        }
        let k = exponent_of(&self.points);
        let Some(hull) = hull_boundary(&scaled(&self.points, k)) else {
            return out;
        };
        let mut present: HashSet<(u32, u32)> =
            self.segments.iter().map(|s| ekey(s[0], s[1])).collect();
        for (i, &a) in hull.iter().enumerate() {
            let b = hull[(i + 1) % hull.len()];
            if present.insert(ekey(a, b)) {
                out.segments.push([a, b]);
                if let Some(m) = &mut out.labels.segment_markers {
                    m.push(0);
                }
            }
        }
        out
    }

    /// Refuses a PSLG whose segments do not enclose what they must (module docs): no region at
    /// all (`NoEnclosedRegion`), the first segment outside the region or in a hole
    /// (`SegmentOutsideDomain`), the first point outside it (`PointOutsideDomain`). A point
    /// set passes (its domain is its bounding hexagon). Expects the rest of `check` passed
    /// (no crossing segments, no point inside a segment); an input that spade cannot
    /// triangulate faithfully even scaled (points within 2^-142 of the coordinates of one
    /// another, which every mesher refuses for precision) passes this part undecided.
    pub fn check_enclosed(&self) -> Result<(), InputError> {
        if !self.has_segments() {
            return Ok(());
        }
        let k = exponent_of(&self.points);
        let points = scaled(&self.points, k);
        let holes = scaled(&self.holes, k);
        let Ok(triangles) = triangulate(&points, &self.segments) else {
            return Ok(());
        };
        let unenclosed = |cause| InputError::NoEnclosedRegion {
            segments: self.segments.len(),
            cause,
        };
        if triangles.is_empty() {
            return Err(unenclosed(Unenclosed::Collinear));
        }
        let barriers: HashSet<(u32, u32)> =
            self.segments.iter().map(|s| ekey(s[0], s[1])).collect();
        let kept = carve(&points, &triangles, &barriers, &holes);
        if kept.is_empty() {
            let without_holes = carve(&points, &triangles, &barriers, &[]);
            return Err(unenclosed(if without_holes.is_empty() {
                Unenclosed::Open
            } else {
                Unenclosed::Holes
            }));
        }
        let edges: HashSet<(u32, u32)> = kept
            .iter()
            .flat_map(|t| (0..3).map(move |i| ekey(t[i], t[(i + 1) % 3])))
            .collect();
        if let Some(segment) = self
            .segments
            .iter()
            .position(|s| !edges.contains(&ekey(s[0], s[1])))
        {
            return Err(InputError::SegmentOutsideDomain { segment });
        }
        let mut used = vec![false; self.points.len()];
        for &v in kept.iter().flatten() {
            used[v as usize] = true;
        }
        match used.iter().position(|&u| !u) {
            Some(point) => Err(InputError::PointOutsideDomain { point }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pslg(points: &[Point], segments: &[[u32; 2]], holes: &[Point]) -> Pslg {
        Pslg {
            points: points.to_vec(),
            segments: segments.to_vec(),
            holes: holes.to_vec(),
            ..Pslg::default()
        }
    }

    const SQUARE: [Point; 4] = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
    const RING: [[u32; 2]; 4] = [[0, 1], [1, 2], [2, 3], [3, 0]];

    #[test]
    fn an_open_polyline_encloses_no_region() {
        let p = pslg(
            &[[0.0, 0.0], [1.0, 0.1], [0.4, 0.6]],
            &[[0, 1], [1, 2]],
            &[],
        );
        assert_eq!(
            p.check_enclosed(),
            Err(InputError::NoEnclosedRegion {
                segments: 2,
                cause: Unenclosed::Open
            })
        );
        let e = p.check_enclosed().unwrap_err().describe(1);
        assert!(
            e.starts_with("the segments enclose no region: ")
                && e.contains("(1 to 2)")
                && e.contains("--convex-hull"),
            "{e}"
        );
    }

    #[test]
    fn a_square_encloses_its_inside_and_a_seed_inside_empties_it() {
        assert_eq!(pslg(&SQUARE, &RING, &[]).check_enclosed(), Ok(()));
        assert_eq!(
            pslg(&SQUARE, &RING, &[[1.0, 1.0]]).check_enclosed(),
            Err(InputError::NoEnclosedRegion {
                segments: 4,
                cause: Unenclosed::Holes
            })
        );
        // A seed outside the square changes nothing.
        assert_eq!(pslg(&SQUARE, &RING, &[[9.0, 1.0]]).check_enclosed(), Ok(()));
    }

    #[test]
    fn collinear_points_enclose_nothing_even_with_their_hull() {
        let p = pslg(&[[0.0, 0.0], [1.0, 1.0], [3.0, 3.0]], &[[0, 1]], &[]);
        let want = Err(InputError::NoEnclosedRegion {
            segments: 1,
            cause: Unenclosed::Collinear,
        });
        assert_eq!(p.check_enclosed(), want);
        assert_eq!(p.with_convex_hull(), p);
    }

    #[test]
    fn a_point_set_keeps_its_bounding_hexagon_and_gets_no_hull() {
        let p = pslg(&SQUARE, &[], &[]);
        assert_eq!(p.check_enclosed(), Ok(()));
        assert_eq!(p.with_convex_hull(), p);
    }

    #[test]
    fn a_segment_or_a_point_beyond_the_boundary_is_outside_the_domain() {
        let mut p = pslg(&SQUARE, &RING, &[]);
        p.points.extend([[6.0, 1.0], [7.0, 2.0], [0.5, 0.5]]);
        p.segments.push([4, 5]);
        assert_eq!(
            p.check_enclosed(),
            Err(InputError::SegmentOutsideDomain { segment: 4 })
        );
        // Inside the square, the same segment is a slit of the domain.
        p.points[4] = [2.0, 1.0];
        p.points[5] = [3.0, 2.0];
        assert_eq!(p.check_enclosed(), Ok(()));
        p.points.push([5.0, 5.0]);
        assert_eq!(
            p.check_enclosed(),
            Err(InputError::PointOutsideDomain { point: 7 })
        );
    }

    #[test]
    fn a_segment_in_a_hole_is_outside_the_domain() {
        let mut p = pslg(&SQUARE, &RING, &[[2.0, 2.0]]);
        p.points
            .extend([[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0], [1.5, 2.0]]);
        p.segments.extend([[4, 5], [5, 6], [6, 7], [7, 4], [8, 4]]);
        assert_eq!(
            p.check_enclosed(),
            Err(InputError::SegmentOutsideDomain { segment: 8 })
        );
    }

    #[test]
    fn the_convex_hull_closes_an_open_polyline_keeping_its_segments_first() {
        let mut p = pslg(
            &[[0.0, 0.0], [1.0, 0.1], [0.4, 0.6], [0.5, -0.4]],
            &[[0, 1], [1, 2]],
            &[],
        );
        p.labels.segment_markers = Some(vec![7, 8]);
        let h = p.with_convex_hull();
        assert_eq!(&h.segments[..2], &p.segments[..]);
        // Hull 0 → 3 → 1 → 2 → 0; the hull edge 1-2 is already segment 1.
        assert_eq!(&h.segments[2..], &[[0, 3], [3, 1], [2, 0]]);
        assert_eq!(h.labels.segment_markers, Some(vec![7, 8, 0, 0, 0]));
        assert_eq!(h.check(), Ok(()));
    }

    #[test]
    fn points_on_the_hull_split_its_edges() {
        // A square with a point in the middle of every side and one more on the bottom, and
        // an interior point: every side point is a corner of the hull boundary.
        let points = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [2.0, 0.0],
            [4.0, 2.0],
            [2.0, 4.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [1.0, 1.0],
        ];
        let p = pslg(&points, &[[9, 5]], &[]);
        let h = p.with_convex_hull();
        assert_eq!(
            &h.segments[1..],
            &[
                [0, 8],
                [8, 4],
                [4, 1],
                [1, 5],
                [5, 2],
                [2, 6],
                [6, 3],
                [3, 7],
                [7, 0]
            ]
        );
        assert_eq!(h.check(), Ok(()));
    }
}
