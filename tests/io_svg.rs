//! SVG pictures: y up, every triangle coloured by its smallest angle with a legend, zoom
//! windows clip, titles are escaped, and 100k triangles stay small.

use std::path::{Path, PathBuf};

use hexmesh::io::{write_svg, SvgOptions};
use hexmesh::TriMesh;

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("io_svg");
    std::fs::create_dir_all(&dir).expect("dir");
    dir.join(name)
}

/// An n × n grid of unit squares split into two triangles each, its interior vertices
/// pushed around deterministically so that the angles vary.
fn jittered_grid(n: usize) -> TriMesh {
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let interior = i > 0 && j > 0 && i < n && j < n;
            let (dx, dy) = if interior {
                let h = (i * 7919 + j * 104_729) % 1000;
                (
                    (h as f64 / 1000.0 - 0.5) * 0.6,
                    ((h * 31 % 1000) as f64 / 1000.0 - 0.5) * 0.6,
                )
            } else {
                (0.0, 0.0)
            };
            vertices.push([i as f64 + dx, j as f64 + dy]);
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    TriMesh {
        vertices,
        triangles,
    }
}

/// The numbers of SVG path data, where a minus sign also separates numbers.
fn numbers(d: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut current = String::new();
    for c in d.chars() {
        if c.is_ascii_digit() || c == '.' {
            current.push(c);
            continue;
        }
        if !current.is_empty() && current != "-" {
            out.push(current.parse().expect("number"));
        }
        current.clear();
        if c == '-' {
            current.push(c);
        }
    }
    out
}

fn paths(svg: &str) -> usize {
    svg.matches("<path ").count()
}

/// Number of triangles drawn: each starts its subpath with 'M'.
fn drawn(svg: &str) -> usize {
    svg.lines()
        .filter(|l| l.starts_with("<path "))
        .map(|l| l.matches('M').count())
        .sum()
}

#[test]
fn every_triangle_is_drawn_once_with_a_legend() {
    let mesh = jittered_grid(6);
    let path = scratch("grid.svg");
    let opts = SvgOptions {
        title: Some("grid <6×6> & jitter".to_string()),
        highlight: mesh.vertices.clone(),
        ..SvgOptions::default()
    };
    write_svg(&path, &mesh, &opts).expect("svg");
    let svg = std::fs::read_to_string(&path).expect("read");
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(drawn(&svg), mesh.triangles.len());
    assert!(paths(&svg) > 1, "angles vary, so colours must too");
    assert!(svg.contains("grid &lt;6×6&gt; &amp; jitter"));
    assert!(svg.contains("linearGradient") && svg.contains("60°"));
    assert_eq!(svg.matches("<circle ").count(), mesh.vertices.len());
}

#[test]
fn y_points_up() {
    // One triangle whose apex is high in mesh coordinates must be high in the picture,
    // which in SVG means a small y.
    let mesh = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]],
        triangles: vec![[0, 1, 2]],
    };
    let path = scratch("up.svg");
    write_svg(&path, &mesh, &SvgOptions::default()).expect("svg");
    let svg = std::fs::read_to_string(&path).expect("read");
    let d = svg
        .lines()
        .find(|l| l.starts_with("<path "))
        .and_then(|l| l.split("d=\"").nth(1))
        .expect("path data");
    // "Mx0 y0l dx1 dy1 dx2 dy2z": absolute first corner, then relative moves.
    let v = numbers(d);
    assert_eq!(v.len(), 6, "{d}");
    let ys = [v[1], v[1] + v[3], v[1] + v[3] + v[5]];
    assert_eq!(ys.len(), 3);
    assert!(ys[2] < ys[0] && ys[2] < ys[1], "{ys:?}");
}

#[test]
fn a_zoom_window_draws_only_the_triangles_it_meets_and_clips() {
    let mesh = jittered_grid(20);
    let path = scratch("zoom.svg");
    let opts = SvgOptions {
        zoom: Some([2.0, 2.0, 4.0, 4.0]),
        ..SvgOptions::default()
    };
    write_svg(&path, &mesh, &opts).expect("svg");
    let svg = std::fs::read_to_string(&path).expect("read");
    let n = drawn(&svg);
    assert!(n > 8 && n < 60, "{n} triangles drawn for a 2×2 window");
    assert!(svg.contains("clip-path=\"url(#plot)\""));
}

#[test]
fn a_bad_zoom_window_or_mesh_is_an_error_not_a_panic() {
    let mesh = jittered_grid(2);
    let path = scratch("bad.svg");
    for zoom in [[1.0, 0.0, 0.0, 1.0], [0.0, 0.0, f64::NAN, 1.0]] {
        let opts = SvgOptions {
            zoom: Some(zoom),
            ..SvgOptions::default()
        };
        assert!(write_svg(&path, &mesh, &opts).is_err(), "{zoom:?}");
    }
    let broken = TriMesh {
        vertices: vec![[0.0, 0.0]],
        triangles: vec![[0, 1, 2]],
    };
    assert!(write_svg(&path, &broken, &SvgOptions::default()).is_err());
    let empty = TriMesh::default();
    write_svg(&scratch("empty.svg"), &empty, &SvgOptions::default()).expect("empty mesh");
}

#[test]
fn a_hundred_thousand_triangles_stay_under_four_megabytes() {
    let mesh = jittered_grid(224);
    assert!(mesh.triangles.len() > 100_000);
    let path = scratch("large.svg");
    write_svg(&path, &mesh, &SvgOptions::default()).expect("svg");
    let bytes = std::fs::metadata(&path).expect("size").len();
    assert!(bytes < 4_000_000, "{bytes} bytes");
}

#[test]
fn a_deep_zoom_keeps_every_coordinate_inside_the_picture() {
    // A window a millionth of the triangle's size: unclipped, the corners would sit ~1e9 px
    // away, beyond what float32 renderers can place.
    let mesh = TriMesh {
        vertices: vec![[-1000.0, -1000.0], [1000.0, -1000.0], [0.0, 1000.0]],
        triangles: vec![[0, 1, 2]],
    };
    let path = scratch("deep.svg");
    let opts = SvgOptions {
        zoom: Some([0.0, 0.0, 1e-3, 1e-3]),
        ..SvgOptions::default()
    };
    write_svg(&path, &mesh, &opts).expect("svg");
    let svg = std::fs::read_to_string(&path).expect("read");
    let d = svg
        .lines()
        .find(|l| l.starts_with("<path "))
        .and_then(|l| l.split("d=\"").nth(1))
        .expect("path data");
    let v = numbers(d);
    let (mut x, mut y) = (v[0], v[1]);
    for step in v[2..].chunks(2) {
        assert!(
            (0.0..=800.0).contains(&x) && (0.0..=900.0).contains(&y),
            "({x}, {y})"
        );
        x += step[0];
        y += step[1];
    }
    assert!(
        (0.0..=800.0).contains(&x) && (0.0..=900.0).contains(&y),
        "({x}, {y})"
    );
}
