//! What the tests of our meshers check beside `quality::verdict`: the numbering promise of
//! every mesher of ours (the input points are the mesh's first vertices, in order).
// Each test crate that includes this module uses part of it.
#![allow(dead_code)]

use hexmesh::quality::{verdict, Verdict};
use hexmesh::{Point, Pslg, TriMesh};

/// Input point i is vertex i of `mesh`, bit for bit; the error names the first that is not.
pub fn inputs_first(mesh: &TriMesh, points: &[Point]) -> Result<(), String> {
    match points
        .iter()
        .enumerate()
        .find(|&(i, p)| mesh.vertices.get(i) != Some(p))
    {
        Some((i, p)) => Err(format!(
            "input point {i} ({}, {}) is not vertex {i}",
            p[0], p[1]
        )),
        None => Ok(()),
    }
}

/// `mesh` of the point set `points` keeps the promise `verify --bounds NAME` checks, and
/// input point i is vertex i: the verdict, or the first problem found.
pub fn meets(mesh: &TriMesh, points: &[Point], name: &str) -> Result<Verdict, String> {
    inputs_first(mesh, points)?;
    let bounds = hexmesh::registry::bounds(name).map_err(|e| e.to_string())?;
    let input = Pslg::from_points(points.to_vec());
    let v = verdict(mesh, (!points.is_empty()).then_some(&input), Some(&bounds));
    if v.passed() {
        Ok(v)
    } else {
        Err(v.to_string())
    }
}
