//! Gmsh MSH 4.1 ASCII (Gmsh reference manual, "MSH file format"): one surface entity holding
//! every node and every 3-node triangle (element type 2), tags 1-based, for Gmsh and meshio.

use std::fmt::Write as _;
use std::path::Path;

use super::triangle::write_file;
use crate::error::Result;
use crate::mesh::TriMesh;

/// Gmsh's element type number for a 3-node triangle.
const MSH_TRIANGLE: u8 = 2;

/// Writes `mesh` as a Gmsh 4.1 ASCII file; coordinates keep full precision.
pub fn write_msh(path: &Path, mesh: &TriMesh) -> Result<()> {
    super::check_mesh(path, mesh)?;
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let mut text = String::with_capacity(n * 48 + m * 24 + 512);
    text.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");

    // $Entities: no points, no curves, one surface (tag 1) with its bounding box, no
    // physical tags and no bounding curves.
    let [xmin, ymin, xmax, ymax] = bounding_box(mesh);
    text.push_str("$Entities\n0 0 1 0\n");
    let _ = writeln!(text, "1 {xmin:?} {ymin:?} 0 {xmax:?} {ymax:?} 0 0 0");
    text.push_str("$EndEntities\n");

    // $Nodes: numEntityBlocks numNodes minNodeTag maxNodeTag, then one block on surface 1.
    text.push_str("$Nodes\n");
    if n == 0 {
        text.push_str("0 0 0 0\n");
    } else {
        let _ = writeln!(text, "1 {n} 1 {n}\n2 1 0 {n}");
        for tag in 1..=n {
            let _ = writeln!(text, "{tag}");
        }
        for p in &mesh.vertices {
            let _ = writeln!(text, "{:?} {:?} 0", p[0], p[1]);
        }
    }
    text.push_str("$EndNodes\n");

    text.push_str("$Elements\n");
    if m == 0 {
        text.push_str("0 0 0 0\n");
    } else {
        let _ = writeln!(text, "1 {m} 1 {m}\n2 1 {MSH_TRIANGLE} {m}");
        for (k, t) in mesh.triangles.iter().enumerate() {
            let _ = writeln!(text, "{} {} {} {}", k + 1, t[0] + 1, t[1] + 1, t[2] + 1);
        }
    }
    text.push_str("$EndElements\n");
    write_file(path, &text)
}

/// The bounding box of all vertices, [xmin, ymin, xmax, ymax]; zeros for an empty mesh.
pub(crate) fn bounding_box(mesh: &TriMesh) -> [f64; 4] {
    if mesh.vertices.is_empty() {
        return [0.0; 4];
    }
    mesh.vertices.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_surface_entity_carries_the_mesh_bounding_box() {
        let mesh = TriMesh {
            vertices: vec![[-1.5, 2.0], [3.0, -0.25], [0.5, 7.0]],
            triangles: vec![[0, 1, 2]],
        };
        assert_eq!(bounding_box(&mesh), [-1.5, -0.25, 3.0, 7.0]);
        let dir = std::env::temp_dir().join(format!("hexmesh-io-msh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("bbox.msh");
        write_msh(&path, &mesh).expect("write");
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(text.contains("$Entities\n0 0 1 0\n1 -1.5 -0.25 0 3.0 7.0 0 0 0\n$EndEntities"));
        assert!(text.contains("$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
