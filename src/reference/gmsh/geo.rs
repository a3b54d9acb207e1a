//! The domain as a script of Gmsh's built-in geometry kernel (a `.geo` file): one point per
//! domain point with its mesh size, one line per segment, and for each region the segments
//! bound a plane surface whose outer curve loop and hole loops are those segments, with the
//! segments inside the region embedded as curves and the isolated points as points.
//!
//! The regions are found the way every other mesher here finds the domain (Triangle's
//! convention): the constrained Delaunay triangulation of the domain without the triangles
//! outside the segments or in holes (`refine::domain_cdt`); its triangles connected across
//! edges that are not segments form one region each. A region's boundary is walked with the
//! region on the left: counter-clockwise loops are outer boundaries, clockwise ones holes.

use std::collections::HashMap;
use std::fmt::Write as _;

use hexmesh_core::internals::refine::domain_cdt;

use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};

/// The script, and the number of points it declares (tags 1..=points).
pub(super) struct Script {
    pub text: String,
    pub points: Vec<[f64; 2]>,
}

/// A region of the domain: its loops (outer first) as directed vertex cycles, and the segments
/// and points inside it.
#[derive(Debug, Default)]
struct Region {
    loops: Vec<Vec<u32>>,
    embedded_segments: Vec<usize>,
    embedded_points: Vec<u32>,
}

/// The `.geo` script of `input`'s domain (`Pslg::reference_domain`). The mesh size at a point
/// is the length of its shortest edge in the domain's triangulation (its nearest neighbour
/// along the domain), at most `max_edge` when given.
pub(super) fn script(input: &Pslg, max_edge: Option<f64>, options: &str) -> Result<Script> {
    let (mesh, segments) = domain_cdt(input, super::NAME)?;
    let regions = regions(&mesh, &segments)?;
    let sizes = sizes(&mesh, max_edge);

    let mut text = String::with_capacity(64 * mesh.vertices.len() + 1024);
    text.push_str(options);
    for (k, (p, h)) in mesh.vertices.iter().zip(&sizes).enumerate() {
        // `{:?}` writes the shortest decimal that reads back to the same f64.
        let _ = writeln!(
            text,
            "Point({}) = {{{:?}, {:?}, 0, {:?}}};",
            k + 1,
            p[0],
            p[1],
            h
        );
    }
    for (k, s) in segments.iter().enumerate() {
        let _ = writeln!(text, "Line({}) = {{{}, {}}};", k + 1, s[0] + 1, s[1] + 1);
    }
    let line_of: HashMap<(u32, u32), i64> = segments
        .iter()
        .enumerate()
        .flat_map(|(k, s)| {
            let tag = k as i64 + 1;
            [((s[0], s[1]), tag), ((s[1], s[0]), -tag)]
        })
        .collect();
    let mut loop_tag = 0;
    for (f, region) in regions.iter().enumerate() {
        let surface = f + 1;
        let mut loop_tags = Vec::with_capacity(region.loops.len());
        for cycle in &region.loops {
            loop_tag += 1;
            let lines: Vec<String> = (0..cycle.len())
                .map(|i| line_of[&(cycle[i], cycle[(i + 1) % cycle.len()])].to_string())
                .collect();
            let _ = writeln!(text, "Curve Loop({loop_tag}) = {{{}}};", lines.join(", "));
            loop_tags.push(loop_tag.to_string());
        }
        let _ = writeln!(
            text,
            "Plane Surface({surface}) = {{{}}};",
            loop_tags.join(", ")
        );
        if !region.embedded_segments.is_empty() {
            let tags: Vec<String> = region
                .embedded_segments
                .iter()
                .map(|k| (k + 1).to_string())
                .collect();
            let _ = writeln!(
                text,
                "Curve{{{}}} In Surface{{{surface}}};",
                tags.join(", ")
            );
        }
        if !region.embedded_points.is_empty() {
            let tags: Vec<String> = region
                .embedded_points
                .iter()
                .map(|v| (v + 1).to_string())
                .collect();
            let _ = writeln!(
                text,
                "Point{{{}}} In Surface{{{surface}}};",
                tags.join(", ")
            );
        }
    }
    Ok(Script {
        text,
        points: mesh.vertices,
    })
}

/// The shortest edge at each vertex of `mesh`, at most `max_edge`.
fn sizes(mesh: &TriMesh, max_edge: Option<f64>) -> Vec<f64> {
    let mut h = vec![max_edge.unwrap_or(f64::INFINITY); mesh.vertices.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let (p, q) = (mesh.vertices[a], mesh.vertices[b]);
            let d = (p[0] - q[0]).hypot(p[1] - q[1]);
            h[a] = h[a].min(d);
            h[b] = h[b].min(d);
        }
    }
    h
}

/// The regions of the carved triangulation `mesh` whose `segments` are the domain's (in mesh
/// numbering), in the order of their first triangle.
fn regions(mesh: &TriMesh, segments: &[[u32; 2]]) -> Result<Vec<Region>> {
    let n = mesh.triangles.len();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let segment_of: HashMap<(u32, u32), usize> = segments
        .iter()
        .enumerate()
        .map(|(k, s)| (key(s[0], s[1]), k))
        .collect();
    let mut triangle_of: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * n);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            triangle_of.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }

    // Triangles connected across edges that are not segments.
    let mut region_of = vec![usize::MAX; n];
    let mut count = 0;
    for start in 0..n {
        if region_of[start] != usize::MAX {
            continue;
        }
        region_of[start] = count;
        let mut stack = vec![start];
        while let Some(t) = stack.pop() {
            let tri = mesh.triangles[t];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if segment_of.contains_key(&key(a, b)) {
                    continue;
                }
                if let Some(&u) = triangle_of.get(&(b, a)) {
                    if region_of[u] == usize::MAX {
                        region_of[u] = count;
                        stack.push(u);
                    }
                }
            }
        }
        count += 1;
    }
    let mut regions: Vec<Region> = (0..count).map(|_| Region::default()).collect();

    // A directed edge (a, b) of a triangle bounds its region when it is a segment with another
    // region, or nothing, on its right.
    let region_at = |a: u32, b: u32| triangle_of.get(&(a, b)).map(|&t| region_of[t]);
    let bounds =
        |a: u32, b: u32| segment_of.contains_key(&key(a, b)) && region_at(b, a) != region_at(a, b);
    for (k, s) in segments.iter().enumerate() {
        match (region_at(s[0], s[1]), region_at(s[1], s[0])) {
            (Some(r), Some(q)) if r == q => regions[r].embedded_segments.push(k),
            _ => {}
        }
    }

    // Walk each boundary edge's loop once: from (a, b), turn clockwise around b through the
    // region's triangles until the next boundary edge leaving b.
    let mut walked: HashMap<(u32, u32), ()> = HashMap::new();
    let mut outer_loops = vec![0usize; count];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if !bounds(a, b) || walked.contains_key(&(a, b)) {
                continue;
            }
            let r = region_of[t];
            let mut cycle = Vec::new();
            let (mut a, mut b) = (a, b);
            loop {
                walked.insert((a, b), ());
                cycle.push(a);
                let mut t = triangle_of[&(a, b)];
                let next = loop {
                    let tri = mesh.triangles[t];
                    let i = tri.iter().position(|&v| v == b).expect("b is a corner");
                    let c = tri[(i + 1) % 3];
                    if bounds(b, c) {
                        break c;
                    }
                    t = triangle_of[&(c, b)];
                };
                (a, b) = (b, next);
                if walked.contains_key(&(a, b)) {
                    break;
                }
            }
            if signed_area(&mesh.vertices, &cycle) > 0.0 {
                outer_loops[r] += 1;
                regions[r].loops.insert(0, cycle);
            } else {
                regions[r].loops.push(cycle);
            }
        }
    }
    if let Some(r) = outer_loops.iter().position(|&k| k != 1) {
        return Err(Error::mesher(
            super::NAME,
            format!(
                "region {} of the domain has {} outer boundaries; Gmsh's plane surface needs one",
                r + 1,
                outer_loops[r]
            ),
        ));
    }

    // Points on no segment, each in the region of its triangles.
    let mut on_segment = vec![false; mesh.vertices.len()];
    for s in segments {
        on_segment[s[0] as usize] = true;
        on_segment[s[1] as usize] = true;
    }
    let mut seen = vec![false; mesh.vertices.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            if !on_segment[v as usize] && !seen[v as usize] {
                seen[v as usize] = true;
                regions[region_of[t]].embedded_points.push(v);
            }
        }
    }
    for region in &mut regions {
        region.embedded_points.sort_unstable();
    }
    Ok(regions)
}

/// Twice the signed area of the polygon `cycle` (positive when counter-clockwise).
fn signed_area(vertices: &[[f64; 2]], cycle: &[u32]) -> f64 {
    let n = cycle.len();
    (0..n)
        .map(|i| {
            let p = vertices[cycle[i] as usize];
            let q = vertices[cycle[(i + 1) % n] as usize];
            p[0] * q[1] - p[1] * q[0]
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_with_hole() -> Pslg {
        Pslg {
            points: vec![
                [0.0, 0.0],
                [4.0, 0.0],
                [4.0, 4.0],
                [0.0, 4.0],
                [1.0, 1.0],
                [2.0, 1.0],
                [2.0, 2.0],
                [1.0, 2.0],
                [3.0, 3.0],
            ],
            segments: vec![
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [4, 5],
                [5, 6],
                [6, 7],
                [7, 4],
            ],
            holes: vec![[1.5, 1.5]],
            ..Pslg::default()
        }
    }

    #[test]
    fn a_square_with_a_hole_is_one_surface_with_an_outer_and_a_hole_loop() {
        let s = script(&square_with_hole(), None, "").unwrap();
        assert_eq!(s.points.len(), 9);
        assert!(
            s.text.contains("Curve Loop(1) = {1, 2, 3, 4};"),
            "{}",
            s.text
        );
        // The hole is walked with the region on its left: clockwise, lines reversed.
        assert!(s.text.contains("Curve Loop(2) = {"), "{}", s.text);
        assert!(s.text.contains("Plane Surface(1) = {1, 2};"), "{}", s.text);
        assert!(s.text.contains("Point{9} In Surface{1};"), "{}", s.text);
        assert!(!s.text.contains("Plane Surface(2)"), "{}", s.text);
    }

    #[test]
    fn an_enclosed_square_is_a_surface_of_its_own_and_a_dangling_segment_is_embedded() {
        let mut p = square_with_hole();
        p.holes.clear();
        // The inner square is now a region of its own; a segment from its corner inward.
        p.points.push([3.0, 1.0]);
        p.segments.push([8, 9]);
        let s = script(&p, None, "").unwrap();
        assert!(s.text.contains("Plane Surface(2)"), "{}", s.text);
        assert!(s.text.contains("Curve{9} In Surface{"), "{}", s.text);
    }

    #[test]
    fn the_size_is_the_shortest_edge_at_a_point_capped_by_the_largest_edge_asked() {
        let s = script(&square_with_hole(), Some(0.5), "").unwrap();
        assert!(
            s.text.contains("Point(1) = {0.0, 0.0, 0, 0.5};"),
            "{}",
            s.text
        );
        let s = script(&square_with_hole(), None, "").unwrap();
        // The corner (4, 4) is 1.4142... from (3, 3).
        assert!(
            s.text
                .contains(&format!("Point(3) = {{4.0, 4.0, 0, {:?}}};", 2f64.sqrt())),
            "{}",
            s.text
        );
    }
}
