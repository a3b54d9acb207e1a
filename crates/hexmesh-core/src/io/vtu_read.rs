//! Reads VTK XML unstructured grids, `.vtu` (Kitware, "VTK File Formats", XML formats), into
//! a 0-based [`TriMesh`]: `DataArray`s in `ascii`, inline `binary` (base64) or `appended`
//! (raw or base64) format, uncompressed or zlib-compressed
//! (`compressor="vtkZLibDataCompressor"`, meshio's default; needs the `vtu-zlib` feature),
//! with UInt32 or UInt64 headers, in either byte order.
//!
//! - Points (`Float32` or `Float64`, three components) must have z = 0; binary coordinates are
//!   taken bit for bit, ASCII ones with Rust's correctly rounded `f64` parse.
//! - Cells of type 5 (`VTK_TRIANGLE`) become triangles; vertices and lines (types 1 to 4) are
//!   skipped; every other cell type is refused. Several `Piece`s are joined in order.
//! - The XML is read by hand: the layout is fixed, attributes may come in any order, with any
//!   whitespace; comments and the `<?xml ?>` declaration are skipped. Point and cell data
//!   arrays are not decoded.
//!
//! Errors name the file and the line of the element at fault; for appended data, also the
//! byte offset.

use std::path::Path;

use super::vtk_read::cell_name;
use super::vtu_data::{array_bytes, Base64, HeaderType, Source, ZLIB};
use crate::error::{Error, Result};
use crate::mesh::TriMesh;

/// VTK's linear triangle.
const VTK_TRIANGLE: i64 = 5;

/// Reads a `.vtu` file; see the module docs.
pub fn read_vtu(path: &Path) -> Result<TriMesh> {
    parse_vtu(path, &super::read_any::read_bytes(path)?)
}

/// Parses the bytes of a `.vtu` file; `path` is only used in messages.
pub fn parse_vtu(path: &Path, data: &[u8]) -> Result<TriMesh> {
    let doc = Document::read(path, data)?;
    let mut mesh = TriMesh::default();
    if doc.pieces.is_empty() {
        return Err(Error::parse(path, 0, "the file has no <Piece> element"));
    }
    for piece in &doc.pieces {
        doc.add_piece(piece, &mut mesh)?;
    }
    Ok(mesh)
}

/// One start tag: where it starts, its name, its attributes, where it ends.
struct Tag<'a> {
    start: usize,
    name: &'a str,
    attributes: Vec<(&'a str, &'a str)>,
    closing: bool,
    self_closing: bool,
    end: usize,
}

impl<'a> Tag<'a> {
    fn get(&self, name: &str) -> Option<&'a str> {
        self.attributes
            .iter()
            .find(|(k, _)| *k == name)
            .map(|&(_, v)| v)
    }
}

/// A `DataArray` under `Points` or `Cells`.
struct Array<'a> {
    tag: Tag<'a>,
    /// The text between the start and end tags.
    content: &'a [u8],
}

struct Piece<'a> {
    at: usize,
    points: usize,
    cells: usize,
    point_arrays: Vec<Array<'a>>,
    cell_arrays: Vec<Array<'a>>,
}

struct Document<'a> {
    path: &'a Path,
    data: &'a [u8],
    big_endian: bool,
    header: HeaderType,
    compressed: bool,
    pieces: Vec<Piece<'a>>,
    /// `<AppendedData>`: where its data start (after the `_`), and whether they are base64.
    appended: Option<(usize, bool)>,
}

impl<'a> Document<'a> {
    fn line(&self, pos: usize) -> usize {
        line_of(self.data, pos)
    }

    fn error(&self, pos: usize, message: impl Into<String>) -> Error {
        Error::parse(self.path, self.line(pos), message)
    }

    /// Walks the XML up to `<AppendedData>`, collecting the pieces and their arrays.
    fn read(path: &'a Path, data: &'a [u8]) -> Result<Document<'a>> {
        let mut doc = Document {
            path,
            data,
            big_endian: false,
            header: HeaderType::UInt32,
            compressed: false,
            pieces: Vec::new(),
            appended: None,
        };
        let mut stack: Vec<&str> = Vec::new();
        let mut seen_file = false;
        let mut pos = 0;
        while let Some(tag) = next_tag(data, pos).map_err(|(at, m)| doc.error(at, m))? {
            pos = tag.end;
            if tag.closing {
                match stack.pop() {
                    Some(open) if open == tag.name => continue,
                    open => {
                        return Err(doc.error(
                            tag.start,
                            format!(
                                "</{}> closes {}",
                                tag.name,
                                open.map_or("nothing".to_string(), |o| format!("<{o}>"))
                            ),
                        ))
                    }
                }
            }
            if !seen_file {
                if tag.name != "VTKFile" {
                    return Err(doc.error(
                        tag.start,
                        "not a VTK XML file: the first element must be <VTKFile>",
                    ));
                }
                doc.file_attributes(&tag)?;
                seen_file = true;
            }
            match tag.name {
                "Piece" => {
                    let count = |name: &str| -> Result<usize> {
                        tag.get(name)
                            .unwrap_or("0")
                            .trim()
                            .parse()
                            .map_err(|_| doc.error(tag.start, format!("{name} is not a count")))
                    };
                    let piece = Piece {
                        at: tag.start,
                        points: count("NumberOfPoints")?,
                        cells: count("NumberOfCells")?,
                        point_arrays: Vec::new(),
                        cell_arrays: Vec::new(),
                    };
                    doc.pieces.push(piece);
                }
                "DataArray" => {
                    let parent = stack.last().copied();
                    let content_end = if tag.self_closing {
                        tag.end
                    } else {
                        data[tag.end..]
                            .iter()
                            .position(|&b| b == b'<')
                            .map_or(data.len(), |k| tag.end + k)
                    };
                    let content = &data[tag.end..content_end];
                    pos = content_end;
                    let self_closing = tag.self_closing;
                    if let (Some(parent @ ("Points" | "Cells")), Some(piece)) =
                        (parent, doc.pieces.last_mut())
                    {
                        let array = Array { tag, content };
                        if parent == "Points" {
                            piece.point_arrays.push(array);
                        } else {
                            piece.cell_arrays.push(array);
                        }
                    }
                    if !self_closing {
                        stack.push("DataArray");
                    }
                    continue;
                }
                "AppendedData" => {
                    let base64 = match tag.get("encoding").unwrap_or("raw") {
                        "raw" => false,
                        "base64" => true,
                        other => {
                            return Err(doc.error(
                                tag.start,
                                format!("appended data encoding '{other}': expected raw or base64"),
                            ))
                        }
                    };
                    let rest = &data[tag.end..];
                    let underscore = rest
                        .iter()
                        .position(|b| !b.is_ascii_whitespace())
                        .filter(|&k| rest[k] == b'_')
                        .ok_or_else(|| {
                            doc.error(tag.start, "<AppendedData> must begin with '_'")
                        })?;
                    doc.appended = Some((tag.end + underscore + 1, base64));
                    break;
                }
                _ => {}
            }
            if !tag.self_closing {
                stack.push(tag.name);
            }
        }
        if !seen_file {
            return Err(Error::parse(
                path,
                0,
                "not a VTK XML file: no <VTKFile> element",
            ));
        }
        if doc.appended.is_none() {
            if let Some(open) = stack.last() {
                return Err(doc.error(
                    data.len().saturating_sub(1),
                    format!("the file ends inside <{open}>: it is cut short"),
                ));
            }
        }
        Ok(doc)
    }

    /// `type`, `byte_order`, `header_type` and `compressor` of `<VTKFile>`.
    fn file_attributes(&mut self, tag: &Tag) -> Result<()> {
        match tag.get("type") {
            Some("UnstructuredGrid") => {}
            other => {
                return Err(self.error(
                    tag.start,
                    format!(
                        "VTKFile type {}: verify reads UnstructuredGrid (.vtu) files",
                        other.unwrap_or("(none)")
                    ),
                ))
            }
        }
        self.big_endian = match tag.get("byte_order").unwrap_or("LittleEndian") {
            "LittleEndian" => false,
            "BigEndian" => true,
            other => return Err(self.error(tag.start, format!("unknown byte_order '{other}'"))),
        };
        self.header = match tag.get("header_type").unwrap_or("UInt32") {
            "UInt32" => HeaderType::UInt32,
            "UInt64" => HeaderType::UInt64,
            other => {
                return Err(self.error(
                    tag.start,
                    format!("header_type '{other}': expected UInt32 or UInt64"),
                ))
            }
        };
        self.compressed = match tag.get("compressor") {
            None | Some("") => false,
            Some("vtkZLibDataCompressor") if ZLIB => true,
            Some("vtkZLibDataCompressor") => {
                return Err(self.error(
                    tag.start,
                    "the data are zlib-compressed, and hexmesh-core was built without its \
                     `vtu-zlib` feature, which inflates them",
                ))
            }
            Some(other) => {
                return Err(self.error(
                    tag.start,
                    format!(
                        "compressor {other} is not read: write the file uncompressed or with \
                         vtkZLibDataCompressor"
                    ),
                ))
            }
        };
        Ok(())
    }

    /// The array's values as f64 (`Float32` and `Float64` only).
    fn floats(&self, array: &Array) -> Result<Vec<f64>> {
        let ty = array.tag.get("type").unwrap_or("");
        let size = match ty {
            "Float32" => 4,
            "Float64" => 8,
            _ => {
                return Err(self.error(
                    array.tag.start,
                    format!("points of type '{ty}' are not read: use Float32 or Float64"),
                ))
            }
        };
        if let Some(tokens) = self.ascii(array)? {
            return tokens
                .map(|t| {
                    t.parse::<f64>()
                        .map_err(|_| self.array_error(array, format!("'{t}' is not a number")))
                })
                .collect();
        }
        Ok(self
            .words(array, size)?
            .into_iter()
            .map(|b| {
                if size == 4 {
                    f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                } else {
                    f64::from_le_bytes(b)
                }
            })
            .collect())
    }

    /// The array's values as i64 (any integer type).
    fn ints(&self, array: &Array) -> Result<Vec<i64>> {
        let ty = array.tag.get("type").unwrap_or("");
        let (size, signed) = match ty {
            "Int8" => (1, true),
            "UInt8" => (1, false),
            "Int16" => (2, true),
            "UInt16" => (2, false),
            "Int32" => (4, true),
            "UInt32" => (4, false),
            "Int64" => (8, true),
            "UInt64" => (8, false),
            _ => {
                return Err(self.error(
                    array.tag.start,
                    format!("an integer array of type '{ty}' is not read"),
                ))
            }
        };
        if let Some(tokens) = self.ascii(array)? {
            return tokens
                .map(|t| {
                    t.parse::<i64>()
                        .map_err(|_| self.array_error(array, format!("'{t}' is not an integer")))
                })
                .collect();
        }
        self.words(array, size)?
            .into_iter()
            .map(|mut b| {
                let negative = signed && b[size - 1] & 0x80 != 0;
                if negative {
                    b[size..].fill(0xff);
                }
                let v = u64::from_le_bytes(b);
                if signed {
                    Ok(v as i64)
                } else {
                    i64::try_from(v)
                        .map_err(|_| self.array_error(array, format!("{v} is out of range")))
                }
            })
            .collect()
    }

    /// The binary values of `array`, `size` bytes each, as little-endian words in the low
    /// bytes of 8 (the rest zero), whatever the file's byte order.
    fn words(&self, array: &Array, size: usize) -> Result<Vec<[u8; 8]>> {
        let bytes = self.binary(array)?;
        self.whole(array, &bytes, size)?;
        Ok(bytes
            .chunks_exact(size)
            .map(|c| {
                let mut b = [0u8; 8];
                b[..size].copy_from_slice(c);
                if self.big_endian {
                    b[..size].reverse();
                }
                b
            })
            .collect())
    }

    fn whole(&self, array: &Array, bytes: &[u8], size: usize) -> Result<()> {
        if bytes.len() % size == 0 {
            Ok(())
        } else {
            Err(self.array_error(
                array,
                format!(
                    "{} bytes are not a whole number of {size}-byte values",
                    bytes.len()
                ),
            ))
        }
    }

    fn array_error(&self, array: &Array, message: impl AsRef<str>) -> Error {
        let name = array.tag.get("Name").unwrap_or("(unnamed)");
        self.error(
            array.tag.start,
            format!("DataArray '{name}': {}", message.as_ref()),
        )
    }

    /// The tokens of an `ascii` array; `None` for the other formats.
    fn ascii<'s>(&self, array: &'s Array) -> Result<Option<impl Iterator<Item = &'s str>>> {
        match array.tag.get("format").unwrap_or("ascii") {
            "ascii" => {
                let text = std::str::from_utf8(array.content)
                    .map_err(|_| self.array_error(array, "the ASCII data are not UTF-8"))?;
                Ok(Some(text.split_ascii_whitespace()))
            }
            "binary" | "appended" => Ok(None),
            other => Err(self.array_error(
                array,
                format!("format '{other}': expected ascii, binary or appended"),
            )),
        }
    }

    /// The decoded bytes of a `binary` or `appended` array.
    fn binary(&self, array: &Array) -> Result<Vec<u8>> {
        let (mut source, at) = if array.tag.get("format") == Some("appended") {
            let Some((start, base64)) = self.appended else {
                return Err(self.array_error(array, "appended, but the file has no <AppendedData>"));
            };
            let offset: usize = array
                .tag
                .get("offset")
                .and_then(|o| o.trim().parse().ok())
                .ok_or_else(|| self.array_error(array, "appended without an offset"))?;
            let at = start.saturating_add(offset);
            if at > self.data.len() {
                return Err(self.array_error(
                    array,
                    format!("its offset {offset} lies beyond the end of the file"),
                ));
            }
            let source = if base64 {
                Source::Base64(Base64::new(&self.data[at..]))
            } else {
                Source::Raw {
                    data: &self.data[start..],
                    pos: offset,
                }
            };
            (source, Some(at))
        } else {
            (Source::Base64(Base64::new(array.content)), None)
        };
        array_bytes(&mut source, self.header, self.big_endian, self.compressed).map_err(
            |m| match at {
                Some(at) => {
                    self.array_error(array, format!("appended data at byte offset {at}: {m}"))
                }
                None => self.array_error(array, m),
            },
        )
    }

    fn named<'s>(&self, piece: &'s Piece<'a>, name: &str) -> Result<&'s Array<'a>> {
        piece
            .cell_arrays
            .iter()
            .find(|a| a.tag.get("Name") == Some(name))
            .ok_or_else(|| {
                self.error(
                    piece.at,
                    format!("the piece's <Cells> has no '{name}' array"),
                )
            })
    }

    /// Adds a piece's points and triangles to `mesh`.
    fn add_piece(&self, piece: &Piece<'a>, mesh: &mut TriMesh) -> Result<()> {
        let base = mesh.vertices.len();
        let Some(points) = piece.point_arrays.first() else {
            return Err(self.error(piece.at, "the piece has no <Points> DataArray"));
        };
        if points.tag.get("NumberOfComponents").map(str::trim) != Some("3") {
            return Err(self.array_error(points, "points must have NumberOfComponents=\"3\""));
        }
        let xyz = self.floats(points)?;
        if Some(xyz.len()) != piece.points.checked_mul(3) {
            return Err(self.array_error(
                points,
                format!(
                    "{} values, but NumberOfPoints=\"{}\" needs three each",
                    xyz.len(),
                    piece.points
                ),
            ));
        }
        for (k, p) in xyz.chunks_exact(3).enumerate() {
            if let Some(bad) = p.iter().find(|v| !v.is_finite()) {
                return Err(self.array_error(
                    points,
                    format!(
                        "point {k} has the coordinate {bad}: NaN and infinite values are refused"
                    ),
                ));
            }
            if p[2] != 0.0 {
                return Err(self.array_error(
                    points,
                    format!(
                        "point {k} has z = {:?}: verify checks planar meshes in the plane z = 0",
                        p[2]
                    ),
                ));
            }
            mesh.vertices.push([p[0], p[1]]);
        }
        if piece.cells == 0 {
            return Ok(());
        }
        let (connectivity, offsets, types) = (
            self.named(piece, "connectivity")?,
            self.named(piece, "offsets")?,
            self.named(piece, "types")?,
        );
        let corners = self.ints(connectivity)?;
        let ends = self.ints(offsets)?;
        let kinds = self.ints(types)?;
        for (array, n) in [(offsets, ends.len()), (types, kinds.len())] {
            if n != piece.cells {
                return Err(self.array_error(
                    array,
                    format!("{n} values, but NumberOfCells=\"{}\"", piece.cells),
                ));
            }
        }
        let mut start = 0usize;
        for (k, (&end, &kind)) in ends.iter().zip(&kinds).enumerate() {
            let end = usize::try_from(end)
                .ok()
                .filter(|&e| e >= start && e <= corners.len())
                .ok_or_else(|| {
                    self.array_error(
                        offsets,
                        format!(
                            "cell {k} ends at {end}, outside {start}..={} of the connectivity",
                            corners.len()
                        ),
                    )
                })?;
            let cell = &corners[start..end];
            start = end;
            match kind {
                VTK_TRIANGLE if cell.len() == 3 => {
                    let mut t = [0u32; 3];
                    for (slot, &c) in t.iter_mut().zip(cell) {
                        *slot = usize::try_from(c)
                            .ok()
                            .filter(|&c| c < piece.points)
                            .and_then(|c| u32::try_from(base + c).ok())
                            .ok_or_else(|| {
                                self.array_error(
                                    connectivity,
                                    format!(
                                        "cell {k} names point {c}, but the piece has {} points \
                                         numbered from 0",
                                        piece.points
                                    ),
                                )
                            })?;
                    }
                    mesh.triangles.push(t);
                }
                VTK_TRIANGLE => {
                    return Err(self.array_error(
                        types,
                        format!("cell {k} is a triangle (type 5) with {} points", cell.len()),
                    ))
                }
                1..=4 => {}
                other => {
                    return Err(self.array_error(
                        types,
                        format!(
                            "cell {k} has type {other} ({}): verify checks meshes of linear \
                             triangles (type 5); vertices and lines are skipped",
                            cell_name(other)
                        ),
                    ))
                }
            }
        }
        Ok(())
    }
}

/// The 1-based line of byte `pos`.
fn line_of(data: &[u8], pos: usize) -> usize {
    1 + data[..pos.min(data.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// The next tag at or after `from`, skipping text, comments, `<?...?>` and `<!...>`;
/// `Err((offset, message))` for malformed markup.
fn next_tag(data: &[u8], from: usize) -> std::result::Result<Option<Tag<'_>>, (usize, String)> {
    let mut pos = from;
    loop {
        let Some(k) = data
            .get(pos..)
            .and_then(|r| r.iter().position(|&b| b == b'<'))
        else {
            return Ok(None);
        };
        let start = pos + k;
        let rest = &data[start..];
        let skip_to = |close: &[u8]| {
            super::scan::find(rest, close)
                .map(|e| start + e + close.len())
                .ok_or_else(|| (start, "this markup is never closed".to_string()))
        };
        if rest.starts_with(b"<!--") {
            pos = skip_to(b"-->")?;
            continue;
        }
        if rest.starts_with(b"<?") {
            pos = skip_to(b"?>")?;
            continue;
        }
        if rest.starts_with(b"<!") {
            pos = skip_to(b">")?;
            continue;
        }
        let close = rest
            .iter()
            .position(|&b| b == b'>')
            .ok_or_else(|| (start, "this tag is never closed with '>'".to_string()))?;
        let inner = std::str::from_utf8(&rest[1..close])
            .map_err(|_| (start, "this tag is not UTF-8 text".to_string()))?;
        let closing = inner.starts_with('/');
        let self_closing = inner.ends_with('/');
        let inner = inner.trim_start_matches('/').trim_end_matches('/');
        let name_end = inner
            .find(|c: char| c.is_ascii_whitespace())
            .unwrap_or(inner.len());
        let name = &inner[..name_end];
        if name.is_empty() {
            return Err((start, "a tag without a name".into()));
        }
        let attributes = attributes(&inner[name_end..]).map_err(|m| (start, m))?;
        return Ok(Some(Tag {
            start,
            name,
            attributes,
            closing,
            self_closing,
            end: start + close + 1,
        }));
    }
}

/// `name="value"` pairs (single or double quotes, any whitespace around `=`).
fn attributes(mut text: &str) -> std::result::Result<Vec<(&str, &str)>, String> {
    let mut out = Vec::new();
    loop {
        text = text.trim_start();
        if text.is_empty() {
            return Ok(out);
        }
        let eq = text
            .find('=')
            .ok_or_else(|| format!("attribute '{}' has no value", text.trim()))?;
        let name = text[..eq].trim();
        let after = text[eq + 1..].trim_start();
        let quote = after
            .chars()
            .next()
            .filter(|&q| q == '"' || q == '\'')
            .ok_or_else(|| format!("the value of attribute '{name}' is not quoted"))?;
        let value_end = after[1..]
            .find(quote)
            .ok_or_else(|| format!("the value of attribute '{name}' is never closed"))?;
        out.push((name, &after[1..1 + value_end]));
        text = &after[value_end + 2..];
    }
}

#[cfg(test)]
mod tests {
    use super::super::vtu_data::encode;
    use super::*;

    fn parse(bytes: &[u8]) -> Result<TriMesh> {
        parse_vtu(Path::new("t.vtu"), bytes)
    }

    fn message(bytes: &[u8]) -> String {
        parse(bytes).expect_err("refused").to_string()
    }

    const ASCII: &str = "<?xml version=\"1.0\"?>\n\
        <VTKFile byte_order = 'LittleEndian'  type=\"UnstructuredGrid\" version=\"0.1\">\n\
        <!-- a <comment> -->\n<UnstructuredGrid>\n\
        <Piece NumberOfCells=\"3\"\n       NumberOfPoints=\"4\">\n\
        <PointData><DataArray type=\"Float64\" Name=\"u\" format=\"ascii\">1 2 3 4</DataArray></PointData>\n\
        <Points>\n<DataArray NumberOfComponents=\"3\" format=\"ascii\" type=\"Float64\">\n\
        0 0 0 1 0 0\n1 1 0 0.1 1 0\n</DataArray>\n</Points>\n\
        <Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 0 2 3 1</DataArray>\n\
        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3 6 7</DataArray>\n\
        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5 5 1</DataArray>\n\
        </Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";

    #[test]
    fn ascii_arrays_in_any_attribute_order_skipping_point_data_and_vertices() {
        let mesh = parse(ASCII.as_bytes()).expect("ascii");
        assert_eq!(
            mesh.vertices,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.1, 1.0]]
        );
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    /// Three points of awkward bits and one triangle, as little-endian bytes.
    fn parts() -> (Vec<f64>, [Vec<u8>; 4]) {
        let xyz = vec![
            -0.0,
            1.0 / 3.0,
            0.0,
            0.1 + 0.2,
            1e-300,
            0.0,
            7.5e12,
            2.0,
            0.0,
        ];
        let points = xyz.iter().flat_map(|v: &f64| v.to_le_bytes()).collect();
        let connectivity = [0i64, 1, 2].iter().flat_map(|v| v.to_le_bytes()).collect();
        let offsets = 3i64.to_le_bytes().to_vec();
        let types = vec![5u8];
        (xyz, [points, connectivity, offsets, types])
    }

    fn document(file: &str, arrays: [String; 4], appended: &[u8]) -> Vec<u8> {
        let [p, c, o, t] = arrays;
        let mut b = format!(
            "<VTKFile type=\"UnstructuredGrid\" {file}>\n<UnstructuredGrid>\n\
             <Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n\
             <Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" {p}</Points>\n\
             <Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" {c}\n\
             <DataArray type=\"Int64\" Name=\"offsets\" {o}\n\
             <DataArray type=\"UInt8\" Name=\"types\" {t}\n</Cells>\n</Piece>\n\
             </UnstructuredGrid>\n"
        )
        .into_bytes();
        b.extend_from_slice(appended);
        b.extend_from_slice(b"</VTKFile>\n");
        b
    }

    fn check_bits(mesh: &TriMesh, xyz: &[f64]) {
        let got: Vec<u64> = mesh
            .vertices
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect();
        let want: Vec<u64> = xyz
            .chunks(3)
            .flat_map(|p| [p[0].to_bits(), p[1].to_bits()])
            .collect();
        assert_eq!(got, want);
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn inline_base64_with_a_uint64_header_keeps_coordinates_bit_for_bit() {
        let (xyz, [p, c, o, t]) = parts();
        let inline = |data: &[u8]| {
            let mut bytes = (data.len() as u64).to_le_bytes().to_vec();
            bytes.extend_from_slice(data);
            format!("format=\"binary\">\n  {}\n</DataArray>", encode(&bytes))
        };
        let doc = document(
            "header_type=\"UInt64\"",
            [inline(&p), inline(&c), inline(&o), inline(&t)],
            b"",
        );
        check_bits(&parse(&doc).expect("binary"), &xyz);
    }

    /// The four arrays appended one after another: (attributes, appended section).
    fn appended(base64: bool, big_endian: bool) -> ([String; 4], Vec<u8>) {
        let (_, [p, c, o, t]) = parts();
        let mut data = Vec::new();
        let mut attributes = Vec::new();
        for (array, size) in [(p, 8), (c, 8), (o, 8), (t, 1)] {
            let mut block = Vec::new();
            let n = array.len() as u32;
            block.extend_from_slice(&if big_endian {
                n.to_be_bytes()
            } else {
                n.to_le_bytes()
            });
            for value in array.chunks(size) {
                let mut v = value.to_vec();
                if big_endian {
                    v.reverse();
                }
                block.extend_from_slice(&v);
            }
            attributes.push(format!("format=\"appended\" offset=\"{}\"/>", data.len()));
            if base64 {
                data.extend_from_slice(encode(&block).as_bytes());
            } else {
                data.extend_from_slice(&block);
            }
        }
        let encoding = if base64 { "base64" } else { "raw" };
        let mut section = format!("<AppendedData encoding=\"{encoding}\">\n   _").into_bytes();
        section.extend_from_slice(&data);
        section.extend_from_slice(b"\n</AppendedData>\n");
        (attributes.try_into().expect("four"), section)
    }

    /// With a UInt64 header, each array zlib-compressed in blocks of 16 bytes (header and
    /// data encoded apart in base64), as ParaView may write them.
    #[cfg(feature = "vtu-zlib")]
    #[test]
    fn appended_zlib_blocks_with_uint64_headers_in_raw_and_base64() {
        let (xyz, arrays) = parts();
        for base64 in [false, true] {
            let mut data = Vec::new();
            let mut attributes = Vec::new();
            for array in &arrays {
                let chunks: Vec<Vec<u8>> = array
                    .chunks(16)
                    .map(|c| miniz_oxide::deflate::compress_to_vec_zlib(c, 6))
                    .collect();
                let last = (array.len() % 16) as u64;
                let mut header = Vec::new();
                for w in [chunks.len() as u64, 16, last]
                    .into_iter()
                    .chain(chunks.iter().map(|c| c.len() as u64))
                {
                    header.extend_from_slice(&w.to_le_bytes());
                }
                let body = chunks.concat();
                attributes.push(format!("format=\"appended\" offset=\"{}\"/>", data.len()));
                if base64 {
                    data.extend_from_slice(encode(&header).as_bytes());
                    data.extend_from_slice(encode(&body).as_bytes());
                } else {
                    data.extend_from_slice(&header);
                    data.extend_from_slice(&body);
                }
            }
            let encoding = if base64 { "base64" } else { "raw" };
            let mut section = format!("<AppendedData encoding=\"{encoding}\">_").into_bytes();
            section.extend_from_slice(&data);
            section.extend_from_slice(b"</AppendedData>\n");
            let file = "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"";
            let doc = document(file, attributes.try_into().expect("four"), &section);
            check_bits(&parse(&doc).expect("compressed"), &xyz);
        }
    }

    #[test]
    fn appended_raw_and_base64_in_either_byte_order() {
        let (xyz, ..) = parts();
        for (base64, big) in [(false, false), (true, false), (false, true)] {
            let (arrays, section) = appended(base64, big);
            let order = if big { "BigEndian" } else { "LittleEndian" };
            let doc = document(&format!("byte_order=\"{order}\""), arrays, &section);
            check_bits(&parse(&doc).expect("appended"), &xyz);
        }
    }

    /// meshio 5.3.5's `meshio.write("a.vtu", mesh)` of a unit square of two triangles:
    /// binary, zlib-compressed, Int64 cells.
    const MESHIO_ZLIB: &str = "<?xml version=\"1.0\"?>\n\
        <VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" compressor=\"vtkZLibDataCompressor\">\n\
        <!--This file was created by meshio v5.3.5-->\n<UnstructuredGrid>\n\
        <Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n<Points>\n\
        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">\n\
        AQAAAACAAABgAAAAFAAAAA==eJxjYMAHPtjjFyckz8AAALNMBL0=\n</DataArray>\n</Points>\n<Cells>\n\
        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">\n\
        AQAAAACAAAAwAAAAFgAAAA==eJxjYIAARijNxIAKYHxmKA0AANAACQ==\n</DataArray>\n\
        <DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">\n\
        AQAAAACAAAAQAAAADgAAAA==eJxjZoAANigNAABwAAo=\n</DataArray>\n\
        <DataArray type=\"Int64\" Name=\"types\" format=\"binary\">\n\
        AQAAAACAAAAQAAAADgAAAA==eJxjZYAAVigNAACIAAs=\n</DataArray>\n\
        </Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";

    #[cfg(feature = "vtu-zlib")]
    #[test]
    fn meshio_zlib_output_reads_as_its_square() {
        let mesh = parse(MESHIO_ZLIB.as_bytes()).expect("meshio");
        assert_eq!(
            mesh.vertices,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        );
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[cfg(not(feature = "vtu-zlib"))]
    #[test]
    fn zlib_output_is_refused_without_the_feature() {
        assert!(message(MESHIO_ZLIB.as_bytes()).contains("without its `vtu-zlib` feature"));
    }

    #[test]
    fn quadrangles_and_lifted_points_are_refused_at_their_array() {
        let quad = ASCII
            .replace("0 1 2 0 2 3 1<", "0 1 2 0 2 3 1 0 1 2 3<")
            .replace("3 6 7<", "3 6 7 11<")
            .replace("5 5 1<", "5 5 1 9<")
            .replace("NumberOfCells=\"3\"", "NumberOfCells=\"4\"");
        assert_eq!(
            message(quad.as_bytes()),
            "t.vtu:17: DataArray 'types': cell 3 has type 9 (a quadrangle): verify checks \
             meshes of linear triangles (type 5); vertices and lines are skipped"
        );
        let lifted = ASCII.replace("0.1 1 0\n", "0.1 1 2\n");
        assert_eq!(
            message(lifted.as_bytes()),
            "t.vtu:9: DataArray '(unnamed)': point 3 has z = 2.0: verify checks planar meshes \
             in the plane z = 0"
        );
    }

    #[test]
    fn every_truncation_and_byte_change_is_refused_or_read_without_panic() {
        use crate::io::scan::refuses_without_panic;
        let p = |b: &[u8]| parse(b);
        let (arrays, section) = appended(true, false);
        let base64 = document("", arrays, &section);
        let (arrays, section) = appended(false, true);
        let raw = document("byte_order=\"BigEndian\"", arrays, &section);
        let find = |bytes: &[u8], what: &str| {
            crate::io::scan::find(bytes, what.as_bytes()).expect("marker")
        };
        // Without the vtu-zlib feature, meshio's file is refused whole.
        let zlib = if ZLIB { MESHIO_ZLIB } else { ASCII };
        for bytes in [ASCII.as_bytes(), zlib.as_bytes()] {
            // Every cut before the end of </VTKFile> is refused, and no other.
            let end = find(bytes, "</VTKFile>") + "</VTKFile>".len();
            assert_eq!(refuses_without_panic(bytes, p), end);
        }
        for (bytes, padded) in [(&base64, true), (&raw, false)] {
            // Every cut before the end of the appended data is refused, except in base64 the
            // one that drops only the final '=' (a group without padding still decodes).
            let end = find(bytes, "\n</AppendedData>");
            refuses_without_panic(bytes, p);
            let read: Vec<usize> = (0..end).filter(|&k| parse(&bytes[..k]).is_ok()).collect();
            let expected = if padded { vec![end - 1] } else { vec![] };
            assert_eq!(read, expected);
        }
    }

    #[test]
    fn truncated_data_are_refused_with_the_array_and_offset() {
        if ZLIB {
            let cut = MESHIO_ZLIB.replace("eJxjYMAHPtjjFyckz8AAALNMBL0=", "");
            assert_eq!(
                message(cut.as_bytes()),
                "t.vtu:7: DataArray 'Points': the base64 data end inside a compressed block, \
                 which needs 20 bytes (0 decoded)"
            );
        }
        let (arrays, section) = appended(false, false);
        let doc = document("", arrays, &section[..section.len() - 30]);
        let e = message(&doc);
        assert!(
            e.contains("DataArray 'types': appended data at byte offset"),
            "{e}"
        );
        assert!(e.contains("end inside"), "{e}");
        let (_, [p, ..]) = parts();
        let mut huge = u32::MAX.to_le_bytes().to_vec();
        huge.extend_from_slice(&p);
        let arrays = [
            format!("format=\"binary\">{}</DataArray>", encode(&huge)),
            "format=\"ascii\">0 1 2</DataArray>".into(),
            "format=\"ascii\">3</DataArray>".into(),
            "format=\"ascii\">5</DataArray>".into(),
        ];
        let e = message(&document("", arrays, b""));
        assert!(e.contains("needs 4294967295 bytes"), "{e}");
        assert_eq!(
            message(b"<VTKFile type=\"PolyData\">"),
            "t.vtu:1: VTKFile type PolyData: verify reads UnstructuredGrid (.vtu) files"
        );
        assert_eq!(
            message(b"<?xml version=\"1.0\"?>\n<VTKFile"),
            "t.vtu:2: this tag is never closed with '>'"
        );
    }
}
