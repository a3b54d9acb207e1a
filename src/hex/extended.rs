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
//! classified on the machine's threads (`in_parallel`), with results that do not depend on
//! the split. The figures (fuzz campaign, dataset counts, times) are in README.md and
//! reports/.

use std::time::Instant;

use crate::error::{Error, Result};
use crate::geom::{incircle, orient2d, Point};
use crate::hex::blossom;
use crate::hex::classify::{
    classify, fin_class, rings, subdivided_and_neighbours, Class, FinStrip, Rings, Role,
};
use crate::hex::dual::{self, Placement};
use crate::hex::fuzz::angle_deg;
use crate::hex::lattice::{FxHashMap, FxHashSet, Key, KeyBytes, KeySet};
use crate::hex::mc3::{self, Patch};
use crate::hex::parallel::{in_parallel, in_parallel_from, PARALLEL_MIN};
use crate::hex::refine::{drain, refine_simple};
use crate::hex::region::{full_leaves_in, Region, REACH};
use crate::hex::subdivision::{Cell, Hierarchy, Stop};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params};
use crate::quality::rounding::{self, AngleWindow};

/// The smallest angle of the extended refinement, atan(5/(3√3)), in degrees.
pub fn min_angle_bound() -> f64 {
    (5.0 / (3.0 * 3f64.sqrt())).atan().to_degrees()
}

/// Slack of the self-check beyond the rounding allowance of each angle: below the 1e-6° floor
/// of the checks' allowance (`quality::rounding`).
const SELF_CHECK_SLACK: f64 = 1e-7;

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
        let beyond = rounding::beyond(angle_deg(a, b, c), min_angle_bound(), 90.0);
        beyond > SELF_CHECK_SLACK + rounding::placement_allowance(a, b, c)
    })
}

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
        let mut s = String::from("extended refinement (Sec. 5), angles 43.8979-90 deg");
        if params.min_angle.is_some() || params.max_area.is_some() {
            s.push_str("; min-angle and max-area ignored (fixed bounds)");
        }
        s
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        let start = Instant::now();
        // PSLG hook (Sec. 7): segments go to src/hex/pslg.rs.
        if input.has_segments() {
            let out = crate::hex::pslg::mesh_pslg(input, params)?;
            return Ok(MeshRun {
                mesh: out.mesh,
                complete: true,
                stop_reason: None,
                steps: out.hierarchy.steps,
                elapsed: start.elapsed(),
            });
        }
        let mut out = mesh_extended(input, params)?;
        if let Some(t) = dual::first_inverted(&out.mesh) {
            return Err(Error::mesher(
                self.name(),
                format!("internal error: dual triangle {t} is not counter-clockwise"),
            ));
        }
        if out.stop.is_none() {
            settle_rounding(
                &mut out.mesh,
                &input.points,
                out.stats.rounding_pairs,
                params.max_rounding_deg(),
            )?;
        }
        Ok(MeshRun {
            mesh: out.mesh,
            complete: out.stop.is_none(),
            stop_reason: out.stop,
            steps: out.hierarchy.steps,
            elapsed: start.elapsed(),
        })
    }
}

/// The result of `mesh_extended`.
#[derive(Debug, Clone)]
pub struct ExtendedRun {
    pub hierarchy: Hierarchy,
    pub mesh: TriMesh,
    pub stop: Option<String>,
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

/// What the self-check decided about ring cells, beyond their class: kept so that a later
/// extraction (after a local check, or an incremental insertion) places them the same way.
#[derive(Debug, Clone, Default)]
pub struct RingState {
    /// Contested ring cells whose centre moves after all, because keeping it fixed spoiled a
    /// triangle; each cell flips at most once, so the verification still terminates.
    pub flipped: FxHashSet<Key>,
    /// Vertices (by canonical key) that `settle_contested` placed, with their place.
    pub placed: FxHashMap<Key, Point>,
    /// OCCUPIED_2 hexagons whose moved 1-ring shifts towards the corner second nearest to
    /// the point (`switch_corner`); each switches at most once.
    pub second_corner: FxHashSet<Key>,
}

impl RingState {
    /// Forgets the places of cells near `changed`: their class or their neighbours changed.
    /// A vertex is judged by its leaf, the level its triangles are checked at: its canonical
    /// key can be many levels coarser, where a region reaches much farther.
    fn forget_near(&mut self, h: &Hierarchy, changed: &[Key]) {
        if self.placed.is_empty() || changed.is_empty() {
            return;
        }
        let near = Region::around(changed, 3);
        // From the region's cells when it is the smaller (a few subdivisions late in a large
        // run), so that forgetting costs what changed, not a pass over every place.
        let cells: Vec<Key> = near.cells().collect();
        if cells.len() < self.placed.len() {
            for c in cells {
                let k = c.canonical();
                if self.placed.contains_key(&k) && h.leaf_of_vertex(k) == c {
                    self.placed.remove(&k);
                }
            }
        } else {
            self.placed
                .retain(|k, _| !near.contains(h.leaf_of_vertex(*k)));
        }
    }
}

/// Runs the extended refinement and builds the relocated dual.
pub fn mesh_extended(input: &Pslg, params: &Params) -> Result<ExtendedRun> {
    let mut h = super::new_hierarchy(input, params, "hex")?;
    let mut stats = ExtendedStats::default();
    let mut rings = RingState::default();
    let outcome = refine_and_verify(&mut h, &mut stats, &mut rings);
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
                stop: Some(format!("stopped by the {why}")),
                stats,
                rings,
            })
        }
        Err(Stop::Precision(problem)) => Err(Error::input(problem)),
    }
}

fn refine_and_verify(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    state: &mut RingState,
) -> Result<TriMesh, Stop> {
    refine_simple(h)?;
    // The extended rules act on full leaves only, and `extended_actions` sorts what it finds,
    // so the full leaves as a block set do (not every leaf with its cell, sorted: at plane-1m
    // about 5 GB built and sorted once).
    let candidates: KeySet = h.full_leaves_iter().collect();
    match extend_and_verify(h, stats, state, candidates, None)? {
        Some(mesh) => Ok(mesh),
        None => Ok(final_dual(h, state)),
    }
}

/// The relocated dual of the whole subdivision, with the ring decisions of `state`
/// (`extend_and_verify` has verified it).
pub(crate) fn final_dual(h: &Hierarchy, state: &RingState) -> TriMesh {
    let r = rings_with_flips(h, state);
    let (mut moved, patch) = relocations(h, &r);
    apply_placed(&mut moved, state);
    dual::extract_patched(h, Placement::Relocated, &moved, &patch).0
}

/// The whole dual once a check has passed. After a complete check (no `inner` region) it is
/// the checked `mesh`; after local checks, `splice` of the complete dual kept then (`base`)
/// and the region's `mesh`, whose `keys` get back the ones `blamed` replaced. `None` when
/// there is no complete dual to splice into (incremental insertion) or the seam does not
/// close: the caller extracts it whole.
fn whole_dual(
    h: &Hierarchy,
    stats: &mut ExtendedStats,
    base: Option<(TriMesh, Vec<Key>)>,
    mesh: TriMesh,
    keys: &mut [Key],
    blamed: &[(usize, Key)],
    inner: Option<&Region>,
) -> Option<TriMesh> {
    let Some(inner) = inner else {
        return Some(mesh);
    };
    unblame(keys, blamed);
    let whole = splice(h, base?, &mesh, keys, inner);
    match whole {
        Some(_) => stats.spliced += 1,
        None => stats.splice_refused += 1,
    }
    whole
}

/// Gives the vertex keys back that blaming triangles on MOVED_CENTER_3 hexagons replaced.
fn unblame(keys: &mut [Key], blamed: &[(usize, Key)]) {
    for &(v, k) in blamed {
        keys[v] = k;
    }
}

/// After a complete check that failed, when local repairs begin: the complete dual and its
/// vertex keys (unblamed) become the `base` that `whole_dual` splices into.
fn keep_for_splice(
    base: &mut Option<(TriMesh, Vec<Key>)>,
    mesh: &mut TriMesh,
    keys: &mut Vec<Key>,
    blamed: &[(usize, Key)],
) {
    unblame(keys, blamed);
    *base = Some((std::mem::take(mesh), std::mem::take(keys)));
}

/// The whole dual after local repairs without a second pass over the whole hierarchy: the
/// complete dual `old` (with the canonical key of each vertex) keeps its triangles whose
/// vertices' leaves all lie outside `inner`, and takes from `part` (the dual of the repaired
/// region, with its keys) the triangles with a vertex inside. Beyond the reach of the changed
/// cells nothing changed (`region`), which is what the local checks rely on too; the splice
/// checks it where it matters: the replaced and the new triangles must meet the kept ones
/// along the same seam (their boundary edges between vertices outside `inner`, as directed
/// edges between vertex keys), and every vertex outside `inner` that a new triangle uses must
/// be a vertex of a replaced one, in the same place; the new triangles' other boundary edges
/// must lie on the rim of the bounding hexagon (no hole). `None` when not.
/// Kept triangles and vertices keep their order (the input points stay the first vertices);
/// the new ones follow in the order of `part`.
pub(crate) fn splice(
    h: &Hierarchy,
    old: (TriMesh, Vec<Key>),
    part: &TriMesh,
    part_keys: &[Key],
    inner: &Region,
) -> Option<TriMesh> {
    let (old, old_keys) = old;
    let inside = |k: &Key| inner.contains(h.leaf_of_vertex(*k));
    let old_in: Vec<bool> = old_keys.iter().map(inside).collect();
    let part_in: Vec<bool> = part_keys.iter().map(inside).collect();
    let TriMesh {
        mut vertices,
        mut triangles,
    } = old;
    // The vertices of the replaced triangles by key, and their directed edges. The kept
    // triangles stay in the old array, in order (no second mesh-sized array).
    let mut seam: FxHashMap<Key, u32> = FxHashMap::default();
    let mut replaced: FxHashSet<(Key, Key)> = FxHashSet::default();
    triangles.retain(|t| {
        let gone = t.iter().any(|&v| old_in[v as usize]);
        if gone {
            for e in 0..3 {
                replaced.insert((old_keys[t[e] as usize], old_keys[t[(e + 1) % 3] as usize]));
                seam.insert(old_keys[t[e] as usize], t[e]);
            }
        }
        !gone
    });
    let added: Vec<[u32; 3]> = part
        .triangles
        .iter()
        .filter(|t| t.iter().any(|&v| part_in[v as usize]))
        .copied()
        .collect();
    let mut new_edges: FxHashSet<(Key, Key)> = FxHashSet::default();
    for t in &added {
        for e in 0..3 {
            new_edges.insert((part_keys[t[e] as usize], part_keys[t[(e + 1) % 3] as usize]));
        }
    }
    // The seam: the boundary edges between vertices outside `inner` (an edge at an inside
    // vertex can only be on the boundary of the whole dual, which may change there).
    let boundary = |edges: &FxHashSet<(Key, Key)>| {
        let mut b: Vec<(Key, Key)> = edges
            .iter()
            .filter(|&&(a, b)| !edges.contains(&(b, a)) && !inside(&a) && !inside(&b))
            .copied()
            .collect();
        b.sort_unstable();
        b
    };
    if boundary(&replaced) != boundary(&new_edges) {
        return None;
    }
    // The other boundary edges of the new triangles (at an inside vertex) must lie on the
    // boundary of the whole dual: both ends at hexagons on the rim of the bounding hexagon.
    // Anywhere else such an edge would border a hole, a triangle the region missed.
    let rim = |k: &Key| {
        let leaf = h.leaf_of_vertex(*k);
        leaf.on_boundary() || (0..6).any(|d| !leaf.neighbor(d).inside())
    };
    if new_edges.iter().any(|&(a, b)| {
        !new_edges.contains(&(b, a)) && (inside(&a) || inside(&b)) && !(rim(&a) && rim(&b))
    }) {
        return None;
    }
    let same =
        |a: Point, b: Point| a[0].to_bits() == b[0].to_bits() && a[1].to_bits() == b[1].to_bits();
    let mut map = vec![u32::MAX; part.vertices.len()];
    for t in &added {
        for &v in t {
            let v = v as usize;
            if map[v] != u32::MAX {
                continue;
            }
            let p = part.vertices[v];
            map[v] = match seam.get(&part_keys[v]) {
                Some(&o) if same(vertices[o as usize], p) => o,
                _ if !part_in[v] => return None,
                // An input point whose hexagon was subdivided (its vertex key changed): it
                // keeps its number, as in a whole extraction, where the points come first.
                _ => match h.occupants(h.leaf_of_vertex(part_keys[v])) {
                    &[i] if (i as usize) < h.points.len()
                        && same(vertices[i as usize], p)
                        && same(h.points[i as usize], p) =>
                    {
                        i
                    }
                    _ => {
                        vertices.push(p);
                        (vertices.len() - 1) as u32
                    }
                },
            };
        }
    }
    triangles.extend(added.iter().map(|t| t.map(|v| map[v as usize])));
    // Vertices no triangle uses any more (inside `inner`, replaced) are dropped, the rest
    // renumbered in order.
    let mut used = vec![false; vertices.len()];
    for t in &triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    if used.iter().all(|&u| u) {
        return Some(TriMesh {
            vertices,
            triangles,
        });
    }
    // Compacted in place: `retain` visits the vertices in order, and a kept vertex's new
    // number is the count kept before it.
    let mut renumber = vec![u32::MAX; vertices.len()];
    let (mut v, mut next) = (0, 0);
    vertices.retain(|_| {
        let keep = used[v];
        if keep {
            renumber[v] = next;
            next += 1;
        }
        v += 1;
        keep
    });
    for t in &mut triangles {
        *t = t.map(|v| renumber[v as usize]);
    }
    Some(TriMesh {
        vertices,
        triangles,
    })
}

/// Keeps in `placed` the place of every vertex of `mesh` (with canonical keys `keys`) that
/// `moves` moved and that ends elsewhere than it stood before.
fn record_moves(placed: &mut FxHashMap<Key, Point>, moves: Moves, mesh: &TriMesh, keys: &[Key]) {
    let mut from = moves.from;
    // Stable: the first entry of a vertex holds where it stood before it moved at all.
    from.sort_by_key(|e| e.0);
    from.dedup_by_key(|e| e.0);
    for (v, old) in from {
        let new = mesh.vertices[v];
        if old != new {
            placed.insert(keys[v], new);
        }
    }
}

/// What `settle_contested` or `polish_rings` did: how many moves it made, and each vertex it
/// moved with the place it had before (`record_moves` keeps those that end elsewhere), instead
/// of a copy of every vertex of the mesh to compare with afterwards (0.9 GB at plane-1m).
#[derive(Debug, Default)]
struct Moves {
    count: u64,
    from: Vec<(usize, Point)>,
}

impl Moves {
    /// Moves vertex `v` of `mesh` to `p`.
    fn make(&mut self, mesh: &mut TriMesh, v: usize, p: Point) {
        self.count += 1;
        self.from.push((v, mesh.vertices[v]));
        mesh.vertices[v] = p;
    }
}

fn apply_placed(moved: &mut FxHashMap<Key, Point>, state: &RingState) {
    let mut placed: Vec<(Key, Point)> = state.placed.iter().map(|(k, p)| (*k, *p)).collect();
    placed.sort_by_key(|e| e.0);
    moved.extend(placed);
}

/// The rings of `h` with the decisions of `state`: the moved 1-rings of the hexagons in
/// `second_corner` shifted towards their second corner, then the contested cells in
/// `flipped` given their moved role.
fn rings_with_flips(h: &Hierarchy, state: &RingState) -> Rings {
    let mut r = rings(h);
    apply_flips(h, &mut r, state, &mut Undo::default());
    r
}

/// Gives the rings `r` the decisions of `state` in place, logging in `undo` what they
/// replace.
fn apply_flips(h: &Hierarchy, r: &mut Rings, state: &RingState, undo: &mut Undo) {
    let mut owners: Vec<Key> = state.second_corner.iter().copied().collect();
    owners.sort_unstable();
    for owner in owners {
        switch_corner(h, r, owner, undo);
    }
    let mut keys: Vec<Key> = state.flipped.iter().copied().collect();
    keys.sort_unstable();
    for key in keys {
        flip(r, key, undo);
    }
}

/// The roles the decisions of `RingState` replaced in a set of rings, oldest first (`true`
/// for `Rings::contested`, `false` for `Rings::roles`): undone in reverse, they give the
/// rings back as `RingCache` keeps them, without copying the tables each round.
#[derive(Default)]
struct Undo(Vec<(bool, Key, Option<Role>)>);

impl Undo {
    fn table(r: &mut Rings, contested: bool) -> &mut FxHashMap<Key, Role> {
        if contested {
            &mut r.contested
        } else {
            &mut r.roles
        }
    }

    fn set(&mut self, r: &mut Rings, contested: bool, key: Key, role: Role) {
        let old = Undo::table(r, contested).insert(key, role);
        self.0.push((contested, key, old));
    }

    fn restore(self, r: &mut Rings) {
        for (contested, key, old) in self.0.into_iter().rev() {
            let map = Undo::table(r, contested);
            match old {
                Some(role) => map.insert(key, role),
                None => map.remove(&key),
            };
        }
    }
}

/// The contested cell `key` takes its moved role.
fn flip(r: &mut Rings, key: Key, undo: &mut Undo) {
    if let Some(&alt) = r.contested.get(&key) {
        undo.set(r, false, key, alt);
    }
}

/// Departure from Sec. 5.4 (a last resort before a subdivision): the moved 1-ring of the
/// OCCUPIED_2 hexagon `owner` shifts by half the vector to the corner second nearest to its
/// point. A point near the border of two corners' regions lies in the region Fig. 8 allows
/// for both, and when a cell of the ring is held fixed by another point's 2-ring (three
/// hexagons apart), the shift towards the nearest corner can pull the ring cell beside it
/// too far from the fixed one (38.8° on fixture hex-second-corner-*), where the other
/// corner keeps every angle; a subdivision there would go below the r_min of Sec. 6.3.
fn switch_corner(h: &Hierarchy, r: &mut Rings, owner: Key, undo: &mut Undo) {
    let Some(&p) = h.occupants(owner).first().map(|&i| &h.points[i as usize]) else {
        return;
    };
    let shift = crate::hex::classify::ring_shift_ranked(h, owner, p, 1);
    for d in 0..6 {
        let cell = owner.neighbor(d);
        for contested in [false, true] {
            let map = if contested { &r.contested } else { &r.roles };
            if let Some(&Role::Moved { owner: o, .. }) = map.get(&cell) {
                if o == owner {
                    undo.set(r, contested, cell, Role::Moved { owner, shift });
                }
            }
        }
    }
}

/// The rings of the occupied hexagons, brought up to date only around the hexagons whose
/// occupancy changed (the hierarchy logs them): the rule loop asks for them after every
/// batch of subdivisions, and most batches (fins spreading outwards) do not touch an
/// occupied hexagon. No pass over all occupied hexagons per batch.
#[derive(Default)]
struct RingCache {
    rings: Option<Rings>,
}

impl RingCache {
    fn get(&mut self, h: &mut Hierarchy) -> &Rings {
        match &mut self.rings {
            Some(r) => {
                let changed = h.take_occupancy_changes();
                if !changed.is_empty() {
                    // Only the cells near hexagons that changed are claimed again.
                    r.update_changed(h, changed);
                    debug_assert!(same_rings(r, &rings(h)), "incremental rings differ");
                }
            }
            None => {
                h.track_occupancy();
                self.rings = Some(rings(h));
            }
        }
        self.rings.get_or_insert_with(|| rings(h))
    }

    /// The up-to-date rings, taken out of the cache until `put` gives them back unchanged.
    fn take(&mut self, h: &mut Hierarchy) -> Rings {
        self.get(h);
        self.rings.take().expect("`get` fills the cache")
    }

    fn put(&mut self, r: Rings) {
        self.rings = Some(r);
    }
}

/// True when two ring sets give every cell the same role, contest, class and conflicts.
fn same_rings(a: &Rings, b: &Rings) -> bool {
    let roles = |x: &FxHashMap<Key, Role>, y: &FxHashMap<Key, Role>| {
        x.len() == y.len() && x.iter().all(|(k, v)| y.get(k) == Some(v))
    };
    roles(&a.roles, &b.roles)
        && roles(&a.contested, &b.contested)
        && a.occupied == b.occupied
        && a.conflicts == b.conflicts
}

/// The extended rules on `candidates` to a fixed point, then the self-check of the dual,
/// repeated until the dual meets every bound. With `changed == None` the first check covers
/// the whole dual and, when it passes, that dual is returned; otherwise (and after any
/// repair) each check covers only the triangles near the cells changed since the previous
/// check (`region`), so that the work of a repair is proportional to what it changes, not
/// to how many other places are still being repaired. When every check has passed, one
/// more covers the triangles near every cell changed since the complete check, and the
/// whole dual is spliced from the complete one and that region's (`splice`); `None` says
/// that the whole dual passes but is still to be extracted (`final_dual`): there was no
/// complete check (incremental insertion), or the splice was refused. `state` keeps the
/// ring decisions of the self-check.
pub(crate) fn extend_and_verify(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    state: &mut RingState,
    mut candidates: KeySet,
    mut changed: Option<Vec<Key>>,
) -> Result<Option<TriMesh>, Stop> {
    let mut cache = RingCache::default();
    let mut coarsened = false;
    // The shortest edge Sec. 6.3 promises, √7/(12√3)·d_min: placing a contested cell must not
    // undercut it.
    let l_min = crate::quality::closest_pair(&h.points).map_or(0.0, |c| {
        c.distance * crate::quality::bounds::HEX_MIN_EDGE_OVER_DMIN * (1.0 + 1e-9)
    });
    if let Some(c) = &changed {
        state.forget_near(h, c);
    }
    // The last complete dual that failed the check, with its vertex keys, once local repairs
    // began: the whole dual they end with is spliced from it (`splice`).
    let mut base: Option<(TriMesh, Vec<Key>)> = None;
    // The cells changed since the last local check, and the vertices of offending triangles
    // left for later (see below); `changed` gathers both once, for the dual the splice takes.
    let mut fresh: Vec<Key> = changed.clone().unwrap_or_default();
    let mut stuck: Vec<Key> = Vec::new();
    let mut scope = Scope::Fresh;
    loop {
        stats.rounds += 1;
        loop {
            h.check_time()?;
            let r = cache.get(h);
            let actions = extended_actions(h, r, &candidates);
            if actions.is_empty() {
                // The final local coarsening of Sec. 5.3, once, on the first complete
                // refinement; the rules then run again around the blossoms (they find
                // nothing to do there, or undo a blossom, which is not formed again).
                if changed.is_none() && !coarsened {
                    coarsened = true;
                    let leaves = h.full_leaves_unordered();
                    let r = cache.get(h).clone();
                    let tops = blossom::candidate_tops(h, &r, &leaves);
                    let merged = blossom::coarsen(h, &r, &tops);
                    stats.blossoms += merged.len() as u64 / 7;
                    if !merged.is_empty() {
                        candidates = around(&merged);
                        continue;
                    }
                }
                break;
            }
            h.log.clear();
            for (key, why) in actions {
                let before = h.steps;
                match h.cell(key) {
                    Cell::Full { subdivided: false } => h.subdivide(key)?,
                    Cell::Semi { .. } | Cell::Absent => h.ensure_full(key)?,
                    _ => {}
                }
                stats.rule_splits += h.steps - before;
                if why == Why::Mc3 {
                    stats.mc3_splits += h.steps - before;
                }
            }
            drain(h)?;
            if let Some(c) = changed.as_mut() {
                c.extend_from_slice(&h.log);
                fresh.extend_from_slice(&h.log);
                state.forget_near(h, &h.log);
            }
            candidates = around(&h.log);
        }
        // The work list of the subdivisions is empty now but holds the room of its longest
        // batch (25 cells a subdivision: about 2 GB at plane-1m), which the check does not
        // need.
        h.work = Vec::new();
        // The rings with the decisions of `state`, changed in place and given back to the
        // cache (undone) before the next subdivisions.
        let mut r = cache.take(h);
        let mut undo = Undo::default();
        apply_flips(h, &mut r, state, &mut undo);
        let settle_cells = if changed.is_none() {
            SettleCells::listed(h, &r)
        } else {
            SettleCells::Lookup
        };
        let bad = loop {
            h.check_time()?;
            let full = changed.is_none();
            // A local check covers the cells changed since the last one (`fresh`), or, for
            // the dual the splice takes, every cell changed since the complete check.
            let around_all = scope == Scope::All;
            let (mut mesh, mut keys, patch, movable, inner) = match &changed {
                None => {
                    let (mut moved, patch) = relocations(h, &r);
                    apply_placed(&mut moved, state);
                    let (mesh, keys) =
                        dual::extract_patched(h, Placement::Relocated, &moved, &patch);
                    (mesh, keys, patch, None, None)
                }
                Some(c) => {
                    let centre = if around_all { &c[..] } else { &fresh[..] };
                    // Relocations reach a little further than the triangles checked, so that
                    // every vertex of a checked triangle has its final place.
                    let wide = Region::around(centre, REACH + 3);
                    fresh.clear();
                    let (moved, patch) = relocations_of(h, &r, full_leaves_in(h, &wide));
                    let region = wide.within(REACH);
                    let (mesh, keys) = dual::extract_region_patched(
                        h,
                        Placement::Relocated,
                        (&state.placed, &moved),
                        &patch,
                        &region,
                    );
                    // The vertices `splice` takes from this part of the dual.
                    let inner = wide.within(REACH - 1);
                    // Only vertices whose every triangle is in this part of the dual may be
                    // placed by `settle_contested`.
                    (mesh, keys, patch, Some(wide.within(REACH - 3)), Some(inner))
                }
            };
            stats.checked_triangles += mesh.triangles.len() as u64;
            let movable = |k: Key| {
                movable
                    .as_ref()
                    .is_none_or(|m| m.contains(h.leaf_of_vertex(k)))
            };
            let w = &settle_cells;
            let mut settled = Moves::default();
            for with_neighbours in [false, true] {
                let pass = SettlePass {
                    rings: &r,
                    cells: w,
                    with_neighbours,
                };
                let moves = settle_contested(h, &mut mesh, &keys, l_min, pass, &movable);
                stats.settled += moves.count;
                settled.from.extend(moves.from);
            }
            record_moves(&mut state.placed, settled, &mesh, &keys);
            // A triangle at a fin vertex is blamed on the MOVED_CENTER_3 hexagon of the fin
            // (`blamed` keeps the vertex keys this replaces, for `splice`).
            let mut blamed = Vec::new();
            for (v, k) in keys.iter_mut().enumerate() {
                if let Some(&owner) = patch.fin_owner.get(k) {
                    blamed.push((v, *k));
                    *k = owner;
                }
            }
            let mut bad = offending_leaves(h, &mesh, &keys, &mut stats.rounding_pairs);
            stats.mc3_rejected += bad
                .iter()
                .filter(|b| b.vertices.iter().any(|v| patch.chain_cells.contains(v)))
                .count() as u64;
            // Before any subdivision (which would go below the r_min of Sec. 6.3), let the
            // contested cells of the offending triangles take the moved role instead.
            let can_flip = |c: &Key| r.contested.contains_key(c) && !state.flipped.contains(c);
            let mut flips: Vec<Key> = bad
                .iter()
                .flat_map(|b| b.vertices.iter().copied())
                .filter(can_flip)
                .collect();
            flips.sort_unstable();
            flips.dedup();
            // Next, the OCCUPIED_2 points of the offending triangles shift their moved
            // 1-ring towards their second corner (`switch_corner`).
            let can_switch = |c: &Key| {
                r.occupied.get(c) == Some(&Class::Occupied2) && !state.second_corner.contains(c)
            };
            let mut switches: Vec<Key> = bad
                .iter()
                .flat_map(|b| b.vertices.iter().copied())
                .filter(can_switch)
                .collect();
            switches.sort_unstable();
            switches.dedup();
            if !bad.is_empty() && flips.is_empty() && switches.is_empty() && stuck.is_empty() {
                // Before subdividing (which below r_min = d_min/(6√3) would break the
                // shortest-edge bound of Sec. 6.3), polish the ring cells of the rejected
                // triangles with a finer local search; only a mesh it repairs whole is kept.
                let tris: Vec<usize> = bad.iter().map(|b| b.triangle).collect();
                // Its moves never add a bad triangle or a short edge, so they are kept even
                // when other triangles (elsewhere) still need a subdivision.
                let moved = polish_rings(h, &r, &mut mesh, &keys, &tris, l_min, &movable);
                if moved.count > 0 {
                    stats.polished += moved.count;
                    record_moves(&mut state.placed, moved, &mesh, &keys);
                    bad = offending_leaves(h, &mesh, &keys, &mut stats.rounding_pairs);
                }
                if !bad.is_empty() {
                    if full {
                        keep_for_splice(&mut base, &mut mesh, &mut keys, &blamed);
                    }
                    break bad;
                }
            }
            if bad.is_empty() && stuck.is_empty() {
                if full || around_all || base.is_none() {
                    return Ok(whole_dual(
                        h,
                        stats,
                        base.take(),
                        mesh,
                        &mut keys,
                        &blamed,
                        inner.as_ref(),
                    ));
                }
                // Every local check passed: the dual around all the changes once more, for
                // the splice (and checked again, since settling may move a vertex anew).
                scope = Scope::All;
                continue;
            }
            // Only the offending triangles acted on are checked again at once; the others
            // wait (`stuck`) until nothing else is left to try, so that a repair needing
            // many rounds in one place does not re-examine every other place each round.
            let acted = |b: &BadTriangle, on: &dyn Fn(&Key) -> bool| b.vertices.iter().any(on);
            if !flips.is_empty() || !switches.is_empty() {
                let on: &dyn Fn(&Key) -> bool = if flips.is_empty() {
                    &can_switch
                } else {
                    &can_flip
                };
                let all = changed.get_or_insert_with(Vec::new);
                for b in &bad {
                    all.extend_from_slice(&b.vertices);
                    let to = if acted(b, on) { &mut fresh } else { &mut stuck };
                    to.extend_from_slice(&b.vertices);
                }
            }
            if flips.is_empty() && !switches.is_empty() {
                for owner in switches {
                    switch_corner(h, &mut r, owner, &mut undo);
                    state.second_corner.insert(owner);
                    state.forget_near(h, &[owner]);
                    let ring = std::iter::once(owner).chain((0..6).map(|d| owner.neighbor(d)));
                    fresh.extend(ring.clone());
                    changed.get_or_insert_with(Vec::new).extend(ring);
                    stats.corner_switches += 1;
                }
                if full {
                    keep_for_splice(&mut base, &mut mesh, &mut keys, &blamed);
                }
                scope = Scope::Fresh;
                continue;
            }
            if flips.is_empty() && !stuck.is_empty() {
                // Nothing to try here, but the waiting triangles may still have a flip or a
                // switch: check them (and these) again together.
                fresh.append(&mut stuck);
                let vertices = bad.iter().flat_map(|b| b.vertices.iter().copied());
                fresh.extend(vertices.clone());
                changed.get_or_insert_with(Vec::new).extend(vertices);
                scope = Scope::Fresh;
                continue;
            }
            // The flipped cells are checked again, with the offending triangles they touch.
            for c in flips {
                flip(&mut r, c, &mut undo);
                state.flipped.insert(c);
                state.placed.remove(&c.canonical());
                fresh.push(c);
                changed.get_or_insert_with(Vec::new).push(c);
                stats.ring_flips += 1;
            }
            if full {
                keep_for_splice(&mut base, &mut mesh, &mut keys, &blamed);
            }
            scope = Scope::Fresh;
        };
        undo.restore(&mut r);
        cache.put(r);
        let mut bad: Vec<Key> = bad.into_iter().map(|b| b.coarsest).collect();
        bad.sort();
        bad.dedup();
        // A rejected triangle breaks a bound by more than rounding explains (`breaks_bounds`),
        // so subdividing is the repair at any level; the hierarchy's guard (`check_budget`)
        // stops descents that rounding would spoil.
        h.log.clear();
        for key in bad {
            let before = h.steps;
            h.subdivide(key)?;
            stats.verify_splits += h.steps - before;
        }
        drain(h)?;
        state.forget_near(h, &h.log);
        changed
            .get_or_insert_with(Vec::new)
            .extend_from_slice(&h.log);
        fresh.extend_from_slice(&h.log);
        scope = Scope::Fresh;
        candidates = around(&h.log);
    }
}

/// What a local check of `extend_and_verify` covers.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scope {
    /// The cells changed since the last check.
    Fresh,
    /// Every cell changed since the complete check: the part of the dual `splice` takes.
    All,
}

/// The hexagons the extended rules of Sec. 5.2 (with the departures of the module docs) want
/// subdivided or made full, sorted.
pub(crate) fn extended_actions(h: &Hierarchy, r: &Rings, candidates: &KeySet) -> Vec<(Key, Why)> {
    let mut acts: Vec<(Key, Why)> = r.conflicts.iter().map(|&k| (k, Why::Other)).collect();
    // Only an unsubdivided cell with a subdivided neighbour (a full leaf with fins) has a rule
    // here, and most candidates have none: a whole block of candidates is sifted with its
    // subdivided cells and theirs beside it at once (`Hierarchy::subdivided_block`), and only
    // what is left is examined cell by cell. The blocks are examined independently
    // (read-only), so long lists are split over the machine's threads; the result is sorted,
    // the same for any split.
    let blocks: Vec<(Key, u64)> = candidates.blocks().collect();
    let parts = in_parallel_from(&blocks, PARALLEL_MIN / 16, |chunk| {
        let mut keys = Vec::new();
        for &(b, word) in chunk {
            let (subdivided, beside) = h.subdivided_block(b);
            let mut left = word & !subdivided & beside;
            while left != 0 {
                let n = left.trailing_zeros() as i64;
                left &= left - 1;
                keys.push(KeySet::cell_in_block(b, n));
            }
        }
        actions_of(h, r, &keys)
    });
    for part in parts {
        acts.extend(part);
    }
    acts.sort_unstable_by_key(|a| (a.0.packed(), a.1));
    acts.dedup_by_key(|a| a.0);
    acts
}

/// The actions of `extended_actions` for some of the candidates, unsorted.
fn actions_of(h: &Hierarchy, r: &Rings, candidates: &[Key]) -> Vec<(Key, Why)> {
    let mut acts = Vec::new();
    for &key in candidates {
        // Only full leaves with fins have rules here: the fins (the cell and its neighbours
        // from one block lookup, mostly) rule most candidates out before the parents are
        // looked at.
        if !key.inside() {
            continue;
        }
        let (subdivided, mask) = subdivided_and_neighbours(h, key);
        if subdivided || mask == 0 || !h.is_full_leaf(key) {
            continue;
        }
        let (class, strip) = fin_class(mask);
        // SUBDIVIDE, and MOVED_CENTER_3 (departure, module docs).
        if class == Class::Subdivide {
            acts.push((key, Why::Other));
            continue;
        }
        // A moved centre in the 1-ring of OCCUPIED_1 or the 1- or 2-ring of OCCUPIED_2; and
        // (departure) a hexagon with fins centred on the boundary of the bounding hexagon,
        // whose centre cannot move inwards without spoiling the boundary triangles.
        if (r.marked.contains(&key) && r.roles.contains_key(&key)) || key.on_boundary() {
            acts.push((key, Why::Other));
            continue;
        }
        // Every full hexagon adjacent to a fin must have a fixed centre.
        let Some(strip) = strip else { continue };
        let fixed_beyond = (0..strip.len).all(|t| {
            let d = (strip.first + t) % 6;
            let n = key.neighbor(d);
            [
                n.central_child(),
                n.edge_child((d + 2) % 6),
                n.edge_child((d + 4) % 6),
            ]
            .into_iter()
            .filter(|&c| h.is_full_leaf(c))
            .all(|c| {
                // `mc3::is_mc4` without classifying twice: MOVED_CENTER_4 is a regular
                // full leaf below which a MOVED_CENTER_3 hexagon lies.
                let class = classify(h, r, c).0;
                class.is_fixed()
                    && !(class == Class::FixedCenterRegular && mc3::mc3_below(h, r, c) != 0)
            })
        });
        if !fixed_beyond {
            acts.push((key, Why::Other));
            continue;
        }
        // Departure (found by the self-check, which subdivided such hexagons on every
        // random set): three mutually adjacent MOVED_CENTER_1/2 hexagons whose fins point
        // different ways (a strip of one level between finer regions on both sides, or a
        // corner of a transition) move apart, and their triangle drops to 35°-40°. Sec. 5.4
        // derives each relocation with fixed hexagons beside the moved one. The triangle is
        // measured here, with the relocations of Sec. 5.4, and its smallest key subdivided,
        // as the self-check would, before any dual is built.
        if let Some(k) = spread_moved_triangle(h, key, class, strip) {
            acts.push((k, Why::Other));
            continue;
        }
        // The rules on MOVED_CENTER_3 hexagons and their top neighbour (Sec. 5.2, `mc3`).
        if class == Class::MovedCenter3 {
            acts.extend(
                mc3::actions_for(h, r, key)
                    .into_iter()
                    .map(|k| (k, Why::Mc3)),
            );
        }
    }
    acts
}

/// Which rule asked for a subdivision (for `ExtendedStats`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Why {
    /// A MOVED_CENTER_3 rule.
    Mc3,
    Other,
}

/// The cells whose extended rules can change when the hexagons `subdivided` are split: the
/// next level around each (its children and the rings of a point moved into them), its own
/// level (neighbours that got fins, rings that lost their point), and the level above (hexagons
/// whose fins border those neighbours). As a block set: at plane-1m a round's candidates are
/// tens of millions of cells, a few bytes each here against 24 in a list of keys.
pub(crate) fn around(subdivided: &[Key]) -> KeySet {
    // A disc of radius R around a cell lies inside the union of the discs of radius R around
    // its six neighbours (a step from the cell towards any point of the disc brings it within
    // R of that neighbour), and the same holds for the discs around central children (radius
    // 4 around 2c is covered by the discs around the 2n). So a source whose six neighbours
    // are sources of the same kind adds nothing and is skipped; the rest are unioned with a
    // block bitset (`KeySet::insert_disc`), a few table lookups per disc.
    let own: FxHashSet<Key> = subdivided.iter().copied().collect();
    let parents: FxHashSet<Key> = subdivided
        .iter()
        .filter(|s| s.k > 0)
        .map(|s| Key::new(s.k - 1, s.i.div_euclid(2), s.j.div_euclid(2)))
        .collect();
    let interior = |set: &FxHashSet<Key>, c: Key| (0..6).all(|d| set.contains(&c.neighbor(d)));
    let mut cells = KeySet::with_capacity(4 * subdivided.len() + 64);
    for &s in subdivided {
        if !interior(&own, s) {
            cells.insert_disc(s.central_child(), 4);
            cells.insert_disc(s, 3);
        }
    }
    for &p in &parents {
        if !interior(&parents, p) {
            cells.insert_disc(p, 3);
        }
    }
    cells
}

/// The centre of a MOVED_CENTER_1 or MOVED_CENTER_2 full leaf relocated as in Sec. 5.4:
/// Ĉ = 5/6·C + 1/6·C_f0 towards the full hexagon beyond the fin, or Ĉ = 3/5·C + 2/5·C_f01
/// towards the full hexagon between the two fins.
fn moved_centre(h: &Hierarchy, key: Key, class: Class, strip: FinStrip) -> Option<Point> {
    let c = h.lattice.center(key);
    let lerp = |a: Point, b: Point, t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    match class {
        Class::MovedCenter1 => Some(lerp(
            c,
            h.lattice.center(key.neighbor(strip.first)),
            1.0 / 6.0,
        )),
        Class::MovedCenter2 => {
            let a = key.neighbor(strip.first);
            let b = key.neighbor((strip.first + 1) % 6);
            let m = Key::new(key.k + 1, a.i + b.i, a.j + b.j);
            Some(lerp(c, h.lattice.center(m), 2.0 / 5.0))
        }
        _ => None,
    }
}

/// The MOVED_CENTER_1/2 full leaf with fins of `key`'s level adjacent to it, with its class
/// and strip.
fn moved_neighbour(h: &Hierarchy, n: Key) -> Option<(Class, FinStrip)> {
    if !n.inside() {
        return None;
    }
    let (subdivided, mask) = subdivided_and_neighbours(h, n);
    if subdivided || mask == 0 || !h.is_full_leaf(n) {
        return None;
    }
    match fin_class(mask) {
        (c @ (Class::MovedCenter1 | Class::MovedCenter2), Some(s)) => Some((c, s)),
        _ => None,
    }
}

/// A triangle of `key` (MOVED_CENTER_1/2 with `strip`) and two adjacent MOVED_CENTER_1/2
/// neighbours whose relocated centres break the angle bounds of the self-check: the key to
/// subdivide (the smallest of the three, as the self-check picks), if any.
fn spread_moved_triangle(h: &Hierarchy, key: Key, class: Class, strip: FinStrip) -> Option<Key> {
    let here = moved_centre(h, key, class, strip)?;
    let near: Vec<Option<(Key, Point)>> = (0..6)
        .map(|d| {
            let n = key.neighbor(d);
            let (c, s) = moved_neighbour(h, n)?;
            Some((n, moved_centre(h, n, c, s)?))
        })
        .collect();
    let filter = angle_filter();
    for d in 0..6 {
        let (Some((a, pa)), Some((b, pb))) = (near[d], near[(d + 1) % 6]) else {
            continue;
        };
        let t = [here, pa, pb];
        if filter.clearly_within(&t) {
            continue;
        }
        if breaks_bounds(&t) {
            return [key, a, b].into_iter().min_by_key(|k| (k.k, *k));
        }
    }
    None
}

/// The relocated centres of Sec. 5.4, keyed by `Key::canonical`, and the dual rebuilt around
/// MOVED_CENTER_3 hexagons (`mc3`). Occupied centres are replaced by their points in the dual
/// builder.
pub fn relocations(h: &Hierarchy, r: &Rings) -> (FxHashMap<Key, Point>, Patch) {
    // The relocations of the leaves do not depend on their order (the chains are sorted).
    relocations_of(h, r, h.full_leaves_unordered())
}

/// The relocated centres and the MOVED_CENTER_3 patch of `relocations`, for the full leaves
/// `leaves` only (chains are built for the MOVED_CENTER_3 hexagons among them).
pub fn relocations_of(
    h: &Hierarchy,
    r: &Rings,
    leaves: impl IntoIterator<Item = Key>,
) -> (FxHashMap<Key, Point>, Patch) {
    let leaves: Vec<Key> = leaves.into_iter().collect();
    let lerp = |a: Point, b: Point, t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    // Each leaf's relocation depends only on the hierarchy and the rings: computed over
    // threads for long lists, then collected in the order of `leaves`.
    let parts = in_parallel(&leaves, |chunk| {
        let mut out: Vec<(Key, Option<Point>)> = Vec::new();
        for &key in chunk {
            let c = h.lattice.center(key);
            let (class, strip) = classify(h, r, key);
            let p = match (class, strip) {
                (Class::MovedCenterInRing, _) => match r.roles.get(&key) {
                    Some(Role::Moved { shift, .. }) => [c[0] + shift[0], c[1] + shift[1]],
                    _ => continue,
                },
                // Ĉ = 5/6·C + 1/6·C_f0, towards the full hexagon beyond the fin.
                (Class::MovedCenter1, Some(s)) => {
                    lerp(c, h.lattice.center(key.neighbor(s.first)), 1.0 / 6.0)
                }
                // Ĉ = 3/5·C + 2/5·C_f01, towards the full hexagon between the two fins.
                (Class::MovedCenter2, Some(s)) => {
                    let a = key.neighbor(s.first);
                    let b = key.neighbor((s.first + 1) % 6);
                    let m = Key::new(key.k + 1, a.i + b.i, a.j + b.j);
                    lerp(c, h.lattice.center(m), 2.0 / 5.0)
                }
                // MOVED_CENTER_3 hexagons go to the chains (`mc3`).
                (Class::MovedCenter3, _) => {
                    out.push((key, None));
                    continue;
                }
                _ => continue,
            };
            out.push((key, Some(p)));
        }
        out
    });
    let mut moved = FxHashMap::with_capacity_and_hasher(leaves.len() / 2, Default::default());
    let mut mc3_keys = Vec::new();
    for (key, p) in parts.into_iter().flatten() {
        match p {
            Some(p) => {
                moved.insert(key.canonical(), p);
            }
            None => mc3_keys.push(key),
        }
    }
    let mut patch = Patch::default();
    for chain in mc3::chains(h, r, &mc3_keys) {
        mc3::build(h, r, chain, &mut moved, &mut patch);
    }
    (moved, patch)
}

/// How far a triangle is inside the bounds of Sec. 6.1, in degrees: the smaller of
/// (smallest angle − α) and (90° − largest angle); negative when a bound is broken, and -180
/// for a triangle that is not counter-clockwise.
fn angle_margin(t: [Point; 3]) -> f64 {
    if orient2d(t[0], t[1], t[2]) <= 0.0 {
        return -180.0;
    }
    let a = [
        angle_deg(t[0], t[1], t[2]),
        angle_deg(t[1], t[2], t[0]),
        angle_deg(t[2], t[0], t[1]),
    ];
    let lo = a[0].min(a[1]).min(a[2]);
    let hi = a[0].max(a[1]).max(a[2]);
    (lo - min_angle_bound()).min(90.0 - hi)
}

/// The cheap test that every angle of a triangle lies clearly inside the self-check's bounds
/// [α − slack, 90° + slack] (`quality::rounding::AngleWindow`).
fn angle_filter() -> AngleWindow {
    AngleWindow::new(min_angle_bound(), 90.0, SELF_CHECK_SLACK)
}

/// Places the centres of contested ring cells (departure from Sec. 5.4, module docs).
///
/// A cell in the moved 1-ring of one OCCUPIED_2 point and the fixed 2-ring of another, three
/// cells apart, cannot in general keep either position: the point's ring wants it shifted by
/// ½r towards its corner, the other ring wants it at its centre, and when the two points lie
/// on the far sides of their hexagons each choice leaves an angle below α (Sec. 6.3 lets such
/// pairs exist without refining them). The angles at a contested cell depend only on its own
/// position once its neighbours are placed, so each contested cell whose triangles break a
/// bound is moved, one cell at a time, to the candidate position (its centre, or r/16 to ½r in steps of r/16,
/// in one of twenty-four directions) that most reduces the summed bound violation of
/// its triangles, never making an edge shorter than `l_min` (Sec. 6.3); a few sweeps settle
/// neighbouring contested cells. Cells whose triangles are good stay where their role put
/// them. A second pass (`with_neighbours`) also moves the ring cells next to contested ones,
/// accepting only moves that lower the number of bad triangles around the moved cell.
/// Returns its moves (`Moves`).
fn settle_contested(
    h: &Hierarchy,
    mesh: &mut TriMesh,
    keys: &[Key],
    l_min: f64,
    pass: SettlePass<'_>,
    movable: &dyn Fn(Key) -> bool,
) -> Moves {
    let SettlePass {
        rings: r,
        cells: wanted,
        with_neighbours,
    } = pass;
    if r.contested.is_empty() && !with_neighbours {
        return Moves::default();
    }
    let slack = SELF_CHECK_SLACK;
    // The vertices of contested cells, with their lattice centre and radius, sorted by key.
    let mut cells: Vec<(Key, usize, Point, f64)> = Vec::new();
    for (v, k) in keys.iter().enumerate() {
        if let Some(leaf) = wanted.cell(h, r, *k, with_neighbours) {
            if v >= h.points.len() && movable(*k) {
                cells.push((leaf, v, h.lattice.center(leaf), h.lattice.radius(leaf.k)));
            }
        }
    }
    if cells.is_empty() {
        return Moves::default();
    }
    cells.sort_by_key(|c| c.0);
    // The cell of each mesh vertex (u32::MAX: none), and the triangles around each cell.
    let mut cell_of = vec![u32::MAX; mesh.vertices.len()];
    for (n, c) in cells.iter().enumerate() {
        cell_of[c.1] = n as u32;
    }
    // Compressed rows: the triangles of cell n are incident_tris[start[n]..start[n + 1]].
    let mut start = vec![0usize; cells.len() + 1];
    for tri in &mesh.triangles {
        for &v in tri {
            let n = cell_of[v as usize];
            if n != u32::MAX {
                start[n as usize + 1] += 1;
            }
        }
    }
    for n in 0..cells.len() {
        start[n + 1] += start[n];
    }
    let mut fill = start.clone();
    let mut incident_tris = vec![0usize; start[cells.len()]];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            let n = cell_of[v as usize];
            if n != u32::MAX {
                incident_tris[fill[n as usize]] = t;
                fill[n as usize] += 1;
            }
        }
    }
    let incident = |n: usize| &incident_tris[start[n]..start[n + 1]];
    // Around vertex `v` placed at `p`: how far edges fall short of `l_min`, triangles breaking an angle
    // bound, their summed violation (degrees, negative) and the worst margin.
    // A triangle that is counter-clockwise and whose angles are clearly within the bounds
    // (`angle_filter`) has a margin above -slack: it adds nothing to `bad` or `pen`, and
    // its margin is measured only when `worst` is asked for.
    let filter = angle_filter();
    let corners_at = |mesh: &TriMesh, t: usize, v: usize, p: Point| -> [Point; 3] {
        let mut c = mesh.corners(t);
        for (m, &w) in mesh.triangles[t].iter().enumerate() {
            if w as usize == v {
                c[m] = p;
            }
        }
        c
    };
    let score = |mesh: &TriMesh, tris: &[usize], v: usize, p: Point| -> Score {
        let mut sc = Score {
            short: 0.0,
            bad: 0,
            pen: 0.0,
            worst: None,
        };
        for &t in tris {
            let c = corners_at(mesh, t, v, p);
            sc.short += (0..3)
                .map(|e| (l_min - crate::geom::dist(c[e], c[(e + 1) % 3])).max(0.0))
                .sum::<f64>();
            if orient2d(c[0], c[1], c[2]) > 0.0 && filter.clearly_within(&c) {
                continue;
            }
            let m = angle_margin(c);
            if m < -slack {
                sc.pen += m;
                sc.bad += 1;
            }
        }
        sc
    };
    // The smallest margin of the triangles around `v` at `p`, measured once per score.
    let worst = |sc: &mut Score, mesh: &TriMesh, tris: &[usize], v: usize, p: Point| -> f64 {
        *sc.worst.get_or_insert_with(|| {
            tris.iter()
                .map(|&t| angle_margin(corners_at(mesh, t, v, p)))
                .fold(f64::INFINITY, f64::min)
        })
    };
    // The first pass never makes an edge shorter than l_min; the second, which moves cells
    // that are not contested, never adds a bad triangle around the moved cell either, and
    // shortens no edge for the sake of an angle (or the reverse). With as much violation,
    // the larger smallest margin wins.
    let better = |mesh: &TriMesh,
                  tris: &[usize],
                  v: usize,
                  (a, pa): (&mut Score, Point),
                  (b, pb): (&mut Score, Point)| {
        if with_neighbours && a.bad != b.bad {
            return a.bad < b.bad && a.short <= b.short;
        }
        if a.short != b.short {
            return a.short < b.short && (!with_neighbours || a.bad <= b.bad);
        }
        a.pen > b.pen
            || (a.pen == b.pen && worst(a, mesh, tris, v, pa) > worst(b, mesh, tris, v, pb))
    };
    // A triangle adds to `bad` or `short` in `score` exactly when it breaks an angle bound
    // by more than the slack or has an edge shorter than `l_min`: a cell none of whose
    // triangles does so scores (0, 0) and stays, so only the cells of flagged triangles are
    // scored (flags are refreshed around every move).
    let flag = |mesh: &TriMesh, t: usize| -> bool {
        let c = mesh.corners(t);
        (0..3).any(|e| crate::geom::dist(c[e], c[(e + 1) % 3]) < l_min)
            || orient2d(c[0], c[1], c[2]) <= 0.0
            || (!filter.clearly_within(&c) && angle_margin(c) < -slack)
    };
    // Per triangle: 0 not around a cell, 1 fine, 2 flagged.
    let mut flagged = vec![0u8; mesh.triangles.len()];
    for &t in &incident_tris {
        if flagged[t] == 0 {
            flagged[t] = 1 + flag(mesh, t) as u8;
        }
    }
    let mut moves = Moves::default();
    for _sweep in 0..6 {
        let mut changed = false;
        for (n, &(_, v, centre, radius)) in cells.iter().enumerate() {
            if !incident(n).iter().any(|&t| flagged[t] == 2) {
                continue;
            }
            let here = mesh.vertices[v];
            let mut best_score = score(mesh, incident(n), v, here);
            if best_score.bad == 0 && best_score.short == 0.0 {
                continue;
            }
            let mut best = here;
            for step in 0..=8 {
                let rho = radius * step as f64 / 16.0;
                for dir in 0..if step == 0 { 1 } else { 24 } {
                    let a = (dir as f64 * 15.0).to_radians();
                    let p = [centre[0] + rho * a.cos(), centre[1] + rho * a.sin()];
                    let mut sc = score(mesh, incident(n), v, p);
                    if better(mesh, incident(n), v, (&mut sc, p), (&mut best_score, best)) {
                        (best_score, best) = (sc, p);
                    }
                }
            }
            if best != here {
                moves.make(mesh, v, best);
                changed = true;
                for &t in incident(n) {
                    flagged[t] = 1 + flag(mesh, t) as u8;
                }
            }
        }
        if !changed {
            break;
        }
    }
    moves
}

/// The last local search before a subdivision (departure from Sec. 5.4, as
/// `settle_contested`): the ring cells among the vertices of the rejected triangles `bad`,
/// and the ring cells beside them, move by a pattern search (16 directions, steps from r/4
/// halving down to r/4096, at most 0.6·r from the lattice centre) to the first position that
/// lowers the number of triangles around the cell breaking an angle bound, without an edge
/// shorter than `l_min` (Sec. 6.3); with as many bad triangles, to one that lowers their
/// summed violation. Sweeps repeat while something moves (at most 24). Two OCCUPIED_2 points
/// three cells apart and 5.1·r to 7.2·r apart need this: their rings pull the cells between
/// them two ways, the coarser search of `settle_contested` left 0.06° to 5° of violation on 3
/// of 100,000 fuzzed sets (fixtures hex-polish-*), and a subdivision there goes below r_min
/// (Sec. 6.3) and shortens edges below `l_min`. Returns its moves (`Moves`).
fn polish_rings(
    h: &Hierarchy,
    r: &Rings,
    mesh: &mut TriMesh,
    keys: &[Key],
    bad: &[usize],
    l_min: f64,
    movable: &dyn Fn(Key) -> bool,
) -> Moves {
    let slack = SELF_CHECK_SLACK;
    // Ring cells by canonical key.
    let mut ring: FxHashMap<Key, Key> = FxHashMap::default();
    for &c in r.roles.keys() {
        if h.is_full_leaf(c) {
            ring.insert(c.canonical(), c);
        }
    }
    let is_cell = |v: usize| -> Option<Key> {
        if v < h.points.len() || !movable(keys[v]) {
            return None;
        }
        ring.get(&keys[v]).copied()
    };
    // Triangles around each vertex.
    let mut around_vertex: Vec<Vec<usize>> = vec![Vec::new(); mesh.vertices.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            around_vertex[v as usize].push(t);
        }
    }
    // The cells to move: ring vertices of bad triangles, and ring vertices sharing a triangle
    // with them.
    let mut first: Vec<usize> = bad
        .iter()
        .flat_map(|&t| mesh.triangles[t].iter().map(|&v| v as usize))
        .filter(|&v| is_cell(v).is_some())
        .collect();
    first.sort_unstable();
    first.dedup();
    let mut cells: Vec<usize> = first.clone();
    for &v in &first {
        for &t in &around_vertex[v] {
            cells.extend(
                mesh.triangles[t]
                    .iter()
                    .map(|&w| w as usize)
                    .filter(|&w| is_cell(w).is_some()),
            );
        }
    }
    cells.sort_unstable();
    cells.dedup();
    let score = |mesh: &TriMesh, v: usize, p: Point| -> Score {
        let mut sc = Score {
            short: 0.0,
            bad: 0,
            pen: 0.0,
            worst: None,
        };
        for &t in &around_vertex[v] {
            let mut c = mesh.corners(t);
            for (m, &w) in mesh.triangles[t].iter().enumerate() {
                if w as usize == v {
                    c[m] = p;
                }
            }
            sc.short += (0..3)
                .map(|e| (l_min - crate::geom::dist(c[e], c[(e + 1) % 3])).max(0.0))
                .sum::<f64>();
            let m = angle_margin(c);
            if m < -slack {
                sc.pen += m;
                sc.bad += 1;
            }
        }
        sc
    };
    let better = |a: &Score, b: &Score| {
        if a.short > b.short {
            return false;
        }
        if a.bad != b.bad {
            return a.bad < b.bad;
        }
        a.short < b.short || a.pen > b.pen
    };
    let dirs: Vec<(f64, f64)> = (0..16)
        .map(|d| {
            let a = (d as f64 * 22.5).to_radians();
            (a.cos(), a.sin())
        })
        .collect();
    let mut moves = Moves::default();
    for _sweep in 0..24 {
        let mut changed = false;
        for &v in &cells {
            let Some(cell) = is_cell(v) else { continue };
            let centre = h.lattice.center(cell);
            let radius = h.lattice.radius(cell.k);
            let mut here = mesh.vertices[v];
            let mut best = score(mesh, v, here);
            if best.bad == 0 && best.short == 0.0 {
                continue;
            }
            let mut step = radius / 4.0;
            while step >= radius / 4096.0 {
                let mut improved = false;
                for &(dx, dy) in &dirs {
                    let p = [here[0] + step * dx, here[1] + step * dy];
                    if crate::geom::dist(p, centre) > 0.6 * radius {
                        continue;
                    }
                    let sc = score(mesh, v, p);
                    if better(&sc, &best) {
                        (best, here, improved) = (sc, p, true);
                        break;
                    }
                }
                if !improved {
                    step /= 2.0;
                }
            }
            if here != mesh.vertices[v] {
                moves.make(mesh, v, here);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    moves
}

/// One pass of `settle_contested`: the rings, their `SettleCells`, and whether the ring
/// cells next to contested ones may move too.
#[derive(Clone, Copy)]
struct SettlePass<'a> {
    rings: &'a Rings,
    cells: &'a SettleCells,
    with_neighbours: bool,
}

/// The cells `settle_contested` may move, by the canonical key of their vertex: the
/// contested cells; in the second pass every ring cell that is a full leaf, since when a
/// contested cell alone cannot reach a good position its neighbour in the same ring has to
/// give way, and a moved ring cell may come closer to an OCCUPIED_2 point than l_min. They
/// depend only on which cells the rings hold (a flip or a corner switch changes roles, not
/// cells): for the complete check they are listed once per set of rings (`Listed`); a local
/// check, on a small part of the dual, looks its vertices up in the rings (`Lookup`) instead
/// of listing all of them each round. Of two contested cells with the same centre (at two
/// levels) the finer one is taken, either way.
/// A listed cell is kept as its level under the canonical key (the cell is the canonical
/// key's central child that many levels down), in 8 × 8 blocks: every vertex of the complete
/// dual is looked up, in the dual's order, and neighbouring vertices share a block.
enum SettleCells {
    Listed { contested: KeyBytes, ring: KeyBytes },
    Lookup,
}

impl SettleCells {
    fn listed(h: &Hierarchy, r: &Rings) -> SettleCells {
        let mut contested = KeyBytes::default();
        for &c in r.contested.keys() {
            let k = c.canonical();
            if contested.get(&k).is_none_or(|level| c.k > level) {
                contested.insert(k, c.k);
            }
        }
        let mut ring = contested.clone();
        for &c in r.roles.keys() {
            if h.is_full_leaf(c) {
                ring.insert(c.canonical(), c.k);
            }
        }
        SettleCells::Listed { contested, ring }
    }

    /// The cell of the vertex with canonical key `key` that the first pass (or, with
    /// `with_neighbours`, the second) may move.
    fn cell(&self, h: &Hierarchy, r: &Rings, key: Key, with_neighbours: bool) -> Option<Key> {
        match self {
            SettleCells::Listed { contested, ring } => {
                let map = if with_neighbours { ring } else { contested };
                map.get(&key).map(|level| {
                    let s = level - key.k;
                    Key::new(level, key.i << s, key.j << s)
                })
            }
            SettleCells::Lookup => {
                // The cells with this centre: one per level from `key` down; a ring cell
                // lies at the level of an occupied hexagon, so no deeper than `deepest`.
                let mut c = key;
                let mut leaf = None;
                let mut found = None;
                loop {
                    if r.contested.contains_key(&c) {
                        found = Some(c);
                    }
                    if leaf.is_none() && !h.is_subdivided(c) {
                        leaf = Some(c);
                    }
                    if c.k >= h.deepest() {
                        break;
                    }
                    c = c.central_child();
                }
                match leaf {
                    Some(l) if with_neighbours && r.roles.contains_key(&l) && h.is_full_leaf(l) => {
                        Some(l)
                    }
                    _ => found,
                }
            }
        }
    }
}

/// How the triangles around one vertex fare (`settle_contested`).
struct Score {
    /// Summed shortfall of the edges below `l_min`.
    short: f64,
    bad: usize,
    pen: f64,
    /// The smallest angle margin (`angle_margin`), when measured.
    worst: Option<f64>,
}

/// A triangle of the dual that breaks the angle bounds or the exact empty-circle test.
struct BadTriangle {
    /// Its index in the checked mesh.
    triangle: usize,
    /// The leaf hexagons of its three vertices.
    vertices: [Key; 3],
    /// The coarsest of them, the one to subdivide.
    coarsest: Key,
}

/// The triangles that break the angle bounds or the exact empty-circle test.
fn offending_leaves(
    h: &Hierarchy,
    mesh: &TriMesh,
    keys: &[Key],
    rounding_pairs: &mut u64,
) -> Vec<BadTriangle> {
    let filter = angle_filter();
    let mut bad_tris: Vec<usize> = Vec::new();
    for t in 0..mesh.triangles.len() {
        let c = mesh.corners(t);
        if filter.clearly_within(&c) {
            continue;
        }
        if breaks_bounds(&c) {
            bad_tris.push(t);
        }
    }
    // A pair that only rounding made non-Delaunay is flipped once the mesh is finished
    // (`settle_rounding`), not refined.
    for (t, u) in delaunay_violations(mesh) {
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
    let mut out = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
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
}

/// The pair (t, u) sharing an edge, as (p, q, w1, w2): t = (p, q, w1) and u = (q, p, w2), both
/// counter-clockwise, so that the quadrilateral is p, w2, q, w1.
fn shared_edge(mesh: &TriMesh, t: usize, u: usize) -> Option<[u32; 4]> {
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
fn rounding_made(mesh: &TriMesh, t: usize, u: usize) -> bool {
    let Some([p, q, w1, w2]) = shared_edge(mesh, t, u) else {
        return false;
    };
    if flipped(mesh, [p, q, w1, w2]).is_none() {
        return false;
    }
    let v = |i: u32| mesh.vertices[i as usize];
    let (p, q, w1, w2) = (v(p), v(q), v(w1), v(w2));
    let excess = angle_deg(w1, p, q) + angle_deg(w2, q, p) - 180.0;
    excess <= SELF_CHECK_SLACK
        || excess
            <= SELF_CHECK_SLACK
                + rounding::angle_allowance(w1, p, q)
                + rounding::angle_allowance(w2, q, p)
                - 2.0 * rounding::ANGLE_FLOOR_DEG
}

/// The two triangles of the other diagonal of the quadrilateral p, w2, q, w1 of a shared edge
/// (`shared_edge`), when both are counter-clockwise and keep the angle bounds within the
/// self-check's slack (`breaks_bounds`).
fn flipped(mesh: &TriMesh, [p, q, w1, w2]: [u32; 4]) -> Option<[[u32; 3]; 2]> {
    let new = [[p, w2, w1], [w2, q, w1]];
    let corners = new.map(|tri| tri.map(|i| mesh.vertices[i as usize]));
    corners
        .iter()
        .all(|c| orient2d(c[0], c[1], c[2]) > 0.0 && !breaks_bounds(c))
        .then_some(new)
}

/// Rounds of flips `settle_rounding` makes before it gives up.
const FLIP_ROUNDS: usize = 64;

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
    rounding::check_angles(mesh, points, (min_angle_bound(), 90.0), max_rounding, "hex")
}

/// The flips of `settle_rounding`, at most `FLIP_ROUNDS` rounds of them.
fn flip_rounding_pairs(mesh: &mut TriMesh) {
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

    /// The finished `hex` dual of plane-100 with its vertex keys, the hierarchy, and an
    /// interior vertex far from the bounding hexagon with its region (reach 2).
    fn plane_100() -> (ExtendedRun, TriMesh, Vec<Key>, usize, Region) {
        let input = crate::datasets::by_name("plane-100").expect("a dataset");
        let run = mesh_extended(&input, &Params::default()).expect("meshes");
        let h = &run.hierarchy;
        let r = rings_with_flips(h, &run.rings);
        let (mut moved, patch) = relocations(h, &r);
        apply_placed(&mut moved, &run.rings);
        let (mesh, keys) = dual::extract_patched(h, Placement::Relocated, &moved, &patch);
        let centre = [0.5, 0.5];
        let v = (0..mesh.vertices.len())
            .min_by(|&a, &b| {
                crate::geom::dist2(mesh.vertices[a], centre)
                    .total_cmp(&crate::geom::dist2(mesh.vertices[b], centre))
            })
            .expect("vertices");
        let inner = Region::around(&[h.leaf_of_vertex(keys[v])], 2);
        (run, mesh, keys, v, inner)
    }

    #[test]
    fn a_dual_spliced_with_itself_is_itself() {
        let (run, mesh, keys, _, inner) = plane_100();
        let whole = splice(
            &run.hierarchy,
            (mesh.clone(), keys.clone()),
            &mesh,
            &keys,
            &inner,
        )
        .expect("the seam closes");
        assert_eq!(whole.corner_bits_sorted(), mesh.corner_bits_sorted());
        assert_eq!(whole.vertices.len(), mesh.vertices.len());
    }

    #[test]
    fn a_region_missing_a_triangle_is_not_spliced() {
        let (run, mesh, keys, v, inner) = plane_100();
        let mut part = mesh.clone();
        let t = part
            .triangles
            .iter()
            .position(|t| t.contains(&(v as u32)))
            .expect("a triangle at the vertex");
        part.triangles.remove(t);
        assert!(splice(&run.hierarchy, (mesh, keys.clone()), &part, &keys, &inner).is_none());
    }

    #[test]
    fn a_region_that_moves_a_seam_vertex_is_not_spliced() {
        let (run, mesh, keys, _, inner) = plane_100();
        let h = &run.hierarchy;
        let inside = |w: u32| inner.contains(h.leaf_of_vertex(keys[w as usize]));
        // A vertex outside the region on a triangle that has one inside: on the seam.
        let seam = mesh
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&w| inside(w)))
            .flat_map(|t| t.iter().copied())
            .find(|&w| !inside(w))
            .expect("a seam vertex");
        let mut part = mesh.clone();
        part.vertices[seam as usize][0] += 1e-9;
        assert!(splice(h, (mesh, keys.clone()), &part, &keys, &inner).is_none());
    }
}
