//! VTK legacy ASCII unstructured grid ("File Formats for VTK Version 4.2", Kitware): the
//! triangles as cells of type 5 (VTK_TRIANGLE), points with z = 0, for ParaView and meshio.
//! `CELL_DATA` holds `min_angle`, `max_angle` (degrees), `radius_ratio` (R/(2r)) and `region`
//! (the regional attribute, 0 without regions), all `double`; `POINT_DATA` holds
//! `boundary_marker` (`int`, or `long` when a marker does not fit 32 bits).

use std::fmt::Write as _;
use std::path::Path;

use super::boundary::{derive_boundary, Boundary};
use super::fields::{cell_arrays, CELL_ARRAYS, POINT_ARRAY};
use super::triangle::write_file;
use crate::error::Result;
use crate::mesh::TriMesh;

/// VTK's cell type number for a linear triangle.
const VTK_TRIANGLE: u8 = 5;

/// Writes `mesh` as a legacy VTK file; coordinates keep full precision (`{:?}` round-trips).
/// The labels are those of the mesh alone (`derive_boundary(mesh, None)`).
pub fn write_vtk(path: &Path, mesh: &TriMesh) -> Result<()> {
    super::check_mesh(path, mesh)?;
    write_vtk_with(path, mesh, &derive_boundary(mesh, None))
}

/// Writes `mesh` as a legacy VTK file with the data arrays of `boundary`, which must have
/// been derived from `mesh`.
pub fn write_vtk_with(path: &Path, mesh: &TriMesh, boundary: &Boundary) -> Result<()> {
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
    let _ = writeln!(text, "CELL_DATA {m}");
    for (name, values) in CELL_ARRAYS.iter().zip(cell_arrays(mesh, boundary)) {
        let _ = writeln!(text, "SCALARS {name} double 1\nLOOKUP_TABLE default");
        for v in values {
            let _ = writeln!(text, "{v:?}");
        }
    }
    let markers = &boundary.vertex_markers;
    let fits = markers.iter().all(|&v| i32::try_from(v).is_ok());
    let kind = if fits { "int" } else { "long" };
    let _ = writeln!(
        text,
        "POINT_DATA {n}\nSCALARS {POINT_ARRAY} {kind} 1\nLOOKUP_TABLE default"
    );
    for v in markers {
        let _ = writeln!(text, "{v}");
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
        assert!(text.contains("CELL_DATA 1\nSCALARS min_angle double 1\nLOOKUP_TABLE default\n"));
        assert!(text.ends_with(
            "POINT_DATA 3\nSCALARS boundary_marker int 1\nLOOKUP_TABLE default\n1\n1\n1\n"
        ));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
