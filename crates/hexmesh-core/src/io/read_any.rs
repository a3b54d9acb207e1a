//! One entry point for `verify`: a mesh in any format hexmesh reads, chosen by the file's
//! extension ([`read_any_mesh`]).

use std::path::Path;

use crate::error::{Error, Result};
use crate::mesh::TriMesh;

/// A mesh read from a file, with the numbers the file gives its vertices and triangles when
/// they are not simply their positions (a Gmsh file's node and element tags).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    /// The mesh, 0-based, vertices and triangles in the order the file lists them.
    pub mesh: TriMesh,
    /// The file's own tag of each vertex (`vertex_tags[i]` for vertex i), for Gmsh files.
    pub vertex_tags: Option<Vec<u64>>,
    /// The file's own tag of each triangle, for Gmsh files.
    pub triangle_tags: Option<Vec<u64>>,
    /// The number the file's own numbering gives its first vertex and triangle, by which
    /// messages name them (`quality::Numbering::mesh`): a `.node` file's first index (0 or 1),
    /// 1 for Gmsh (whose tags usually count from 1; `vertex_tags` says when they do not), 0
    /// for VTK (point and cell ids count from 0, as ParaView shows them).
    pub first_index: u32,
}

impl LoadedMesh {
    /// A mesh whose vertices and triangles are named by their positions counted from
    /// `first_index`.
    pub fn untagged(mesh: TriMesh, first_index: u32) -> LoadedMesh {
        LoadedMesh {
            mesh,
            vertex_tags: None,
            triangle_tags: None,
            first_index,
        }
    }
}

/// The mesh formats [`read_any_mesh`] tells apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Triangle's PREFIX.node + PREFIX.ele.
    Triangle,
    /// Gmsh `.msh`, 4.1 or 2.2, ASCII or binary.
    Msh,
    /// VTK legacy `.vtk`, ASCII or BINARY.
    Vtk,
    /// VTK XML `.vtu`: ASCII, base64 or appended data, plain or zlib-compressed.
    Vtu,
}

impl MeshFormat {
    /// The format of `path` by its extension (case-insensitive): `.msh`, `.vtk`, `.vtu`;
    /// anything else is a Triangle prefix (with or without `.node`/`.ele`).
    pub fn of(path: &Path) -> MeshFormat {
        let extension = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            Some("msh") => MeshFormat::Msh,
            Some("vtk") => MeshFormat::Vtk,
            Some("vtu") => MeshFormat::Vtu,
            _ => MeshFormat::Triangle,
        }
    }
}

/// Reads a triangle mesh from `path`, in the format its extension names ([`MeshFormat::of`]):
/// Gmsh `.msh` ([`super::read_msh`]), VTK legacy `.vtk` ([`super::read_vtk`]), VTK XML
/// `.vtu` ([`super::read_vtu`]), or else Triangle's PREFIX.node + PREFIX.ele
/// ([`super::read_mesh`]). Geometric defects are kept for `verify` to report; files that do
/// not hold a mesh of 3-node triangles in the plane are errors naming the file and the line
/// (or byte offset).
pub fn read_any_mesh(path: &Path) -> Result<LoadedMesh> {
    match MeshFormat::of(path) {
        MeshFormat::Msh => super::read_msh(path),
        MeshFormat::Vtk => super::read_vtk(path).map(|m| LoadedMesh::untagged(m, 0)),
        MeshFormat::Vtu => super::read_vtu(path).map(|m| LoadedMesh::untagged(m, 0)),
        MeshFormat::Triangle => super::read_mesh_numbered(path)
            .map(|(mesh, first_index)| LoadedMesh::untagged(mesh, first_index)),
    }
}

/// The whole file, or an I/O error naming it.
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}
