//! The extra refinement rules for segments, paper Sec. 7.2, applied for every crossed
//! hexagon h on top of the rules of Sec. 5.2:
//! - a crossed semi-hexagon is joined (it has a full hexagon of lower level beside it);
//! - h has a finer neighbour (a fin): subdivide h; a coarser neighbour: make it full;
//! - a neighbour of h with fins (a MOVED_CENTER_[123] hexagon in the 1-ring) is subdivided;
//! - h crossed by segments that do not all share one endpoint is subdivided. The paper allows
//!   "two consecutive" segments; segments meeting at one input point are consecutive at that
//!   point, and three or more of them meeting there are allowed too (ours: subdividing cannot
//!   separate them near their common point).

use std::collections::BTreeMap;

use super::{crossed_cells, PslgStats};
use crate::geom::Point;
use crate::hex::classify::{fin_mask, rings};
use crate::hex::extended::rules::{around, extended_actions};
use crate::hex::lattice::{Key, KeySet};
use crate::hex::refine::{drain, is_fin};
use crate::hex::subdivision::{Cell, Hierarchy, Stop};
use crate::mesh::Pslg;

/// True when the segments `set` all share one endpoint (one segment trivially does).
fn share_an_endpoint(input: &Pslg, set: &[u32]) -> bool {
    let Some(&first) = set.first() else {
        return true;
    };
    input.segments[first as usize]
        .iter()
        .any(|&v| set.iter().all(|&s| input.segments[s as usize].contains(&v)))
}

/// The cells the rules of Sec. 7.2 (module docs) want subdivided (full leaves) or made full
/// (semi-hexagons and absent cells), sorted.
pub fn segment_actions(h: &Hierarchy, input: &Pslg, crossed: &BTreeMap<Key, Vec<u32>>) -> Vec<Key> {
    let mut acts = Vec::new();
    for (&key, set) in crossed {
        match h.cell(key) {
            Cell::Semi { .. } => acts.push(key),
            Cell::Full { subdivided: false } => {
                let mut split = !share_an_endpoint(input, set);
                for d in 0..6 {
                    if is_fin(h, key.edge_child(d)) {
                        split = true;
                    }
                    let n = key.neighbor(d);
                    match h.cell(n) {
                        Cell::Semi { .. } | Cell::Absent => acts.push(n),
                        Cell::Full { subdivided: false } if fin_mask(h, n) != 0 => acts.push(n),
                        _ => {}
                    }
                }
                if split {
                    acts.push(key);
                }
            }
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
/// Sec. 7.2 (to every crossed leaf) until none fires; returns the final assignment.
pub(super) fn apply_rules(
    h: &mut Hierarchy,
    input: &Pslg,
    segments: &[[Point; 2]],
    mut candidates: KeySet,
    stats: &mut PslgStats,
) -> std::result::Result<BTreeMap<Key, Vec<u32>>, Stop> {
    loop {
        h.check_time()?;
        let crossed = crossed_cells(h, segments);
        let mut actions: Vec<Key> = extended_actions(h, &rings(h), &candidates)
            .into_iter()
            .map(|(k, _)| k)
            .collect();
        actions.extend(segment_actions(h, input, &crossed));
        actions.sort();
        actions.dedup();
        if actions.is_empty() {
            return Ok(crossed);
        }
        stats.rule_splits += apply(h, actions)?;
        candidates = around(&h.log);
    }
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
}
