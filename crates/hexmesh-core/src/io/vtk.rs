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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_triangles_with_0_based_corners_and_z_is_zero() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, -0.0]],
            triangles: vec![[0, 1, 2]],
        };
        let dir = std::env::temp_dir().join(format!("hexmesh-io-vtk-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("one.vtk");
        write_vtk(&path, &mesh).expect("write");
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(text.starts_with("# vtk DataFile Version 4.2\n"));
        assert!(text.contains("POINTS 3 double\n0.0 0.0 0\n1.0 0.0 0\n0.0 -0.0 0\n"));
        assert!(text.contains("CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
