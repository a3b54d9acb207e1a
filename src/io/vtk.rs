//! VTK legacy ASCII unstructured grid ("File Formats for VTK Version 4.2", Kitware): the
//! triangles as cells of type 5 (VTK_TRIANGLE), points with z = 0, for ParaView and meshio.

use std::fmt::Write as _;
use std::path::Path;

use super::triangle::write_file;
use crate::error::Result;
use crate::mesh::TriMesh;

/// VTK's cell type number for a linear triangle.
const VTK_TRIANGLE: u8 = 5;

/// Writes `mesh` as a legacy VTK file; coordinates keep full precision (`{:?}` round-trips).
pub fn write_vtk(path: &Path, mesh: &TriMesh) -> Result<()> {
    super::check_mesh(path, mesh)?;
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let mut text = String::with_capacity(n * 40 + m * 24 + 256);
    text.push_str(
        "# vtk DataFile Version 4.2\nhexmesh triangle mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n",
    );
    let _ = writeln!(text, "POINTS {n} double");
    for p in &mesh.vertices {
        let _ = writeln!(text, "{:?} {:?} 0", p[0], p[1]);
    }
    let _ = writeln!(text, "CELLS {m} {}", 4 * m);
    for t in &mesh.triangles {
        let _ = writeln!(text, "3 {} {} {}", t[0], t[1], t[2]);
    }
    let _ = writeln!(text, "CELL_TYPES {m}");
    for _ in 0..m {
        let _ = writeln!(text, "{VTK_TRIANGLE}");
    }
    write_file(path, &text)
}
