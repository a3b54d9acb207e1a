//! VTK XML UnstructuredGrid, binary (`.vtu`; "VTK File Formats", Kitware, XML formats), for
//! large meshes: every array is appended raw after the XML (`<AppendedData encoding="raw">`),
//! each preceded by its length in bytes as a UInt64 (`header_type="UInt64"`), all
//! little-endian. Points are Float64 with z = 0, connectivity and offsets Int64, cell types
//! UInt8 (5, VTK_TRIANGLE). The cell and point data are those of the legacy writer:
//! `min_angle`, `max_angle`, `radius_ratio`, `region` (Float64) and `boundary_marker` (Int64).
//! No compression: the file is written with the standard library only.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use super::boundary::{derive_boundary, Boundary};
use super::fields::{cell_arrays, CELL_ARRAYS, POINT_ARRAY};
use crate::error::{Error, Result};
use crate::mesh::TriMesh;

/// VTK's cell type number for a linear triangle.
const VTK_TRIANGLE: u8 = 5;

/// One appended array: its XML attributes and its little-endian bytes.
struct Array {
    element: String,
    bytes: Vec<u8>,
}

fn le_f64(values: impl Iterator<Item = f64>) -> Vec<u8> {
    values.flat_map(f64::to_le_bytes).collect()
}

fn le_i64(values: impl Iterator<Item = i64>) -> Vec<u8> {
    values.flat_map(i64::to_le_bytes).collect()
}

/// Writes `mesh` as a binary `.vtu` file with the labels of the mesh alone.
pub fn write_vtu(path: &Path, mesh: &TriMesh) -> Result<()> {
    super::check_mesh(path, mesh)?;
    write_vtu_with(path, mesh, &derive_boundary(mesh, None))
}

/// Writes `mesh` as a binary `.vtu` file with the data arrays of `boundary`, which must have
/// been derived from `mesh`.
pub fn write_vtu_with(path: &Path, mesh: &TriMesh, boundary: &Boundary) -> Result<()> {
    super::check_mesh(path, mesh)?;
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let data_array = |kind: &str, name: &str, components: usize| {
        let components = match components {
            1 => String::new(),
            c => format!(" NumberOfComponents=\"{c}\""),
        };
        format!("<DataArray type=\"{kind}\" Name=\"{name}\"{components} format=\"appended\"")
    };
    let point_data = vec![Array {
        element: data_array("Int64", POINT_ARRAY, 1),
        bytes: le_i64(boundary.vertex_markers.iter().copied()),
    }];
    let cell_data: Vec<Array> = CELL_ARRAYS
        .iter()
        .zip(cell_arrays(mesh, boundary))
        .map(|(name, values)| Array {
            element: data_array("Float64", name, 1),
            bytes: le_f64(values.into_iter()),
        })
        .collect();
    let points = vec![Array {
        element: data_array("Float64", "Points", 3),
        bytes: le_f64(mesh.vertices.iter().flat_map(|p| [p[0], p[1], 0.0])),
    }];
    let cells = vec![
        Array {
            element: data_array("Int64", "connectivity", 1),
            bytes: le_i64(mesh.triangles.iter().flatten().map(|&v| i64::from(v))),
        },
        Array {
            element: data_array("Int64", "offsets", 1),
            bytes: le_i64((1..=m as i64).map(|k| 3 * k)),
        },
        Array {
            element: data_array("UInt8", "types", 1),
            bytes: vec![VTK_TRIANGLE; m],
        },
    ];

    // The blocks are appended in the reverse order of their DataArray elements. meshio 5.3
    // turns raw appended data into base64 block by block, in the order of the data, finding
    // each block's element by its offset attribute after rewriting the earlier blocks'
    // offsets to base64 positions: in document order, an earlier element's new offset could
    // equal the raw offset looked for (it did, for 8 triangles: the radius ratio and the
    // region swapped). With the data reversed, the element looked for always comes first.
    let sections = [
        (
            format!("<PointData Scalars=\"{POINT_ARRAY}\">"),
            "</PointData>",
            point_data,
        ),
        (
            format!("<CellData Scalars=\"{}\">", CELL_ARRAYS[0]),
            "</CellData>",
            cell_data,
        ),
        ("<Points>".to_string(), "</Points>", points),
        ("<Cells>".to_string(), "</Cells>", cells),
    ];
    let arrays: Vec<&Array> = sections.iter().flat_map(|s| &s.2).collect();
    let mut offsets = vec![0usize; arrays.len()];
    let mut offset = 0usize;
    for (k, a) in arrays.iter().enumerate().rev() {
        offsets[k] = offset;
        offset += 8 + a.bytes.len();
    }

    let mut xml = String::new();
    xml.push_str(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n",
    );
    let _ = writeln!(xml, "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{m}\">");
    let mut k = 0;
    for (open, close, section) in &sections {
        let _ = writeln!(xml, "{open}");
        for a in section {
            let _ = writeln!(xml, "{} offset=\"{}\"/>", a.element, offsets[k]);
            k += 1;
        }
        let _ = writeln!(xml, "{close}");
    }
    xml.push_str("</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");

    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(io)?);
    file.write_all(xml.as_bytes()).map_err(io)?;
    for a in arrays.iter().rev() {
        file.write_all(&(a.bytes.len() as u64).to_le_bytes())
            .map_err(io)?;
        file.write_all(&a.bytes).map_err(io)?;
    }
    file.write_all(b"\n</AppendedData>\n</VTKFile>\n")
        .map_err(io)?;
    file.flush().map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_are_appended_raw_after_their_uint64_lengths_at_the_stated_offsets() {
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
        };
        let dir = std::env::temp_dir().join(format!("hexmesh-io-vtu-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("two.vtu");
        write_vtu(&path, &mesh).expect("write");
        let bytes = std::fs::read(&path).expect("read");
        let start = bytes.windows(2).position(|w| w == b"\n_").expect("marker") + 2;
        let text = String::from_utf8_lossy(&bytes[..start]).into_owned();
        // The arrays in XML order, their blocks appended in reverse: each block is 8 bytes
        // of length and then its bytes, and its offset is where that length starts.
        let sizes = [
            4 * 8,
            2 * 8,
            2 * 8,
            2 * 8,
            2 * 8,
            4 * 3 * 8,
            6 * 8,
            2 * 8,
            2,
        ];
        let total: usize = sizes.iter().map(|s| 8 + s).sum();
        let mut offset = total;
        let mut at = Vec::new();
        for (k, size) in sizes.iter().enumerate() {
            offset -= 8 + size;
            at.push(offset);
            assert!(
                text.contains(&format!("offset=\"{offset}\"/>")),
                "array {k}: {text}"
            );
            let p = start + offset;
            let length = u64::from_le_bytes(bytes[p..p + 8].try_into().expect("8 bytes"));
            assert_eq!(length as usize, *size, "array {k}");
        }
        assert_eq!(offset, 0);
        assert_eq!(&bytes[start + total..], b"\n</AppendedData>\n</VTKFile>\n");
        // The connectivity block (the seventh array) holds the corners as Int64.
        let corner = |k: usize| {
            let p = start + at[6] + 8 + 8 * k;
            i64::from_le_bytes(bytes[p..p + 8].try_into().expect("8 bytes"))
        };
        assert_eq!(
            (0..6).map(corner).collect::<Vec<_>>(),
            vec![0, 1, 2, 1, 3, 2]
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
