//! The data arrays the VTK writers attach to a mesh, so that ParaView can colour by them:
//! per triangle its smallest and largest angle (degrees), its radius ratio R/(2r) and its
//! regional attribute; per vertex its boundary marker. The shape figures are the quality
//! module's (`quality::triangle_shape`), the labels `io::boundary`'s.

use super::boundary::Boundary;
use crate::mesh::TriMesh;
use crate::quality::metrics::triangle_shape;

/// The per-triangle arrays, in the order the writers emit them.
pub(crate) const CELL_ARRAYS: [&str; 4] = ["min_angle", "max_angle", "radius_ratio", "region"];

/// The per-vertex array.
pub(crate) const POINT_ARRAY: &str = "boundary_marker";

/// The values of [`CELL_ARRAYS`], one vector per array, one value per triangle.
pub(crate) fn cell_arrays(mesh: &TriMesh, boundary: &Boundary) -> [Vec<f64>; 4] {
    let m = mesh.triangles.len();
    let mut out: [Vec<f64>; 4] = std::array::from_fn(|_| Vec::with_capacity(m));
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let shape = triangle_shape(tri.map(|v| mesh.vertices[v as usize]));
        let [a, b, c] = shape.angles;
        out[0].push(a.min(b).min(c));
        out[1].push(a.max(b).max(c));
        out[2].push(shape.radius_ratio);
        out[3].push(boundary.triangle_regions[t]);
    }
    out
}
