//! Shewchuk's Triangle file formats (`.node`, `.poly`, `.ele`; Triangle 1.6 documentation,
//! "File formats"), read and written so that a write → read round trip is bit-exact.
//!
//! The structs hold what a file says: vertex numbers stay as written (numbered from the
//! `.node` section's first index, 0 or 1, detected from the first point as Triangle does);
//! `io::read_input` and `io::read_mesh` shift them to 0-based. Floats are written with Rust's
//! shortest round-trip formatting (`{:?}`), which C's `strtod` also reads exactly.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use super::lines::{read_text, Lines, Row};
use crate::error::{Error, Result};
use crate::geom::{Hexagon, Point, Turn};
pub use crate::mesh::Region;

/// Triangle's default numbering when a file has no row to detect it from.
const DEFAULT_FIRST_INDEX: u32 = 1;

/// Rows are collected without trusting the header's count: a header claiming 10¹² points
/// must not allocate before the rows are there.
const MAX_PREALLOCATION: usize = 1 << 16;

/// A `.node` file, or the nodes section of a `.poly` file.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeFile {
    /// The coordinates, in file order.
    pub points: Vec<Point>,
    /// Number of attributes per point, as in the header.
    pub attribute_count: usize,
    /// One row of `attribute_count` values per point; empty when `attribute_count` is 0 (the
    /// writer also accepts one empty row per point).
    pub attributes: Vec<Vec<f64>>,
    /// Boundary markers, present when the header's marker flag is 1.
    pub markers: Option<Vec<i64>>,
    /// The number of the first point, 0 or 1; segments and triangles count from it.
    pub first_index: u32,
    /// The bounding hexagon from a `# hexmesh: hexagon CX CY R [COS SIN]` comment (R the
    /// circumradius, COS SIN its turn).
    pub hexagon: Option<Hexagon>,
    /// 1-based source line of each point; empty for data not read from a file. Not written.
    pub lines: Vec<usize>,
}

impl Default for NodeFile {
    fn default() -> NodeFile {
        NodeFile {
            points: Vec::new(),
            attribute_count: 0,
            attributes: Vec::new(),
            markers: None,
            first_index: DEFAULT_FIRST_INDEX,
            hexagon: None,
            lines: Vec::new(),
        }
    }
}

impl NodeFile {
    /// Points without attributes or markers, numbered from `first_index`.
    pub fn from_points(points: Vec<Point>, first_index: u32) -> NodeFile {
        NodeFile {
            points,
            first_index,
            ..NodeFile::default()
        }
    }
}

/// A `.poly` file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PolyFile {
    /// The inline nodes; no points (header "0 2 0 0") means they are in the sibling `.node`.
    pub nodes: NodeFile,
    /// Endpoints as written, numbered from the nodes' `first_index`.
    pub segments: Vec<[u32; 2]>,
    /// Segment boundary markers, present when the segment header's marker flag is 1.
    pub segment_markers: Option<Vec<i64>>,
    /// One point inside each hole, in file order.
    pub holes: Vec<Point>,
    /// `None` when the optional regional attributes section is absent.
    pub regions: Option<Vec<Region>>,
    /// 1-based source lines of the segments and holes; empty when not read from a file.
    pub segment_lines: Vec<usize>,
    /// 1-based source line of each hole; empty when not read from a file.
    pub hole_lines: Vec<usize>,
}

/// An `.ele` file of 3-node triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct EleFile {
    /// Corners as written, numbered from the `.node` file's `first_index`.
    pub triangles: Vec<[u32; 3]>,
    /// Number of attributes per triangle, as in the header.
    pub attribute_count: usize,
    /// One row of `attribute_count` values per triangle; empty when `attribute_count` is 0.
    pub attributes: Vec<Vec<f64>>,
    /// The number of the first triangle, 0 or 1 (Triangle uses the same base as the nodes).
    pub first_index: u32,
    /// 1-based source line of each triangle; empty when not read from a file. Not written.
    pub lines: Vec<usize>,
}

impl Default for EleFile {
    fn default() -> EleFile {
        EleFile {
            triangles: Vec::new(),
            attribute_count: 0,
            attributes: Vec::new(),
            first_index: DEFAULT_FIRST_INDEX,
            lines: Vec::new(),
        }
    }
}

/// Reads a `.node` file.
pub fn read_node(path: &Path) -> Result<NodeFile> {
    parse_node(path, &read_text(path)?)
}

/// Reads a `.poly` file as written: when its nodes section is empty the points are not loaded
/// here (`io::read_input` reads the sibling `.node`).
pub fn read_poly(path: &Path) -> Result<PolyFile> {
    parse_poly(path, &read_text(path)?)
}

/// Reads an `.ele` file. 6-node (quadratic) triangles are refused.
pub fn read_ele(path: &Path) -> Result<EleFile> {
    parse_ele(path, &read_text(path)?)
}

/// Parses the text of a `.node` file; `path` is only used to name errors.
pub fn parse_node(path: &Path, text: &str) -> Result<NodeFile> {
    let mut lines = Lines::new(path, text);
    let nodes = parse_nodes_section(&mut lines)?;
    let points = nodes.points.len();
    lines.expect_end(&format!("the {points} points the header declares"))?;
    // The directive may sit anywhere, so it is read once the whole file has been seen.
    let hexagon = hexagon_directive(&lines)?;
    Ok(NodeFile { hexagon, ..nodes })
}

/// Parses the text of a `.poly` file; `path` is only used to name errors.
pub fn parse_poly(path: &Path, text: &str) -> Result<PolyFile> {
    let mut lines = Lines::new(path, text);
    // Every section parser reads to the end of the file, so all directives have been seen.
    let mut poly = parse_poly_sections(&mut lines)?;
    poly.nodes.hexagon = hexagon_directive(&lines)?;
    Ok(poly)
}

fn parse_poly_sections(lines: &mut Lines) -> Result<PolyFile> {
    let nodes = parse_nodes_section(lines)?;
    let mut poly = PolyFile {
        nodes,
        ..PolyFile::default()
    };

    let header = lines.expect_row("the segment header '<#segments> <#markers>'")?;
    lines.fields(&header, 1, 2, "<#segments> [<#markers>]")?;
    let count = lines.count(&header, 0, "the number of segments")?;
    let has_markers = header.tokens.len() > 1 && lines.flag(&header, 1, "the marker flag")?;
    let mut markers = Vec::new();
    let width = 3 + usize::from(has_markers);
    let layout = if has_markers {
        "<segment #> <endpoint> <endpoint> <marker>"
    } else {
        "<segment #> <endpoint> <endpoint>"
    };
    poly.segments.reserve(count.min(MAX_PREALLOCATION));
    for k in 0..count {
        let row = expect_item(lines, "segment", k, count, header.line)?;
        lines.fields(&row, width, width, layout)?;
        lines.int(&row, 0, "the segment number")?;
        let a = lines.vertex(&row, 1, "the first endpoint")?;
        let b = lines.vertex(&row, 2, "the second endpoint")?;
        poly.segments.push([a, b]);
        if has_markers {
            markers.push(lines.int(&row, 3, "the segment marker")?);
        }
        poly.segment_lines.push(row.line);
    }
    poly.segment_markers = has_markers.then_some(markers);

    // Triangle requires the hole count; a file that ends after the segments has no holes.
    let Some(header) = lines.next_row() else {
        return Ok(poly);
    };
    lines.fields(&header, 1, 1, "<#holes>")?;
    let count = lines.count(&header, 0, "the number of holes")?;
    for k in 0..count {
        let row = expect_item(lines, "hole", k, count, header.line)?;
        lines.fields(&row, 3, 3, "<hole #> <x> <y>")?;
        lines.int(&row, 0, "the hole number")?;
        let x = lines.float(&row, 1, "the hole's x coordinate")?;
        let y = lines.float(&row, 2, "the hole's y coordinate")?;
        poly.holes.push([x, y]);
        poly.hole_lines.push(row.line);
    }

    if let Some(header) = lines.next_row() {
        lines.fields(
            &header,
            1,
            1,
            "<#regional attributes and/or area constraints>",
        )?;
        let count = lines.count(&header, 0, "the number of regions")?;
        let mut regions = Vec::new();
        for k in 0..count {
            let row = expect_item(lines, "region", k, count, header.line)?;
            lines.fields(
                &row,
                4,
                5,
                "<region #> <x> <y> <attribute> [<maximum area>]",
            )?;
            lines.int(&row, 0, "the region number")?;
            let x = lines.float(&row, 1, "the region's x coordinate")?;
            let y = lines.float(&row, 2, "the region's y coordinate")?;
            let attribute = lines.float(&row, 3, "the regional attribute")?;
            let max_area = match row.tokens.len() {
                5 => Some(lines.float(&row, 4, "the area constraint")?),
                _ => None,
            };
            regions.push(Region {
                point: [x, y],
                attribute,
                max_area,
            });
        }
        poly.regions = Some(regions);
        lines.expect_end("the regions section")?;
    }
    Ok(poly)
}

/// Parses the text of an `.ele` file; `path` is only used to name errors.
pub fn parse_ele(path: &Path, text: &str) -> Result<EleFile> {
    let mut lines = Lines::new(path, text);
    let Some(header) = lines.next_row() else {
        return Err(lines.error(
            lines.end_line(),
            "the file is empty: expected the header '<#triangles> <nodes per triangle> <#attributes>'",
        ));
    };
    lines.fields(
        &header,
        1,
        3,
        "<#triangles> [<nodes per triangle>] [<#attributes>]",
    )?;
    let count = lines.count(&header, 0, "the number of triangles")?;
    if header.tokens.len() > 1 {
        match lines.int(&header, 1, "the number of nodes per triangle")? {
            3 => {}
            6 => {
                return Err(lines.error(
                    header.line,
                    "6-node (quadratic) triangles are not supported: hexmesh reads 3-node \
                     triangles only (mesh without Triangle's -o2)",
                ))
            }
            n => {
                return Err(lines.error(
                    header.line,
                    format!("a triangle has 3 nodes, but the header says {n}"),
                ))
            }
        }
    }
    let attribute_count = match header.tokens.len() {
        3 => lines.count(&header, 2, "the number of attributes")?,
        _ => 0,
    };
    let width = 4 + attribute_count;
    let layout =
        format!("<triangle #> <corner> <corner> <corner> and {attribute_count} attributes");
    let mut ele = EleFile {
        attribute_count,
        ..EleFile::default()
    };
    ele.triangles.reserve(count.min(MAX_PREALLOCATION));
    for k in 0..count {
        let row = expect_item(&mut lines, "triangle", k, count, header.line)?;
        lines.fields(&row, width, width, &layout)?;
        let number = lines.int(&row, 0, "the triangle number")?;
        if k == 0 {
            ele.first_index = first_index(&lines, &row, number, "triangle")?;
        }
        let mut corners = [0u32; 3];
        for (c, corner) in corners.iter_mut().enumerate() {
            *corner = lines.vertex(&row, 1 + c, "a corner")?;
        }
        ele.triangles.push(corners);
        if attribute_count > 0 {
            let attributes = (0..attribute_count)
                .map(|a| lines.float(&row, 4 + a, "an attribute"))
                .collect::<Result<Vec<f64>>>()?;
            ele.attributes.push(attributes);
        }
        ele.lines.push(row.line);
    }
    lines.expect_end(&format!("the {count} triangles the header declares"))?;
    Ok(ele)
}

/// The row of item `k` of `count`; a missing row is reported with the header's promise.
fn expect_item<'a>(
    lines: &mut Lines<'a>,
    what: &str,
    k: usize,
    count: usize,
    header_line: usize,
) -> Result<Row<'a>> {
    lines.expect_row(&format!(
        "{what} {} of the {count} that the header on line {header_line} declares",
        k + 1
    ))
}

/// Triangle detects 0- or 1-based numbering from the first row's number.
fn first_index(lines: &Lines, row: &Row, number: i64, what: &str) -> Result<u32> {
    match number {
        0 => Ok(0),
        1 => Ok(1),
        n => Err(lines.error(
            row.line,
            format!("the first {what} is numbered {n}; numbering must start at 0 or 1"),
        )),
    }
}

/// The nodes section shared by `.node` and `.poly` files.
fn parse_nodes_section(lines: &mut Lines) -> Result<NodeFile> {
    let Some(header) = lines.next_row() else {
        return Err(lines.error(
            lines.end_line(),
            "the file is empty: expected the header '<#points> 2 <#attributes> <#markers>'",
        ));
    };
    lines.fields(
        &header,
        1,
        4,
        "<#points> [<dimension>] [<#attributes>] [<#markers>]",
    )?;
    let count = lines.count(&header, 0, "the number of points")?;
    if header.tokens.len() > 1 {
        let dimension = lines.int(&header, 1, "the dimension")?;
        if dimension != 2 {
            return Err(lines.error(
                header.line,
                format!("the dimension must be 2, found {dimension}"),
            ));
        }
    }
    let attribute_count = match header.tokens.len() {
        3.. => lines.count(&header, 2, "the number of attributes")?,
        _ => 0,
    };
    let has_markers = header.tokens.len() > 3 && lines.flag(&header, 3, "the marker flag")?;
    let width = 3 + attribute_count + usize::from(has_markers);
    let layout = format!(
        "<point #> <x> <y>, {attribute_count} attributes{}",
        if has_markers { ", <marker>" } else { "" }
    );
    let mut nodes = NodeFile {
        attribute_count,
        markers: has_markers.then(Vec::new),
        ..NodeFile::default()
    };
    nodes.points.reserve(count.min(MAX_PREALLOCATION));
    for k in 0..count {
        let row = expect_item(lines, "point", k, count, header.line)?;
        lines.fields(&row, width, width, &layout)?;
        let number = lines.int(&row, 0, "the point number")?;
        if k == 0 {
            nodes.first_index = first_index(lines, &row, number, "point")?;
        } else if number != i64::from(nodes.first_index) + k as i64 {
            // Segments and triangles refer to points by number: a gap would shift them all.
            return Err(lines.error(
                row.line,
                format!(
                    "point numbered {number}, expected {}: points must be numbered consecutively",
                    i64::from(nodes.first_index) + k as i64
                ),
            ));
        }
        let x = lines.float(&row, 1, "the x coordinate")?;
        let y = lines.float(&row, 2, "the y coordinate")?;
        nodes.points.push([x, y]);
        if attribute_count > 0 {
            let attributes = (0..attribute_count)
                .map(|a| lines.float(&row, 3 + a, "an attribute"))
                .collect::<Result<Vec<f64>>>()?;
            nodes.attributes.push(attributes);
        }
        if let Some(markers) = nodes.markers.as_mut() {
            markers.push(lines.int(&row, 3 + attribute_count, "the boundary marker")?);
        }
        nodes.lines.push(row.line);
    }
    Ok(nodes)
}

/// The `# hexmesh: hexagon CX CY R [COS SIN]` comment seen so far, if any (COS SIN: the
/// hexagon's `Turn`, absent for the flat-topped hexagon).
fn hexagon_directive(lines: &Lines) -> Result<Option<Hexagon>> {
    let mut found = None;
    for d in &lines.directives {
        let bad = |message: &str| Error::parse(lines.path(), d.line, message.to_string());
        if d.tokens.first() != Some(&"hexagon") {
            return Err(bad(
                "unknown hexmesh directive; expected '# hexmesh: hexagon CX CY R [COS SIN]'",
            ));
        }
        if d.tokens.len() != 4 && d.tokens.len() != 6 {
            return Err(bad(
                "expected '# hexmesh: hexagon CX CY R [COS SIN]' with three or five numbers",
            ));
        }
        let mut v = [1.0, 0.0, 0.0, 1.0, 0.0];
        for (slot, token) in v.iter_mut().zip(&d.tokens[1..]) {
            *slot = token
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad("the hexagon's numbers must be finite"))?;
        }
        if v[2] <= 0.0 {
            return Err(bad("the hexagon's circumradius must be positive"));
        }
        let turn = Turn {
            cos: v[3],
            sin: v[4],
        };
        if ((turn.cos * turn.cos + turn.sin * turn.sin) - 1.0).abs() > 1e-12 {
            return Err(bad(
                "the hexagon's turn (COS SIN) must be a unit vector: cos² + sin² = 1",
            ));
        }
        if found.is_some() {
            return Err(bad("a second hexagon directive"));
        }
        found = Some(Hexagon {
            turn,
            ..Hexagon::new([v[0], v[1]], v[2])
        });
    }
    Ok(found)
}

/// The `# hexmesh: hexagon` comment that `read_input` reads back as `h`, bit for bit (the
/// turn only when there is one), without the line break.
pub fn hexagon_directive_text(h: &Hexagon) -> String {
    let mut s = format!(
        "# hexmesh: hexagon {:?} {:?} {:?}",
        h.center[0], h.center[1], h.circumradius
    );
    if !h.turn.is_none() {
        s.push_str(&format!(" {:?} {:?}", h.turn.cos, h.turn.sin));
    }
    s
}

/// Writes a `.node` file.
pub fn write_node(path: &Path, nodes: &NodeFile) -> Result<()> {
    let head = node_header(path, nodes)?;
    write_lines(path, &head, nodes.points.len(), |k, text| {
        node_line(nodes, k, text)
    })
}

/// Writes a `.poly` file; a `PolyFile` whose nodes are empty writes the "0 2 0 0" header.
pub fn write_poly(path: &Path, poly: &PolyFile) -> Result<()> {
    let mut text = node_header(path, &poly.nodes)?;
    for k in 0..poly.nodes.points.len() {
        node_line(&poly.nodes, k, &mut text);
    }
    let base = poly.nodes.first_index as usize;
    if let Some(markers) = &poly.segment_markers {
        if markers.len() != poly.segments.len() {
            return Err(invalid(
                path,
                format!(
                    "{} segment markers for {} segments",
                    markers.len(),
                    poly.segments.len()
                ),
            ));
        }
    }
    let flag = usize::from(poly.segment_markers.is_some());
    let _ = writeln!(text, "{} {flag}", poly.segments.len());
    for (k, s) in poly.segments.iter().enumerate() {
        let _ = write!(text, "{} {} {}", base + k, s[0], s[1]);
        if let Some(markers) = &poly.segment_markers {
            let _ = write!(text, " {}", markers[k]);
        }
        text.push('\n');
    }
    let _ = writeln!(text, "{}", poly.holes.len());
    for (k, h) in poly.holes.iter().enumerate() {
        finite(path, h, "a hole")?;
        let _ = writeln!(text, "{} {:?} {:?}", base + k, h[0], h[1]);
    }
    if let Some(regions) = &poly.regions {
        let _ = writeln!(text, "{}", regions.len());
        for (k, r) in regions.iter().enumerate() {
            finite(path, &[r.point[0], r.point[1], r.attribute], "a region")?;
            let _ = write!(
                text,
                "{} {:?} {:?} {:?}",
                base + k,
                r.point[0],
                r.point[1],
                r.attribute
            );
            if let Some(area) = r.max_area {
                finite(path, &[area], "a region's area constraint")?;
                let _ = write!(text, " {area:?}");
            }
            text.push('\n');
        }
    }
    write_file(path, &text)
}

/// Writes an `.ele` file of 3-node triangles.
pub fn write_ele(path: &Path, ele: &EleFile) -> Result<()> {
    let n = ele.triangles.len();
    check_attributes(path, &ele.attributes, ele.attribute_count, n, "triangles")?;
    for attributes in &ele.attributes {
        finite(path, attributes, "a triangle attribute")?;
    }
    let head = format!("{n} 3 {}\n", ele.attribute_count);
    let base = ele.first_index as usize;
    write_lines(path, &head, n, |k, text| {
        let t = ele.triangles[k];
        let _ = write!(text, "{} {} {} {}", base + k, t[0], t[1], t[2]);
        if let Some(attributes) = ele.attributes.get(k) {
            for a in attributes {
                let _ = write!(text, " {a:?}");
            }
        }
        text.push('\n');
    })
}

/// The header of a `.node` file (with the hexagon's line, if any), after checking every
/// point, attribute and marker, so that `node_line` cannot meet a value it refuses.
fn node_header(path: &Path, nodes: &NodeFile) -> Result<String> {
    let n = nodes.points.len();
    check_attributes(path, &nodes.attributes, nodes.attribute_count, n, "points")?;
    if let Some(markers) = &nodes.markers {
        if markers.len() != n {
            return Err(invalid(
                path,
                format!("{} boundary markers for {n} points", markers.len()),
            ));
        }
    }
    if nodes.first_index > 1 {
        return Err(invalid(path, "numbering must start at 0 or 1"));
    }
    let mut text = String::new();
    let flag = usize::from(nodes.markers.is_some());
    let _ = writeln!(text, "{n} 2 {} {flag}", nodes.attribute_count);
    if let Some(h) = nodes.hexagon {
        finite(
            path,
            &[
                h.center[0],
                h.center[1],
                h.circumradius,
                h.turn.cos,
                h.turn.sin,
            ],
            "the hexagon",
        )?;
        let _ = writeln!(text, "{}", hexagon_directive_text(&h));
    }
    for (k, p) in nodes.points.iter().enumerate() {
        finite(path, p, "a point")?;
        if let Some(attributes) = nodes.attributes.get(k) {
            finite(path, attributes, "a point attribute")?;
        }
    }
    Ok(text)
}

/// The line of point `k` of a `.node` file that `node_header` has checked.
fn node_line(nodes: &NodeFile, k: usize, text: &mut String) {
    let p = nodes.points[k];
    let _ = write!(
        text,
        "{} {:?} {:?}",
        nodes.first_index as usize + k,
        p[0],
        p[1]
    );
    if let Some(attributes) = nodes.attributes.get(k) {
        for a in attributes {
            let _ = write!(text, " {a:?}");
        }
    }
    if let Some(markers) = &nodes.markers {
        let _ = write!(text, " {}", markers[k]);
    }
    text.push('\n');
}

/// Writes `head`, then the lines of items `0..count` (`line` appends item k's line), formatted
/// a chunk at a time over the machine's threads and written in order: the same bytes as one
/// thread formatting them all, without the whole text in memory (at plane-100k, hex's
/// `.node` and `.ele` texts are 280 and 370 MB).
fn write_lines(
    path: &Path,
    head: &str,
    count: usize,
    line: impl Fn(usize, &mut String) + Sync,
) -> Result<()> {
    const CHUNK: usize = 1 << 15;
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(io)?);
    file.write_all(head.as_bytes()).map_err(io)?;
    let chunks: Vec<std::ops::Range<usize>> = (0..count)
        .step_by(CHUNK)
        .map(|from| from..(from + CHUNK).min(count))
        .collect();
    for batch in chunks.chunks(4 * threads) {
        let texts = crate::hex::parallel::each_in_parallel(threads, batch, |range| {
            let mut text = String::with_capacity(48 * range.len());
            for k in range.clone() {
                line(k, &mut text);
            }
            text
        });
        for text in texts {
            file.write_all(text.as_bytes()).map_err(io)?;
        }
    }
    file.flush().map_err(io)
}

/// Attribute rows must match the count: either one row per item, or none when the count is 0.
fn check_attributes(
    path: &Path,
    attributes: &[Vec<f64>],
    count: usize,
    items: usize,
    what: &str,
) -> Result<()> {
    let rows_ok = attributes.len() == items || (attributes.is_empty() && count == 0);
    if !rows_ok {
        return Err(invalid(
            path,
            format!("{} attribute rows for {items} {what}", attributes.len()),
        ));
    }
    if let Some((k, row)) = attributes
        .iter()
        .enumerate()
        .find(|(_, r)| r.len() != count)
    {
        return Err(invalid(
            path,
            format!(
                "item {k} has {} attributes, the header would say {count}",
                row.len()
            ),
        ));
    }
    Ok(())
}

/// Our readers refuse NaN and infinity, so the writers do too: a file hexmesh writes is a
/// file hexmesh reads.
fn finite(path: &Path, values: &[f64], what: &str) -> Result<()> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(invalid(
            path,
            format!("{what} has the non-finite value {v}; refusing to write it"),
        )),
        None => Ok(()),
    }
}

/// An error for data that cannot be written as asked (the file is not created).
pub(crate) fn invalid(path: &Path, message: impl Into<String>) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message.into()),
    }
}

pub(crate) fn write_file(path: &Path, text: &str) -> Result<()> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(io)?);
    file.write_all(text.as_bytes()).map_err(io)?;
    file.flush().map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(text: &str) -> Result<NodeFile> {
        parse_node(Path::new("t.node"), text)
    }

    fn line_of(e: Error) -> usize {
        match e {
            Error::Parse { line, .. } => line,
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn files_formatted_in_chunks_over_threads_are_the_lines_in_order() {
        // More than three chunks of points and triangles, with lines of differing lengths.
        let n = 3 * (1 << 15) + 123;
        let nodes = NodeFile {
            points: (0..n)
                .map(|k| [k as f64 / 7.0, -(k as f64) * 1e-3])
                .collect(),
            attribute_count: 1,
            attributes: (0..n).map(|k| vec![(k % 10) as f64]).collect(),
            markers: Some((0..n).map(|k| (k % 3) as i64).collect()),
            first_index: 1,
            ..NodeFile::default()
        };
        let dir = std::env::temp_dir().join(format!("hexmesh-chunks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        let path = dir.join("m.node");
        write_node(&path, &nodes).expect("written");
        let mut expected = node_header(&path, &nodes).expect("a header");
        for k in 0..n {
            node_line(&nodes, k, &mut expected);
        }
        let written = std::fs::read_to_string(&path).expect("read back");
        assert!(
            written == expected,
            "the .node text differs from the lines in order"
        );
        assert_eq!(node(&written).expect("parsed").points, nodes.points);
        let ele = EleFile {
            triangles: (0..n as u32).map(|k| [k, k + 1, k + 2]).collect(),
            attribute_count: 0,
            attributes: Vec::new(),
            first_index: 0,
            lines: Vec::new(),
        };
        let path = dir.join("m.ele");
        write_ele(&path, &ele).expect("written");
        let written = std::fs::read_to_string(&path).expect("read back");
        let mut lines = written.lines();
        assert_eq!(lines.next(), Some(format!("{n} 3 0").as_str()));
        for (k, line) in lines.enumerate() {
            assert_eq!(line, format!("{k} {k} {} {}", k + 1, k + 2));
        }
        assert_eq!(written.lines().count(), n + 1);
        std::fs::remove_dir_all(&dir).expect("removed");
    }

    #[test]
    fn header_fields_after_the_count_default_as_in_triangle() {
        let n = node("2\n1 0 0\n2 1 0\n").expect("short header");
        assert_eq!((n.attribute_count, n.markers.is_none()), (0, true));
        assert_eq!(n.first_index, 1);
    }

    #[test]
    fn numbering_is_detected_from_the_first_point() {
        assert_eq!(node("1 2 0 0\n0 5 5\n").expect("0-based").first_index, 0);
        assert_eq!(node("1 2 0 0\n1 5 5\n").expect("1-based").first_index, 1);
        assert_eq!(line_of(node("1 2 0 0\n\n7 5 5\n").expect_err("7-based")), 3);
    }

    #[test]
    fn a_gap_in_point_numbers_is_refused_at_its_line() {
        assert_eq!(
            line_of(node("3 2 0 0\n1 0 0\n2 1 0\n4 1 1\n").expect_err("gap")),
            4
        );
    }

    #[test]
    fn more_rows_than_the_header_declares_are_refused() {
        assert_eq!(
            line_of(node("1 2 0 0\n1 0 0\n2 1 0\n").expect_err("extra row")),
            3
        );
    }

    #[test]
    fn a_huge_header_count_fails_at_the_end_without_allocating_it() {
        let e = node("999999999999 2 0 0\n1 0 0\n").expect_err("huge count");
        assert_eq!(line_of(e), 2);
    }

    #[test]
    fn six_node_triangles_are_refused_with_a_clear_message() {
        let e = parse_ele(Path::new("t.ele"), "1 6 0\n1 1 2 3 4 5 6\n").expect_err("6 nodes");
        assert!(e.to_string().contains("6-node"), "{e}");
        assert_eq!(line_of(e), 1);
    }

    #[test]
    fn regions_are_parsed_with_or_without_an_area() {
        let text = "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n2\n\
                    1 0.2 0.2 7\n2 0.1 0.1 7 0.5\n";
        let p = parse_poly(Path::new("t.poly"), text).expect("regions");
        let r = p.regions.expect("regions section");
        assert_eq!(r[0].max_area, None);
        assert_eq!(r[1].max_area, Some(0.5));
    }

    #[test]
    fn the_hexagon_directive_is_read_back() {
        let n = node("# hexmesh: hexagon 0.5 -1 2\n1 2 0 0\n1 0 0\n").expect("directive");
        assert_eq!(n.hexagon, Some(Hexagon::new([0.5, -1.0], 2.0)));
        assert!(node("1 2 0 0\n1 0 0\n# hexmesh: square 1\n").is_err());
    }

    #[test]
    fn a_turned_hexagon_is_written_and_read_back_bit_for_bit() {
        let turn = crate::geom::principal_turn(&[[0.0, 0.0], [1.0, 0.37], [0.4, 0.148]]);
        for hex in [
            Hexagon::new([0.5, -1.0], 2.0),
            Hexagon {
                turn,
                ..Hexagon::new([0.1, 1.0 / 3.0], 0.7)
            },
        ] {
            let text = format!("{}\n1 2 0 0\n1 0 0\n", hexagon_directive_text(&hex));
            assert_eq!(node(&text).expect("directive").hexagon, Some(hex));
        }
        assert_eq!(
            hexagon_directive_text(&Hexagon::new([0.5, -1.0], 2.0)),
            "# hexmesh: hexagon 0.5 -1.0 2.0"
        );
    }

    #[test]
    fn a_hexagon_turn_that_is_not_a_unit_vector_or_half_given_is_refused() {
        let e = node("# hexmesh: hexagon 0 0 1 0.6 0.7\n1 2 0 0\n1 0 0\n").expect_err("0.6 0.7");
        assert!(e.to_string().contains("unit vector"), "{e}");
        assert_eq!(line_of(e), 1);
        let e = node("# hexmesh: hexagon 0 0 1 0.6\n1 2 0 0\n1 0 0\n").expect_err("one number");
        assert!(e.to_string().contains("three or five numbers"), "{e}");
        assert!(node("# hexmesh: hexagon 0 0 1 0.6 -0.8\n1 2 0 0\n1 0 0\n").is_ok());
    }
}
