//! `rhomb`: the rhomboidal quad-tree mesher of Neugebauer & Diekmann, "Improved Mesh Generation:
//! Not Simple but Good" (paper 001), for point sets inside their bounding hexagon and for
//! polygonal domains.
//!
//! Steps (paper Sec. 4): root rhomb (`lattice`), split crowded rhombs with 2:1 balance (`tree`,
//! steps 1–3), centre every point in a patch of melted rhombs (`centring`, steps 4–5, Sec. 5.4),
//! triangulate rhombs by the fixed patterns and the patches (`patterns`, steps 10 and 12).
//! Promise on point sets: every angle in [30°, 90°]; the mesh covers the bounding hexagon;
//! every input point is a vertex bit-exactly (vertex i is input point i); the six hexagon
//! corners are vertices. Refused: points closer than 2^-48 of the hexagon (the lattice depth)
//! and inputs whose triangles f64 output would move beyond the bounds by more than
//! `--max-rounding` (see `rounding_check`). A point that is a lattice vertex of the hexagon's
//! edge bit for bit (on the edge in real arithmetic, rounding left it just inside) is meshed
//! as that vertex (`Frame::boundary_vertex`). Budgets: a step is one rhomb split; the vertex
//! budget counts rhombs (about one output vertex each). A run stopped by a budget returns the
//! balanced tree's triangulation without the input points (`complete == false`), which still
//! meets the angle bounds.
//!
//! Inputs with segments are polygonal domains (`domain`, Sec. 3–5): one or more outer
//! polygons, polygonal holes and single interior points; every angle in [30°, 90°] but at an
//! input corner sharper than 30°, which is kept whole. What the paper does not permit (a
//! segment inside the domain, a dangling one, crossing ones) is refused by name. A budget
//! stops a domain with its reason and no mesh.
//!
//! Size (ours): `Params::max_area` (with the regions' smallest area limit) and
//! `Params::max_edge` are kept on point sets by splitting every rhomb coarser than the level
//! whose triangles respect both (`size_level`) and every patch whose triangles could exceed
//! either (`centring::Patch::area_factor`, `edge_factor`); with segments they are refused.

mod centring;
mod domain;
#[cfg(test)]
mod fixtures;
mod lattice;
mod patterns;
mod tree;

use std::time::Instant;

use crate::error::{Error, InputError, Result};
use crate::mesh::Pslg;
use crate::mesher::{MeshRun, Mesher, Params};
use crate::quality::Bounds;

use lattice::Frame;
use tree::{Guard, Stop, Tree};

/// The rhomboidal quad-tree mesher (paper 001): point sets and polygonal domains.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rhomb;

const NAME: &str = "rhomb";

impl Mesher for Rhomb {
    fn name(&self) -> &'static str {
        NAME
    }

    fn version(&self) -> String {
        format!("hexmesh {}", env!("CARGO_PKG_VERSION"))
    }

    fn settings(&self, params: &Params) -> String {
        let mut s = String::from("window x=5; melted centring patches; bounds 30-90 deg fixed");
        if let Some(a) = params.max_area {
            s.push_str(&format!("; max_area {a}"));
        }
        if let Some(l) = params.max_edge {
            s.push_str(&format!("; max_edge {l}"));
        }
        if params.min_angle.is_some() {
            s.push_str("; min_angle ignored");
        }
        s
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        // Every triangle, near segments too, but at input corners sharper than 30° taken
        // whole (paper 001's promise); the size limits on point sets (domains refuse them).
        Bounds {
            interior_only_on_segments: false,
            whole_sharp_corners: true,
            ..Bounds::angles(NAME, 30.0, 90.0).with_size_limits(params.max_area, params.max_edge)
        }
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        params.refuse_switches(self.name())?;
        let start = Instant::now();
        input.validate_input()?;
        if input.has_segments() {
            // The domain quad-tree has no size control yet: a limit is refused, not ignored.
            if let Some(a) = input.smallest_area_limit(params.max_area) {
                return Err(Error::mesher(
                    NAME,
                    format!(
                        "an input with segments is meshed without size control, so the area \
                         limit {a} cannot be kept: mesh the domain with triangle, cgal, spade, \
                         gmsh, lsb or hex, or drop the limit"
                    ),
                ));
            }
            params.refuse_max_edge(
                NAME,
                "an input with segments is meshed without size control",
            )?;
            return domain::mesh(input, params);
        }
        let hex = input.bounding_hexagon();
        if !(hex.circumradius.is_finite() && hex.circumradius > 0.0) {
            return Err(Error::mesher(
                NAME,
                format!("the bounding hexagon has circumradius {}", hex.circumradius),
            ));
        }
        if let Some(i) = input.points.iter().position(|&p| !hex.contains_strictly(p)) {
            return Err(Error::input(InputError::OutsideHexagon {
                index: i,
                point: input.points[i],
                fitted: input.hexagon.is_none(),
            }));
        }
        let frame = Frame::new(hex);
        let coords: Vec<[f64; 2]> = input.points.iter().map(|&p| frame.locate(p)).collect();
        let pins = input
            .points
            .iter()
            .zip(&coords)
            .map(|(&p, &st)| frame.boundary_vertex(p, st))
            .collect();
        // max_area in units of the root side 2R squared, max_edge in units of 2R, and the
        // coarsest level whose triangles respect both (`size_level`).
        let root_side = 2.0 * hex.circumradius;
        // The regions' area limits are kept with the smallest of them everywhere.
        let max_area = match input.smallest_area_limit(params.max_area) {
            None => None,
            Some(a) if a > 0.0 && a.is_finite() => Some(a / (root_side * root_side)),
            Some(a) => {
                return Err(Error::mesher(
                    NAME,
                    format!("max_area must be positive and finite, not {a}"),
                ))
            }
        };
        let max_edge = params.size_limits()?.1.map(|l| l / root_side);
        let area_level = size_level(max_area, max_edge);
        let mut tree = Tree::new(coords, area_level).with_pins(pins);
        let guard = Guard::new(params.budget);
        let n = input.points.len() as u32;
        let outcome = tree.split_crowded(&guard).and_then(|()| {
            centring::centre_points(
                &mut tree,
                &(0..n).collect::<Vec<u32>>(),
                (max_area, max_edge),
                &guard,
            )
        });
        let (patches, stop_reason) = match outcome {
            Ok(patches) => (patches, None),
            Err(Stop::Budget(reason)) => (Vec::new(), Some(reason)),
            // More levels than the lattice keys hold (`lattice::MAX_LEVEL`). When the closest
            // pair of the input, or a point and the hexagon's edge, lie within 2^8 rhombs of
            // that level, they forced it: a refusal naming them. Farther apart, closeness
            // does not explain the depth, and the error says so.
            Err(Stop::Depth) => return Err(depth_error(input, &hex, params)),
        };
        let mesh = patterns::triangulate(&tree, &frame, &input.points, &patches);
        rounding_check(&mesh, &input.points, params.max_rounding_deg())?;
        Ok(MeshRun {
            mesh,
            complete: stop_reason.is_none(),
            stop_reason,
            steps: tree.steps,
            elapsed: start.elapsed(),
        })
    }
}

/// The coarsest level whose triangles respect the size limits, both in units of the root side
/// (2R): a leaf of level k has side l = 2^-k, its equilateral halves area √3/4·l², and the
/// edges of its triangles (halves, the 30-60-90 triangles of a splitting point, the
/// quarters) are at most l long. Patches carry their own factors (`centring::Patch`).
fn size_level(max_area: Option<f64>, max_edge: Option<f64>) -> u8 {
    let mut level = 0u8;
    while level < lattice::MAX_LEVEL {
        let side = 0.5f64.powi(i32::from(level));
        let area_ok = max_area.is_none_or(|a| 3f64.sqrt() / 4.0 * side * side <= a);
        let edge_ok = max_edge.is_none_or(|l| side <= l);
        if area_ok && edge_ok {
            break;
        }
        level += 1;
    }
    level
}

/// Why the rhombs reached the lattice's deepest level (`Stop::Depth`): the closest pair of
/// input points, or the point nearest the hexagon's edge, when either is within 2^8 rhombs of
/// that level; otherwise a defect of the splitting rules, reported as such.
fn depth_error(input: &Pslg, hex: &crate::geom::Hexagon, params: &Params) -> Error {
    let deepest = 2.0 * hex.circumradius * 0.5f64.powi(i32::from(lattice::MAX_LEVEL) - 8);
    let pair = crate::quality::closest_pair(&input.points);
    let corners = hex.corners();
    let edge = |p: crate::geom::Point| {
        (0..6)
            .map(|k| {
                let (a, b) = (corners[k], corners[(k + 1) % 6]);
                crate::geom::orient2d(a, b, p) / crate::geom::dist(a, b)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let nearest_edge = (0..input.points.len())
        .map(|i| (edge(input.points[i]), i))
        .min_by(|a, b| a.0.total_cmp(&b.0));
    match (pair, nearest_edge) {
        (_, Some((distance, index)))
            if distance <= deepest && pair.is_none_or(|c| distance <= c.distance) =>
        {
            Error::input(crate::error::InputError::NearBoundary { index, distance })
        }
        (Some(c), _) if c.distance <= deepest => Error::input(crate::error::InputError::Rounding {
            first: c.first,
            second: c.second,
            distance: c.distance,
            needed: f64::INFINITY,
            allowed: params.max_rounding_deg(),
        }),
        _ => Error::mesher(
            NAME,
            format!(
                "the rhombs were split to the lattice's deepest level ({}) although no two \
                 input points, and no point and the hexagon's edge, are closer than {:e}: a \
                 configuration the crowdedness rules do not settle",
                lattice::MAX_LEVEL,
                deepest
            ),
        ),
    }
}

/// The construction's angles are exactly 30°–90° (patterns) or inside it with margin (moved
/// points); only the rounding of lattice vertices to f64 can push one out, by at most the
/// allowance of `quality::rounding`. That grows when the input forces triangles far smaller
/// than the coordinates (points very close together, or to the fitted hexagon's edge, far
/// from the origin): an input whose mesh would lie beyond [30°, 90°] by more than
/// `max_rounding` degrees is refused, naming its points.
fn rounding_check(
    mesh: &crate::mesh::TriMesh,
    points: &[crate::geom::Point],
    max_rounding: f64,
) -> Result<()> {
    crate::quality::rounding::check_angles(mesh, points, (30.0, 90.0), max_rounding, NAME)
}
