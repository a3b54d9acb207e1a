//! The extended refinement of paper 000 Sec. 5 (mesher `hex`): the simple refinement, then
//! the extended rules of Sec. 5.2 on the classified hexagons until none fires, then the centre
//! relocations of Sec. 5.4. Promised (Sec. 6): angles in [atan(5/(3√3)) ≈ 43.8979°, 90°],
//! radius ratio ≤ 1.20787, Delaunay, shortest edge ≥ √7/(12√3)·d_min.
//!
//! MOVED_CENTER_3 hexagons are kept and the dual is rebuilt around them (fin centres,
//! MOVED_CENTER_4 tops, the Fig. 6 rule, blossoms when they arise): `mc3`, whose module docs
//! hold the derivation of the missing figures and its own departures.
//!
//! Departures from the paper (all but the ring rule only refine more):
//! - Rings of two points (Sec. 5.1): a cell in the fixed ring of one point and the moved
//!   1-ring of another is FIXED_CENTER_IN_RING (the order of Sec. 5.1, and Sec. 6.3 lets
//!   OCCUPIED_2 hexagons three apart share ring cells). An occupied hexagon in another's
//!   ring, or two moved 1-rings overlapping (occupied hexagons two apart), subdivides both,
//!   but only when the two points are at most 5.10·r apart. Sec. 6.3 takes (√7/2)·r_min as
//!   the shortest edge, but an OCCUPIED_2 point on its hexagon's edge, a quarter of the edge
//!   from its nearest corner, is only (3√3/4)·r from the ring cell across that edge after the
//!   ½r shift of Sec. 5.4: with r = 1, corner (1, 0) and the point (1 - t/2, t·√3/2) on the
//!   edge to (½, √3/2), that cell moves from (3/2, √3/2) to (2, √3/2), at squared distance
//!   7/4 - t/2 + t², smallest at t = ¼ (27/16) and √7/2 only at the corner (t = 0).
//!   Splitting gives hexagons of r/2, which keep √7/(12√3)·d_min only if
//!   (3√3/4)·r/2 ≥ √7/(12√3)·d, d ≤ 5.10·r; points up to 5.29·r apart can sit two cells apart,
//!   and a grid of spacing 5.14·r had its shortest edge at 0.1262·d_min (fixture
//!   hex-shortest-edge-grid-*). Farther apart the shared cells are contested instead.
//! - Contested ring cells are placed, not just fixed or moved (departs from Sec. 5.4, which
//!   has one position per class). Two OCCUPIED_2 points three cells apart on the far sides of
//!   their hexagons pull the cells between them both ways: A's 1-ring shifts ½r towards A's
//!   corner, B's 1-ring towards B's, and the cells of one ring that touch the other ring's
//!   are then up to r out of line (fixture hex-contested-ring-far-pair-*: points 5.49r apart,
//!   smallest angle 39.4° with the cells fixed, 34.3° with them moved). Splitting them is no
//!   way out there: two points in hexagons three apart
//!   can be 6.9r apart, farther than the 3√3·r = 5.2r up to which hexagons of radius r/2 keep
//!   the r_min = d_min/(6√3) of Sec. 6.3. A search in a local model of the two rings found a
//!   good position for the contested cells in every sampled configuration, so
//!   `settle_contested` searches for it: each contested cell in a rejected triangle moves to
//!   the candidate position (its centre, or r/16 … r/2 away in one of 24 directions) that
//!   most reduces the angle violation of its triangles; a second pass also moves the other
//!   ring cells (a contested cell may need its neighbour to give way, and a moved ring cell
//!   can come closer to an OCCUPIED_2 point than l_min = √7/(12√3)·d_min) but never adds a
//!   bad triangle around the moved cell. No move makes an edge shorter than l_min. A contested
//!   cell whose triangle the self-check still rejects takes its moved role once, then the
//!   search runs again, before anything is subdivided.
//! - Precision (README "Checks"): the self-check accepts an angle beyond the bounds by what
//!   rounding of its corners explains (`breaks_bounds`), and leaves a pair that only rounding
//!   made non-Delaunay to be flipped once the mesh is done (`settle_rounding`). Before
//!   that, rejected triangles that were rounding's doing were subdivided below the precision
//!   level (one set took 358 such splits, to 0.035·d_min); now a rejection is a real defect,
//!   subdivided at any level up to the hierarchy's guard (`ROUNDING_GUARD`), and the finished
//!   mesh is refused, naming its two closest points, if it uses more than `--max-rounding`.
//! - Sec. 6.1 admits that the bounds were checked on "almost all configurations". As a last
//!   rule, the finished dual is verified (angles, exact empty-circle test) and the coarsest
//!   hexagon of each offending triangle is subdivided, and the rules run again. The count of such
//!   subdivisions is reported so that fuzzing can find and name the configurations behind them.
//!
//! - A hexagon with fins centred on the boundary of the bounding hexagon is subdivided: moving
//!   a boundary centre inwards spoils the boundary triangles (found on a 10-point set, where
//!   such configurations repeated at every level).
//! - Three mutually adjacent MOVED_CENTER_1/2 hexagons whose fins point different ways (a
//!   one-level strip between finer regions, a corner of a transition) move apart and leave a
//!   35°–40° triangle; Sec. 5.4 derives each relocation with fixed hexagons beside the moved
//!   one. The rule phase measures such triangles with the Sec. 5.4 relocations and subdivides
//!   the smallest key, as the self-check would (`spread_moved_triangle`): on plane-2k the
//!   self-check's subdivisions fell from 124 to 3, and its rounds with them.
//! - Two last resorts before a subdivision that would go below r_min = d_min/(6√3) (Sec. 6.3)
//!   and shorten edges below l_min (fuzz: 0.124 and 0.120·d_min): the OCCUPIED_2 points of a
//!   rejected triangle shift their moved 1-ring towards the corner second nearest to the
//!   point (`switch_corner`; a point near the border of two corners' regions), and a finer
//!   pattern search places the ring cells of the rejected triangles (`polish_rings`). Fixtures
//!   hex-short-edge-below-r-min-* and hex-second-corner-*.
//! - The local coarsening of Sec. 5.3 runs once, after the first fixed point of the rules
//!   (`blossom`, with its reading of the condition).
//!
//! Budgets: `Params::budget` (steps, vertices, time) stops the refinement; the mesh so far
//! comes back with `complete == false`, its centres unmoved.
//!
//! Work: a work list of the cells around each batch of subdivisions (`around`), the rings
//! updated only around occupied hexagons that changed (`Rings::update_changed`), the
//! self-check over the whole dual once and then only near what changed (`region`), and the
//! dual returned after local repairs spliced from the complete one and the repaired region's
//! (`splice`) instead of extracted a second time; long candidate lists are
//! classified over the hierarchy's threads (`in_parallel`), with results that do not depend on
//! the split. The figures (fuzz campaign, dataset counts, times) are in README.md and
//! reports/.
//!
//! The steps, one a file:
//! - this file: the mesher (`Hex`) and its run (`mesh_extended`, `ExtendedStats`);
//! - `rules`: the extended rules of Sec. 5.2 and the hexagons they act on;
//! - `relocate`: the centre relocations of Sec. 5.4;
//! - `rings`: the ring decisions of the self-check (`RingState`) and the ring cache;
//! - `undo`: the undo log of ring roles (not in the paper);
//! - `settle`: the local searches that place ring cells (`settle_contested`, `polish_rings`);
//! - `check`: the self-check (`breaks_bounds`, `offending_leaves`, `settle_rounding`);
//! - `splice`: the whole dual spliced after local repairs (not in the paper);
//! - `repair`: the loop of rules, checks and repairs (`extend_and_verify`);
//! - `tiles`: the refinement of large inputs started tile by tile over the threads (not in
//!   the paper).

pub(crate) mod check;
pub(crate) mod relocate;
mod repair;
mod rings;
pub(crate) mod rules;
mod settle;
mod splice;
mod tiles;
mod undo;

use std::time::Instant;

use crate::error::{Error, Result};
use crate::hex::classify::Rings;
use crate::hex::dual::{self, Placement};
use crate::hex::lattice::{Key, KeySet};
use crate::hex::refine::refine_simple;
use crate::hex::size;
use crate::hex::subdivision::{Hierarchy, Stop};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params, StopReason};
use crate::progress::{self, Progress};
use crate::quality::{Bounds, HEX};

pub use check::{delaunay_violations, settle_rounding};
pub use relocate::{chain_relocations, chain_triangles, relocated, relocations, relocations_of};
pub(crate) use repair::extend_and_verify;
pub use rings::RingState;
use rings::{apply_placed, rings_with_flips};
pub(crate) use rules::around;

/// The extended hexagonal mesher (Sec. 5).
#[derive(Debug, Clone, Copy, Default)]
pub struct Hex;

/// Facts about an extended refinement run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExtendedStats {
    /// Subdivisions made by the extended rules of Sec. 5.2 (and the departures above).
    pub rule_splits: u64,
    /// Of `rule_splits`, those made because a hexagon was MOVED_CENTER_3 (or the top or end
    /// neighbour of MOVED_CENTER_3 hexagons, rules of Sec. 5.2).
    pub mc3_splits: u64,
    /// Subdivisions made by the last-resort verification of the finished dual.
    pub verify_splits: u64,
    /// Triangles the verification rejected that touch a MOVED_CENTER_3 chain (a fin, a chain
    /// centre or its top): configurations the rules of `mc3` do not cover.
    pub mc3_rejected: u64,
    /// Contested ring cells (fixed for one point, moved for another) moved after all.
    pub ring_flips: u64,
    /// Times the self-check let a pair of triangles pass that only rounding made
    /// non-Delaunay (`rounding_made`), to be flipped by `settle_rounding`.
    pub rounding_pairs: u64,
    /// Rounds of rules-then-verification.
    pub rounds: u64,
    /// Triangles the self-check examined, over all rounds (the whole dual once, then only
    /// the neighbourhoods of changes).
    pub checked_triangles: u64,
    /// Contested ring cells placed by `settle_contested` away from both roles' positions.
    pub settled: u64,
    /// Blossoms formed by the local coarsening of Sec. 5.3 (`blossom`).
    pub blossoms: u64,
    /// Ring cells moved by `polish_rings`.
    pub polished: u64,
    /// OCCUPIED_2 rings shifted towards their second corner (`switch_corner`).
    pub corner_switches: u64,
    /// 1 when the dual returned after local repairs was spliced from the last complete one
    /// (`splice`) instead of extracted again whole.
    pub spliced: u64,
    /// 1 when a splice was refused (its seam did not close) and the dual extracted whole.
    pub splice_refused: u64,
}

impl Mesher for Hex {
    fn name(&self) -> &'static str {
        "hex"
    }

    fn version(&self) -> String {
        format!("hexmesh {}", env!("CARGO_PKG_VERSION"))
    }

    fn settings(&self, params: &Params) -> String {
        // The summary line states what the mesh is promised: on a domain the triangles with a
        // corner on a segment have a bound of their own (`pslg::band`).
        let mut s = String::from(
            "extended refinement (Sec. 5), angles 43.8979-90 deg off the segments, \
             30-120 deg at them",
        );
        crate::hex::size_settings(&mut s, params);
        s
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        let bounds = HEX
            .bounds()
            .with_size_limits(params.max_area, params.max_edge);
        if params.max_area.is_some() || params.max_edge.is_some() {
            // The shortest edge of Sec. 6.3 is relative to the closest input points; a size
            // limit finer than they are makes every edge as short as it requires (`size`).
            return Bounds {
                min_edge_over_dmin: None,
                ..bounds
            };
        }
        bounds
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        params.refuse_switches(self.name())?;
        let start = Instant::now();
        // PSLG hook (Sec. 7): segments go to src/hex/pslg.rs.
        if input.has_segments() {
            let limits = size::limits(input, params)?;
            // The hierarchy is built on the points alone, so the regions' smallest area limit
            // travels as the maximum area.
            let sized = Params {
                max_area: limits.0,
                ..params.clone()
            };
            let out = crate::hex::pslg::mesh_pslg(input, &sized)?;
            // Away from the segments the triangles keep the limits (`size`); next to them,
            // the re-triangulated neighbourhoods of Sec. 7 are not refined for them.
            size::check(&out.mesh, limits, self.name(), |t| {
                out.mesh.triangles[t]
                    .iter()
                    .all(|&v| !out.on_segment[v as usize])
            })?;
            // The interior keeps the Sec. 6 angles under the rounding contract: refused,
            // naming the points, where rounding would move one more than `max_rounding`.
            crate::quality::rounding::check_interior_angles(
                &out.mesh,
                input,
                (HEX.min_angle, HEX.max_angle),
                params.max_rounding_deg(),
                self.name(),
            )?;
            return Ok(MeshRun {
                mesh: out.mesh,
                complete: true,
                stop_reason: None,
                steps: out.hierarchy.steps,
                elapsed: start.elapsed(),
            });
        }
        mesh_points(input, params, start, tiles::TILE_POINTS)
    }
}

/// `hex` with tiles of at most `per_tile` points on average (`tiles`; `hex` itself takes
/// `TILE_POINTS`): the fuzz campaign's `hex-tiled` (16 points a tile), which meshes its small
/// point sets in tiles as `hex` meshes large inputs, so that the tiles' join is fuzzed too.
/// Its name and promise are `hex`'s.
#[derive(Debug, Clone, Copy)]
pub struct HexInTiles(pub usize);

impl Mesher for HexInTiles {
    fn name(&self) -> &'static str {
        Hex.name()
    }

    fn version(&self) -> String {
        Hex.version()
    }

    fn settings(&self, params: &Params) -> String {
        format!("{}; tiles of {} points", Hex.settings(params), self.0)
    }

    /// Domains go to `hex` as they are (`pslg`), which does not tile.
    fn supports_segments(&self) -> bool {
        Hex.supports_segments()
    }

    fn promise(&self, params: &Params) -> Bounds {
        Hex.promise(params)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        params.refuse_switches(self.name())?;
        if input.has_segments() {
            return Hex.mesh(input, params);
        }
        mesh_points(input, params, Instant::now(), self.0)
    }
}

/// `hex` on a point set, with tiles of at most `per_tile` points on average.
fn mesh_points(input: &Pslg, params: &Params, start: Instant, per_tile: usize) -> Result<MeshRun> {
    let limits = size::limits(input, params)?;
    let mut out = mesh_extended_in_tiles(input, params, per_tile)?;
    let threads = out.hierarchy.threads();
    if let Some(t) = dual::first_inverted_over(&out.mesh, threads) {
        return Err(Error::mesher(
            Hex.name(),
            format!("internal error: dual triangle {t} is not counter-clockwise"),
        ));
    }
    if out.stop.is_none() {
        settle_rounding(
            &mut out.mesh,
            &input.points,
            out.stats.rounding_pairs,
            params.max_rounding_deg(),
            threads,
        )?;
        size::check(&out.mesh, limits, Hex.name(), |_| true)?;
    }
    Ok(MeshRun {
        mesh: out.mesh,
        complete: out.stop.is_none(),
        stop_reason: out.stop,
        steps: out.hierarchy.steps,
        elapsed: start.elapsed(),
    })
}

/// The result of `mesh_extended`.
#[derive(Debug, Clone)]
pub struct ExtendedRun {
    /// The final subdivision.
    pub hierarchy: Hierarchy,
    /// Its relocated dual; after a budget stop, the plain dual (centres unmoved).
    pub mesh: TriMesh,
    /// Why a budget stopped the refinement; `None` when it finished.
    pub stop: Option<StopReason>,
    /// What the run did.
    pub stats: ExtendedStats,
    /// The contested ring cells moved after all and the cells placed by `settle_contested`.
    pub rings: RingState,
}

impl ExtendedRun {
    /// The relocated dual of the run's final subdivision extracted again, whole, with the
    /// ring decisions of its self-check: the mesh a run returns without this second pass
    /// (spliced from its last complete dual after local repairs) must be this one.
    pub fn extract_again(&self) -> TriMesh {
        final_dual(&self.hierarchy, &self.rings)
    }
}

/// Runs the extended refinement and builds the relocated dual.
pub fn mesh_extended(input: &Pslg, params: &Params) -> Result<ExtendedRun> {
    mesh_extended_in_tiles(input, params, tiles::TILE_POINTS)
}

/// `mesh_extended` with tiles of at most `per_tile` points on average (`tiles`; `HexInTiles`
/// takes small tiles).
fn mesh_extended_in_tiles(input: &Pslg, params: &Params, per_tile: usize) -> Result<ExtendedRun> {
    let mut h = super::new_hierarchy(input, params, "hex")?;
    let mut stats = ExtendedStats::default();
    let mut rings = RingState::default();
    let progress = params.progress.as_ref();
    let outcome = tiles::refine_tiled(&mut h, &mut stats, per_tile, progress)
        .and_then(|_| refine_and_verify(&mut h, &mut stats, &mut rings, progress));
    match outcome {
        Ok(mesh) => Ok(ExtendedRun {
            hierarchy: h,
            mesh,
            stop: None,
            stats,
            rings,
        }),
        Err(Stop::Budget(why)) => {
            let mesh = dual::extract(&h, Placement::Plain);
            Ok(ExtendedRun {
                hierarchy: h,
                mesh,
                stop: Some(why),
                stats,
                rings,
            })
        }
        Err(Stop::Precision(problem)) => Err(Error::input(problem)),
    }
}

/// The whole run from the root or from the tiles' join: the simple refinement, the extended
/// rules, the self-check and its repairs, the final dual; `progress` hears of each phase.
fn refine_and_verify(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    state: &mut RingState,
    progress: Option<&Progress>,
) -> Result<TriMesh, Stop> {
    progress::phase(progress, "simple refinement");
    refine_simple(h)?;
    size::refine(h)?;
    let (candidates, rings) = full_leaves_and_rings(h);
    match extend_and_verify(h, stats, state, (candidates, Some(rings)), None, progress)? {
        Some(mesh) => Ok(mesh),
        None => {
            progress::phase(progress, "final dual");
            Ok(final_dual(h, state))
        }
    }
}

/// The simple refinement and the subdivisions of the size limits, then the cells the
/// extended rules look at first: every full leaf (the whole run's start, and a tile's).
pub(crate) fn refine_simple_and_sizes(h: &mut Hierarchy) -> Result<KeySet, Stop> {
    refine_simple(h)?;
    size::refine(h)?;
    // The extended rules act on full leaves only, and `extended_actions` sorts what it finds,
    // so the full leaves as a block set do (not every leaf with its cell, sorted: at plane-1m
    // about 5 GB built and sorted once).
    Ok(h.full_leaves_iter().collect())
}

/// The full leaves as `refine_simple_and_sizes` gives them, and the rings the extended rules
/// read first (`classify::rings`, with the occupancy tracked from here on, as the ring cache
/// does): both only read the hierarchy, and on more than one thread they are made side by
/// side (at plane-100k the rings take 0.6 s, the set of 5.6 million leaves about 0.25 s).
fn full_leaves_and_rings(h: &mut Hierarchy) -> (KeySet, Rings) {
    use crate::hex::classify::rings;
    h.track_occupancy();
    let h = &*h;
    if h.threads() < 2 {
        return (h.full_leaves_iter().collect(), rings(h));
    }
    std::thread::scope(|scope| {
        let made = scope.spawn(|| rings(h));
        let leaves = h.full_leaves_iter().collect();
        match made.join() {
            Ok(r) => (leaves, r),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

/// The relocated dual of the whole subdivision, with the ring decisions of `state`
/// (`extend_and_verify` has verified it).
pub(crate) fn final_dual(h: &Hierarchy, state: &RingState) -> TriMesh {
    let r = rings_with_flips(h, state);
    let (mut moved, patch, chains) = chain_relocations(h, &r);
    apply_placed(&mut moved, state);
    let relocate = |k| relocated(h, &r, k);
    let later = |emit: &mut dyn FnMut([Key; 3])| chain_triangles(h, &r, &chains, emit);
    dual::extract_relocated(h, (&moved, &relocate), &patch, &later).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::progress::{Count, Event};
    use crate::xorshift::XorShift;
    use std::sync::{Arc, Mutex};

    /// `n` points uniform in the unit square, from the xorshift sequence that starts at
    /// `seed` (the tiles' tests share it).
    pub(super) fn scattered(n: usize, seed: u64) -> Vec<Point> {
        let mut x = XorShift::new(seed);
        let mut next = || (x.next() >> 11) as f64 / (1u64 << 53) as f64;
        (0..n).map(|_| [next(), next()]).collect()
    }

    /// The run of `mesher` on `input` with `params`, and the events it reported.
    fn observed(mesher: &dyn Mesher, input: &Pslg, params: &Params) -> (MeshRun, Vec<Event>) {
        let events = Arc::new(Mutex::new(Vec::new()));
        let progress = {
            let events = Arc::clone(&events);
            Progress::new(move |e| events.lock().unwrap().push(e))
        };
        let run = mesher
            .mesh(input, &params.clone().with_progress(progress))
            .expect("meshes");
        let events = events.lock().unwrap().clone();
        (run, events)
    }

    fn bits(mesh: &TriMesh) -> (Vec<u64>, &[[u32; 3]]) {
        let v = mesh.vertices.iter().flat_map(|p| p.map(f64::to_bits));
        (v.collect(), &mesh.triangles)
    }

    /// The phases of `events`, each once where it repeats.
    fn phases(events: &[Event]) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = events.iter().map(|e| e.phase).collect();
        out.dedup();
        out
    }

    #[test]
    fn hex_reports_its_tiles_in_order_then_its_phases_and_meshes_the_same_bytes() {
        // More points than a tile of `hex` holds, so that `hex` itself tiles them; `HexInTiles`
        // cuts them into many more tiles, finished on three threads.
        let input = Pslg::from_points(scattered(tiles::TILE_POINTS + 52, 0x9e37_79b9_7f4a_7c15));
        let params = Params::default().with_threads(std::num::NonZeroUsize::new(3).unwrap());
        for (mesher, least_tiles) in [(&Hex as &dyn Mesher, 2), (&HexInTiles(64), 30)] {
            let unobserved = mesher.mesh(&input, &params).expect("meshes");
            let (run, events) = observed(mesher, &input, &params);
            assert!(run.complete && unobserved.complete);
            assert_eq!(bits(&run.mesh), bits(&unobserved.mesh), "the same bytes");

            // The tiles first: 0 of them, then each count once and in order, up to all.
            let tiles: Vec<Count> = events
                .iter()
                .take_while(|e| e.phase == "tiles")
                .map(|e| e.count.expect("tiles are counted"))
                .collect();
            let total = tiles[0].total.expect("the tiles' number is known");
            assert!(total >= least_tiles, "{total} tiles");
            let counts: Vec<u64> = tiles.iter().map(|c| c.done).collect();
            assert_eq!(counts, (0..=total).collect::<Vec<u64>>());
            assert!(tiles.iter().all(|c| c.total == Some(total)));

            // Then the whole run's phases in order, up to the complete check.
            let seen = phases(&events);
            let complete_check = [
                "tiles",
                "joining the tiles",
                "simple refinement",
                "extended rules",
                "self-check: the dual",
                "self-check: ring cells",
                "self-check: angles and circles",
            ];
            assert_eq!(seen[..complete_check.len()], complete_check, "{seen:?}");
            // The complete check of these points rejects triangles: local checks and rounds
            // of rules follow, each counted from 1 in order, and the final dual is spliced
            // last.
            let after = &events[events
                .iter()
                .position(|e| e.phase == complete_check[6])
                .unwrap()
                + 1..];
            assert!(!after.is_empty(), "the complete check passed: {seen:?}");
            for phase in ["local checks", "repair round"] {
                let counts: Vec<u64> = after
                    .iter()
                    .filter(|e| e.phase == phase)
                    .map(|e| e.count.expect("counted").done)
                    .collect();
                assert_eq!(counts, (1..=counts.len() as u64).collect::<Vec<u64>>());
            }
            assert!(after
                .iter()
                .all(|e| ["local checks", "repair round", "final dual"].contains(&e.phase)));
            assert_eq!(seen.last(), Some(&"final dual"), "{seen:?}");
        }
    }
}
