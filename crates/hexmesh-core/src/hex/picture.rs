//! Pictures of the hexagon subdivision with its dual mesh over it, in the style of paper 000
//! Figs. 3, 4 and 7: full hexagons, semi-hexagons and occupied hexagons in their own colours,
//! the dual triangles as lines, the input points as dots. For the extended refinement (`hex`)
//! every full hexagon is coloured by its class of Sec. 5.1, with a legend as in Figs. 5 and 7.

use std::fmt::Write as _;
use std::path::Path;

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::hex::classify::{classify, rings, Class};
use crate::hex::dual::{self, Placement};
use crate::hex::lattice::{FxHashMap, Key};
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

/// Meshes `input` with the extended refinement (`hex`) and writes the picture of its final
/// subdivision, each full hexagon coloured by its class of Sec. 5.1, with the relocated dual
/// over it. This is what `hexmesh mesh … --mesher hex --hexagons P.svg` calls.
pub fn write_extended_hexagons_svg(input: &Pslg, params: &Params, path: &Path) -> Result<()> {
    let (h, mesh) = if input.has_segments() {
        let run = super::pslg::mesh_pslg(input, params)?;
        (run.hierarchy, run.mesh)
    } else {
        let run = super::extended::mesh_extended(input, params)?;
        (run.hierarchy, run.mesh)
    };
    let classes = full_leaf_classes(&h);
    write_svg(path, svg(&h, &mesh, Some(&classes)))
}

/// The class of Sec. 5.1 of every full leaf of `h`, classified against the rings of its
/// occupied hexagons as they stand.
pub fn full_leaf_classes(h: &Hierarchy) -> FxHashMap<Key, Class> {
    let r = rings(h);
    h.leaves()
        .into_iter()
        .filter(|&(_, cell)| cell == (Cell::Full { subdivided: false }))
        .map(|(key, _)| (key, classify(h, &r, key).0))
        .collect()
}

/// Writes the picture of a hierarchy and a mesh (usually its dual) to `path`.
pub fn write_hierarchy_svg(h: &Hierarchy, mesh: &TriMesh, path: &Path) -> Result<()> {
    write_svg(path, hierarchy_svg(h, mesh))
}

fn write_svg(path: &Path, svg: String) -> Result<()> {
    std::fs::write(path, svg).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The fill colour of each class, and the order of the legend.
pub const CLASS_COLOURS: [(Class, &str); 10] = [
    (Class::MovedCenter1, "#9ecae1"),
    (Class::MovedCenter2, "#4292c6"),
    (Class::MovedCenter3, "#08519c"),
    (Class::Subdivide, "#000000"),
    (Class::Occupied1, "#e6550d"),
    (Class::Occupied2, "#fd8d3c"),
    (Class::FixedCenterInRing, "#a1d99b"),
    (Class::MovedCenterInRing, "#fdd0a2"),
    (Class::MovedCenter4, "#9e9ac8"),
    (Class::FixedCenterRegular, "#f2f2f2"),
];

fn class_colour(class: Class) -> &'static str {
    CLASS_COLOURS
        .iter()
        .find(|(c, _)| *c == class)
        .map_or("#ffffff", |(_, colour)| colour)
}

/// The SVG text of `write_hierarchy_svg`.
pub fn hierarchy_svg(h: &Hierarchy, mesh: &TriMesh) -> String {
    svg(h, mesh, None)
}

/// The SVG text of the picture, full hexagons coloured by `classes` when given (with a legend
/// of the classes that occur), else by occupancy.
fn svg(h: &Hierarchy, mesh: &TriMesh, classes: Option<&FxHashMap<Key, Class>>) -> String {
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
            Cell::Semi { owner, .. } => (
                semi_corners(key, owner, &corners),
                if classes.is_some() {
                    "#ffffff"
                } else {
                    "#cfe3f7"
                },
            ),
            _ => match classes.and_then(|c| c.get(&key)) {
                Some(&class) => (corners.to_vec(), class_colour(class)),
                None if h.is_occupied(key) => (corners.to_vec(), "#f7b267"),
                None => (corners.to_vec(), "#f2f2f2"),
            },
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
    let _ = writeln!(s, "</g>");
    if let Some(classes) = classes {
        legend(&mut s, classes);
    }
    let _ = writeln!(s, "</svg>");
    s
}

/// A legend in the top left corner: one swatch per class that occurs, with its count.
fn legend(s: &mut String, classes: &FxHashMap<Key, Class>) {
    let mut y = 14.0;
    let _ = writeln!(
        s,
        r#"<g font-family="DejaVu Sans, sans-serif" font-size="13">"#
    );
    for (class, colour) in CLASS_COLOURS {
        let n = classes.values().filter(|&&c| c == class).count();
        if n == 0 {
            continue;
        }
        let _ = writeln!(
            s,
            r##"<rect x="8" y="{:.0}" width="14" height="14" fill="{colour}" stroke="#555"/><text x="28" y="{:.0}">{} ({n})</text>"##,
            y - 11.0,
            y + 1.0,
            class.name()
        );
        y += 19.0;
    }
    let _ = writeln!(s, "</g>");
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
