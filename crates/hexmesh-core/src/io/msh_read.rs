//! Reads Gmsh `.msh` meshes (Gmsh reference manual, "MSH file format"): versions 4.1 and 2.2,
//! ASCII and binary, into a 0-based [`TriMesh`] of the file's 3-node triangles.
//!
//! - Nodes become vertices in the order the file lists them, whatever their tags (which may be
//!   sparse and unordered); [`LoadedMesh::vertex_tags`] keeps each vertex's tag, and
//!   [`LoadedMesh::triangle_tags`] each triangle's element tag, so that messages can use them.
//! - Elements of type 2 (3-node triangle) become triangles; points (15) and lines (1, and the
//!   higher-order lines 8, 26, 27, 28) are skipped; every other type (quadrangles,
//!   higher-order triangles, volumes) is refused, since `verify` checks 3-node triangles.
//! - Every node must have z = 0. Binary coordinates are taken bit for bit; ASCII ones with
//!   Rust's correctly rounded `f64` parse.
//! - Sections other than `$MeshFormat`, `$Nodes` and `$Elements` (`$Entities`,
//!   `$PhysicalNames`, data sections, ...) are skipped to their `$End` line.
//!
//! Errors name the file and, in text, the line; in binary data, the byte offset.

use std::collections::HashMap;
use std::path::Path;

use super::read_any::LoadedMesh;
use super::scan::{Endian, Scan};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::TriMesh;

/// No more than this many items are reserved ahead of reading them, whatever a header claims.
const MAX_PREALLOCATION: usize = 1 << 16;

/// Gmsh's 3-node triangle.
const TRIANGLE: i32 = 2;

/// Reads a Gmsh `.msh` file (4.1 or 2.2, ASCII or binary); see the module docs.
pub fn read_msh(path: &Path) -> Result<LoadedMesh> {
    parse_msh(path, &super::read_any::read_bytes(path)?)
}

/// Parses the bytes of a `.msh` file; `path` is only used in messages.
pub fn parse_msh(path: &Path, data: &[u8]) -> Result<LoadedMesh> {
    let mut msh = Msh::start(Scan::new(path, data))?;
    let mut nodes: Option<Nodes> = None;
    let mut elements: Option<Elements> = None;
    while let Some((at, line)) = msh.scan.next_nonblank_line()? {
        match line {
            "$Nodes" => {
                if nodes.is_some() {
                    return Err(msh.scan.error_at(at, "a second $Nodes section"));
                }
                nodes = Some(match msh.version {
                    Version::V2 => msh.nodes_v2()?,
                    Version::V41 => msh.nodes_v41()?,
                });
                msh.end_of_section("$EndNodes")?;
            }
            "$Elements" => {
                let Some(nodes) = nodes.as_ref() else {
                    return Err(msh
                        .scan
                        .error_at(at, "$Elements comes before any $Nodes section"));
                };
                if elements.is_some() {
                    return Err(msh.scan.error_at(at, "a second $Elements section"));
                }
                elements = Some(match msh.version {
                    Version::V2 => msh.elements_v2(nodes)?,
                    Version::V41 => msh.elements_v41(nodes)?,
                });
                msh.end_of_section("$EndElements")?;
            }
            _ if line.starts_with('$') && !line.starts_with("$End") && !line.contains(' ') => {
                let end = format!("$End{}", &line[1..]);
                msh.scan
                    .skip_past_line(&end, &format!("the section {line}"))?;
            }
            _ => {
                return Err(msh.scan.error_at(
                    at,
                    format!("expected a section such as $Nodes or $Elements, found '{line}'"),
                ))
            }
        }
    }
    let Some(nodes) = nodes else {
        return Err(Error::parse(path, 0, "the file has no $Nodes section"));
    };
    let Some(elements) = elements else {
        return Err(Error::parse(path, 0, "the file has no $Elements section"));
    };
    Ok(LoadedMesh {
        mesh: TriMesh {
            vertices: nodes.points,
            triangles: elements.triangles,
        },
        vertex_tags: Some(nodes.tags),
        triangle_tags: Some(elements.tags),
        first_index: 1,
    })
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Version {
    /// 2.2 (and the identical 2.0, 2.1).
    V2,
    /// 4.1.
    V41,
}

/// What to do with an element type.
enum Kind {
    Triangle,
    /// Skipped, with this many nodes.
    Skip(usize),
    /// Refused, with what it is.
    Refuse(&'static str),
}

fn kind(element_type: i32) -> Kind {
    match element_type {
        TRIANGLE => Kind::Triangle,
        15 => Kind::Skip(1),
        1 => Kind::Skip(2),
        8 => Kind::Skip(3),
        26 => Kind::Skip(4),
        27 => Kind::Skip(5),
        28 => Kind::Skip(6),
        3 => Kind::Refuse("a 4-node quadrangle"),
        10 => Kind::Refuse("a 9-node second-order quadrangle"),
        16 => Kind::Refuse("an 8-node second-order quadrangle"),
        9 => Kind::Refuse("a 6-node second-order triangle"),
        20..=25 => Kind::Refuse("a higher-order triangle"),
        4 | 5 | 6 | 7 | 11 | 12 | 13 | 14 | 17 | 18 | 19 | 29 | 30 | 31 => {
            Kind::Refuse("a volume element")
        }
        _ => Kind::Refuse("an element type verify does not read"),
    }
}

/// The nodes read so far: vertices in file order, their tags, and tag → vertex.
#[derive(Default)]
struct Nodes {
    points: Vec<Point>,
    tags: Vec<u64>,
    index: HashMap<u64, u32>,
}

struct Elements {
    triangles: Vec<[u32; 3]>,
    tags: Vec<u64>,
}

/// The scanner with the file's version and encoding.
struct Msh<'a> {
    scan: Scan<'a>,
    version: Version,
    binary: bool,
    endian: Endian,
}

impl<'a> Msh<'a> {
    /// Reads `$MeshFormat`.
    fn start(mut scan: Scan<'a>) -> Result<Msh<'a>> {
        let (at, first) = scan.expect_line("$MeshFormat")?;
        if first != "$MeshFormat" {
            return Err(scan.error_at(
                at,
                "not a Gmsh .msh file: it must start with a $MeshFormat line",
            ));
        }
        let (at, line) = scan.expect_line("the version line of $MeshFormat")?;
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 3 {
            return Err(scan.error_at(
                at,
                format!("expected 'version file-type data-size' in $MeshFormat, found '{line}'"),
            ));
        }
        let version = match fields[0] {
            "2" | "2.0" | "2.1" | "2.2" => Version::V2,
            "4.1" => Version::V41,
            other => {
                return Err(scan.error_at(
                    at,
                    format!(
                        "MSH version {other} is not read: save the mesh as MSH 4.1 or 2.2 \
                         (gmsh -format msh41 or -format msh22)"
                    ),
                ))
            }
        };
        let binary = match fields[1] {
            "0" => false,
            "1" => true,
            other => {
                return Err(scan.error_at(
                    at,
                    format!("the file type must be 0 (ASCII) or 1 (binary), found '{other}'"),
                ))
            }
        };
        if fields[2] != "8" {
            return Err(scan.error_at(
                at,
                format!(
                    "the data size must be 8 (64-bit size_t and doubles), found '{}'",
                    fields[2]
                ),
            ));
        }
        let mut endian = Endian::Little;
        if binary {
            let one_at = scan.pos();
            let one = scan.bytes(4, "the binary integer 1 of $MeshFormat")?;
            let word = [one[0], one[1], one[2], one[3]];
            endian = if u32::from_le_bytes(word) == 1 {
                Endian::Little
            } else if u32::from_be_bytes(word) == 1 {
                Endian::Big
            } else {
                return Err(scan.error_at_byte(
                    one_at,
                    "the binary integer 1 after the version line is not 1 in either byte order",
                ));
            };
            scan.skip_line()?;
        }
        let (at, end) = scan.expect_line("$EndMeshFormat")?;
        if end != "$EndMeshFormat" {
            return Err(scan.error_at(at, format!("expected $EndMeshFormat, found '{end}'")));
        }
        Ok(Msh {
            scan,
            version,
            binary,
            endian,
        })
    }

    /// Where the next item starts (past whitespace in ASCII), to name in errors.
    fn mark(&mut self) -> usize {
        if !self.binary {
            self.scan.skip_whitespace();
        }
        self.scan.pos()
    }

    /// An error at `pos`: its line in ASCII, its byte offset in binary.
    fn error(&self, pos: usize, message: impl Into<String>) -> Error {
        if self.binary {
            self.scan.error_at_byte(pos, message.into())
        } else {
            self.scan.error_at(pos, message)
        }
    }

    fn end_of_section(&mut self, marker: &str) -> Result<()> {
        let (at, line) = self.scan.expect_line(marker)?;
        if line == marker {
            Ok(())
        } else {
            let shown: String = line.chars().take(60).collect();
            Err(self.scan.error_at(
                at,
                format!(
                    "expected {marker}, found '{shown}': the section holds more or other data \
                     than its counts say"
                ),
            ))
        }
    }

    /// A 4.1 `size_t`: a token in ASCII, 8 bytes in binary.
    fn size(&mut self, what: &str) -> Result<u64> {
        if self.binary {
            self.scan.u64(self.endian, what)
        } else {
            self.scan.int(what)
        }
    }

    /// A 4.1 `int`.
    fn int(&mut self, what: &str) -> Result<i32> {
        if self.binary {
            self.scan.i32(self.endian, what)
        } else {
            let (at, token) = self.scan.token(what)?;
            token.parse().map_err(|_| {
                self.scan
                    .error_at(at, format!("{what} must be an integer, found '{token}'"))
            })
        }
    }

    fn float(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            self.scan.f64(self.endian, what)
        } else {
            self.scan.float(what)
        }
    }

    /// A count from a header, as a usize.
    fn count(&mut self, what: &str) -> Result<usize> {
        let at = self.mark();
        let n = self.size(what)?;
        usize::try_from(n).map_err(|_| self.error(at, format!("{what} {n} is too large")))
    }

    /// Adds node `tag` at (x, y, z), read at `at`.
    fn add_node(&self, nodes: &mut Nodes, at: usize, tag: u64, p: [f64; 3]) -> Result<()> {
        if let Some(bad) = p.iter().find(|v| !v.is_finite()) {
            return Err(self.error(
                at,
                format!("node {tag} has the coordinate {bad}: NaN and infinite values are refused"),
            ));
        }
        if p[2] != 0.0 {
            return Err(self.error(
                at,
                format!(
                    "node {tag} has z = {:?}: verify checks planar meshes in the plane z = 0",
                    p[2]
                ),
            ));
        }
        let vertex = u32::try_from(nodes.points.len())
            .map_err(|_| self.error(at, "more nodes than 32-bit vertex indices can number"))?;
        if nodes.index.insert(tag, vertex).is_some() {
            return Err(self.error(at, format!("node tag {tag} is used twice")));
        }
        nodes.points.push([p[0], p[1]]);
        nodes.tags.push(tag);
        Ok(())
    }

    /// The vertex of node `tag`, named by element `element` read at `at`.
    fn vertex(&self, nodes: &Nodes, at: usize, element: u64, tag: u64) -> Result<u32> {
        nodes.index.get(&tag).copied().ok_or_else(|| {
            self.error(
                at,
                format!("element {element} names node {tag}, which $Nodes does not list"),
            )
        })
    }

    fn refuse(&self, at: usize, element_type: i32, what: &str) -> Error {
        self.error(
            at,
            format!(
                "element type {element_type} is {what}: verify checks meshes of 3-node \
                 triangles (type 2) only"
            ),
        )
    }

    /// `$Nodes` of MSH 2.2: a count, then `tag x y z` per node.
    fn nodes_v2(&mut self) -> Result<Nodes> {
        let count = self.scan.int::<usize>("the number of nodes")?;
        let mut nodes = Nodes::default();
        nodes.points.reserve(count.min(MAX_PREALLOCATION));
        if self.binary {
            self.scan.skip_line()?;
            self.scan.require(count, 4 + 3 * 8, "$Nodes")?;
        }
        for _ in 0..count {
            let at = self.mark();
            let tag = if self.binary {
                let tag = self.scan.i32(self.endian, "a node tag")?;
                u64::try_from(tag)
                    .ok()
                    .filter(|&t| t > 0)
                    .ok_or_else(|| self.error(at, format!("node tag {tag} is not positive")))?
            } else {
                self.scan.int::<u64>("a node tag")?
            };
            let p = [self.float("x")?, self.float("y")?, self.float("z")?];
            self.add_node(&mut nodes, at, tag, p)?;
        }
        Ok(nodes)
    }

    /// `$Nodes` of MSH 4.1: a header, then entity blocks of tags followed by coordinates.
    fn nodes_v41(&mut self) -> Result<Nodes> {
        let header_at = self.mark();
        let blocks = self.count("the number of node blocks")?;
        let total = self.count("the number of nodes")?;
        self.size("the smallest node tag")?;
        self.size("the largest node tag")?;
        let mut nodes = Nodes::default();
        nodes.points.reserve(total.min(MAX_PREALLOCATION));
        for _ in 0..blocks {
            let at = self.mark();
            let dim = self.int("the entity dimension")?;
            self.int("the entity tag")?;
            let parametric = self.int("the parametric flag")?;
            let count = self.count("the number of nodes in the block")?;
            if !(0..=3).contains(&dim) || !(0..=1).contains(&parametric) {
                return Err(self.error(
                    at,
                    format!(
                        "a node block of entity dimension {dim} with parametric flag \
                         {parametric}: expected 0 to 3 and 0 or 1"
                    ),
                ));
            }
            let extra = if parametric == 1 { dim as usize } else { 0 };
            if self.binary {
                self.scan.require(count, 8, "the node tags of a block")?;
            }
            let mut tags = Vec::with_capacity(count.min(MAX_PREALLOCATION));
            for _ in 0..count {
                tags.push(self.size("a node tag")?);
            }
            if self.binary {
                self.scan
                    .require(count, 8 * (3 + extra), "the coordinates of a block")?;
            }
            for &tag in &tags {
                let at = self.mark();
                let p = [self.float("x")?, self.float("y")?, self.float("z")?];
                for _ in 0..extra {
                    self.float("a parametric coordinate")?;
                }
                self.add_node(&mut nodes, at, tag, p)?;
            }
        }
        if nodes.points.len() != total {
            return Err(self.error(
                header_at,
                format!(
                    "the header says {total} nodes, but the blocks hold {}",
                    nodes.points.len()
                ),
            ));
        }
        Ok(nodes)
    }

    /// `$Elements` of MSH 4.1: a header, then entity blocks of one element type each.
    fn elements_v41(&mut self, nodes: &Nodes) -> Result<Elements> {
        let header_at = self.mark();
        let blocks = self.count("the number of element blocks")?;
        let total = self.count("the number of elements")?;
        self.size("the smallest element tag")?;
        self.size("the largest element tag")?;
        let mut out = Elements {
            triangles: Vec::new(),
            tags: Vec::new(),
        };
        let mut seen = 0usize;
        for _ in 0..blocks {
            self.int("the entity dimension")?;
            self.int("the entity tag")?;
            let type_at = self.mark();
            let element_type = self.int("the element type")?;
            let count = self.count("the number of elements in the block")?;
            let corners = match kind(element_type) {
                Kind::Refuse(what) => return Err(self.refuse(type_at, element_type, what)),
                Kind::Skip(n) => n,
                Kind::Triangle => 3,
            };
            if self.binary {
                self.scan
                    .require(count, 8 * (1 + corners), "an element block")?;
            }
            if element_type == TRIANGLE {
                out.triangles.reserve(count.min(MAX_PREALLOCATION));
                out.tags.reserve(count.min(MAX_PREALLOCATION));
            }
            for _ in 0..count {
                let at = self.mark();
                let tag = self.size("an element tag")?;
                let mut t = [0u32; 3];
                for k in 0..corners {
                    let node = self.size("a node tag of an element")?;
                    if let (true, Some(slot)) = (element_type == TRIANGLE, t.get_mut(k)) {
                        *slot = self.vertex(nodes, at, tag, node)?;
                    }
                }
                if element_type == TRIANGLE {
                    out.triangles.push(t);
                    out.tags.push(tag);
                }
            }
            seen = seen.saturating_add(count);
        }
        if seen != total {
            return Err(self.error(
                header_at,
                format!("the header says {total} elements, but the blocks hold {seen}"),
            ));
        }
        Ok(out)
    }

    /// `$Elements` of MSH 2.2: a count, then `tag type ntags tags... nodes...` per element in
    /// ASCII; in binary, headers `type count ntags` each followed by that many elements.
    fn elements_v2(&mut self, nodes: &Nodes) -> Result<Elements> {
        let total = self.scan.int::<usize>("the number of elements")?;
        let mut out = Elements {
            triangles: Vec::new(),
            tags: Vec::new(),
        };
        if self.binary {
            self.scan.skip_line()?;
            let mut seen = 0usize;
            while seen < total {
                let at = self.mark();
                let element_type = self.scan.i32(self.endian, "an element type")?;
                let follow = self.scan.i32(self.endian, "an element count")?;
                let ntags = self.scan.i32(self.endian, "a number of tags")?;
                let corners = match kind(element_type) {
                    Kind::Refuse(what) => return Err(self.refuse(at, element_type, what)),
                    Kind::Skip(n) => n,
                    Kind::Triangle => 3,
                };
                let (follow, ntags) = match (usize::try_from(follow), usize::try_from(ntags)) {
                    (Ok(f), Ok(t)) if f > 0 && f <= total - seen => (f, t),
                    _ => {
                        return Err(self.error(
                            at,
                            format!(
                                "an element header with {follow} elements and {ntags} tags, \
                                 where {} elements are left",
                                total - seen
                            ),
                        ))
                    }
                };
                let ints = ntags.saturating_add(1 + corners);
                self.scan
                    .require(follow, ints.saturating_mul(4), "an element block")?;
                for _ in 0..follow {
                    let at = self.mark();
                    let tag = self.scan.i32(self.endian, "an element tag")?;
                    for _ in 0..ntags {
                        self.scan.i32(self.endian, "an element's tag")?;
                    }
                    let mut t = [0u32; 3];
                    for k in 0..corners {
                        let node = self.scan.i32(self.endian, "a node of an element")?;
                        if let (true, Some(slot)) = (element_type == TRIANGLE, t.get_mut(k)) {
                            let node = u64::try_from(node).unwrap_or(0);
                            *slot = self.vertex(nodes, at, tag as u64, node)?;
                        }
                    }
                    if element_type == TRIANGLE {
                        out.triangles.push(t);
                        out.tags.push(tag as u64);
                    }
                }
                seen += follow;
            }
            return Ok(out);
        }
        for _ in 0..total {
            let at = self.mark();
            let tag = self.scan.int::<u64>("an element tag")?;
            let type_at = self.mark();
            let element_type = self.int("the element type")?;
            let ntags = self.scan.int::<usize>("the number of element tags")?;
            let corners = match kind(element_type) {
                Kind::Refuse(what) => return Err(self.refuse(type_at, element_type, what)),
                Kind::Skip(n) => n,
                Kind::Triangle => 3,
            };
            for _ in 0..ntags {
                self.int("an element's tag")?;
            }
            let mut t = [0u32; 3];
            for k in 0..corners {
                let node = self.scan.int::<u64>("a node of an element")?;
                if let (true, Some(slot)) = (element_type == TRIANGLE, t.get_mut(k)) {
                    *slot = self.vertex(nodes, at, tag, node)?;
                }
            }
            if element_type == TRIANGLE {
                out.triangles.push(t);
                out.tags.push(tag);
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &[u8]) -> Result<LoadedMesh> {
        parse_msh(Path::new("t.msh"), text)
    }

    fn message(text: &[u8]) -> String {
        parse(text).expect_err("refused").to_string()
    }

    /// A 4.1 ASCII square of two triangles: node tags 40, 7, 1000, 3 in that order, over two
    /// blocks (the second parametric on a surface), with a skipped $Entities, a line and a
    /// point element.
    const SQUARE_41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
        $Entities\n1 0 1 0\n1 0 0 0 0\n1 0 0 0 1 1 0 0 0\n$EndEntities\n\
        $Nodes\n2 4 3 1000\n\
        0 1 0 1\n40\n0 0 0\n\
        2 1 1 3\n7\n1000\n3\n1 0 0 0.5 0.5\n1 1 0 0.1 0.2\n0 1 0 0.3 0.4\n\
        $EndNodes\n\
        $Elements\n3 4 1 9\n\
        0 1 15 1\n1 40\n\
        1 1 1 1\n2 40 7\n\
        2 1 2 2\n8 40 7 1000\n9 40 1000 3\n\
        $EndElements\n";

    #[test]
    fn msh41_ascii_maps_sparse_tags_to_file_order_and_skips_points_and_lines() {
        let read = parse(SQUARE_41.as_bytes()).expect("square");
        assert_eq!(
            read.mesh.vertices,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        );
        assert_eq!(read.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(read.vertex_tags, Some(vec![40, 7, 1000, 3]));
        assert_eq!(read.triangle_tags, Some(vec![8, 9]));
    }

    #[test]
    fn msh22_ascii_reads_tags_and_skips_other_sections() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
            $PhysicalNames\n1\n2 1 \"domain\"\n$EndPhysicalNames\n\
            $Nodes\n4\n5 0 0 0\n2 1 0 0\n9 1 1 0\n4 0.1 1 0\n$EndNodes\n\
            $Elements\n3\n1 15 2 0 1 5\n2 1 2 0 1 5 2\n7 2 2 1 1 5 2 9\n$EndElements\n\
            $NodeData\n1\n\"t\"\n$EndNodeData\n";
        let read = parse(text.as_bytes()).expect("2.2");
        assert_eq!(read.mesh.vertices.len(), 4);
        assert_eq!(read.mesh.vertices[3], [0.1, 1.0]);
        assert_eq!(read.mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(read.vertex_tags, Some(vec![5, 2, 9, 4]));
        assert_eq!(read.triangle_tags, Some(vec![7]));
    }

    /// Binary bytes built by hand, little-endian.
    struct Bin(Vec<u8>);

    impl Bin {
        fn text(mut self, s: &str) -> Bin {
            self.0.extend_from_slice(s.as_bytes());
            self
        }
        fn i32(mut self, v: i32) -> Bin {
            self.0.extend_from_slice(&v.to_le_bytes());
            self
        }
        fn u64(mut self, v: u64) -> Bin {
            self.0.extend_from_slice(&v.to_le_bytes());
            self
        }
        fn f64(mut self, v: f64) -> Bin {
            self.0.extend_from_slice(&v.to_le_bytes());
            self
        }
    }

    fn binary_41_header() -> Bin {
        Bin(Vec::new())
            .text("$MeshFormat\n4.1 1 8\n")
            .i32(1)
            .text("\n$EndMeshFormat\n$Nodes\n")
    }

    #[test]
    fn msh41_binary_keeps_every_coordinate_bit_for_bit() {
        let third = 1.0 / 3.0;
        let odd = 0.1 + 0.2;
        let bin = binary_41_header()
            .u64(1)
            .u64(3)
            .u64(2)
            .u64(11)
            .i32(2)
            .i32(1)
            .i32(0)
            .u64(3)
            .u64(11)
            .u64(2)
            .u64(5);
        let bin = bin
            .f64(-0.0)
            .f64(third)
            .f64(0.0)
            .f64(odd)
            .f64(1e-300)
            .f64(0.0)
            .f64(7.5e12)
            .f64(2.0)
            .f64(-0.0)
            .text("\n$EndNodes\n$Elements\n")
            .u64(2)
            .u64(2)
            .u64(1)
            .u64(2);
        let bin = bin
            .i32(1)
            .i32(1)
            .i32(1)
            .u64(1)
            .u64(1)
            .u64(11)
            .u64(2)
            .i32(2)
            .i32(1)
            .i32(2)
            .u64(1)
            .u64(2)
            .u64(11)
            .u64(2)
            .u64(5)
            .text("\n$EndElements\n");
        let read = parse(&bin.0).expect("binary 4.1");
        let bits: Vec<[u64; 2]> = read
            .mesh
            .vertices
            .iter()
            .map(|p| [p[0].to_bits(), p[1].to_bits()])
            .collect();
        let want = [[-0.0, third], [odd, 1e-300], [7.5e12, 2.0]];
        let want: Vec<[u64; 2]> = want
            .iter()
            .map(|p| [p[0].to_bits(), p[1].to_bits()])
            .collect();
        assert_eq!(bits, want);
        assert_eq!(read.mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(read.vertex_tags, Some(vec![11, 2, 5]));
    }

    fn binary_22(element_type: i32, corners: &[i32]) -> Vec<u8> {
        let mut bin = Bin(Vec::new())
            .text("$MeshFormat\n2.2 1 8\n")
            .i32(1)
            .text("\n$EndMeshFormat\n$Nodes\n3\n");
        for (tag, p) in [(30, [0.0, 0.0]), (10, [2.0, 0.0]), (20, [0.0, 0.7])] {
            bin = bin.i32(tag).f64(p[0]).f64(p[1]).f64(0.0);
        }
        bin = bin.text("\n$EndNodes\n$Elements\n2\n");
        // One line with two tags, then one element of `element_type`.
        bin = bin
            .i32(1)
            .i32(1)
            .i32(2)
            .i32(1)
            .i32(0)
            .i32(0)
            .i32(30)
            .i32(10);
        bin = bin.i32(element_type).i32(1).i32(2).i32(2).i32(0).i32(0);
        for &c in corners {
            bin = bin.i32(c);
        }
        bin.text("\n$EndElements\n").0
    }

    #[test]
    fn msh22_binary_reads_element_headers_and_skips_lines() {
        let read = parse(&binary_22(2, &[30, 10, 20])).expect("binary 2.2");
        assert_eq!(read.mesh.vertices[2], [0.0, 0.7]);
        assert_eq!(read.mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(read.vertex_tags, Some(vec![30, 10, 20]));
        assert_eq!(read.triangle_tags, Some(vec![2]));
    }

    #[test]
    fn higher_order_triangles_are_refused_at_their_byte_offset() {
        let bytes = binary_22(9, &[30, 10, 20, 30, 10, 20]);
        let header = 72 + 24 + 16; // nodes end, "\n$EndNodes\n$Elements\n2\n", the line
        let e = message(&bytes);
        assert!(
            e.contains("element type 9 is a 6-node second-order triangle"),
            "{e}"
        );
        let offset: usize = e
            .split("at byte offset ")
            .nth(1)
            .and_then(|r| r.split(':').next())
            .and_then(|n| n.parse().ok())
            .expect("an offset");
        assert!(offset > header, "{e}");
        assert_eq!(&bytes[offset..offset + 4], &9i32.to_le_bytes());
    }

    #[test]
    fn quadrangles_are_refused_at_their_line() {
        let text = SQUARE_41.replace(
            "2 1 2 2\n8 40 7 1000\n9 40 1000 3\n",
            "2 1 3 1\n8 40 7 1000 3\n",
        );
        let text = text.replace("$Elements\n3 4 1 9\n", "$Elements\n3 3 1 8\n");
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:28: element type 3 is a 4-node quadrangle: verify checks meshes of 3-node \
             triangles (type 2) only"
        );
    }

    #[test]
    fn truncated_files_are_refused_with_where_they_end() {
        let cut = &SQUARE_41[..SQUARE_41.find("1 1 0 0.1").expect("row")];
        assert_eq!(
            message(cut.as_bytes()),
            "t.msh:18: the file ends where x was expected"
        );
        let e = message(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 0 0\n");
        assert_eq!(e, "t.msh:5: the file ends where $EndNodes was expected");
        let bytes = binary_22(2, &[30, 10, 20]);
        let e = message(&bytes[..bytes.len() - 20]);
        assert!(e.starts_with("t.msh: at byte offset "), "{e}");
        assert!(
            e.contains("do not fit in the 18 bytes left in the file"),
            "{e}"
        );
        let e = message(&bytes[..bytes.len() - 50]);
        assert!(e.contains("the file ends (at byte "), "{e}");
        assert_eq!(
            message(b""),
            "t.msh:1: the file ends where $MeshFormat was expected"
        );
    }

    #[test]
    fn a_header_claiming_a_trillion_nodes_fails_without_allocating() {
        let bin = binary_41_header()
            .u64(1)
            .u64(1_000_000_000_000)
            .u64(1)
            .u64(1_000_000_000_000)
            .i32(2)
            .i32(1)
            .i32(0)
            .u64(1_000_000_000_000)
            .u64(1);
        let e = message(&bin.0);
        assert!(
            e.contains("1000000000000 records of 8 bytes do not fit"),
            "{e}"
        );
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1000000000000\n1 0 0 0\n";
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:6: the file ends where a node tag was expected"
        );
    }

    #[test]
    fn bad_nodes_and_references_are_named_by_their_tags() {
        let text = SQUARE_41.replace("1 0 0 0.5 0.5", "1 0 0.25 0.5 0.5");
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:18: node 7 has z = 0.25: verify checks planar meshes in the plane z = 0"
        );
        let text = SQUARE_41.replace("9 40 1000 3", "9 40 1000 4");
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:30: element 9 names node 4, which $Nodes does not list"
        );
        let text = SQUARE_41.replace("\n3\n1 0 0", "\n40\n1 0 0");
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:20: node tag 40 is used twice"
        );
        let text = SQUARE_41.replace("$Elements\n3 4 1 9", "$Elements\n3 5 1 9");
        assert_eq!(
            message(text.as_bytes()),
            "t.msh:23: the header says 5 elements, but the blocks hold 4"
        );
    }

    #[test]
    fn every_truncation_and_byte_change_is_refused_or_read_without_panic() {
        use crate::io::scan::refuses_without_panic;
        let p = |b: &[u8]| parse(b);
        let samples = [
            SQUARE_41.as_bytes().to_vec(),
            binary_22(2, &[30, 10, 20]),
            binary_41_header()
                .u64(1)
                .u64(1)
                .u64(4)
                .u64(4)
                .i32(2)
                .i32(1)
                .i32(0)
                .u64(1)
                .u64(4)
                .f64(0.5)
                .f64(0.25)
                .f64(0.0)
                .text("\n$EndNodes\n")
                .0,
        ];
        for bytes in samples {
            // Every cut before the closing $End line of the last section is refused.
            let last = bytes.len()
                - bytes
                    .rsplit(|&b| b == b'$')
                    .next()
                    .map_or(0, |r| r.len() + 1);
            let refused = refuses_without_panic(&bytes, p);
            assert!(refused >= last, "{refused} of {last}");
        }
    }

    #[test]
    fn other_versions_and_foreign_files_are_refused_by_name() {
        let e = message(b"$MeshFormat\n4 0 8\n$EndMeshFormat\n");
        assert!(e.starts_with("t.msh:2: MSH version 4 is not read"), "{e}");
        let e = message(b"# vtk DataFile Version 3.0\n");
        assert_eq!(
            e,
            "t.msh:1: not a Gmsh .msh file: it must start with a $MeshFormat line"
        );
        let e =
            message(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n0 0 0 0\n$EndElements\n");
        assert_eq!(e, "t.msh:4: $Elements comes before any $Nodes section");
        let e = message(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 0 0\n$EndNodes\n");
        assert_eq!(e, "t.msh: the file has no $Elements section");
    }
}
