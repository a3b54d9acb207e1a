//! The simple refinement of paper 000 Sec. 4.1: rules 1–5, applied to the hexagons on a work
//! list of affected cells until the list is empty. Every subdivision queues only the cells
//! around it, so the work is proportional to the output, not to (points × hexagons) as in the
//! paper's proof of concept (Sec. 8).
//!
//! Rules 3–5 speak of "an occupied hexagon" and its neighbours; rule 4 is read the same way
//! (applied to every hexagon it would refine the whole domain). The end state is the one the
//! paper states: each occupied hexagon is a full hexagon holding one point, surrounded by a
//! ring of full, unsubdivided, unoccupied hexagons.

use crate::geom::Point;
use crate::hex::lattice::Key;
use crate::hex::subdivision::{Cell, Hierarchy, Stop};

/// Runs the simple refinement to completion (or until a budget or the precision limit stops
/// it). The root is always subdivided once: a dual needs at least one ring of hexagons.
pub fn refine_simple(h: &mut Hierarchy) -> Result<(), Stop> {
    h.subdivide(Key::ROOT)?;
    let mut initial = h.occupied_sorted();
    initial.reverse();
    h.work.extend(initial);
    drain(h)
}

/// Applies rules 1–5 to the queued cells until the work list is empty.
pub fn drain(h: &mut Hierarchy) -> Result<(), Stop> {
    while let Some(key) = h.work.pop() {
        apply_rules(h, key)?;
    }
    Ok(())
}

/// Applies the first rule of 1–5 that fires on `key`; a subdivision re-queues the cells
/// around it, `key` included, so the remaining rules are checked again later.
fn apply_rules(h: &mut Hierarchy, key: Key) -> Result<(), Stop> {
    if !h.is_occupied(key) {
        return Ok(());
    }
    match h.cell(key) {
        // Rules 1 and 2: an occupied semi-hexagon (by one point or several) becomes full by
        // subdividing the hexagon across its long edge.
        Cell::Semi { fin_of, .. } => h.subdivide(fin_of),
        Cell::Full { subdivided: false } => {
            // Rule 1: several points.
            if h.occupants(key).len() > 1 {
                return h.subdivide(key);
            }
            // Rule 3: an occupied neighbour (full, semi or fin).
            for d in 0..6 {
                let fin = key.edge_child(d);
                let n = key.neighbor(d);
                if (h.is_occupied(fin) && is_fin(h, fin)) || h.is_occupied(n) {
                    return h.subdivide(key);
                }
            }
            // Rule 4: a neighbour of lower level (a semi-hexagon): subdivide the full hexagon
            // at its long edge, which joins it into a full hexagon.
            let mut fired = false;
            for d in 0..6 {
                let n = key.neighbor(d);
                if matches!(h.cell(n), Cell::Semi { .. } | Cell::Absent) {
                    h.ensure_full(n)?;
                    fired = true;
                }
            }
            if fired {
                h.work.push(key);
                return Ok(());
            }
            // Rule 5: a neighbour of higher level (a fin of this hexagon).
            for d in 0..6 {
                if is_fin(h, key.edge_child(d)) {
                    return h.subdivide(key);
                }
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

/// True when the edge child `cell` of an unsubdivided hexagon is a fin of it: a semi-hexagon
/// owned by the subdivided neighbour. A semi-hexagon "owned" by a cell outside the bounding
/// hexagon is the outer half of a boundary cell and is no neighbour at all.
pub fn is_fin(h: &Hierarchy, cell: Key) -> bool {
    matches!(h.cell(cell), Cell::Semi { owner, .. } if owner.inside())
}

/// Why a point could not be added to a refined hierarchy.
#[derive(Debug, Clone, PartialEq)]
pub enum InsertError {
    /// The point has a NaN or infinite coordinate.
    NonFinite {
        /// The point as given.
        point: Point,
    },
    /// The point does not lie strictly inside the bounding hexagon, which a refined hierarchy
    /// cannot grow.
    Outside {
        /// The point as given.
        point: Point,
    },
    /// The point equals input point `existing`.
    Duplicate {
        /// The point as given.
        point: Point,
        /// The 0-based index of the input point (and mesh vertex) it equals.
        existing: u32,
    },
    /// Refinement stopped (budget or precision).
    Stopped(Stop),
}

/// Adds points to a refined hierarchy and refines locally (paper 000 Sec. 1 and 9: the
/// iterative subdivision "allows incremental addition of further input points"): each point
/// is located by the descent of `Hierarchy::leaf_of`, joins that leaf, and only that leaf goes
/// on the work list of rules 1–5, so the work is proportional to the hexagons that change.
/// Returns the indices the new points got; they are appended to `h.points`.
pub fn insert_points(h: &mut Hierarchy, points: &[Point]) -> Result<Vec<u32>, InsertError> {
    let root = h.lattice.root();
    let mut ids = Vec::with_capacity(points.len());
    for &p in points {
        if !p[0].is_finite() || !p[1].is_finite() {
            return Err(InsertError::NonFinite { point: p });
        }
        if !root.contains_strictly(p) {
            return Err(InsertError::Outside { point: p });
        }
        let leaf = h.leaf_of(p);
        if let Some(&existing) = h
            .occupants(leaf)
            .iter()
            .find(|&&q| h.points[q as usize] == p)
        {
            return Err(InsertError::Duplicate { point: p, existing });
        }
        let id = h.add_point(leaf, p);
        ids.push(id);
        h.work.push(leaf);
        drain(h).map_err(InsertError::Stopped)?;
    }
    Ok(ids)
}
