//! A mesh as Triangle writes it (Triangle 1.6 documentation, "File formats", "Boundary
//! markers"), 1-based:
//! - PREFIX.node: header `N 2 A 1`, each vertex with the input's A attributes (see
//!   `Boundary::vertex_attributes`) and its boundary marker;
//! - PREFIX.ele: header `M 3 0`, or `M 3 1` with each triangle's regional attribute when the
//!   input has regions;
//! - PREFIX.poly: an empty nodes section `0 2 A 1` (the points are PREFIX.node's, as in
//!   Triangle's output with `-p`), every boundary edge and every edge on an input segment as
//!   a segment with its marker, the input's holes and its regions;
//! - PREFIX.edge: every edge of the mesh with its marker (Triangle's `-e`): boundary and
//!   segment edges as in the .poly file, every other edge 0.

use std::fmt::Write as _;
use std::path::Path;

use super::boundary::Boundary;
use super::triangle::{write_file, EleFile, NodeFile, PolyFile};
use crate::error::Result;
use crate::mesh::{Pslg, TriMesh};

/// PREFIX.node's content.
pub(crate) fn node_file(mesh: &TriMesh, boundary: &Boundary) -> NodeFile {
    NodeFile {
        attribute_count: boundary.vertex_attributes.first().map_or(0, Vec::len),
        attributes: boundary.vertex_attributes.clone(),
        markers: Some(boundary.vertex_markers.clone()),
        ..NodeFile::from_points(mesh.vertices.clone(), 1)
    }
}

/// PREFIX.ele's content.
pub(crate) fn ele_file(mesh: &TriMesh, boundary: &Boundary) -> EleFile {
    EleFile {
        triangles: mesh
            .triangles
            .iter()
            .map(|t| [t[0] + 1, t[1] + 1, t[2] + 1])
            .collect(),
        attribute_count: usize::from(boundary.has_regions),
        attributes: match boundary.has_regions {
            true => boundary.triangle_regions.iter().map(|&a| vec![a]).collect(),
            false => Vec::new(),
        },
        first_index: 1,
        ..EleFile::default()
    }
}

/// PREFIX.poly's content.
pub(crate) fn poly_file(boundary: &Boundary, input: Option<&Pslg>) -> PolyFile {
    let marked: Vec<_> = boundary.marked_edges().collect();
    PolyFile {
        nodes: NodeFile {
            attribute_count: boundary.vertex_attributes.first().map_or(0, Vec::len),
            markers: Some(Vec::new()),
            ..NodeFile::default()
        },
        segments: marked
            .iter()
            .map(|e| [e.vertices[0] + 1, e.vertices[1] + 1])
            .collect(),
        segment_markers: Some(marked.iter().map(|e| e.marker).collect()),
        holes: input.map_or_else(Vec::new, |i| i.holes.clone()),
        regions: input
            .filter(|i| !i.labels.regions.is_empty())
            .map(|i| i.labels.regions.clone()),
        ..PolyFile::default()
    }
}

/// Writes PREFIX.edge: `E 1`, then `k a b marker` for every edge, numbered from 1.
pub(crate) fn write_edge(path: &Path, boundary: &Boundary) -> Result<()> {
    let mut text = String::with_capacity(boundary.edges.len() * 24 + 16);
    let _ = writeln!(text, "{} 1", boundary.edges.len());
    for (k, e) in boundary.edges.iter().enumerate() {
        let _ = writeln!(
            text,
            "{} {} {} {}",
            k + 1,
            e.vertices[0] + 1,
            e.vertices[1] + 1,
            e.marker
        );
    }
    write_file(path, &text)
}
