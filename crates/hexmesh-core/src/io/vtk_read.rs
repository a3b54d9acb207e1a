//! Reads VTK legacy `.vtk` meshes (Kitware, "VTK File Formats", the legacy format) into a
//! 0-based [`TriMesh`]: `DATASET UNSTRUCTURED_GRID` and `DATASET POLYDATA`, ASCII or BINARY
//! (big-endian), in the classic layout (`CELLS n size` with a count before each cell) and the
//! 5.x one (`CELLS` followed by `OFFSETS` and `CONNECTIVITY` arrays, as meshio 5 writes).
//!
//! - `POINTS n float|double`: every point must have z = 0. BINARY coordinates are taken bit
//!   for bit; ASCII ones with Rust's correctly rounded `f64` parse.
//! - Unstructured grids: cells of type 5 (`VTK_TRIANGLE`) become triangles; vertices (1, 2)
//!   and lines (3, 4) are skipped; every other cell type is refused.
//! - Poly data: `POLYGONS` of 3 points become triangles, other polygons are refused;
//!   `VERTICES` and `LINES` are skipped; `TRIANGLE_STRIPS` are refused.
//! - `FIELD` and `METADATA` blocks are skipped; reading stops at `POINT_DATA` or `CELL_DATA`.
//!
//! Errors name the file and, in text, the line; in BINARY data, the byte offset.

use std::path::Path;

use super::scan::{Endian, Scan};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::TriMesh;

/// No more than this many items are reserved ahead of reading them, whatever a header claims.
const MAX_PREALLOCATION: usize = 1 << 16;

/// VTK's linear triangle.
const VTK_TRIANGLE: i64 = 5;

/// Integers read from the file, with the offset of each, for messages.
type Ints = (Vec<i64>, Vec<usize>);

/// Reads a VTK legacy `.vtk` file; see the module docs.
pub fn read_vtk(path: &Path) -> Result<TriMesh> {
    parse_vtk(path, &super::read_any::read_bytes(path)?)
}

/// Parses the bytes of a VTK legacy file; `path` is only used in messages.
pub fn parse_vtk(path: &Path, data: &[u8]) -> Result<TriMesh> {
    let mut vtk = Vtk::start(Scan::new(path, data))?;
    let mut points: Option<Vec<Point>> = None;
    let mut cells: Option<Cells> = None;
    let mut types: Option<(usize, Ints)> = None;
    let mut polygons: Vec<Cells> = Vec::new();
    while let Some((at, line)) = vtk.scan.next_nonblank_line()? {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let keyword = fields[0].to_ascii_uppercase();
        match keyword.as_str() {
            "POINTS" => {
                if points.is_some() {
                    return Err(vtk.scan.error_at(at, "a second POINTS section"));
                }
                points = Some(vtk.points(at, &fields)?);
            }
            "CELLS" | "POLYGONS" | "VERTICES" | "LINES" => {
                let read = vtk.cells(at, &fields)?;
                match keyword.as_str() {
                    "CELLS" if vtk.polydata => {
                        return Err(vtk.scan.error_at(at, "CELLS in a POLYDATA dataset"))
                    }
                    "CELLS" => cells = Some(read),
                    "POLYGONS" if !vtk.polydata => {
                        return Err(vtk.scan.error_at(at, "POLYGONS in an UNSTRUCTURED_GRID"))
                    }
                    "POLYGONS" => polygons.push(read),
                    _ => {}
                }
            }
            "CELL_TYPES" => {
                let n = vtk.header_count(at, &fields, 2, "CELL_TYPES n")?;
                types = Some((at, vtk.ints(n, "int", "a cell type")?));
            }
            "TRIANGLE_STRIPS" => {
                return Err(vtk.scan.error_at(
                    at,
                    "TRIANGLE_STRIPS are not read: verify checks meshes of separate triangles",
                ))
            }
            "FIELD" => vtk.skip_field(at, &fields)?,
            "METADATA" => vtk.skip_metadata()?,
            "POINT_DATA" | "CELL_DATA" => break,
            _ => {
                return Err(vtk.scan.error_at(
                    at,
                    format!(
                        "unexpected '{line}' where a section such as POINTS or CELLS was expected"
                    ),
                ))
            }
        }
    }
    let Some(points) = points else {
        return Err(Error::parse(path, 0, "the file has no POINTS section"));
    };
    let n = points.len();
    let mut triangles = Vec::new();
    if vtk.polydata {
        for cells in &polygons {
            for k in 0..cells.len() {
                let corners = cells.cell(k);
                if corners.len() != 3 {
                    return Err(vtk.error(
                        cells.at[k],
                        format!(
                            "polygon {k} of this section has {} points: verify checks meshes \
                             of triangles",
                            corners.len()
                        ),
                    ));
                }
                triangles.push(vtk.triangle(cells.at[k], "polygon", k, corners, n)?);
            }
        }
    } else {
        let Some(cells) = cells else {
            return Err(Error::parse(path, 0, "the file has no CELLS section"));
        };
        let Some((types_line, (types, types_at))) = types else {
            return Err(Error::parse(path, 0, "the file has no CELL_TYPES section"));
        };
        if types.len() != cells.len() {
            return Err(vtk.scan.error_at(
                types_line,
                format!(
                    "CELL_TYPES lists {} cells, but CELLS has {}",
                    types.len(),
                    cells.len()
                ),
            ));
        }
        for (k, &cell_type) in types.iter().enumerate() {
            match cell_type {
                VTK_TRIANGLE => {
                    let corners = cells.cell(k);
                    if corners.len() != 3 {
                        return Err(vtk.error(
                            cells.at[k],
                            format!(
                                "cell {k} is a triangle (type 5) with {} points",
                                corners.len()
                            ),
                        ));
                    }
                    triangles.push(vtk.triangle(cells.at[k], "cell", k, corners, n)?);
                }
                1..=4 => {}
                other => {
                    return Err(vtk.error(
                        types_at[k],
                        format!(
                            "cell {k} has type {other} ({}): verify checks meshes of linear \
                             triangles (type 5); vertices and lines are skipped",
                            cell_name(other)
                        ),
                    ))
                }
            }
        }
    }
    Ok(TriMesh {
        vertices: points,
        triangles,
    })
}

/// What a VTK cell type is, for messages.
pub(crate) fn cell_name(cell_type: i64) -> &'static str {
    match cell_type {
        6 => "a triangle strip",
        7 => "a polygon",
        8 => "a pixel",
        9 => "a quadrangle",
        22 => "a quadratic triangle",
        23 | 28 | 30 => "a quadratic quadrangle",
        34 | 69 => "a higher-order triangle",
        10..=14 | 24..=27 | 29 | 31..=33 => "a volume cell",
        _ => "a cell type verify does not read",
    }
}

/// Cells as offsets into a connectivity list.
struct Cells {
    /// `offsets[k]..offsets[k + 1]` are cell k's points; `offsets[0]` is 0.
    offsets: Vec<usize>,
    connectivity: Vec<i64>,
    /// Where each cell is in the file, for messages.
    at: Vec<usize>,
}

impl Cells {
    fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    fn cell(&self, k: usize) -> &[i64] {
        &self.connectivity[self.offsets[k]..self.offsets[k + 1]]
    }
}

struct Vtk<'a> {
    scan: Scan<'a>,
    binary: bool,
    /// Version 5 or later: cells as OFFSETS and CONNECTIVITY.
    offsets_layout: bool,
    polydata: bool,
}

impl<'a> Vtk<'a> {
    /// Reads the header: version, title, ASCII or BINARY, and the DATASET line.
    fn start(mut scan: Scan<'a>) -> Result<Vtk<'a>> {
        let (at, first) = scan
            .next_line()?
            .ok_or_else(|| scan.end_error("the VTK header"))?;
        let version = first
            .trim()
            .strip_prefix("# vtk DataFile Version")
            .map(str::trim)
            .ok_or_else(|| {
                scan.error_at(
                    at,
                    "not a VTK legacy file: it must start with '# vtk DataFile Version'",
                )
            })?;
        let major: u32 = version
            .split('.')
            .next()
            .and_then(|m| m.parse().ok())
            .ok_or_else(|| scan.error_at(at, format!("unreadable VTK version '{version}'")))?;
        scan.next_line()?
            .ok_or_else(|| scan.end_error("the title line"))?;
        let (at, encoding) = scan.expect_line("ASCII or BINARY")?;
        let binary = match encoding.to_ascii_uppercase().as_str() {
            "ASCII" => false,
            "BINARY" => true,
            _ => {
                return Err(
                    scan.error_at(at, format!("expected ASCII or BINARY, found '{encoding}'"))
                )
            }
        };
        let (at, dataset) = scan.expect_line("the DATASET line")?;
        let fields: Vec<&str> = dataset.split_whitespace().collect();
        let polydata = match fields.as_slice() {
            [d, kind] if d.eq_ignore_ascii_case("DATASET") => {
                match kind.to_ascii_uppercase().as_str() {
                    "UNSTRUCTURED_GRID" => false,
                    "POLYDATA" => true,
                    _ => {
                        return Err(scan.error_at(
                            at,
                            format!(
                                "DATASET {kind} is not read: verify reads UNSTRUCTURED_GRID and \
                                 POLYDATA"
                            ),
                        ))
                    }
                }
            }
            _ => {
                return Err(scan.error_at(
                    at,
                    format!("expected 'DATASET UNSTRUCTURED_GRID', found '{dataset}'"),
                ))
            }
        };
        Ok(Vtk {
            scan,
            binary,
            offsets_layout: major >= 5,
            polydata,
        })
    }

    /// Field 1 (and, with `width` 3, field 2) of a section line as counts.
    fn header_count(
        &self,
        at: usize,
        fields: &[&str],
        width: usize,
        layout: &str,
    ) -> Result<usize> {
        if fields.len() != width {
            return Err(self.scan.error_at(
                at,
                format!("expected '{layout}', found '{}'", fields.join(" ")),
            ));
        }
        fields[1].parse().map_err(|_| {
            self.scan.error_at(
                at,
                format!("expected '{layout}', found '{}'", fields.join(" ")),
            )
        })
    }

    /// An error at `pos`: its line in ASCII, its byte offset in BINARY.
    fn error(&self, pos: usize, message: impl Into<String>) -> Error {
        if self.binary {
            self.scan.error_at_byte(pos, message.into())
        } else {
            self.scan.error_at(pos, message)
        }
    }

    /// After a BINARY block, the line end that closes it.
    fn end_binary(&mut self) -> Result<()> {
        if self.binary {
            self.scan.skip_newline();
        }
        Ok(())
    }

    /// `POINTS n type` and its data.
    fn points(&mut self, at: usize, fields: &[&str]) -> Result<Vec<Point>> {
        let n = self.header_count(at, fields, 3, "POINTS n float|double")?;
        let size = match fields[2] {
            "float" => 4,
            "double" => 8,
            other => {
                return Err(self.scan.error_at(
                    at,
                    format!("points of type '{other}' are not read: use float or double"),
                ))
            }
        };
        if self.binary {
            self.scan.require(n, 3 * size, "the points")?;
        }
        let mut points = Vec::with_capacity(n.min(MAX_PREALLOCATION));
        for k in 0..n {
            let at = self.mark();
            let mut p = [0.0; 3];
            for v in &mut p {
                *v = if !self.binary {
                    self.scan.float("a point coordinate")?
                } else if size == 4 {
                    f64::from(self.scan.f32(Endian::Big, "a point coordinate")?)
                } else {
                    self.scan.f64(Endian::Big, "a point coordinate")?
                };
            }
            if let Some(bad) = p.iter().find(|v| !v.is_finite()) {
                return Err(self.error(
                    at,
                    format!(
                        "point {k} has the coordinate {bad}: NaN and infinite values are refused"
                    ),
                ));
            }
            if p[2] != 0.0 {
                return Err(self.error(
                    at,
                    format!(
                        "point {k} has z = {:?}: verify checks planar meshes in the plane z = 0",
                        p[2]
                    ),
                ));
            }
            points.push([p[0], p[1]]);
        }
        self.end_binary()?;
        Ok(points)
    }

    /// Where the next item starts (past whitespace in ASCII), to name in errors.
    fn mark(&mut self) -> usize {
        if !self.binary {
            self.scan.skip_whitespace();
        }
        self.scan.pos()
    }

    /// `n` integers of VTK type `ty` (BINARY: big-endian), with the offset of each in the
    /// file, for messages.
    fn ints(&mut self, n: usize, ty: &str, what: &str) -> Result<Ints> {
        let size = match ty.to_ascii_lowercase().as_str() {
            "int" | "unsigned_int" | "vtktypeint32" | "vtktypeuint32" => 4,
            "long" | "unsigned_long" | "vtktypeint64" | "vtktypeuint64" | "vtkidtype" => 8,
            _ => {
                return Err(self.scan.error_at(
                    self.scan.pos(),
                    format!("integers of type '{ty}' are not read"),
                ))
            }
        };
        if self.binary {
            self.scan.require(n, size, what)?;
        }
        let mut out = Vec::with_capacity(n.min(MAX_PREALLOCATION));
        let mut positions = Vec::with_capacity(n.min(MAX_PREALLOCATION));
        for _ in 0..n {
            positions.push(self.mark());
            out.push(if !self.binary {
                let (at, token) = self.scan.token(what)?;
                token.parse().map_err(|_| {
                    self.scan
                        .error_at(at, format!("{what} must be an integer, found '{token}'"))
                })?
            } else if size == 4 {
                i64::from(self.scan.i32(Endian::Big, what)?)
            } else {
                self.scan.i64(Endian::Big, what)?
            });
        }
        self.end_binary()?;
        Ok((out, positions))
    }

    /// `CELLS`, `POLYGONS`, `VERTICES` or `LINES` and its data, in either layout.
    fn cells(&mut self, at: usize, fields: &[&str]) -> Result<Cells> {
        let layout = format!("{} n size", fields[0]);
        if fields.len() != 3 {
            return Err(self.scan.error_at(
                at,
                format!("expected '{layout}', found '{}'", fields.join(" ")),
            ));
        }
        let n = self.header_count(at, &fields[..2], 2, &layout)?;
        let size = self.header_count(at, &[fields[0], fields[2]], 2, &layout)?;
        if self.offsets_layout {
            let (offsets, offsets_at) = self.typed_array("OFFSETS", n)?;
            let (connectivity, connectivity_at) = self.typed_array("CONNECTIVITY", size)?;
            let mut checked = Vec::with_capacity(offsets.len().min(MAX_PREALLOCATION));
            for (k, &o) in offsets.iter().enumerate() {
                let ok = usize::try_from(o)
                    .ok()
                    .filter(|&o| o <= connectivity.len() && checked.last().is_none_or(|&p| p <= o));
                match ok {
                    Some(o) if k > 0 || o == 0 => checked.push(o),
                    _ => {
                        return Err(self.error(
                            offsets_at[k],
                            format!(
                                "offset {k} is {o}: offsets start at 0 and rise to the {} \
                                 connectivity entries",
                                connectivity.len()
                            ),
                        ))
                    }
                }
            }
            if checked.last().is_some_and(|&o| o != connectivity.len()) {
                return Err(self
                    .scan
                    .error_at(at, "the last offset is not the length of the connectivity"));
            }
            if checked.is_empty() {
                checked.push(0);
            }
            // Each cell is named at its first corner, or at its offset when it has none.
            let at = (0..checked.len() - 1)
                .map(|k| {
                    connectivity_at
                        .get(checked[k])
                        .filter(|_| checked[k] < checked[k + 1])
                        .copied()
                        .unwrap_or(offsets_at[k + 1])
                })
                .collect();
            return Ok(Cells {
                offsets: checked,
                connectivity,
                at,
            });
        }
        let data_at = self.mark();
        let (list, list_at) = self.ints(size, "int", "a cell entry")?;
        let mut cells = Cells {
            offsets: vec![0],
            connectivity: Vec::with_capacity(list.len()),
            at: Vec::with_capacity(n.min(MAX_PREALLOCATION)),
        };
        let mut i = 0;
        for k in 0..n {
            let count = list
                .get(i)
                .and_then(|&c| usize::try_from(c).ok())
                .filter(|&c| c < list.len() - i)
                .ok_or_else(|| {
                    self.error(
                        list_at.get(i).copied().unwrap_or(data_at),
                        format!(
                            "cell {k}: the {size} entries of {} end inside it",
                            fields[0]
                        ),
                    )
                })?;
            cells
                .connectivity
                .extend_from_slice(&list[i + 1..i + 1 + count]);
            cells.offsets.push(cells.connectivity.len());
            cells.at.push(list_at[i]);
            i += 1 + count;
        }
        if i != list.len() {
            return Err(self.error(
                data_at,
                format!(
                    "{} has {size} entries, but its {n} cells use {i}",
                    fields[0]
                ),
            ));
        }
        Ok(cells)
    }

    /// `NAME type` and `n` integers (the 5.x OFFSETS and CONNECTIVITY arrays).
    fn typed_array(&mut self, name: &str, n: usize) -> Result<Ints> {
        let (mut at, mut line) = self.scan.expect_line(name)?;
        // VTK 9 may follow an array with a METADATA block.
        while line.eq_ignore_ascii_case("METADATA") {
            self.skip_metadata()?;
            (at, line) = self.scan.expect_line(name)?;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        match fields.as_slice() {
            [found, ty] if found.eq_ignore_ascii_case(name) => {
                self.ints(n, ty, &format!("an entry of {name}"))
            }
            _ => Err(self.scan.error_at(
                at,
                format!("expected '{name} vtktypeint64', found '{line}'"),
            )),
        }
    }

    /// `FIELD name count` and its arrays `name components tuples type` with their data.
    fn skip_field(&mut self, at: usize, fields: &[&str]) -> Result<()> {
        let arrays = self.header_count(
            at,
            &[fields[0], fields.last().copied().unwrap_or("")],
            2,
            "FIELD name count",
        )?;
        for _ in 0..arrays {
            let (at, line) = self.scan.expect_line("a FIELD array")?;
            let f: Vec<&str> = line.split_whitespace().collect();
            let (Some(components), Some(tuples), Some(ty)) = (
                f.get(1).and_then(|c| c.parse::<usize>().ok()),
                f.get(2).and_then(|t| t.parse::<usize>().ok()),
                f.get(3),
            ) else {
                return Err(self.scan.error_at(
                    at,
                    format!("expected 'name components tuples type', found '{line}'"),
                ));
            };
            let n = components
                .checked_mul(tuples)
                .ok_or_else(|| self.scan.error_at(at, "the array's size overflows"))?;
            if self.binary {
                let size = match ty.to_ascii_lowercase().as_str() {
                    "bit" => return Err(self.scan.error_at(at, "bit arrays are not read")),
                    "unsigned_char" | "char" => 1,
                    "short" | "unsigned_short" => 2,
                    "int" | "unsigned_int" | "float" | "vtktypeint32" | "vtktypeuint32" => 4,
                    _ => 8,
                };
                let bytes = n
                    .checked_mul(size)
                    .ok_or_else(|| self.scan.error_at(at, "the array's size overflows"))?;
                self.scan.bytes(bytes, "a FIELD array")?;
                self.end_binary()?;
            } else {
                for _ in 0..n {
                    self.scan.token("a FIELD value")?;
                }
            }
        }
        Ok(())
    }

    /// `METADATA` and its lines, up to the blank line that ends them.
    fn skip_metadata(&mut self) -> Result<()> {
        while let Some((_, line)) = self.scan.next_line()? {
            if line.trim().is_empty() {
                break;
            }
        }
        Ok(())
    }

    /// The triangle of `corners` (0-based point numbers), checked against the `n` points.
    fn triangle(
        &self,
        at: usize,
        what: &str,
        k: usize,
        corners: &[i64],
        n: usize,
    ) -> Result<[u32; 3]> {
        let mut t = [0u32; 3];
        for (slot, &c) in t.iter_mut().zip(corners) {
            *slot = u32::try_from(c)
                .ok()
                .filter(|&v| (v as usize) < n)
                .ok_or_else(|| {
                    self.error(
                        at,
                        format!(
                            "{what} {k} names point {c}, but there are {n} points numbered from 0"
                        ),
                    )
                })?;
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<TriMesh> {
        parse_vtk(Path::new("t.vtk"), bytes)
    }

    fn message(bytes: &[u8]) -> String {
        parse(bytes).expect_err("refused").to_string()
    }

    const CLASSIC: &str = "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\n\
        FIELD FieldData 1\ntime 1 1 double\n0.5\n\
        POINTS 4 double\n0 0 0 1 0 0\n1 1 0\n0.1 1 0\n\
        CELLS 4 13\n1 0\n3 0 1 2\n2 2 3\n3 0 2 3\n\
        CELL_TYPES 4\n1\n5\n3\n5\n\
        CELL_DATA 4\nSCALARS m int 1\nLOOKUP_TABLE default\n1 2 3 4\n";

    #[test]
    fn classic_ascii_grid_keeps_triangles_and_skips_vertices_lines_field_and_data() {
        let mesh = parse(CLASSIC.as_bytes()).expect("classic");
        assert_eq!(
            mesh.vertices,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.1, 1.0]]
        );
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn version_5_ascii_offsets_and_connectivity_as_meshio_writes_them() {
        let text = "# vtk DataFile Version 5.1\nwritten by meshio v5.3.5\nASCII\n\
            DATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0.0 0.0 0.0 2.0 0.0 0.0 0.0 3.0 0.0\n\
            CELLS 2 3\nOFFSETS vtktypeint64\n0\n3\nCONNECTIVITY vtktypeint64\n0\n1\n2\n\
            CELL_TYPES 1\n5\n";
        let mesh = parse(text.as_bytes()).expect("5.1");
        assert_eq!(mesh.vertices, vec![[0.0, 0.0], [2.0, 0.0], [0.0, 3.0]]);
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        // VTK 9 puts METADATA blocks (ended by a blank line) after arrays.
        let metadata =
            "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 3\n\n";
        let text = text
            .replace("CELLS 2 3", &format!("{metadata}CELLS 2 3"))
            .replace("CONNECTIVITY", &format!("{metadata}CONNECTIVITY"));
        assert_eq!(parse(text.as_bytes()).expect("metadata"), mesh);
    }

    /// A BINARY 5.1 file of `points` (big-endian doubles) and one triangle per triple.
    fn binary_51(points: &[[f64; 3]], triangles: &[[i64; 3]]) -> Vec<u8> {
        let mut b = b"# vtk DataFile Version 5.1\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\n".to_vec();
        b.extend_from_slice(format!("POINTS {} double\n", points.len()).as_bytes());
        for v in points.iter().flatten() {
            b.extend_from_slice(&v.to_be_bytes());
        }
        let m = triangles.len();
        b.extend_from_slice(
            format!("\nCELLS {} {}\nOFFSETS vtktypeint64\n", m + 1, 3 * m).as_bytes(),
        );
        for k in 0..=m as i64 {
            b.extend_from_slice(&(3 * k).to_be_bytes());
        }
        b.extend_from_slice(b"\nCONNECTIVITY vtktypeint64\n");
        for v in triangles.iter().flatten() {
            b.extend_from_slice(&v.to_be_bytes());
        }
        b.extend_from_slice(format!("\nCELL_TYPES {m}\n").as_bytes());
        for _ in 0..m {
            b.extend_from_slice(&5i32.to_be_bytes());
        }
        b.push(b'\n');
        b
    }

    #[test]
    fn binary_points_are_big_endian_and_kept_bit_for_bit() {
        let points = [
            [-0.0, 1.0 / 3.0, 0.0],
            [0.1 + 0.2, 1e-300, 0.0],
            [7.5e12, 2.0, -0.0],
        ];
        let mesh = parse(&binary_51(&points, &[[0, 1, 2], [2, 1, 0]])).expect("binary");
        for (got, want) in mesh.vertices.iter().zip(&points) {
            assert_eq!(got[0].to_bits(), want[0].to_bits());
            assert_eq!(got[1].to_bits(), want[1].to_bits());
        }
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [2, 1, 0]]);
    }

    #[test]
    fn classic_binary_with_float_points() {
        let mut b =
            b"# vtk DataFile Version 4.2\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 float\n"
                .to_vec();
        for v in [0.5f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.25, 0.0] {
            b.extend_from_slice(&v.to_be_bytes());
        }
        b.extend_from_slice(b"\nCELLS 1 4\n");
        for v in [3i32, 0, 1, 2] {
            b.extend_from_slice(&v.to_be_bytes());
        }
        b.extend_from_slice(b"\nCELL_TYPES 1\n");
        b.extend_from_slice(&5i32.to_be_bytes());
        let mesh = parse(&b).expect("classic binary");
        assert_eq!(mesh.vertices, vec![[0.5, 0.0], [1.0, 0.0], [0.0, 0.25]]);
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn polydata_polygons_of_three_are_triangles_and_of_four_refused() {
        let text = "# vtk DataFile Version 3.0\np\nASCII\nDATASET POLYDATA\n\
            POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\nLINES 1 3\n2 0 1\n\
            POLYGONS 2 8\n3 0 1 2\n3 0 2 3\n";
        let mesh = parse(text.as_bytes()).expect("polydata");
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        let quad = text.replace(
            "POLYGONS 2 8\n3 0 1 2\n3 0 2 3\n",
            "POLYGONS 1 5\n4 0 1 2 3\n",
        );
        assert_eq!(
            message(quad.as_bytes()),
            "t.vtk:10: polygon 0 of this section has 4 points: verify checks meshes of triangles"
        );
    }

    #[test]
    fn quadrangles_and_other_cells_are_refused_by_name() {
        let text = CLASSIC.replace("CELL_TYPES 4\n1\n5\n3\n5\n", "CELL_TYPES 4\n1\n5\n3\n9\n");
        assert_eq!(
            message(text.as_bytes()),
            "t.vtk:21: cell 3 has type 9 (a quadrangle): verify checks meshes of linear \
             triangles (type 5); vertices and lines are skipped"
        );
        let text = CLASSIC.replace("0.1 1 0\n", "0.1 1 1e-9\n");
        assert_eq!(
            message(text.as_bytes()),
            "t.vtk:11: point 3 has z = 1e-9: verify checks planar meshes in the plane z = 0"
        );
        let text = CLASSIC.replace("3 0 2 3\n", "3 0 2 4\n");
        assert_eq!(
            message(text.as_bytes()),
            "t.vtk:16: cell 3 names point 4, but there are 4 points numbered from 0"
        );
    }

    #[test]
    fn every_truncation_and_byte_change_is_refused_or_read_without_panic() {
        use crate::io::scan::refuses_without_panic;
        let p = |b: &[u8]| parse(b);
        let binary = binary_51(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        // Cut before its last cell type, the binary file is refused.
        assert!(refuses_without_panic(&binary, p) >= binary.len() - 5);
        let classic = CLASSIC.as_bytes();
        let data = CLASSIC.find("CELL_DATA").expect("cell data");
        assert!(refuses_without_panic(classic, p) >= data - 2);
    }

    #[test]
    fn truncated_files_are_refused_with_line_or_byte_offset() {
        let cut = &CLASSIC[..CLASSIC.find("CELL_TYPES").expect("types")];
        assert_eq!(
            message(cut.as_bytes()),
            "t.vtk: the file has no CELL_TYPES section"
        );
        let cut = &CLASSIC[..CLASSIC.find("3 0 2 3").expect("cell")];
        assert_eq!(
            message(cut.as_bytes()),
            "t.vtk:15: the file ends where a cell entry was expected"
        );
        let bytes = binary_51(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        let cut = &bytes[..bytes.len() - 3];
        let e = message(cut);
        assert!(e.starts_with("t.vtk: at byte offset "), "{e}");
        assert!(e.contains("do not fit"), "{e}");
        let head = b"# vtk DataFile Version 5.1\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 1000000000000 double\n";
        let e = message(head);
        assert!(
            e.contains("1000000000000 records of 24 bytes do not fit in the 0 bytes"),
            "{e}"
        );
        assert_eq!(
            message(b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"),
            "t.vtk:4: DATASET STRUCTURED_POINTS is not read: verify reads UNSTRUCTURED_GRID and POLYDATA"
        );
        assert_eq!(
            message(b"$MeshFormat\n"),
            "t.vtk:1: not a VTK legacy file: it must start with '# vtk DataFile Version'"
        );
    }
}
