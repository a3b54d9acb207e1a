//! Incremental insertion into a finished `hex` mesh (paper 000 Sec. 1 and 9: the iterative
//! subdivision "allows incremental addition of further input points").
//!
//! An added point joins the leaf that holds it and the simple rules of Sec. 4.1 refine around
//! it (`refine::insert_points`); then the extended rules of Sec. 5.2 run on the cells around
//! what changed, and the self-check of `extended` examines only the dual near the changed
//! cells (`region`). The work per insertion is proportional to the hexagons that change, plus
//! the rings of the occupied hexagons (one entry per input point), not to the mesh. Reading
//! the mesh out (`mesh`) is linear in its size, as producing any output is.
//!
//! The result meets every bound of Sec. 6; it need not equal the mesh of all points meshed
//! at once (hexagons subdivided for the first points stay subdivided).

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::hex::extended::{self, around, extend_and_verify, final_dual, ExtendedStats, RingState};
use crate::hex::refine::{insert_points, InsertError};
use crate::hex::subdivision::Hierarchy;
use crate::hex::{insert_error, stop_error};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Params;

/// A finished extended hexagon mesh that accepts further points. The bounding hexagon stays
/// the one of the first input, so added points must lie strictly inside it.
#[derive(Debug, Clone)]
pub struct IncrementalHex {
    hierarchy: Hierarchy,
    rings: RingState,
    stats: ExtendedStats,
    /// Why the hierarchy is unusable: an insertion stopped half-way (budget or precision).
    broken: Option<String>,
}

impl IncrementalHex {
    /// Meshes `input` (a point set) to completion; a budget that stops the first meshing is an
    /// error here, since a partial hierarchy cannot take more points.
    pub fn new(input: &Pslg, params: &Params) -> Result<IncrementalHex> {
        let run = extended::mesh_extended(input, params)?;
        if let Some(why) = run.stop {
            return Err(Error::mesher("hex", format!("stopped: {why}")));
        }
        Ok(IncrementalHex {
            hierarchy: run.hierarchy,
            rings: run.rings,
            stats: run.stats,
            broken: None,
        })
    }

    /// Adds points and refines locally. Returns the vertex indices they got in `mesh()`.
    ///
    /// Points that are not finite, lie outside the bounding hexagon or repeat a point are
    /// refused before anything changes. A refinement stopped half-way (a budget, or points too
    /// close for f64) leaves the mesh unfinished: that error is returned, and every later call
    /// returns it again.
    pub fn insert(&mut self, points: &[Point]) -> Result<Vec<u32>> {
        if let Some(why) = &self.broken {
            return Err(Error::mesher("hex", why.clone()));
        }
        self.check_new(points)?;
        let h = &mut self.hierarchy;
        h.log.clear();
        let ids = match insert_points(h, points) {
            Ok(ids) => ids,
            Err(e) => {
                let e = insert_error("hex", e);
                self.broken = Some(format!("an earlier insertion failed: {e}"));
                return Err(e);
            }
        };
        // The leaves that received a point change class (and their rings appear) even when
        // no hexagon had to be subdivided for them.
        let mut changed = std::mem::take(&mut h.log);
        changed.extend(ids.iter().map(|&id| h.leaf_of(h.points[id as usize])));
        changed.sort_unstable();
        changed.dedup();
        let candidates = around(&changed);
        if let Err(stop) = extend_and_verify(
            h,
            &mut self.stats,
            &mut self.rings,
            (candidates, None),
            Some(changed),
            None,
        ) {
            let e = stop_error("hex", stop);
            self.broken = Some(format!("an earlier insertion failed: {e}"));
            return Err(e);
        }
        Ok(ids)
    }

    /// Refuses, before anything changes, the points `insert_points` would refuse one by one.
    fn check_new(&self, points: &[Point]) -> Result<()> {
        let h = &self.hierarchy;
        let root = h.lattice.root();
        let mut batch: Vec<Point> = Vec::with_capacity(points.len());
        for &p in points {
            let refused = if !p[0].is_finite() || !p[1].is_finite() {
                Some(InsertError::NonFinite { point: p })
            } else if !root.contains_strictly(p) {
                Some(InsertError::Outside { point: p })
            } else {
                let leaf = h.leaf_of(p);
                h.occupants(leaf)
                    .iter()
                    .find(|&&q| h.points[q as usize] == p)
                    .map(|&existing| InsertError::Duplicate { point: p, existing })
            };
            if let Some(e) = refused {
                return Err(insert_error("hex", e));
            }
            batch.push(p);
        }
        batch.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        if let Some(w) = batch.windows(2).find(|w| w[0] == w[1]) {
            return Err(Error::mesher(
                "hex",
                format!("added point ({}, {}) is given twice", w[0][0], w[0][1]),
            ));
        }
        Ok(())
    }

    /// The current mesh: input point i (first the initial points, then the added ones in
    /// order) is vertex i.
    pub fn mesh(&self) -> TriMesh {
        final_dual(&self.hierarchy, &self.rings)
    }

    /// The subdivision as it stands after the last insertion.
    pub fn hierarchy(&self) -> &Hierarchy {
        &self.hierarchy
    }

    /// The statistics of all refinement so far; `checked_triangles` counts the triangles the
    /// self-check examined, the measure of how local an insertion was.
    pub fn stats(&self) -> &ExtendedStats {
        &self.stats
    }
}
