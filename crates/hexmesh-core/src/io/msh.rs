//! Gmsh MSH 4.1 ASCII (Gmsh reference manual, "MSH file format"), for Gmsh and meshio, with
//! the boundary a finite-element user sets conditions on. Tags are 1-based.
//!
//! - Surfaces: one entity holding every triangle (element type 2), or, when the input has
//!   regions, one per regional attribute (ascending). Every node sits on surface 1.
//! - Curves: one entity per boundary loop and marker (a loop whose edges carry two markers
//!   gives two curves), in loop order, then one per marker for the edges of input segments
//!   inside the domain (ascending markers). Each holds its edges as 2-node lines (type 1).
//! - Physical groups, numbered from 1 in this order and named in `$PhysicalNames`: dimension
//!   1, `marker M` for every edge marker M (ascending), `outer boundary` (every
//!   counter-clockwise loop), `hole K` for each clockwise loop (K from 1, in loop order);
//!   dimension 2, `domain` (every triangle) and `region A` for each regional attribute A.
//!   Every element is in at least one group, so meshio puts every cell in a cell set.
//!
//! Triangles are elements 1..m in mesh order; lines follow, m+1.., curve by curve.

use std::fmt::Write as _;
use std::path::Path;

use super::boundary::{derive_boundary, Boundary, LoopKind};
use super::triangle::write_file;
use crate::error::Result;
use crate::mesh::TriMesh;

/// Gmsh's element type number for a 2-node line.
const MSH_LINE: u8 = 1;

/// Gmsh's element type number for a 3-node triangle.
const MSH_TRIANGLE: u8 = 2;

/// An entity of dimension 1 or 2: its elements (edge or triangle indices) and groups.
struct Entity {
    elements: Vec<usize>,
    physical: Vec<usize>,
}

/// A physical group: dimension and name; its tag is its position + 1.
struct Group {
    dimension: u8,
    name: String,
}

/// Writes `mesh` as a Gmsh 4.1 ASCII file with the labels of the mesh alone (every boundary
/// edge marked 1); coordinates keep full precision.
pub fn write_msh(path: &Path, mesh: &TriMesh) -> Result<()> {
    super::check_mesh(path, mesh)?;
    write_msh_with(path, mesh, &derive_boundary(mesh, None))
}

/// Writes `mesh` as a Gmsh 4.1 ASCII file with the curves and physical groups of `boundary`,
/// which must have been derived from `mesh`.
pub fn write_msh_with(path: &Path, mesh: &TriMesh, boundary: &Boundary) -> Result<()> {
    super::check_mesh(path, mesh)?;
    let (groups, curves, surfaces) = layout(mesh, boundary);
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let lines: usize = curves.iter().map(|c| c.elements.len()).sum();
    let mut text = String::with_capacity(n * 48 + m * 24 + lines * 24 + 512);
    text.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");

    let _ = writeln!(text, "$PhysicalNames\n{}", groups.len());
    for (k, g) in groups.iter().enumerate() {
        let _ = writeln!(text, "{} {} \"{}\"", g.dimension, k + 1, g.name);
    }
    text.push_str("$EndPhysicalNames\n");

    // $Entities: no points; each curve and surface with its bounding box, its physical tags
    // and no bounding entities.
    let _ = writeln!(text, "$Entities\n0 {} {} 0", curves.len(), surfaces.len());
    let entity =
        |text: &mut String, tag: usize, e: &Entity, vertices: &mut dyn Iterator<Item = u32>| {
            let [xmin, ymin, xmax, ymax] = bounding_box_of(mesh, vertices);
            let _ = write!(
                text,
                "{tag} {xmin:?} {ymin:?} 0 {xmax:?} {ymax:?} 0 {}",
                e.physical.len()
            );
            for p in &e.physical {
                let _ = write!(text, " {}", p + 1);
            }
            text.push_str(" 0\n");
        };
    for (k, c) in curves.iter().enumerate() {
        let mut vertices = c.elements.iter().flat_map(|&e| boundary.edges[e].vertices);
        entity(&mut text, k + 1, c, &mut vertices);
    }
    for (k, s) in surfaces.iter().enumerate() {
        let mut vertices = s.elements.iter().flat_map(|&t| mesh.triangles[t]);
        entity(&mut text, k + 1, s, &mut vertices);
    }
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
    let blocks = surfaces.len() + curves.len();
    let total = m + lines;
    match total {
        0 => text.push_str("0 0 0 0\n"),
        _ => {
            let _ = writeln!(text, "{blocks} {total} 1 {total}");
        }
    }
    if total > 0 {
        for (k, s) in surfaces.iter().enumerate() {
            let _ = writeln!(text, "2 {} {MSH_TRIANGLE} {}", k + 1, s.elements.len());
            for &t in &s.elements {
                let c = mesh.triangles[t];
                let _ = writeln!(text, "{} {} {} {}", t + 1, c[0] + 1, c[1] + 1, c[2] + 1);
            }
        }
        let mut tag = m;
        for (k, c) in curves.iter().enumerate() {
            let _ = writeln!(text, "1 {} {MSH_LINE} {}", k + 1, c.elements.len());
            for &e in &c.elements {
                tag += 1;
                let [a, b] = boundary.edges[e].vertices;
                let _ = writeln!(text, "{tag} {} {}", a + 1, b + 1);
            }
        }
    }
    text.push_str("$EndElements\n");
    write_file(path, &text)
}

/// The physical groups, the curve entities and the surface entities of the module
/// documentation. Empty entities are left out.
fn layout(mesh: &TriMesh, boundary: &Boundary) -> (Vec<Group>, Vec<Entity>, Vec<Entity>) {
    let mut groups: Vec<Group> = Vec::new();
    let mut group = |dimension: u8, name: String| {
        groups.push(Group { dimension, name });
        groups.len() - 1
    };

    let mut markers: Vec<i64> = boundary.marked_edges().map(|e| e.marker).collect();
    markers.sort_unstable();
    markers.dedup();
    let marker_group: Vec<usize> = markers
        .iter()
        .map(|m| group(1, format!("marker {m}")))
        .collect();
    let marker_tag = |m: i64| marker_group[markers.binary_search(&m).unwrap_or(0)];
    let outer = boundary
        .loops
        .iter()
        .any(|l| l.kind == LoopKind::Outer)
        .then(|| group(1, "outer boundary".to_string()));
    let mut holes = 0;
    let loop_group: Vec<Option<usize>> = boundary
        .loops
        .iter()
        .map(|l| match l.kind {
            LoopKind::Outer => outer,
            LoopKind::Hole => {
                holes += 1;
                Some(group(1, format!("hole {holes}")))
            }
        })
        .collect();

    // Curves: each loop split by marker (in order of first appearance along it), then the
    // marked edges on no loop (interior segments), one curve per marker.
    let mut curves: Vec<Entity> = Vec::new();
    let mut on_loop = vec![false; boundary.edges.len()];
    for (l, lp) in boundary.loops.iter().enumerate() {
        let mut order: Vec<i64> = Vec::new();
        for &e in &lp.edges {
            on_loop[e] = true;
            let m = boundary.edges[e].marker;
            if !order.contains(&m) {
                order.push(m);
            }
        }
        for m in order {
            curves.push(Entity {
                elements: lp
                    .edges
                    .iter()
                    .copied()
                    .filter(|&e| boundary.edges[e].marker == m)
                    .collect(),
                physical: std::iter::once(marker_tag(m))
                    .chain(loop_group[l])
                    .collect(),
            });
        }
    }
    for &m in &markers {
        let elements: Vec<usize> = (0..boundary.edges.len())
            .filter(|&e| {
                let edge = &boundary.edges[e];
                edge.is_marked() && !on_loop[e] && edge.marker == m
            })
            .collect();
        if !elements.is_empty() {
            curves.push(Entity {
                elements,
                physical: vec![marker_tag(m)],
            });
        }
    }

    let domain = group(2, "domain".to_string());
    let mut regions: Vec<f64> = Vec::new();
    if boundary.has_regions {
        regions = boundary.triangle_regions.clone();
        regions.sort_unstable_by(f64::total_cmp);
        regions.dedup_by(|a, b| a.total_cmp(b).is_eq());
    }
    let surfaces = if regions.is_empty() {
        vec![Entity {
            elements: (0..mesh.triangles.len()).collect(),
            physical: vec![domain],
        }]
    } else {
        regions
            .iter()
            .map(|&a| Entity {
                elements: (0..mesh.triangles.len())
                    .filter(|&t| boundary.triangle_regions[t].total_cmp(&a).is_eq())
                    .collect(),
                physical: vec![domain, group(2, format!("region {a}"))],
            })
            .collect()
    };
    (groups, curves, surfaces)
}

/// The bounding box of the given vertices, [xmin, ymin, xmax, ymax]; zeros for none.
fn bounding_box_of(mesh: &TriMesh, vertices: &mut dyn Iterator<Item = u32>) -> [f64; 4] {
    let mut any = false;
    let b = vertices.fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, v| {
            any = true;
            let p = mesh.vertices[v as usize];
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    );
    if any {
        b
    } else {
        [0.0; 4]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_triangle_has_one_outer_curve_its_groups_and_the_surface_bounding_box() {
        let mesh = TriMesh {
            vertices: vec![[-1.5, 2.0], [3.0, -0.25], [0.5, 7.0]],
            triangles: vec![[0, 1, 2]],
        };
        let all = &mut (0..3u32);
        assert_eq!(bounding_box_of(&mesh, all), [-1.5, -0.25, 3.0, 7.0]);
        assert_eq!(bounding_box_of(&mesh, &mut (0..0u32)), [0.0; 4]);
        let dir = std::env::temp_dir().join(format!("hexmesh-io-msh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("bbox.msh");
        write_msh(&path, &mesh).expect("write");
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(text.contains(
            "$PhysicalNames\n3\n1 1 \"marker 1\"\n1 2 \"outer boundary\"\n2 3 \"domain\"\n\
             $EndPhysicalNames\n"
        ));
        assert!(text.contains(
            "$Entities\n0 1 1 0\n1 -1.5 -0.25 0 3.0 7.0 0 2 1 2 0\n\
             1 -1.5 -0.25 0 3.0 7.0 0 1 3 0\n$EndEntities"
        ));
        assert!(text.contains(
            "$Elements\n2 4 1 4\n2 1 2 1\n1 1 2 3\n1 1 1 3\n2 1 2\n3 2 3\n4 3 1\n$EndElements"
        ));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
