//! The `spade` reference mesher: spade 2.15.1's constrained Delaunay triangulation and its
//! Delaunay refinement (Ruppert 1995 / Chew 1993 style, `ConstrainedDelaunayTriangulation::
//! refine`), run on the domain of the paper's Sec. 8 comparison (`Pslg::reference_domain`).
//!
//! Angle limit: spade refines a triangle when circumradius / shortest edge exceeds a limit
//! and `AngleLimit::from_deg(θ)` sets that limit to 1/(2 sin θ). By the law of sines the
//! shortest edge of a triangle with smallest angle α is 2R sin α, so R/ℓ_min = 1/(2 sin α) and
//! the limit refines exactly the triangles with α < θ: `from_deg` needs no correction.
//!
//! Domain: spade's `exclude_outer_faces` peels layers of faces between segments, alternately
//! outer and inner, while Triangle's rule, which ours follows, removes the outside plus the regions
//! around hole seeds. Spade's exclusion is used during refinement only when it excludes
//! nothing this rule keeps (otherwise kept faces would go unrefined): it is tried when no
//! face an even number of crossings deep is kept, and its `excluded_faces` are checked after
//! the refinement, which runs again without it when they hold a kept face. (Its peeling puts
//! a face reachable both with and without crossing a segment into two layers: around an
//! interior slit it excludes the whole square.) The output is always cut by this rule, with a
//! flood fill across non-segment edges.
//!
//! Budget: one spade step inserts one vertex, so `max_steps` and `max_vertices` (minus the
//! initial vertices) both become `max_additional_vertices`, the smaller one winning; an
//! exhausted budget is `complete == false` (spade's `refinement_complete`). Spade has no
//! clock: `max_time` is left to `isolate::run_isolated`'s timeout. Spade panics (it asserts
//! and expects inside `refine`) are caught and returned as this mesher's error.

use std::collections::VecDeque;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use spade::handles::{FixedFaceHandle, InnerTag};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, PositionInTriangulation,
    RefinementParameters, Triangulation,
};

use super::check_params;
use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params, StopReason};
use crate::quality::Bounds;

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

const NAME: &str = "spade";

/// Spade's default minimum angle when none is requested (`RefinementParameters::new`).
pub const DEFAULT_MIN_ANGLE: f64 = 30.0;

/// The vertex budget when `Params` sets none: spade's own default of 10 × the initial vertex
/// count, raised to at least this many. Spade's default alone stops small inputs early
/// (8 points of a square with a hole may add only 80 vertices, too few for an area bound),
/// which would count as a failure that is the budget's, not the algorithm's.
pub const MIN_DEFAULT_EXTRA_VERTICES: usize = 1_000_000;

/// spade's refinement as a `Mesher`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SpadeMesher;

/// The spade parameters one call uses, resolved from `Params` and the input size.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Effective {
    min_angle: f64,
    max_area: Option<f64>,
    /// `None`: no budget in `Params`, so the default (see `default_extra_vertices`).
    max_additional_vertices: Option<usize>,
}

/// Which budget a refinement that added `limit` vertices to `initial` ran out of: the step
/// budget when it is what bounded `limit`, otherwise the vertex budget (the caller's or the
/// default one), counted in vertices of the whole mesh.
fn stop_reason(params: &Params, initial: usize, limit: usize) -> StopReason {
    match params.budget.max_steps {
        Some(steps) if usize::try_from(steps).is_ok_and(|s| s == limit) => StopReason::Steps(steps),
        _ => StopReason::Vertices(initial + limit),
    }
}

fn effective(params: &Params, initial_vertices: Option<usize>) -> Effective {
    let by_vertices = params
        .budget
        .max_vertices
        .map(|max| match initial_vertices {
            Some(n) => max.saturating_sub(n),
            None => max,
        });
    // One refinement step of spade inserts one vertex.
    let by_steps = params
        .budget
        .max_steps
        .map(|s| usize::try_from(s).unwrap_or(usize::MAX));
    let max_additional_vertices = match (by_vertices, by_steps) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    Effective {
        min_angle: params.min_angle.unwrap_or(DEFAULT_MIN_ANGLE),
        max_area: params.max_area,
        max_additional_vertices,
    }
}

impl Mesher for SpadeMesher {
    fn name(&self) -> &'static str {
        NAME
    }

    fn version(&self) -> String {
        "spade 2.15.1".to_string()
    }

    fn settings(&self, params: &Params) -> String {
        let e = effective(params, None);
        let ratio = AngleLimit::from_deg(e.min_angle).radius_to_shortest_edge_limit();
        let area = match e.max_area {
            Some(a) => format!("max_allowed_area={a}"),
            None => "max_allowed_area=none".to_string(),
        };
        let budget = match (params.budget.max_vertices, params.budget.max_steps) {
            (Some(v), Some(s)) => {
                format!("max_additional_vertices=min({v} - initial vertices, {s})")
            }
            (Some(v), None) => format!("max_additional_vertices={v} - initial vertices"),
            (None, Some(s)) => format!("max_additional_vertices={s}"),
            (None, None) => format!(
                "max_additional_vertices=max(10*initial vertices, {MIN_DEFAULT_EXTRA_VERTICES})"
            ),
        };
        let time = if params.budget.max_time.is_some() {
            "; time budget not enforced in-process (use isolation)"
        } else {
            ""
        };
        format!(
            "angle_limit=from_deg({}) (R/l_min <= {ratio:.6}); {area}; {budget}; \
             exclude_outer_faces when it matches the domain; keep_constraint_edges=false{time}",
            e.min_angle
        )
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        super::asked_angle(self.name(), params, DEFAULT_MIN_ANGLE).with_area_limits(params.max_area)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        // Every mesher checks its input (`Pslg::check`): segments that enclose no region,
        // and a segment or point outside the region, are refused here as by ours.
        input.validate_input()?;
        check_params(NAME, params)?;
        params.refuse_max_edge(
            NAME,
            "spade's refinement bounds areas and angles, not edge lengths; ask for --max-area \
             instead",
        )?;
        // The regions' area limits are kept with the smallest of them everywhere.
        let params = &Params {
            max_area: input.smallest_area_limit(params.max_area),
            ..params.clone()
        };
        let domain = input.reference_domain();
        let start = Instant::now();
        // spade asserts and expects inside its refinement (e.g. a circumcentre it cannot
        // insert for loss of precision); such a panic becomes this mesher's error.
        let outcome = catch_unwind(AssertUnwindSafe(|| mesh_domain(&domain, params)));
        let elapsed = start.elapsed();
        let (mesh, complete, stop_reason, steps) = match outcome {
            Ok(r) => r?,
            Err(payload) => {
                let text = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown panic".to_string());
                return Err(Error::mesher(NAME, format!("spade panicked: {text}")));
            }
        };
        Ok(MeshRun {
            mesh,
            complete,
            stop_reason,
            steps,
            elapsed,
        })
    }
}

fn default_extra_vertices(initial: usize) -> usize {
    initial.saturating_mul(10).max(MIN_DEFAULT_EXTRA_VERTICES)
}

type Outcome = (TriMesh, bool, Option<StopReason>, u64);

fn mesh_domain(domain: &Pslg, params: &Params) -> Result<Outcome> {
    let vertices: Vec<Point2<f64>> = domain
        .points
        .iter()
        .map(|p| Point2::new(p[0], p[1]))
        .collect();
    let edges: Vec<[usize; 2]> = domain
        .segments
        .iter()
        .map(|s| [s[0] as usize, s[1] as usize])
        .collect();
    let mut cdt = Cdt::bulk_load_cdt(vertices, edges).map_err(|e| {
        Error::mesher(
            NAME,
            format!("spade refused the input points: {e:?} (coordinates out of spade's range)"),
        )
    })?;
    if cdt.num_vertices() != domain.points.len() {
        return Err(Error::mesher(
            NAME,
            "spade merged input points it considers equal",
        ));
    }
    let seeds = locate_seeds(&cdt, &domain.holes, true)?;
    let removed = removed_faces(&cdt, &seeds);
    let parity_outer = crossing_depth(&cdt)
        .iter()
        .enumerate()
        .skip(1)
        .any(|(f, d)| d % 2 == 0 && !removed[f]);
    // Spade's own exclusion may be used only if it excludes nothing the domain keeps.
    let exclude = !parity_outer;

    let initial = cdt.num_vertices();
    let e = effective(params, Some(initial));
    let limit = e
        .max_additional_vertices
        .unwrap_or_else(|| default_extra_vertices(initial));
    let parameters = |exclude: bool| {
        let mut rp = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(e.min_angle))
            .exclude_outer_faces(exclude);
        if let Some(a) = e.max_area {
            rp = rp.with_max_allowed_area(a);
        }
        rp.with_max_additional_vertices(limit)
    };
    let unrefined = exclude.then(|| cdt.clone());
    let mut result = cdt.refine(parameters(exclude));
    let mut removed = removed_faces(&cdt, &locate_seeds(&cdt, &domain.holes, false)?);
    if let Some(fresh) = unrefined {
        // Spade's peeling is not the crossing parity tested above; where it left out a face
        // the domain keeps, that face went unrefined: refine again without the exclusion.
        if result.excluded_faces.iter().any(|f| !removed[f.index()]) {
            cdt = fresh;
            result = cdt.refine(parameters(false));
            removed = removed_faces(&cdt, &locate_seeds(&cdt, &domain.holes, false)?);
        }
    }
    let added = cdt.num_vertices() - initial;
    let mesh = extract(&cdt, &removed, domain.points.len());
    let stop_reason = (!result.refinement_complete).then(|| stop_reason(params, initial, limit));
    Ok((mesh, result.refinement_complete, stop_reason, added as u64))
}

/// The inner face containing each hole seed. Before refinement (`strict`), a seed on a vertex
/// or on a segment is refused: the region it names is ambiguous. Seeds outside the convex
/// hull name nothing to remove and are skipped.
fn locate_seeds(
    cdt: &Cdt,
    holes: &[[f64; 2]],
    strict: bool,
) -> Result<Vec<FixedFaceHandle<InnerTag>>> {
    let mut faces = Vec::with_capacity(holes.len());
    for (i, h) in holes.iter().enumerate() {
        let ambiguous = |what: &str| {
            Error::mesher(
                NAME,
                format!("hole {i} at ({}, {}) lies on {what}", h[0], h[1]),
            )
        };
        match cdt.locate(Point2::new(h[0], h[1])) {
            PositionInTriangulation::OnFace(f) => faces.push(f),
            PositionInTriangulation::OnEdge(e) => {
                let e = cdt.directed_edge(e);
                if strict && e.is_constraint_edge() {
                    return Err(ambiguous("a segment"));
                }
                if let Some(f) = e.face().as_inner().or_else(|| e.rev().face().as_inner()) {
                    faces.push(f.fix());
                }
            }
            PositionInTriangulation::OnVertex(v) => {
                if strict {
                    return Err(ambiguous("an input point"));
                }
                // A Steiner vertex off every segment: all faces around it share a region.
                if let Some(f) = cdt.vertex(v).out_edges().find_map(|e| e.face().as_inner()) {
                    faces.push(f.fix());
                }
            }
            PositionInTriangulation::OutsideOfConvexHull(_)
            | PositionInTriangulation::NoTriangulation => {}
        }
    }
    Ok(faces)
}

/// Faces outside the domain, indexed by face index: those reachable from the unbounded face
/// and those reachable from a hole seed, in both cases without crossing a segment.
fn removed_faces(cdt: &Cdt, seeds: &[FixedFaceHandle<InnerTag>]) -> Vec<bool> {
    let mut removed = vec![false; cdt.num_all_faces()];
    let mut queue: VecDeque<FixedFaceHandle<InnerTag>> = VecDeque::new();
    for e in cdt.convex_hull() {
        let inside = e.rev();
        if !inside.is_constraint_edge() {
            if let Some(f) = inside.face().as_inner() {
                queue.push_back(f.fix());
            }
        }
    }
    queue.extend(seeds.iter().copied());
    while let Some(f) = queue.pop_front() {
        if removed[f.index()] {
            continue;
        }
        removed[f.index()] = true;
        for e in cdt.face(f).adjacent_edges() {
            if e.is_constraint_edge() {
                continue;
            }
            if let Some(g) = e.rev().face().as_inner() {
                if !removed[g.index()] {
                    queue.push_back(g.fix());
                }
            }
        }
    }
    removed
}

/// The least number of segments crossed on a path from the unbounded face to each face
/// (0-1 breadth-first search); index 0, the unbounded face itself, gets 0. Spade's
/// `exclude_outer_faces` peels exactly the faces at even depth.
fn crossing_depth(cdt: &Cdt) -> Vec<u32> {
    let mut depth = vec![u32::MAX; cdt.num_all_faces()];
    depth[0] = 0;
    let mut deque: VecDeque<(FixedFaceHandle<InnerTag>, u32)> = VecDeque::new();
    for e in cdt.convex_hull() {
        let inside = e.rev();
        if let Some(f) = inside.face().as_inner() {
            let d = u32::from(inside.is_constraint_edge());
            if d == 0 {
                deque.push_front((f.fix(), 0));
            } else {
                deque.push_back((f.fix(), 1));
            }
        }
    }
    while let Some((f, d)) = deque.pop_front() {
        if d >= depth[f.index()] {
            continue;
        }
        depth[f.index()] = d;
        for e in cdt.face(f).adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner() {
                let step = u32::from(e.is_constraint_edge());
                let nd = d + step;
                if nd < depth[g.index()] {
                    if step == 0 {
                        deque.push_front((g.fix(), nd));
                    } else {
                        deque.push_back((g.fix(), nd));
                    }
                }
            }
        }
    }
    depth
}

/// The kept faces as a `TriMesh`: the input vertices first in input order (spade's bulk load
/// keeps the order and the bits), then the Steiner vertices that kept faces use.
fn extract(cdt: &Cdt, removed: &[bool], n_input: usize) -> TriMesh {
    let mut index: Vec<u32> = vec![u32::MAX; cdt.num_vertices()];
    let mut vertices: Vec<[f64; 2]> = Vec::with_capacity(cdt.num_vertices());
    for v in cdt.vertices().take(n_input) {
        let p = v.position();
        index[v.fix().index()] = vertices.len() as u32;
        vertices.push([p.x, p.y]);
    }
    let mut triangles = Vec::with_capacity(cdt.num_inner_faces());
    for f in cdt.inner_faces() {
        if removed[f.fix().index()] {
            continue;
        }
        let mut tri = [0u32; 3];
        for (k, v) in f.vertices().iter().enumerate() {
            let slot = &mut index[v.fix().index()];
            if *slot == u32::MAX {
                let p = v.position();
                *slot = vertices.len() as u32;
                vertices.push([p.x, p.y]);
            }
            tri[k] = *slot;
        }
        triangles.push(tri);
    }
    TriMesh {
        vertices,
        triangles,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_deg_is_the_law_of_sines_ratio() {
        for deg in [20.0f64, 30.0, 33.0] {
            let r = AngleLimit::from_deg(deg).radius_to_shortest_edge_limit();
            assert!((r - 0.5 / deg.to_radians().sin()).abs() < 1e-15);
        }
    }

    #[test]
    fn vertex_budget_is_the_smaller_of_steps_and_vertices() {
        let mut p = Params::default().with_min_angle(25.0);
        p.budget.max_vertices = Some(100);
        p.budget.max_steps = Some(50);
        assert_eq!(effective(&p, Some(70)).max_additional_vertices, Some(30));
        p.budget.max_vertices = None;
        assert_eq!(effective(&p, Some(70)).max_additional_vertices, Some(50));
        assert_eq!(
            effective(&Params::default(), Some(7)).max_additional_vertices,
            None
        );
    }

    #[test]
    fn an_unseeded_inner_loop_is_meshed_and_refined() {
        // A square inside a square without a hole seed: spade's parity rule would skip the
        // inner square, the domain rule keeps it.
        let input = Pslg {
            points: vec![
                [0.0, 0.0],
                [4.0, 0.0],
                [4.0, 4.0],
                [0.0, 4.0],
                [1.0, 1.0],
                [3.0, 1.0],
                [3.0, 3.0],
                [1.0, 3.0],
            ],
            segments: vec![
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [4, 5],
                [5, 6],
                [6, 7],
                [7, 4],
            ],
            ..Pslg::default()
        };
        let run = SpadeMesher
            .mesh(&input, &Params::default().with_min_angle(25.0))
            .expect("mesh");
        assert!(run.complete);
        assert!((run.mesh.area() - 16.0).abs() < 1e-9);
    }

    #[test]
    fn a_square_with_an_interior_slit_is_refined_to_the_requested_angle() {
        // Spade's peeling puts every face of this square in two layers and excludes them
        // all: without the check after refinement, the six triangles of the constrained
        // Delaunay triangulation came back unrefined (smallest angle 21.8°).
        let input = Pslg {
            points: vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.25, 0.375],
                [0.75, 0.625],
            ],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0], [4, 5]],
            ..Pslg::default()
        };
        let run = SpadeMesher
            .mesh(&input, &Params::default().with_min_angle(30.0))
            .expect("mesh");
        assert!(run.complete);
        assert!(run.mesh.triangles.len() > 6, "{}", run.mesh.triangles.len());
        let m = crate::quality::metrics(&run.mesh, Some(&input));
        let min = m.min_angle.map_or(0.0, |w| w.value);
        assert!(min >= 30.0 - 1e-6, "{min}");
        assert!((run.mesh.area() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_hole_seed_on_a_segment_is_refused() {
        // On the diagonal of a square inside a square (a seed on the boundary would empty
        // the domain, which `Pslg::check` refuses before spade sees the seed).
        let input = crate::io::read_input(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("tests/fixtures/refs/hole_seed_on_inner_diagonal.poly"),
        )
        .expect("fixture");
        let err = SpadeMesher.mesh(&input, &Params::default()).unwrap_err();
        assert!(err.to_string().contains("hole 0"), "{err}");
    }
}
