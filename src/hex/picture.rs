//! Pictures of the hexagon subdivision with its dual mesh over it, in the style of paper 000
//! Figs. 3, 4 and 7: full hexagons, semi-hexagons and occupied hexagons in their own colours,
//! the dual triangles as lines, the input points as dots.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::hex::dual::{self, Placement};
use crate::hex::lattice::Key;
use crate::hex::subdivision::{Cell, Hierarchy};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Params;

/// Meshes `input` with the simple refinement and writes the picture of the final hexagon
/// subdivision and its dual to `path` (an SVG file). This is what `hexmesh mesh … --mesher
/// hex-simple --hexagons P.svg` calls.
pub fn write_hexagons_svg(input: &Pslg, params: &Params, path: &Path) -> Result<()> {
    let (h, stop) = super::mesh_with_hierarchy(input, params)?;
    let placement = if stop.is_none() {
        Placement::Relocated
    } else {
        Placement::Plain
    };
    let mesh = dual::extract(&h, placement);
    write_hierarchy_svg(&h, &mesh, path)
}

/// Writes the picture of a hierarchy and a mesh (usually its dual) to `path`.
pub fn write_hierarchy_svg(h: &Hierarchy, mesh: &TriMesh, path: &Path) -> Result<()> {
    let svg = hierarchy_svg(h, mesh);
    std::fs::write(path, svg).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The SVG text of `write_hierarchy_svg`.
pub fn hierarchy_svg(h: &Hierarchy, mesh: &TriMesh) -> String {
    const SIZE: f64 = 1000.0;
    let root = h.lattice.root();
    let (o, r0) = (root.center, root.circumradius);
    let scale = SIZE / (2.2 * r0);
    let map = |p: Point| -> (f64, f64) {
        (
            SIZE / 2.0 + (p[0] - o[0]) * scale,
            SIZE / 2.0 - (p[1] - o[1]) * scale,
        )
    };
    let poly = |pts: &[Point]| -> String {
        pts.iter()
            .map(|&p| {
                let (x, y) = map(p);
                format!("{x:.3},{y:.3}")
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    // Line widths shrink with the finest level so that dense pictures stay readable.
    let stroke = (0.6 * scale * h.lattice.radius(deepest(h)) / 4.0).clamp(0.02, 1.0);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {SIZE} {SIZE}" width="{SIZE}" height="{SIZE}">"#
    );
    let _ = writeln!(
        s,
        r#"<clipPath id="root"><polygon points="{}"/></clipPath>"#,
        poly(&root.corners())
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r##"<g clip-path="url(#root)" stroke="#555" stroke-width="{stroke:.3}">"##
    );
    for (key, cell) in h.leaves() {
        let corners = h.lattice.corners(key);
        let (pts, fill) = match cell {
            Cell::Semi { owner, .. } => (semi_corners(key, owner, &corners), "#cfe3f7"),
            _ if h.is_occupied(key) => (corners.to_vec(), "#f7b267"),
            _ => (corners.to_vec(), "#f2f2f2"),
        };
        let _ = writeln!(s, r#"<polygon points="{}" fill="{fill}"/>"#, poly(&pts));
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r##"<polygon points="{}" fill="none" stroke="black" stroke-width="{:.3}"/>"##,
        poly(&root.corners()),
        2.0 * stroke
    );
    let _ = writeln!(
        s,
        r##"<g stroke="#1f4e9c" stroke-width="{:.3}" fill="none">"##,
        stroke * 0.8
    );
    for t in 0..mesh.triangles.len() {
        let _ = writeln!(s, r#"<polygon points="{}"/>"#, poly(&mesh.corners(t)));
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, r##"<g fill="#c0392b">"##);
    for &p in &h.points {
        let (x, y) = map(p);
        let _ = writeln!(
            s,
            r#"<circle cx="{x:.3}" cy="{y:.3}" r="{:.3}"/>"#,
            2.5 * stroke
        );
    }
    let _ = writeln!(s, "</g>\n</svg>");
    s
}

fn deepest(h: &Hierarchy) -> u8 {
    h.subdivided_sorted()
        .iter()
        .map(|k| k.k + 1)
        .max()
        .unwrap_or(0)
}

/// The four corners of the half of cell `key` that lies inside `owner`: the corners within 90°
/// of the direction towards the owner's centre (the two ends of the long edge included).
fn semi_corners(key: Key, owner: Key, corners: &[Point; 6]) -> Vec<Point> {
    let towards = (0..6)
        .find(|&d| key.neighbor(d) == owner.central_child())
        .unwrap_or(0);
    // Direction d points at 30° + 60°·d; corners m at 60°·m; the owner side holds m = d - 1 ..= d + 2.
    (0..4).map(|t| corners[(towards + 5 + t) % 6]).collect()
}
