//! The settling searches: our departure from paper 000 (Sußner & Greiner 2009) Sec. 5.4,
//! which gives each ring cell one position by its class. A cell in the moved ring of one
//! OCCUPIED_2 point and the fixed ring of another cannot in general keep either position;
//! `settle_contested` searches for a position that keeps the angle bounds (and the shortest
//! edge of Sec. 6.3), and `polish_rings`, a finer pattern search, is the last resort before a
//! subdivision below the r_min of Sec. 6.3.

use crate::geom::angle_deg;
use crate::geom::{orient2d, Point};
use crate::hex::classify::Rings;
use crate::hex::lattice::{FxHashMap, Key, KeyBytes};
use crate::hex::parallel::{
    each_in_parallel, fill_in_parallel, in_parallel, merge_sorted_runs, ranges_in_parallel,
    PARALLEL_MIN,
};
use crate::hex::subdivision::Hierarchy;
use crate::mesh::TriMesh;
use crate::quality::HEX;

/// Keeps in `placed` the place of every vertex of `mesh` (with canonical keys `keys`) that
/// `moves` moved and that ends elsewhere than it stood before.
pub(super) fn record_moves(
    placed: &mut FxHashMap<Key, Point>,
    moves: Moves,
    mesh: &TriMesh,
    keys: &[Key],
) {
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
pub(super) struct Moves {
    pub(super) count: u64,
    pub(super) from: Vec<(usize, Point)>,
}

impl Moves {
    /// Moves vertex `v` of `mesh` to `p`.
    fn make(&mut self, mesh: &mut TriMesh, v: usize, p: Point) {
        self.count += 1;
        self.from.push((v, mesh.vertices[v]));
        mesh.vertices[v] = p;
    }
}

/// How far a triangle is inside the bounds of Sec. 6.1, in degrees: the smaller of
/// (smallest angle − α) and (90° − largest angle); negative when a bound is broken, and -180
/// for a triangle that is not counter-clockwise.
pub(super) fn angle_margin(t: [Point; 3]) -> f64 {
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
    (lo - HEX.min_angle).min(90.0 - hi)
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
/// Returns its moves (`Moves`). The sweeps run over the hierarchy's threads in stages of cells
/// that share no triangle (`stages`), with the moves of the sweep cell by cell.
pub(super) fn settle_contested(
    h: &Hierarchy,
    mesh: &mut TriMesh,
    keys: &[Key],
    l_min: f64,
    pass: SettlePass<'_>,
    movable: &(dyn Fn(Key) -> bool + Sync),
) -> Moves {
    let SettlePass {
        rings: r,
        cells: wanted,
        with_neighbours,
    } = pass;
    if r.contested.is_empty() && !with_neighbours {
        return Moves::default();
    }
    let slack = HEX.self_check_slack;
    // The vertices of contested cells, with their lattice centre and radius, sorted by key
    // (then vertex); looked up and sorted over the hierarchy's threads in ranges of vertices,
    // the ranges merged (1.4 million cells in the second pass at plane-100k: sorted on one
    // thread, 0.14 s).
    let runs = ranges_in_parallel(h.threads(), keys.len(), PARALLEL_MIN, |range| {
        let mut cells = Vec::new();
        let from = range.start.max(h.points.len());
        for (v, &k) in keys[..range.end].iter().enumerate().skip(from) {
            if let Some(leaf) = wanted.cell(h, r, k, with_neighbours) {
                if movable(k) {
                    cells.push((leaf, v, h.lattice.center(leaf), h.lattice.radius(leaf.k)));
                }
            }
        }
        cells.sort_unstable_by_key(|c: &(Key, usize, Point, f64)| (c.0.packed(), c.1));
        cells
    });
    let cells = merge_sorted_runs(runs, |c| (c.0.packed(), c.1));
    if cells.is_empty() {
        return Moves::default();
    }
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
    let filter = HEX.angle_filter();
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
    // Per triangle: 0 not around a cell, 1 fine, 2 flagged. Few cells' triangles are flagged
    // one by one; many (the second pass: most of the mesh) over the threads, in ranges of
    // triangles.
    let mut flagged: Vec<u8> = if incident_tris.len() < mesh.triangles.len() / 8 {
        let mut flagged = vec![0u8; mesh.triangles.len()];
        for &t in &incident_tris {
            if flagged[t] == 0 {
                flagged[t] = 1 + flag(mesh, t) as u8;
            }
        }
        flagged
    } else {
        let view: &TriMesh = mesh;
        let mut flagged = vec![0u8; view.triangles.len()];
        fill_in_parallel(h.threads(), &mut flagged, PARALLEL_MIN, |t| {
            let around = view.triangles[t]
                .iter()
                .any(|&v| cell_of[v as usize] != u32::MAX);
            if around {
                1 + flag(view, t) as u8
            } else {
                0
            }
        });
        flagged
    };
    // Where cell n, one of whose triangles is flagged, goes in a sweep: its best candidate
    // (`better`) under the places the sweep has reached, `None` when it stays.
    let search = |mesh: &TriMesh, n: usize| -> Option<Point> {
        let (_, v, centre, radius) = cells[n];
        let here = mesh.vertices[v];
        let mut best_score = score(mesh, incident(n), v, here);
        if best_score.bad == 0 && best_score.short == 0.0 {
            return None;
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
        (best != here).then_some(best)
    };
    // A sweep visits the cells in order, and each move is seen by the cells after it. A
    // search reads only its cell's triangles and their flags, so a cell waits only for the
    // cells before it that share a triangle with it: over threads, the cells go in stages
    // (`stages`), a cell one stage after the last such cell, and the cells of a stage, which
    // share no triangle, are searched side by side against the places the earlier stages
    // left. The moves are those of the sequential sweep, for any number of threads.
    let threads = h.threads();
    // Built at the first sweep with at least `STAGED_MIN` cells to search, and one for every
    // `CELLS_PER_SEARCH` cells: below that, the stages (0.18 s for the 1.4 million cells of
    // plane-100k's second pass) and visiting the cells stage by stage cost more than the
    // threads gain, and the cells go one by one.
    let mut staged: Option<Vec<Vec<u32>>> = None;
    // Whether a cell's flags may have changed since it was last found without a flagged
    // triangle: only a move of a cell sharing a triangle changes them, so the later sweeps
    // look only at the cells near the moves.
    let mut look = vec![true; cells.len()];
    let mut moves = Moves::default();
    // Moves cell n to `best`, refreshing the flags of its triangles and marking the cells
    // that share them.
    let mut apply = |mesh: &mut TriMesh, flagged: &mut [u8], look: &mut [bool], n: usize, best| {
        moves.make(mesh, cells[n].1, best);
        for &t in incident(n) {
            flagged[t] = 1 + flag(mesh, t) as u8;
            for &w in &mesh.triangles[t] {
                if let Some(l) = look.get_mut(cell_of[w as usize] as usize) {
                    *l = true;
                }
            }
        }
    };
    let wanted = |flagged: &[u8], look: &mut [bool], n: usize| -> bool {
        look[n] && {
            look[n] = incident(n).iter().any(|&t| flagged[t] == 2);
            look[n]
        }
    };
    for _sweep in 0..6 {
        let mut changed = false;
        // The cells flagged as the sweep starts (a move can flag more, near it).
        let to_search = if threads < 2 {
            0
        } else {
            (0..cells.len())
                .filter(|&n| look[n] && incident(n).iter().any(|&t| flagged[t] == 2))
                .count()
        };
        if to_search < STAGED_MIN || to_search * CELLS_PER_SEARCH < cells.len() {
            for n in 0..cells.len() {
                if wanted(&flagged, &mut look, n) {
                    if let Some(best) = search(mesh, n) {
                        apply(mesh, &mut flagged, &mut look, n, best);
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
            continue;
        }
        let stages = staged.get_or_insert_with(|| {
            let triangles = &mesh.triangles;
            stages(cells.len(), |n, f| {
                for &t in incident(n) {
                    for &w in &triangles[t] {
                        if let Some(&m) = cell_of.get(w as usize).filter(|&&m| m != u32::MAX) {
                            f(m as usize);
                        }
                    }
                }
            })
        });
        for stage in stages.iter() {
            // The cells of the stage with a flagged triangle, as the sequential sweep finds
            // them at each one's turn.
            let mut active: Vec<usize> = Vec::new();
            for &n in stage {
                if wanted(&flagged, &mut look, n as usize) {
                    active.push(n as usize);
                }
            }
            let view: &TriMesh = mesh;
            // Searches differ several times in cost (a cell with more bad triangles scores
            // more of its places): they are handed out one at a time.
            let places: Vec<Option<Point>> = if active.len() < SETTLE_PARALLEL_MIN {
                active.iter().map(|&n| search(view, n)).collect()
            } else {
                each_in_parallel(threads, &active, |&n| search(view, n))
            };
            for (&n, place) in active.iter().zip(places) {
                if let Some(best) = place {
                    apply(mesh, &mut flagged, &mut look, n, best);
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    moves
}

/// Stages of a sweep with at least this many cells to search are searched over threads: a
/// search scores 193 places, so that a few hundred are worth a thread.
const SETTLE_PARALLEL_MIN: usize = 256;

/// A sweep goes in stages (`stages`) when at least this many cells are flagged as it starts,
/// and at least one in `CELLS_PER_SEARCH` of the cells. A search (about 60 µs) gains half its
/// time on two threads; the stages cost about 0.13 µs a cell to build, and each stage a
/// hand-out to the threads. At plane-100k the first pass (20,703 cells) searches 15,044 cells
/// in its first sweep, 2,889 in its second, 700 to 1,000 in the others; the second pass (1.4
/// million cells) 150 to 1,500: the first two sweeps go in stages. So does plane-10k's first
/// (1,553 of 2,061), which the test of one, two and three threads runs.
const STAGED_MIN: usize = 1024;

/// See `STAGED_MIN`.
const CELLS_PER_SEARCH: usize = 256;

/// The stages of a sweep over `cells` cells (`settle_contested`), where `sharing(n, f)` calls
/// `f` with every cell that shares a triangle with cell n (n itself and repeats allowed):
/// each cell, in order, goes one stage after the latest stage of an earlier cell sharing a
/// triangle with it (the first stage when none does), and each stage lists its cells in
/// order. No two cells of a stage share a triangle, and a cell comes after every earlier cell
/// it shares a triangle with. One number a cell: a number a triangle was 4 bytes an output
/// triangle, about 0.46 GB at plane-1m.
fn stages(cells: usize, sharing: impl Fn(usize, &mut dyn FnMut(usize))) -> Vec<Vec<u32>> {
    let mut stage_of = vec![0u32; cells];
    let mut stages: Vec<Vec<u32>> = Vec::new();
    for n in 0..cells {
        let mut stage = 0;
        sharing(n, &mut |m| {
            if m < n {
                stage = stage.max(stage_of[m] + 1);
            }
        });
        stage_of[n] = stage;
        if stages.len() <= stage as usize {
            stages.push(Vec::new());
        }
        stages[stage as usize].push(n as u32);
    }
    stages
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
pub(super) fn polish_rings(
    h: &Hierarchy,
    r: &Rings,
    mesh: &mut TriMesh,
    keys: &[Key],
    bad: &[usize],
    l_min: f64,
    movable: &dyn Fn(Key) -> bool,
) -> Moves {
    let slack = HEX.self_check_slack;
    // The ring cell of a vertex: the leaf at the end of its canonical key's chain of central
    // children, when the rings hold it. Looked up per vertex, not listed: the rings cover the
    // whole hierarchy (listing them took 0.54 s of a local check at plane-100k).
    let is_cell = |v: usize| -> Option<Key> {
        if v < h.points.len() || !movable(keys[v]) {
            return None;
        }
        let leaf = h.leaf_of_vertex(keys[v]);
        (leaf.canonical() == keys[v] && r.roles.contains_key(&leaf) && h.is_full_leaf(leaf))
            .then_some(leaf)
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
pub(super) struct SettlePass<'a> {
    pub(super) rings: &'a Rings,
    pub(super) cells: &'a SettleCells,
    pub(super) with_neighbours: bool,
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
pub(super) enum SettleCells {
    Listed { contested: KeyBytes, ring: KeyBytes },
    Lookup,
}

impl SettleCells {
    pub(super) fn listed(h: &Hierarchy, r: &Rings) -> SettleCells {
        let mut contested = KeyBytes::default();
        for &c in r.contested.keys() {
            let k = c.canonical();
            if contested.get(&k).is_none_or(|level| c.k > level) {
                contested.insert(k, c.k);
            }
        }
        let mut ring = contested.clone();
        // The ring cells that are full leaves, in the order of the table, found over the
        // threads (a look-up in the hierarchy each: 1.4 M at plane-100k).
        let roles: Vec<Key> = r.roles.keys().copied().collect();
        let leaves = in_parallel(h.threads(), &roles, |chunk| {
            chunk
                .iter()
                .copied()
                .filter(|&c| h.is_full_leaf(c))
                .collect::<Vec<Key>>()
        });
        for c in leaves.into_iter().flatten() {
            ring.insert(c.canonical(), c.k);
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
pub(super) struct Score {
    /// Summed shortfall of the edges below `l_min`.
    short: f64,
    bad: usize,
    pen: f64,
    /// The smallest angle margin (`angle_margin`), when measured.
    worst: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::stages;
    use crate::xorshift::XorShift;

    #[test]
    fn a_stage_holds_no_two_cells_sharing_a_triangle_and_follows_every_earlier_neighbour() {
        // 400 cells with 3 to 8 triangles each among 60, from a fixed xorshift sequence:
        // dense enough that most cells share triangles and chains of stages form.
        let mut x = XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = |m: u64| x.below(m) as usize;
        let around: Vec<Vec<usize>> = (0..400)
            .map(|_| (0..3 + next(6)).map(|_| next(60)).collect())
            .collect();
        // The cells around each triangle, as the mesh's corners give them in the settling.
        let mut on: Vec<Vec<usize>> = vec![Vec::new(); 60];
        for (n, tris) in around.iter().enumerate() {
            for &t in tris {
                on[t].push(n);
            }
        }
        let stages = stages(around.len(), |n, f| {
            for &t in &around[n] {
                on[t].iter().for_each(|&m| f(m));
            }
        });
        let mut stage_of = vec![usize::MAX; around.len()];
        for (s, cells) in stages.iter().enumerate() {
            assert!(
                cells.windows(2).all(|w| w[0] < w[1]),
                "stage {s} out of order"
            );
            for &n in cells {
                assert_eq!(stage_of[n as usize], usize::MAX, "cell {n} in two stages");
                stage_of[n as usize] = s;
            }
        }
        assert!(
            stage_of.iter().all(|&s| s != usize::MAX),
            "a cell in no stage"
        );
        assert!(stages.len() > 5, "too few stages to test: {}", stages.len());
        let share = |m: usize, n: usize| around[m].iter().any(|t| around[n].contains(t));
        for n in 0..around.len() {
            let earlier: Vec<usize> = (0..n).filter(|&m| share(m, n)).collect();
            for &m in &earlier {
                assert!(
                    stage_of[m] < stage_of[n],
                    "cell {n} not after its neighbour {m}"
                );
            }
            // No later than it must be: one after its latest earlier neighbour.
            let want = earlier.iter().map(|&m| stage_of[m] + 1).max().unwrap_or(0);
            assert_eq!(stage_of[n], want, "cell {n}");
        }
    }
}
