//! File formats: Triangle's `.node`/`.poly` in
//! ([`read_input`], with the input's markers, attributes and regions in `Pslg::labels`),
//! Triangle's `.node`/`.ele` in and out ([`read_mesh`], [`write_mesh`]), and out with the
//! input's labels carried to the mesh ([`write_mesh_with`], [`derive_boundary`]):
//! Triangle's `.node`/`.ele`/`.poly`/`.edge` with boundary markers, VTK legacy and binary
//! VTK XML (`.vtu`) with quality and label arrays for ParaView, Gmsh 4.1 with physical groups
//! for Gmsh and meshio, and SVG pictures. The CLI and the harness use only the functions of
//! this module; `triangle` keeps the file-level structs for bit-exact round trips.
//!
//! Meshes made elsewhere are read by [`read_any_mesh`]: Gmsh `.msh` 4.1 and 2.2
//! ([`read_msh`]), VTK legacy `.vtk` ([`read_vtk`]) and VTK XML `.vtu` ([`read_vtu`]).

pub mod boundary;
mod fields;
mod lines;
pub mod msh;
mod msh_read;
mod read_any;
mod scan;
pub mod svg;
pub mod triangle;
mod triangle_out;
pub mod vtk;
mod vtk_read;
pub mod vtu;
mod vtu_data;
mod vtu_read;
mod write;

use std::ffi::OsString;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use crate::error::{Error, InputError, Result};
use crate::mesh::{Labels, Pslg, TriMesh};

pub use msh_read::{parse_msh, read_msh};
pub use read_any::{read_any_mesh, LoadedMesh, MeshFormat};
pub use vtk_read::{parse_vtk, read_vtk};
pub use vtu_read::{parse_vtu, read_vtu};

pub use boundary::{derive_boundary, Boundary, BoundaryLoop, Edge, LoopKind};
pub use msh::{write_msh, write_msh_with};
pub use svg::{write_svg, SvgOptions};
pub use triangle::{
    parse_ele, parse_node, parse_poly, read_ele, read_node, read_poly, write_ele, write_node,
    write_poly, EleFile, NodeFile, PolyFile, Region,
};
pub use vtk::{write_vtk, write_vtk_with};
pub use vtu::{write_vtu, write_vtu_with};
pub use write::{mesh_files, write_mesh, write_mesh_with};

/// An output format of [`write_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// Triangle's PREFIX.node + PREFIX.ele, 1-based, with boundary markers.
    Triangle,
    /// Triangle's PREFIX.poly (boundary and segment edges with markers, holes, regions; its
    /// points are PREFIX.node's, so this format also writes [`Format::Triangle`]) +
    /// PREFIX.edge (every edge with its marker).
    Poly,
    /// VTK legacy ASCII, PREFIX.vtk.
    Vtk,
    /// VTK XML UnstructuredGrid with raw appended binary data, PREFIX.vtu.
    Vtu,
    /// Gmsh 4.1 ASCII, PREFIX.msh.
    Msh,
    /// A picture coloured by smallest angle, PREFIX.svg.
    Svg,
}

impl Format {
    /// Every format, in the order of the enum.
    pub const ALL: [Format; 6] = [
        Format::Triangle,
        Format::Poly,
        Format::Vtk,
        Format::Vtu,
        Format::Msh,
        Format::Svg,
    ];

    /// Parses a command-line format name: "node" (or "triangle", "ele"), "poly" (or "edge"),
    /// "vtk", "vtu", "msh" (or "gmsh"), "svg" (case-insensitive).
    pub fn parse(name: &str) -> Result<Format> {
        match name.trim().to_ascii_lowercase().as_str() {
            "node" | "triangle" | "ele" => Ok(Format::Triangle),
            "poly" | "edge" => Ok(Format::Poly),
            "vtk" => Ok(Format::Vtk),
            "vtu" => Ok(Format::Vtu),
            "msh" | "gmsh" => Ok(Format::Msh),
            "svg" => Ok(Format::Svg),
            _ => Err(Error::Usage(format!(
                "unknown output format '{name}'; known formats: node (or triangle), poly, vtk, \
                 vtu, msh, svg"
            ))),
        }
    }

    /// The name [`Format::parse`] reads back.
    pub fn name(self) -> &'static str {
        match self {
            Format::Triangle => "node",
            Format::Poly => "poly",
            Format::Vtk => "vtk",
            Format::Vtu => "vtu",
            Format::Msh => "msh",
            Format::Svg => "svg",
        }
    }

    /// The extensions of the files written for this format.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            Format::Triangle => &["node", "ele"],
            Format::Poly => &["poly", "edge"],
            Format::Vtk => &["vtk"],
            Format::Vtu => &["vtu"],
            Format::Msh => &["msh"],
            Format::Svg => &["svg"],
        }
    }
}

impl FromStr for Format {
    type Err = Error;
    fn from_str(s: &str) -> Result<Format> {
        Format::parse(s)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Reads an input file, `.node` (points) or `.poly` (points, segments, holes; points from the
/// sibling `.node` when its nodes section is empty), into a 0-based [`Pslg`] and checks it with
/// [`Pslg::check`]. Problems name the file and the line of the offending point, segment or
/// hole: malformed text is [`Error::Parse`], a well-formed but unusable input
/// [`Error::Input`], except duplicate points, which are an [`Error::Parse`] naming both lines.
/// A `# hexmesh: hexagon CX CY R [COS SIN]` comment sets [`Pslg::hexagon`].
pub fn read_input(path: &Path) -> Result<Pslg> {
    read_input_numbered(path).map(|(pslg, _)| pslg)
}

/// [`read_input`], and the number of the file's first point (0 or 1), by which messages name
/// its points, segments and holes (`quality::Numbering::input`).
pub fn read_input_numbered(path: &Path) -> Result<(Pslg, u32)> {
    read_input_enclosed(path, false)
}

/// [`read_input_numbered`], with the convex hull's edges added as segments before the check
/// when `convex_hull` is set ([`Pslg::with_convex_hull`], Triangle's `-c`): the input is then
/// the segments, holes and points of the file in its convex hull. The file's segments keep
/// their numbers; the hull's come after them.
pub fn read_input_enclosed(path: &Path, convex_hull: bool) -> Result<(Pslg, u32)> {
    let (pslg, source, base) = read_sourced(path)?;
    let pslg = if convex_hull {
        pslg.with_convex_hull()
    } else {
        pslg
    };
    match pslg.check() {
        Ok(()) => Ok((pslg, base)),
        Err(problem) => Err(source.locate(&pslg, base, problem)),
    }
}

/// A problem with the input read from `path` found later (a mesher's refusal naming input
/// points), with the file and lines of what it names, as `read_input` gives its own.
pub fn locate_input_error(path: &Path, problem: InputError) -> Error {
    match read_sourced(path) {
        Ok((pslg, source, base)) => source.locate(&pslg, base, problem),
        Err(_) => Error::input(problem),
    }
}

/// The input of `path` unchecked, with where each item came from and the file's first index.
fn read_sourced(path: &Path) -> Result<(Pslg, Source, u32)> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let (nodes, node_path, poly) = match extension.as_deref() {
        Some("node") => (read_node(path)?, path.to_path_buf(), None),
        Some("poly") => {
            let mut poly = read_poly(path)?;
            if poly.nodes.points.is_empty() {
                let node_path = path.with_extension("node");
                let nodes = read_node(&node_path).map_err(|e| match e {
                    Error::Io { source, .. } => Error::parse(
                        path,
                        0,
                        format!(
                            "the file lists no points, so they are read from {}, which failed: {source}",
                            node_path.display()
                        ),
                    ),
                    other => other,
                })?;
                let mut nodes = nodes;
                // A hexagon directive may sit in either file.
                nodes.hexagon = nodes.hexagon.or(poly.nodes.hexagon);
                poly.nodes = NodeFile::default();
                (nodes, node_path, Some(poly))
            } else {
                let nodes = std::mem::take(&mut poly.nodes);
                (nodes, path.to_path_buf(), Some(poly))
            }
        }
        _ => {
            return Err(Error::parse(
                path,
                0,
                "unknown input format: expected a Triangle .node (points) or .poly (PSLG) file",
            ))
        }
    };
    let source = Source {
        node_path,
        poly_path: path.to_path_buf(),
        point_lines: nodes.lines,
        segment_lines: poly
            .as_ref()
            .map(|p| p.segment_lines.clone())
            .unwrap_or_default(),
        hole_lines: poly
            .as_ref()
            .map(|p| p.hole_lines.clone())
            .unwrap_or_default(),
    };
    let base = nodes.first_index;
    let n = nodes.points.len();
    let mut pslg = Pslg {
        points: nodes.points,
        hexagon: nodes.hexagon,
        labels: Labels {
            point_markers: nodes.markers,
            point_attributes: match nodes.attribute_count {
                0 => Vec::new(),
                _ => nodes.attributes,
            },
            ..Labels::default()
        },
        ..Pslg::default()
    };
    if let Some(poly) = poly {
        pslg.segments.reserve(poly.segments.len());
        for (k, s) in poly.segments.iter().enumerate() {
            let mut zero_based = [0u32; 2];
            for (slot, &v) in zero_based.iter_mut().zip(s) {
                *slot = v
                    .checked_sub(base)
                    .filter(|&i| (i as usize) < n)
                    .ok_or_else(|| {
                        let range = match n {
                            0 => "there are no points".to_string(),
                            _ => format!(
                                "the points are numbered {base} to {}",
                                base as usize + n - 1
                            ),
                        };
                        Error::parse(
                            path,
                            source.segment_line(k),
                            format!(
                                "segment {} names vertex {v}, but {range}",
                                base as usize + k
                            ),
                        )
                    })?;
            }
            pslg.segments.push(zero_based);
        }
        pslg.holes = poly.holes;
        pslg.labels.segment_markers = poly.segment_markers;
        pslg.labels.regions = poly.regions.unwrap_or_default();
    }
    Ok((pslg, source, base))
}

/// Where each item of an input came from, to put file and line on [`InputError`]s.
struct Source {
    node_path: PathBuf,
    poly_path: PathBuf,
    point_lines: Vec<usize>,
    segment_lines: Vec<usize>,
    hole_lines: Vec<usize>,
}

impl Source {
    fn segment_line(&self, k: usize) -> usize {
        self.segment_lines.get(k).copied().unwrap_or(0)
    }

    fn point_line(&self, k: usize) -> usize {
        self.point_lines.get(k).copied().unwrap_or(0)
    }

    fn locate(&self, pslg: &Pslg, base: u32, problem: InputError) -> Error {
        let at = |path: &Path, line: usize| Error::Input {
            path: Some(path.to_path_buf()),
            line: (line > 0).then_some(line),
            problem: problem.clone(),
            first_index: base,
        };
        match problem {
            InputError::Empty => Error::Input {
                path: Some(self.node_path.clone()),
                line: None,
                problem,
                first_index: base,
            },
            InputError::NonFinite { index, .. }
            | InputError::OutsideHexagon { index, .. }
            | InputError::NearBoundary { index, .. }
            | InputError::PointOutsideDomain { point: index } => {
                at(&self.node_path, self.point_line(index))
            }
            InputError::Duplicate {
                first,
                second,
                point,
            } => {
                let base = base as usize;
                Error::parse(
                    &self.node_path,
                    self.point_line(second),
                    format!(
                        "point {} duplicates point {} on line {}: both are at ({:?}, {:?})",
                        second + base,
                        first + base,
                        self.point_line(first),
                        point[0],
                        point[1]
                    ),
                )
            }
            InputError::MissingVertex { segment, .. }
            | InputError::DegenerateSegment { segment }
            | InputError::PointOnSegment { segment, .. }
            | InputError::DanglingSegment { segment, .. }
            | InputError::BranchingSegment { segment, .. }
            | InputError::SegmentInsideDomain { segment }
            | InputError::SegmentOutsideDomain { segment } => {
                at(&self.poly_path, self.segment_line(segment))
            }
            // The segments as a whole: the line of the first.
            InputError::NoEnclosedRegion { .. } => at(&self.poly_path, self.segment_line(0)),
            // The later segment is where the conflict shows.
            InputError::CrossingSegments { second, .. } => {
                at(&self.poly_path, self.segment_line(second))
            }
            InputError::NonFiniteHole { index } => at(
                &self.poly_path,
                self.hole_lines.get(index).copied().unwrap_or(0),
            ),
            InputError::Rounding { first, second, .. } => Error::Input {
                path: Some(self.node_path.clone()),
                line: Some(self.point_line(second)).filter(|&l| l > 0),
                problem: InputError::Range {
                    detail: format!(
                        "{} (point {} is on line {})",
                        problem.describe(base),
                        first + base as usize,
                        self.point_line(first)
                    ),
                },
                first_index: base,
            },
            InputError::Range { .. } => {
                let largest = (0..pslg.points.len()).max_by(|&a, &b| {
                    let m = |i: usize| pslg.points[i][0].abs().max(pslg.points[i][1].abs());
                    m(a).total_cmp(&m(b))
                });
                at(&self.node_path, largest.map_or(0, |k| self.point_line(k)))
            }
        }
    }
}

/// `prefix` + "." + `extension`, keeping every dot already in the prefix ("box.1" → "box.1.node").
fn with_suffix(prefix: &Path, extension: &str) -> PathBuf {
    let mut name = OsString::from(prefix.as_os_str());
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

/// The prefix of a mesh path given with or without its `.node`/`.ele` extension.
fn mesh_prefix(path: &Path) -> PathBuf {
    match path.extension().and_then(|e| e.to_str()) {
        Some("node" | "ele") => path.with_extension(""),
        _ => path.to_path_buf(),
    }
}

/// Reads PREFIX.node and PREFIX.ele (the prefix may carry either extension) into a 0-based
/// [`TriMesh`]. A corner naming a missing vertex is an [`Error::Parse`] at its `.ele` line;
/// geometric defects (clockwise or degenerate triangles, duplicate vertices) are kept, so that
/// `verify` can report them.
pub fn read_mesh(prefix: &Path) -> Result<TriMesh> {
    read_mesh_numbered(prefix).map(|(mesh, _)| mesh)
}

/// [`read_mesh`], and the number of the first vertex of the `.node` file (0 or 1), by which
/// messages name its vertices and triangles (`quality::Numbering::mesh`).
pub fn read_mesh_numbered(prefix: &Path) -> Result<(TriMesh, u32)> {
    let prefix = mesh_prefix(prefix);
    let node_path = with_suffix(&prefix, "node");
    let ele_path = with_suffix(&prefix, "ele");
    let nodes = read_node(&node_path)?;
    let ele = read_ele(&ele_path)?;
    let base = nodes.first_index;
    let n = nodes.points.len();
    let mut triangles = Vec::with_capacity(ele.triangles.len());
    for (k, t) in ele.triangles.iter().enumerate() {
        let mut zero_based = [0u32; 3];
        for (slot, &v) in zero_based.iter_mut().zip(t) {
            *slot = v
                .checked_sub(base)
                .filter(|&i| (i as usize) < n)
                .ok_or_else(|| {
                    Error::parse(
                        &ele_path,
                        ele.lines.get(k).copied().unwrap_or(0),
                        format!(
                            "triangle {} names vertex {v}, but {} has {n} points numbered from {base}",
                            ele.first_index as usize + k,
                            node_path.display()
                        ),
                    )
                })?;
        }
        triangles.push(zero_based);
    }
    let mesh = TriMesh {
        vertices: nodes.points,
        triangles,
    };
    Ok((mesh, base))
}

/// The files [`read_input`] reads for `path`: the file itself and, for a `.poly` file that
/// lists no points, the `.node` file beside it.
pub fn input_files(path: &Path) -> Vec<PathBuf> {
    let mut files = vec![path.to_path_buf()];
    let poly = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("poly"));
    // A .poly file that cannot be read here is counted as reading its .node: refusing too
    // much is safe, refusing too little loses data.
    if poly && read_poly(path).map_or(true, |p| p.nodes.points.is_empty()) {
        files.push(path.with_extension("node"));
    }
    files
}

/// Refuses (as [`Error::Usage`], naming both files) to write any of `outputs` over any of
/// `inputs`. Paths are compared as the files they name: `./a.node`, `d/../a.node`, a
/// symbolic link to the input and (on Unix) a hard link to it are all the input.
pub fn refuse_to_overwrite(outputs: &[PathBuf], inputs: &[PathBuf]) -> Result<()> {
    for output in outputs {
        if let Some(input) = inputs.iter().find(|input| same_file(output, input)) {
            return Err(Error::Usage(format!(
                "refusing to write {}: it would replace the input file {}; choose another \
                 output name (nothing was written)",
                output.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

/// Whether `a` and `b` name the same existing file (a path that does not exist is no file).
fn same_file(a: &Path, b: &Path) -> bool {
    if let (Ok(a), Ok(b)) = (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        if a == b {
            return true;
        }
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(a), Ok(b)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return a.dev() == b.dev() && a.ino() == b.ino();
        }
    }
    false
}

/// The extension [`write_pslg`] expects for `pslg`: "poly" when it has segments, holes or
/// regions, "node" for a point set (point markers and attributes fit a `.node` file).
pub fn pslg_extension(pslg: &Pslg) -> &'static str {
    if pslg.segments.is_empty() && pslg.holes.is_empty() && pslg.labels.regions.is_empty() {
        "node"
    } else {
        "poly"
    }
}

/// Writes an input: a `.node` file for a point set, or a `.poly` file with its nodes inline;
/// `path`'s extension must be the one [`pslg_extension`] gives (or `.poly` for a point set).
/// Numbering is 1-based; a given bounding hexagon is kept as a `# hexmesh: hexagon` comment.
pub fn write_pslg(path: &Path, pslg: &Pslg) -> Result<()> {
    let n = pslg.points.len();
    if let Some(s) = pslg
        .segments
        .iter()
        .find(|s| s.iter().any(|&v| v as usize >= n))
    {
        return Err(triangle::invalid(
            path,
            format!("segment {s:?} names a vertex beyond the {n} points"),
        ));
    }
    pslg.labels
        .check_fit(n, pslg.segments.len())
        .map_err(|e| triangle::invalid(path, format!("the input's labels do not fit: {e}")))?;
    let nodes = NodeFile {
        hexagon: pslg.hexagon,
        attribute_count: pslg.labels.attribute_count(),
        attributes: pslg.labels.point_attributes.clone(),
        markers: pslg.labels.point_markers.clone(),
        ..NodeFile::from_points(pslg.points.clone(), 1)
    };
    match path.extension().and_then(|e| e.to_str()) {
        Some("node") if pslg_extension(pslg) == "node" => write_node(path, &nodes),
        Some("node") => Err(triangle::invalid(
            path,
            "the input has segments, holes or regions, which a .node file cannot hold: write a \
             .poly file",
        )),
        Some("poly") => {
            let poly = PolyFile {
                nodes,
                segments: pslg.segments.iter().map(|s| [s[0] + 1, s[1] + 1]).collect(),
                segment_markers: pslg.labels.segment_markers.clone(),
                holes: pslg.holes.clone(),
                regions: (!pslg.labels.regions.is_empty()).then(|| pslg.labels.regions.clone()),
                ..PolyFile::default()
            };
            write_poly(path, &poly)
        }
        _ => Err(triangle::invalid(
            path,
            "an input is written as a .node or .poly file",
        )),
    }
}

/// Refuses a mesh that no format can represent: a corner naming a missing vertex, or a
/// non-finite coordinate (our readers would refuse the file).
pub(crate) fn check_mesh(path: &Path, mesh: &TriMesh) -> Result<()> {
    let n = mesh.vertices.len();
    if let Some((k, t)) = mesh
        .triangles
        .iter()
        .enumerate()
        .find(|(_, t)| t.iter().any(|&v| v as usize >= n))
    {
        return Err(triangle::invalid(
            path,
            format!("triangle {k} {t:?} names a vertex beyond the {n} vertices"),
        ));
    }
    if let Some(k) = mesh
        .vertices
        .iter()
        .position(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return Err(triangle::invalid(
            path,
            format!(
                "vertex {k} has a non-finite coordinate {:?}",
                mesh.vertices[k]
            ),
        ));
    }
    Ok(())
}
