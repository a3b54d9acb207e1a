//! The driver and the self-check of the finished mesh (ours): rounds of refinement (the rules
//! of Sec. 5.2 and 7.2), mesh extraction with the segments inserted, and a check. Every
//! triangle must be counter-clockwise with positive area (exact), every segment a chain of mesh
//! edges, every input point a vertex (`quality::validate`); triangles with no corner on a
//! segment must meet the Sec. 6 angle bounds and the exact empty-circle test. Where the bounds
//! fail, the coarsest hexagon of the offending triangle is subdivided and everything runs
//! again, at most `MAX_ROUNDS` times and while the hexagons grow less than `MAX_GROWTH`-fold;
//! when validity fails or the rounds run out, the mesher returns an error naming the place.
//!
//! Near-segment triangles the band (`band`) could not repair are subdivided around in the
//! same way in rounds before `NEAR_ROUNDS`, the hexagons coarser than the finest level of the
//! first round first. Of the meshes whose interior passed, the one with the fewest such
//! triangles is kept with its hierarchy (`Fallback`) and returned when the finer lattice goes
//! below the Sec. 6.3 shortest edge (not promised under a size limit), grows beyond
//! `MAX_GROWTH`, still breaks an interior bound when the rounds run out, or has no fewer such
//! triangles than the mesh of round `NEAR_ROUNDS`. Before it is returned, the band is run
//! again on it with the thorough search (`band::Effort::thorough`), whose mesh is taken when
//! it leaves fewer such triangles. The near-segment triangles it keeps fail the promise, and
//! the self-check of `hexmesh mesh` says so.

use super::band::Effort;
use super::cavity::{insert_segments, Built};
use super::rules::{apply, apply_rules};
use super::{leaf_of_vertex, PslgStats, MAX_GROWTH, MAX_ROUNDS, NAME, NEAR_ROUNDS};
use crate::error::Error;
use crate::geom::{incircle, Point};
use crate::hex::classify::rings;
use crate::hex::dual::{self, Placement};
use crate::hex::extended::check::breaks_bounds;
use crate::hex::extended::relocate::relocations;
use crate::hex::extended::rules::around;
use crate::hex::lattice::{Key, KeySet};
use crate::hex::refine::refine_simple;
use crate::hex::subdivision::{Hierarchy, Stop};
use crate::mesh::{Pslg, TriMesh};
use crate::quality::{validate, ValidateOptions};
use std::collections::BTreeMap;

/// Why the driver stopped.
pub(super) enum Fail {
    /// A budget ran out, or the points are too close for f64.
    Stop(Stop),
    /// Anything else: the error to return.
    Error(Error),
}

impl From<Stop> for Fail {
    fn from(s: Stop) -> Fail {
        Fail::Stop(s)
    }
}

impl From<Error> for Fail {
    fn from(e: Error) -> Fail {
        Fail::Error(e)
    }
}

/// Refines, meshes and checks in rounds until the mesh passes its self-check (module docs);
/// returns the mesh and, for each vertex, whether it lies on a segment.
pub(super) fn drive(
    h: &mut Hierarchy,
    input: &Pslg,
    segments: &[[Point; 2]],
    stats: &mut PslgStats,
) -> std::result::Result<(TriMesh, Vec<bool>), Fail> {
    refine_simple(h)?;
    crate::hex::size::refine(h)?;
    let mut candidates: KeySet = h.leaves().into_iter().map(|(k, _)| k).collect();
    let mut first_size = None;
    let mut finest: Option<u8> = None;
    // Of the meshes whose interior passed, the one with the fewest near-segment triangles the
    // band left (that count first), kept with its hierarchy while subdivisions try to repair
    // them: if they fail, it is the answer.
    let mut fallback: Option<Fallback> = None;
    // The Sec. 6.3 shortest edge away from the segments, for the band and the fallback, in
    // d_min of the domain (`quality::feature_gap`).
    let min_edge = crate::quality::feature_gap(input).map_or(0.0, |c| {
        c.distance * crate::quality::bounds::HEX.min_edge_over_dmin
    });
    loop {
        stats.rounds += 1;
        let crossed = apply_rules(h, input, segments, candidates, stats)?;
        let first = *first_size.get_or_insert(h.full_leaves);
        if h.full_leaves > MAX_GROWTH * first {
            if let Some(f) = fallback.take() {
                return Ok(f.finish(h, input, segments, min_edge, stats)?);
            }
            return Err(Fail::Error(Error::mesher(
                NAME,
                format!(
                    "the self-check's subdivisions grew the hexagons from {first} to {} \
                     without repairing the triangles away from the segments; giving up",
                    h.full_leaves
                ),
            )));
        }
        stats.crossed = crossed.len();
        stats.crossed_radius = crossed
            .keys()
            .map(|k| h.lattice.radius(k.k))
            .fold(0.0, f64::max);
        let effort = Effort {
            min_edge,
            thorough: false,
        };
        let built = build(h, input, segments, &crossed, effort, stats)?;
        let mut bad = interior_offenders(&built);
        // A lattice refined for the near-segment triangles must not go below the Sec. 6.3
        // shortest edge away from the segments; where it would, the mesh before it is the
        // answer. Under a size limit the limit sets the edges, and hex does not promise the
        // Sec. 6.3 edge (`Mesher::promise`).
        let sized = h.size_level() > 0;
        if fallback.is_some() && bad.is_empty() && !sized && interior_edge_below(&built, min_edge) {
            if let Some(f) = fallback.take() {
                return Ok(f.finish(h, input, segments, min_edge, stats)?);
            }
        }
        if bad.is_empty() && built.stuck.is_empty() {
            checked(&built.mesh, input)?;
            return Ok((built.mesh, built.on_segment));
        }
        let near_only = bad.is_empty();
        if near_only {
            // Ours: the band left near-segment triangles it could not repair; a finer lattice
            // there gives it other points to work with. The mesh with the fewest of them is
            // kept.
            let stuck = built.stuck.len();
            if fallback.as_ref().is_none_or(|f| stuck < f.stuck) {
                fallback = Some(Fallback {
                    stuck,
                    h: h.clone(),
                    crossed: crossed.clone(),
                    mesh: built.mesh.clone(),
                    on_segment: built.on_segment.clone(),
                });
            }
            if stats.rounds >= NEAR_ROUNDS {
                if let Some(f) = fallback.take() {
                    return Ok(f.finish(h, input, segments, min_edge, stats)?);
                }
            }
            bad = built.stuck.clone();
        }
        if stats.rounds >= MAX_ROUNDS {
            if let Some(f) = fallback.take() {
                return Ok(f.finish(h, input, segments, min_edge, stats)?);
            }
            let t = bad[0];
            let c = built.mesh.corners(t);
            return Err(Fail::Error(Error::mesher(
                NAME,
                format!(
                    "after {MAX_ROUNDS} rounds of subdivision, triangle ({:?}, {:?}, {:?}) \
                     away from the segments ({}) still breaks the angle or empty-circle bound",
                    c[0],
                    c[1],
                    c[2],
                    if built.cavity[t] {
                        "in the re-triangulated neighbourhood of a segment"
                    } else {
                        "in the hexagon dual"
                    }
                ),
            )));
        }
        let mut split: Vec<Key> = bad
            .iter()
            .filter_map(|&t| {
                built.mesh.triangles[t]
                    .iter()
                    .map(|&v| built.keys[v as usize])
                    .min_by_key(|k| (k.k, *k))
            })
            .map(|k| leaf_of_vertex(h, k))
            .collect();
        split.sort();
        split.dedup();
        if near_only {
            // Ours: the hexagons coarser than the finest level the rules made first (domain
            // fuzz seed 20261123, case 3283: a coarse triangle beside the outer boundary
            // stuck beside fine ones at a small hole, where a finer level would put an
            // interior edge below Sec. 6.3 and end the rounds before the coarse one is
            // tried).
            let finest = *finest
                .get_or_insert_with(|| h.leaves().iter().map(|(k, _)| k.k).max().unwrap_or(0));
            if split.iter().any(|k| k.k < finest) {
                split.retain(|k| k.k < finest);
            }
        }
        stats.verify_splits += apply(h, split)?;
        candidates = around(&h.log);
    }
}

/// The mesh of hierarchy `h`: its dual with the relocations, the segments inserted into it,
/// and the band's repair with `effort`.
fn build(
    h: &Hierarchy,
    input: &Pslg,
    segments: &[[Point; 2]],
    crossed: &BTreeMap<Key, Vec<u32>>,
    effort: Effort,
    stats: &mut PslgStats,
) -> std::result::Result<Built, Error> {
    let r = rings(h);
    // MOVED_CENTER_3 hexagons keep their rebuilt dual (`mc3`); Sec. 7.2 keeps them away from
    // the segments, so the cavities below never cut into one.
    let (moved, patch) = relocations(h, &r);
    let dual = dual::extract_patched(h, Placement::Relocated, &moved, &patch);
    insert_segments(h, input, segments, crossed, dual, effort, stats)
}

/// A mesh whose interior passed, with near-segment triangles the band left (`stuck` of them),
/// and the hierarchy and crossed cells it was built from.
struct Fallback {
    stuck: usize,
    h: Hierarchy,
    crossed: BTreeMap<Key, Vec<u32>>,
    mesh: TriMesh,
    on_segment: Vec<bool>,
}

impl Fallback {
    /// Makes `h` this fallback's hierarchy and returns its mesh, or the mesh the thorough
    /// band search (`Effort::thorough`) builds on it when that one leaves fewer near-segment
    /// triangles and keeps the interior bounds and, without a size limit, the Sec. 6.3
    /// shortest edge.
    fn finish(
        self,
        h: &mut Hierarchy,
        input: &Pslg,
        segments: &[[Point; 2]],
        min_edge: f64,
        stats: &mut PslgStats,
    ) -> std::result::Result<(TriMesh, Vec<bool>), Error> {
        *h = self.h;
        let effort = Effort {
            min_edge,
            thorough: true,
        };
        let built = build(h, input, segments, &self.crossed, effort, stats)?;
        let sized = h.size_level() > 0;
        if built.stuck.len() < self.stuck
            && interior_offenders(&built).is_empty()
            && (sized || !interior_edge_below(&built, min_edge))
        {
            checked(&built.mesh, input)?;
            return Ok((built.mesh, built.on_segment));
        }
        checked(&self.mesh, input)?;
        Ok((self.mesh, self.on_segment))
    }
}

/// An error when `mesh` is not a valid conforming mesh of `input` (`quality::validate`).
fn checked(mesh: &TriMesh, input: &Pslg) -> std::result::Result<(), Error> {
    let violations = validate(
        mesh,
        Some(input),
        &ValidateOptions {
            single_component: false,
            conforming: true,
        },
    );
    match violations.first() {
        Some(v) => Err(Error::mesher(
            NAME,
            format!("internal error: the PSLG mesh is not valid: {v}"),
        )),
        None => Ok(()),
    }
}

/// True when a triangle with no corner on a segment has an edge shorter than `min_edge`.
fn interior_edge_below(b: &Built, min_edge: f64) -> bool {
    let mesh = &b.mesh;
    mesh.triangles.iter().any(|t| {
        t.iter().all(|&v| !b.on_segment[v as usize])
            && (0..3).any(|e| {
                let (p, q) = (
                    mesh.vertices[t[e] as usize],
                    mesh.vertices[t[(e + 1) % 3] as usize],
                );
                crate::geom::dist(p, q) < min_edge
            })
    })
}

/// Triangles with no corner on a segment that break the Sec. 6 angle bounds, or sit on an edge
/// of two such triangles that fails the exact empty-circle test.
fn interior_offenders(b: &Built) -> Vec<usize> {
    let mesh = &b.mesh;
    let interior: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|t| t.iter().all(|&v| !b.on_segment[v as usize]))
        .collect();
    let mut bad: Vec<usize> = Vec::new();
    for (t, _) in interior.iter().enumerate().filter(|(_, &i)| i) {
        if breaks_bounds(&mesh.corners(t)) {
            bad.push(t);
        }
    }
    let mut edges: Vec<(u32, u32, usize, u32)> = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !interior[t] {
            continue;
        }
        for e in 0..3 {
            let (u, v) = (tri[e], tri[(e + 1) % 3]);
            edges.push((u.min(v), u.max(v), t, tri[(e + 2) % 3]));
        }
    }
    edges.sort_unstable();
    for w in edges.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
            let [p, q, r] = mesh.corners(w[0].2);
            if incircle(p, q, r, mesh.vertices[w[1].3 as usize]) > 0.0 {
                bad.push(w[0].2);
                bad.push(w[1].2);
            }
        }
    }
    bad.sort_unstable();
    bad.dedup();
    bad
}
