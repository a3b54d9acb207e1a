//! The refinement rules for segments (paper Sec. 7.2, with departures), applied for every
//! crossed hexagon h on top of the rules of Sec. 5.2:
//! - h crossed by segments that do not all share one endpoint is subdivided. The paper allows
//!   "two consecutive" segments; segments meeting at one input point are consecutive at that
//!   point, and three or more of them meeting there are allowed too (ours: subdividing cannot
//!   separate them near their common point).
//! - h crossed by segments and holding an input point that is not an endpoint of every one of
//!   them is subdivided (ours, `holds_a_foreign_point`): a point and a segment that does not
//!   end at it are two features in one hexagon, as two segments without a common endpoint
//!   are. Without it an interior point 0.003 from a segment sat in the hexagon the segment
//!   cut, and the triangles between them had 13° (`hexmesh fuzz --domains --mesher hex`, seed
//!   20261123, case 12; tests/fixtures/hex/domains-fuzz-seed20261123-case12-interior-point-beside-segment.poly).
//! - A crossed semi-hexagon that either rule would subdivide is made full first.
//!
//! Departure: the paper's regularity rules along the segments are not applied (a crossed
//! semi-hexagon joined; h subdivided when it has a finer neighbour, its coarser neighbours
//! made full; a neighbour of h with fins subdivided). They keep every crossed hexagon at one
//! level with its neighbours, so the finest level any feature needs runs along the whole chain
//! of segments: a polygon of span 2 with one segment 3.4e-4 long had every boundary segment
//! split every 7.7e-5, 1.7 million triangles (domain fuzz seed 20261123, case 78), and the map
//! coordinates of case 23 ran out of the fuzz's vertex budget
//! (tests/fixtures/hex/domains-fuzz-seed20261123-case23-level-wave-along-segments.poly). The
//! regularity served the projected centres and added triangles of Sec. 7.3/7.4, which this
//! mesher replaces by the constrained Delaunay cavity and the near-segment repair (`cavity`,
//! `band`), held to their own promise; without the rules imr has 5,542 triangles (22,607 with
//! them) and the domain fuzz's largest mesh over its first 200 cases is 9,044 triangles
//! (520,176); case 78 is kept as
//! tests/fixtures/hex/domains-fuzz-seed20261123-case78-level-wave-along-segments.poly.
//!
//! The rules run in rounds until none fires (`apply_rules`). Each round subdivides at least
//! one hexagon or the loop stops with an error naming the cell it stuck at, so the number of
//! subdivisions, bounded by the lattice's depth and the hierarchy's budgets (steps, vertices,
//! time: `Hierarchy::subdivide` stops at each), measures the loop's progress. A round costs
//! what the previous one changed: the assignment is updated, not recomputed
//! (`assign::Assignment`), and the rules of Sec. 7.2 are examined only at the crossed cells near
//! the previous round's subdivisions (the same cells whose Sec. 5.2 rules are examined,
//! `extended::rules::around`): the rules at a crossed cell read the cell, its neighbours, their
//! neighbours and the parents of its neighbours, which are all within that neighbourhood of a
//! subdivision that changes them. When the regularity rules above were applied, a wave of
//! subdivisions along a long segment took a round per cell, and minutes when every round
//! recomputed every crossed cell (fixture tests/fixtures/hex/spade-issue96-box-rule-wave-hang.poly).

use std::collections::BTreeMap;

use super::assign::Assignment;
use super::PslgStats;
use crate::geom::Point;
use crate::hex::classify::rings;
use crate::hex::extended::rules::{around, extended_actions};
use crate::hex::lattice::{Key, KeySet};
use crate::hex::refine::drain;
use crate::hex::subdivision::{Cell, Hierarchy, Stop};
use crate::mesh::Pslg;
use crate::mesher::StopReason;

/// True when the segments `set` all share one endpoint (one segment trivially does).
fn share_an_endpoint(input: &Pslg, set: &[u32]) -> bool {
    let Some(&first) = set.first() else {
        return true;
    };
    input.segments[first as usize]
        .iter()
        .any(|&v| set.iter().all(|&s| input.segments[s as usize].contains(&v)))
}

/// True when the leaf `key` holds an input point that is not an endpoint of every segment in
/// `set`, the segments crossing it (ours): the point and a segment that does not end at it
/// share a hexagon, as two segments without a common endpoint do in the rule of Sec. 7.2.
fn holds_a_foreign_point(h: &Hierarchy, input: &Pslg, key: Key, set: &[u32]) -> bool {
    h.occupants(key).iter().any(|&p| {
        (p as usize) < input.points.len()
            && set
                .iter()
                .any(|&s| !input.segments[s as usize].contains(&p))
    })
}

/// The cells the rules of Sec. 7.2 (module docs) want subdivided (full leaves) or made full
/// (semi-hexagons and absent cells), sorted.
pub fn segment_actions(h: &Hierarchy, input: &Pslg, crossed: &BTreeMap<Key, Vec<u32>>) -> Vec<Key> {
    segment_actions_among(h, input, crossed, None)
}

/// `segment_actions` at the crossed cells among `only` (all of them for `None`).
fn segment_actions_among(
    h: &Hierarchy,
    input: &Pslg,
    crossed: &BTreeMap<Key, Vec<u32>>,
    only: Option<&KeySet>,
) -> Vec<Key> {
    let mut acts = Vec::new();
    let examined: Vec<(Key, &Vec<u32>)> = match only {
        None => crossed.iter().map(|(&k, set)| (k, set)).collect(),
        Some(only) => only
            .iter()
            .filter_map(|k| crossed.get(&k).map(|set| (k, set)))
            .collect(),
    };
    for (key, set) in examined {
        let separate = !share_an_endpoint(input, set) || holds_a_foreign_point(h, input, key, set);
        match h.cell(key) {
            // A semi-hexagon holding features to separate is made full, and split next round.
            Cell::Semi { .. } if separate => acts.push(key),
            Cell::Full { subdivided: false } if separate => acts.push(key),
            _ => {}
        }
    }
    acts.sort();
    acts.dedup();
    acts
}

/// Subdivides the full leaves among `actions` and makes the other cells full. What each key
/// asks for is decided on the state the actions were computed on: a semi-hexagon that an
/// earlier action in the batch joins must not be subdivided as well.
pub(super) fn apply(h: &mut Hierarchy, actions: Vec<Key>) -> std::result::Result<u64, Stop> {
    let before = h.steps;
    h.log.clear();
    let (split, fill): (Vec<Key>, Vec<Key>) = actions.into_iter().partition(|&k| h.is_full_leaf(k));
    for key in fill {
        h.ensure_full(key)?;
    }
    for key in split {
        h.subdivide(key)?;
    }
    drain(h)?;
    Ok(h.steps - before)
}

/// Applies the rules of Sec. 5.2 (to `candidates` and the cells around later splits) and of
/// Sec. 7.2 (to every crossed leaf, then to those around later splits) until none fires;
/// returns the final assignment. A round whose rules fire but subdivide nothing is an error
/// naming the first cell they asked for (module docs), never an endless loop.
pub(super) fn apply_rules(
    h: &mut Hierarchy,
    input: &Pslg,
    segments: &[[Point; 2]],
    mut candidates: KeySet,
    stats: &mut PslgStats,
) -> std::result::Result<BTreeMap<Key, Vec<u32>>, Stop> {
    let mut assignment = Assignment::new(h, segments);
    let mut first = true;
    loop {
        h.check_time()?;
        let mut actions: Vec<Key> = extended_actions(h, &rings(h), &candidates)
            .into_iter()
            .map(|(k, _)| k)
            .collect();
        let only = (!first).then_some(&candidates);
        actions.extend(segment_actions_among(h, input, assignment.crossed(), only));
        first = false;
        actions.sort();
        actions.dedup();
        let Some(&stuck) = actions.first() else {
            return Ok(assignment.into_crossed());
        };
        let splits = apply(h, actions)?;
        if splits == 0 {
            return Err(stalled(h, stuck));
        }
        stats.rule_splits += splits;
        assignment.update(h, &h.log);
        candidates = around(&h.log);
    }
}

/// The stop of a rule round that subdivided nothing, naming the first cell it asked for.
fn stalled(h: &Hierarchy, key: Key) -> Stop {
    let c = h.lattice.center(key);
    Stop::Budget(StopReason::Stalled(format!(
        "the refinement rules of Sec. 5.2 and 7.2 ask for cell (level {}, {}, {}) at ({:?}, \
         {:?}) to be subdivided or made full, but their round subdivided nothing",
        key.k, key.i, key.j, c[0], c[1]
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_sharing_an_endpoint_are_consecutive() {
        let p = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 5.0]],
            segments: vec![[0, 1], [2, 0], [3, 1]],
            ..Pslg::default()
        };
        assert!(share_an_endpoint(&p, &[0, 1]));
        assert!(share_an_endpoint(&p, &[0, 2]));
        assert!(!share_an_endpoint(&p, &[1, 2]));
        assert!(!share_an_endpoint(&p, &[0, 1, 2]));
    }

    /// A unit square with two parallel segments `gap` apart inside it, one of them continued
    /// by a dangling segment: the rules refine between the two down to a level that separates
    /// them, a round per level.
    fn close_parallel_pair(gap: f64) -> Pslg {
        Pslg {
            points: vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [1.0, 1.0],
                [0.0, 1.0],
                [0.2, 0.5],
                [0.6, 0.5],
                [0.3, 0.5 + gap],
                [0.7, 0.5 + gap],
                [0.8, 0.2],
            ],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [6, 7], [7, 8]],
            ..Pslg::default()
        }
    }

    fn refined_hierarchy(input: &Pslg) -> Hierarchy {
        let params = crate::mesher::Params::default();
        let mut h = crate::hex::new_hierarchy(&super::super::point_set(input), &params, "hex")
            .expect("a hierarchy");
        crate::hex::refine::refine_simple(&mut h).expect("the simple refinement");
        h
    }

    #[test]
    fn the_kept_assignment_is_the_one_computed_afresh_after_every_round() {
        use super::super::assign::crossed_cells;
        let input = close_parallel_pair(1.0 / 65_536.0);
        let segments = super::super::segment_points(&input);
        let mut h = refined_hierarchy(&input);
        let mut kept = Assignment::new(&h, &segments);
        assert_eq!(kept.crossed(), &crossed_cells(&h, &segments));
        let mut rounds = 0;
        loop {
            let actions = segment_actions(&h, &input, kept.crossed());
            if actions.is_empty() {
                break;
            }
            apply(&mut h, actions).expect("within the lattice");
            kept.update(&h, &h.log);
            rounds += 1;
            assert_eq!(
                kept.crossed(),
                &crossed_cells(&h, &segments),
                "round {rounds}"
            );
        }
        assert!(
            rounds > 10,
            "only {rounds} rounds: the rounds this test is about did not run"
        );
    }

    #[test]
    fn the_rule_loop_stops_where_no_rule_fires_at_any_crossed_cell() {
        use super::super::assign::crossed_cells;
        let input = close_parallel_pair(1.0 / 64.0);
        let segments = super::super::segment_points(&input);
        let mut h = refined_hierarchy(&input);
        let all: KeySet = h.leaves().into_iter().map(|(k, _)| k).collect();
        let mut stats = PslgStats::default();
        let crossed = apply_rules(&mut h, &input, &segments, all, &mut stats).expect("rules");
        assert!(stats.rule_splits > 0);
        assert_eq!(crossed, crossed_cells(&h, &segments));
        // Examined everywhere, not only near the last round's subdivisions, no rule fires.
        assert_eq!(segment_actions(&h, &input, &crossed), Vec::<Key>::new());
        let leaves: KeySet = h.leaves().into_iter().map(|(k, _)| k).collect();
        assert!(extended_actions(&h, &rings(&h), &leaves).is_empty());
    }

    /// tests/fixtures/hex/rules-one-segment-batch-order.poly: a batch that both joined a
    /// semi-hexagon and subdivided the cell it made full gave a segment endpoint's hexagon a
    /// fin every round, one level deeper each round without end (`apply` decides each key on
    /// the state the batch was computed on).
    #[test]
    fn one_segment_reaches_the_fixed_point_of_the_rules() {
        let name = "rules-one-segment-batch-order.poly";
        let text =
            include_str!("../../../../../tests/fixtures/hex/rules-one-segment-batch-order.poly");
        let poly = crate::io::parse_poly(std::path::Path::new(name), text).expect(name);
        let base = poly.nodes.first_index;
        let input = Pslg {
            points: poly.nodes.points.clone(),
            segments: poly.segments.iter().map(|s| s.map(|v| v - base)).collect(),
            ..Pslg::default()
        };
        let segments = super::super::segment_points(&input);
        let params = crate::mesher::Params::default().with_budget(crate::mesher::Budget {
            max_steps: Some(5_000),
            ..crate::mesher::Budget::default()
        });
        let mut h = crate::hex::new_hierarchy(&super::super::point_set(&input), &params, "hex")
            .expect("a hierarchy");
        crate::hex::refine::refine_simple(&mut h).expect("the simple refinement");
        let all: KeySet = h.leaves().into_iter().map(|(k, _)| k).collect();
        let mut stats = PslgStats::default();
        let crossed = apply_rules(&mut h, &input, &segments, all, &mut stats);
        assert!(crossed.is_ok_and(|c| !c.is_empty()), "{:?}", stats);
    }
}
