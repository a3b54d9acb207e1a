//! The refinement of a large point set started on tiles (ours, not paper 000's): the points
//! are grouped by the lattice cell of one level nearest to them, each group is refined on its
//! own (the simple refinement of Sec. 4.1, the size limits and the extended rules of Sec. 5.2
//! to their fixed point) on whichever thread is free, and the hierarchies are joined
//! (`Hierarchy::absorb`). The whole run then goes on from the joined hierarchy as from the
//! root: the simple rules and the extended rules look at every cell again. They fire where
//! one tile's points change what another tile's hexagons need, along the tiles' edges (at
//! plane-100k the first scan of the 5.59 million full leaves asked for 9,760 subdivisions).
//! The coarsening of Sec. 5.3 and the self-check with its repairs run on the whole as
//! before.
//!
//! - A tile's refinement is a state the whole run could reach as well, and so is a union of
//!   such states; the rules only subdivide, so nothing a tile refined is undone. A tile alone
//!   is coarser near its edge than the whole run (its neighbours' points are missing), which
//!   the rules of the whole make up for; where a tile's rules split a cell that the whole run
//!   would not, the mesh has a few more triangles (0.15 % at plane-100k, 0.05 % at
//!   plane-10k).
//! - The tiles and their number depend on the input alone (`tiles`), not on the threads,
//!   so the mesh is the same bytes on any machine.
//! - Budgets of steps or vertices count subdivisions one at a time, which tiles on several
//!   threads would not do in a fixed order: with such a budget the run is not tiled. A time
//!   budget stops the tiles as it stops the whole run: the hierarchy keeps what the tiles
//!   refined. A tile that meets the precision limit (points too close for f64 at their
//!   coordinates) leaves the run untiled, so that the limit, where the whole run meets it,
//!   names the points in the input's numbering (a tile numbers its points apart).

use super::repair::rules_to_fixed_point;
use super::{refine_simple_and_sizes, ExtendedStats};
use crate::geom::Point;
use crate::hex::lattice::Lattice;
use crate::hex::parallel::each_in_parallel;
use crate::hex::subdivision::{Hierarchy, Stop};
use crate::progress::{self, Counter, Progress};

/// The mean number of points a tile is chosen to hold at most: enough that the band along a
/// tile's edge, where its own hexagons are coarser than the whole run's, is a small part of
/// it; few enough that a tile's tables stay in the caches and that there are many tiles to
/// share out over the threads.
pub(crate) const TILE_POINTS: usize = 2048;

/// The tiles of `points`: the coarsest lattice level at which the occupied cells hold at most
/// `per_tile` points on average, and the indices of the points of each of them, in the order
/// of their cells' keys (each list in increasing order). `None` when the points fit in one
/// tile.
pub(crate) fn tiles(
    lattice: &Lattice,
    points: &[Point],
    per_tile: usize,
) -> Option<(u8, Vec<Vec<u32>>)> {
    let per_tile = per_tile.max(1);
    if points.len() <= per_tile {
        return None;
    }
    for level in 1..=crate::hex::lattice::MAX_LEVEL {
        let mut keyed: Vec<(u128, u32)> = points
            .iter()
            .enumerate()
            .map(|(i, &p)| (lattice.nearest(level, p).packed(), i as u32))
            .collect();
        keyed.sort_unstable();
        let count = 1 + keyed.windows(2).filter(|w| w[0].0 != w[1].0).count();
        if count * per_tile < points.len() {
            continue;
        }
        let mut out: Vec<Vec<u32>> = Vec::with_capacity(count);
        let mut last = None;
        for (key, i) in keyed {
            if last != Some(key) {
                out.push(Vec::new());
                last = Some(key);
            }
            out.last_mut().expect("a tile").push(i);
        }
        return Some((level, out));
    }
    None
}

/// Refines `h` (unrefined) tile by tile and joins the tiles' hierarchies (module docs), with
/// tiles of at most `per_tile` points on average. Returns false, leaving `h` as it was, when
/// the run is not tiled: too few points, a budget of steps or vertices, or a tile at the
/// precision limit. A time budget that runs out stops it after the join. `progress` hears of
/// each tile finished ("tiles", k of the tiles) and of the join.
pub(crate) fn refine_tiled(
    h: &mut Hierarchy,
    stats: &mut ExtendedStats,
    per_tile: usize,
    progress: Option<&Progress>,
) -> Result<bool, Stop> {
    if h.budget().max_steps.is_some() || h.budget().max_vertices.is_some() {
        return Ok(false);
    }
    let Some((_, tiles)) = tiles(&h.lattice, &h.points, per_tile) else {
        return Ok(false);
    };
    let parent = &*h;
    let done = Counter::start(progress, "tiles", tiles.len() as u64);
    let results = each_in_parallel(parent.threads(), &tiles, |tile| {
        let points = tile.iter().map(|&i| parent.points[i as usize]).collect();
        let mut part = parent.part(points);
        let mut part_stats = ExtendedStats::default();
        let outcome = refine_part(&mut part, &mut part_stats);
        done.tick();
        (part.into_subdivided(), part_stats, outcome)
    });
    let mut stop = None;
    let mut sets = Vec::with_capacity(results.len());
    for (set, part_stats, outcome) in results {
        match outcome {
            Err(Stop::Precision(_)) => return Ok(false),
            Err(budget) => stop = stop.or(Some(budget)),
            Ok(()) => {}
        }
        stats.rule_splits += part_stats.rule_splits;
        stats.mc3_splits += part_stats.mc3_splits;
        sets.push(set);
    }
    progress::phase(progress, "joining the tiles");
    h.absorb(sets);
    match stop {
        Some(stop) => Err(stop),
        None => Ok(true),
    }
}

/// One tile's refinement: the simple rules, the size limits, the extended rules to their
/// fixed point.
fn refine_part(h: &mut Hierarchy, stats: &mut ExtendedStats) -> Result<(), Stop> {
    let candidates = refine_simple_and_sizes(h)?;
    rules_to_fixed_point(h, stats, candidates)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Hexagon;
    use crate::hex::lattice::Key;
    use crate::hex::refine::refine_simple;

    /// The level-`level` cell nearest to each point (the tile it belongs to).
    fn tile_keys(lattice: &Lattice, level: u8, points: &[Point]) -> Vec<Key> {
        points.iter().map(|&p| lattice.nearest(level, p)).collect()
    }

    fn grid(n: usize) -> Vec<Point> {
        (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f64, (i / n) as f64);
                // A small skew so that no two points share a lattice line.
                [x + 0.013 * y, y + 0.007 * x]
            })
            .collect()
    }

    #[test]
    fn each_point_is_in_exactly_one_tile_and_tiles_hold_the_asked_mean() {
        let points = grid(40);
        let lattice = Lattice::new(Hexagon::aligned(&points));
        let (level, groups) = tiles(&lattice, &points, 50).expect("1600 points need tiles");
        let mut seen: Vec<u32> = groups.concat();
        seen.sort_unstable();
        assert_eq!(seen, (0..1600).collect::<Vec<u32>>());
        assert!(groups.len() * 50 >= points.len(), "{} tiles", groups.len());
        // The coarsest such level: one level coarser, the tiles hold more on average.
        let coarser = tile_keys(&lattice, level - 1, &points);
        let mut distinct: Vec<u128> = coarser.iter().map(|k| k.packed()).collect();
        distinct.sort_unstable();
        distinct.dedup();
        assert!(distinct.len() * 50 < points.len());
        // Each tile is the points nearest to one cell, listed in increasing order.
        let keys = tile_keys(&lattice, level, &points);
        for tile in &groups {
            assert!(tile.windows(2).all(|w| w[0] < w[1]));
            assert!(tile
                .iter()
                .all(|&i| keys[i as usize] == keys[tile[0] as usize]));
        }
        // Few points: one tile, no tiling.
        assert!(tiles(&lattice, &points[..50], 50).is_none());
    }

    /// `n` points uniform in the unit square from a fixed xorshift sequence.
    fn scattered(n: usize) -> Vec<Point> {
        super::super::tests::scattered(n, 0x2545_f491_4f6c_dd1d)
    }

    fn hierarchy(points: &[Point], params: &crate::mesher::Params) -> Hierarchy {
        let input = crate::mesh::Pslg::from_points(points.to_vec());
        crate::hex::new_hierarchy(&input, params, "hex").expect("a valid point set")
    }

    #[test]
    fn the_joined_tiles_are_a_valid_hierarchy_that_the_whole_run_finishes() {
        let points = scattered(600);
        let params = crate::mesher::Params::default();
        let mut h = hierarchy(&points, &params);
        let mut stats = ExtendedStats::default();
        assert_eq!(refine_tiled(&mut h, &mut stats, 40, None), Ok(true));
        assert!(stats.rule_splits > 0);
        // Balanced (Sec. 3.3), every point in the leaf the descent finds, and the count of
        // full leaves the one a scan gives.
        h.check_invariants().expect("the join keeps the invariants");
        assert_eq!(h.full_leaves, h.full_leaves_iter().count());
        // The tiles did the work: the whole run's simple rules have little left to do, and
        // the end state of Sec. 4.1 holds after them.
        let steps = h.steps;
        refine_simple(&mut h).expect("refines");
        assert!(
            h.steps - steps < steps / 20,
            "{} after {steps}",
            h.steps - steps
        );
        h.check_refined()
            .expect("the simple refinement's end state");
    }

    #[test]
    fn a_budget_of_steps_or_vertices_is_not_tiled() {
        let points = scattered(300);
        for budget in [
            crate::mesher::Budget {
                max_steps: Some(1 << 40),
                ..Default::default()
            },
            crate::mesher::Budget {
                max_vertices: Some(1 << 40),
                ..Default::default()
            },
        ] {
            let params = crate::mesher::Params::default().with_budget(budget);
            let mut h = hierarchy(&points, &params);
            let mut stats = ExtendedStats::default();
            assert_eq!(refine_tiled(&mut h, &mut stats, 40, None), Ok(false));
            assert_eq!(h.steps, 0);
        }
    }
}
