//! The PSLG examples (`datasets::pslg_examples`) are valid inputs with the features their names
//! claim: a 5° input angle, hole seeds inside holes, a slit inside the domain, three nested
//! squares with the middle ring a hole, many short segments beside long ones; the areas they
//! state are the areas their loops bound; they resolve by name and mesh by name.

use std::collections::HashMap;

use hexmesh::datasets::{self, PslgExample, PSLG_EXAMPLES, SHORT_PIECES, WEDGE_DEG};
use hexmesh::quality::verdict;
use hexmesh::{Params, Point, Pslg};

fn example(name: &str) -> PslgExample {
    datasets::pslg_example(name).unwrap_or_else(|| panic!("no example {name}"))
}

/// The closed loops of `p`: chains of segments through vertices of degree two, as vertex
/// lists. Vertices of another degree (a slit's ends) start no loop.
fn loops(p: &Pslg) -> Vec<Vec<usize>> {
    let mut adjacent: HashMap<usize, Vec<usize>> = HashMap::new();
    for s in &p.segments {
        let (a, b) = (s[0] as usize, s[1] as usize);
        adjacent.entry(a).or_default().push(b);
        adjacent.entry(b).or_default().push(a);
    }
    let mut seen = vec![false; p.points.len()];
    let mut out = Vec::new();
    for start in 0..p.points.len() {
        if seen[start] || adjacent.get(&start).map(Vec::len) != Some(2) {
            continue;
        }
        let (mut prev, mut at) = (start, adjacent[&start][0]);
        let mut chain = vec![start];
        seen[start] = true;
        while at != start {
            let next = adjacent[&at].iter().copied().find(|&n| n != prev);
            assert_eq!(adjacent[&at].len(), 2, "vertex {at} ends a chain");
            chain.push(at);
            seen[at] = true;
            (prev, at) = (at, next.expect("a vertex of degree two"));
        }
        out.push(chain);
    }
    out
}

fn polygon(p: &Pslg, l: &[usize]) -> Vec<Point> {
    l.iter().map(|&i| p.points[i]).collect()
}

fn shoelace(poly: &[Point]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        / 2.0
}

/// Even-odd test; `q` must not lie on the polygon's boundary.
fn inside(poly: &[Point], q: Point) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if q[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// How many loops of `p` contain `q` (a point on no loop).
fn depth(p: &Pslg, q: Point) -> usize {
    loops(p)
        .iter()
        .filter(|l| inside(&polygon(p, l), q))
        .count()
}

/// Each loop as a polygon with the number of other loops around it (loops never touch, so
/// testing one vertex decides).
fn nesting(p: &Pslg) -> Vec<(Vec<Point>, usize)> {
    let polys: Vec<Vec<Point>> = loops(p).iter().map(|l| polygon(p, l)).collect();
    polys
        .iter()
        .enumerate()
        .map(|(i, poly)| {
            let around = polys
                .iter()
                .enumerate()
                .filter(|&(j, other)| j != i && inside(other, poly[0]))
                .count();
            (poly.clone(), around)
        })
        .collect()
}

/// The smallest angle between two segments meeting at a vertex, in degrees, and the vertex.
fn smallest_input_angle(p: &Pslg) -> Option<(f64, usize)> {
    let mut around: HashMap<usize, Vec<f64>> = HashMap::new();
    for s in &p.segments {
        for (a, b) in [(s[0], s[1]), (s[1], s[0])] {
            let (pa, pb) = (p.points[a as usize], p.points[b as usize]);
            around
                .entry(a as usize)
                .or_default()
                .push((pb[1] - pa[1]).atan2(pb[0] - pa[0]).to_degrees());
        }
    }
    let mut best: Option<(f64, usize)> = None;
    for (v, mut dirs) in around {
        if dirs.len() < 2 {
            continue;
        }
        dirs.sort_by(f64::total_cmp);
        let n = dirs.len();
        for i in 0..n {
            let gap = if i + 1 < n {
                dirs[i + 1] - dirs[i]
            } else {
                dirs[0] + 360.0 - dirs[n - 1]
            };
            if best.is_none_or(|(b, _)| gap < b) {
                best = Some((gap, v));
            }
        }
    }
    best
}

#[test]
fn every_pslg_example_is_a_valid_input_with_segments() {
    let all = datasets::pslg_examples();
    assert_eq!(all.len(), PSLG_EXAMPLES.len());
    for e in &all {
        assert_eq!(e.pslg.check(), Ok(()), "{}", e.name);
        assert!(e.pslg.has_segments(), "{}", e.name);
        assert!(e.area > 0.0, "{}", e.name);
    }
    assert_eq!(all, datasets::pslg_examples(), "the same bits every time");
}

#[test]
fn the_wedge_has_a_five_degree_input_angle_and_the_others_none_below_thirty() {
    let w = example("pslg-wedge-5");
    let (angle, at) = smallest_input_angle(&w.pslg).expect("segments meet");
    assert!((angle - WEDGE_DEG).abs() < 1e-12, "{angle}");
    assert_eq!(w.pslg.points[at], [0.0, 0.0], "the apex is at the origin");
    for e in datasets::pslg_examples()
        .iter()
        .filter(|e| e.name != "pslg-wedge-5")
    {
        let (a, _) = smallest_input_angle(&e.pslg).expect("segments meet");
        assert!(a >= 30.0, "{}: {a}°", e.name);
    }
}

#[test]
fn every_hole_seed_lies_inside_a_hole_and_the_stated_area_is_what_the_loops_bound() {
    for e in datasets::pslg_examples() {
        let p = &e.pslg;
        // With nested simple loops, a point inside an odd number of them is in the domain,
        // one inside an even number is not: inside none it is outside, inside two or more in
        // a hole. A seed must be in a hole.
        for (i, &h) in p.holes.iter().enumerate() {
            let d = depth(p, h);
            assert!(d >= 2 && d % 2 == 0, "{}: seed {i} at depth {d}", e.name);
        }
        // So a loop inside an even number of others bounds domain, one inside an odd number
        // bounds a hole.
        let area: f64 = nesting(p)
            .iter()
            .map(|(poly, around)| {
                let sign = if around % 2 == 0 { 1.0 } else { -1.0 };
                sign * shoelace(poly).abs()
            })
            .sum();
        assert!(
            (area - e.area).abs() < 1e-12,
            "{}: {area} vs {}",
            e.name,
            e.area
        );
    }
    let holes = example("pslg-holes");
    assert_eq!(holes.pslg.holes.len(), 2);
    let [outer, square, triangle] = <[Vec<usize>; 3]>::try_from(loops(&holes.pslg)).unwrap();
    assert_eq!((outer.len(), square.len(), triangle.len()), (6, 4, 3));
    let (sq, tr) = (
        polygon(&holes.pslg, &square),
        polygon(&holes.pslg, &triangle),
    );
    assert!(inside(&sq, holes.pslg.holes[0]) && !inside(&tr, holes.pslg.holes[0]));
    assert!(inside(&tr, holes.pslg.holes[1]) && !inside(&sq, holes.pslg.holes[1]));
    // The L has a reflex corner: one vertex turns clockwise on a counter-clockwise outline.
    let l = polygon(&holes.pslg, &outer);
    let reflex = (0..l.len())
        .filter(|&i| {
            let (a, b, c) = (l[(i + l.len() - 1) % l.len()], l[i], l[(i + 1) % l.len()]);
            hexmesh::geom::orient2d(a, b, c) < 0.0
        })
        .count();
    assert_eq!(reflex, 1);
}

#[test]
fn nested_is_three_squares_each_inside_the_next_with_the_middle_ring_seeded() {
    let n = example("pslg-nested");
    let mut squares = nesting(&n.pslg);
    squares.sort_by_key(|(_, around)| *around);
    let arounds: Vec<usize> = squares.iter().map(|(_, a)| *a).collect();
    assert_eq!(arounds, [0, 1, 2], "each square inside the next");
    for (poly, _) in &squares {
        assert_eq!(poly.len(), 4, "a square");
        for i in 0..4 {
            let (a, b, c) = (poly[i], poly[(i + 1) % 4], poly[(i + 2) % 4]);
            let dot = (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]);
            let (ab, bc) = (hexmesh::geom::dist(a, b), hexmesh::geom::dist(b, c));
            assert!(dot == 0.0 && ab == bc, "{poly:?}");
        }
    }
    let (middle, inner) = (&squares[1].0, &squares[2].0);
    assert_eq!(n.pslg.holes.len(), 1);
    let seed = n.pslg.holes[0];
    assert!(
        inside(middle, seed) && !inside(inner, seed),
        "the seed is in the middle ring"
    );
}

#[test]
fn the_slit_is_one_segment_inside_the_domain_touching_no_other() {
    let s = example("pslg-slit");
    let mut degree = vec![0usize; s.pslg.points.len()];
    for seg in &s.pslg.segments {
        degree[seg[0] as usize] += 1;
        degree[seg[1] as usize] += 1;
    }
    let slits: Vec<&[u32; 2]> = s
        .pslg
        .segments
        .iter()
        .filter(|seg| degree[seg[0] as usize] == 1 && degree[seg[1] as usize] == 1)
        .collect();
    assert_eq!(slits.len(), 1, "{slits:?}");
    for &v in slits[0] {
        // Inside the one loop (the square), so in the domain, not on its boundary.
        assert_eq!(depth(&s.pslg, s.pslg.points[v as usize]), 1);
    }
    assert!(s.pslg.holes.is_empty());
    assert_eq!(s.area, 1.0);
}

#[test]
fn short_long_has_many_short_segments_meeting_long_ones() {
    let e = example("pslg-short-long");
    let p = &e.pslg;
    let length =
        |s: &[u32; 2]| hexmesh::geom::dist(p.points[s[0] as usize], p.points[s[1] as usize]);
    let longest = p.segments.iter().map(length).fold(0.0, f64::max);
    let short: Vec<&[u32; 2]> = p
        .segments
        .iter()
        .filter(|s| length(s) < longest / 50.0)
        .collect();
    assert_eq!(short.len(), SHORT_PIECES);
    let long: Vec<&[u32; 2]> = p
        .segments
        .iter()
        .filter(|s| length(s) >= longest / 2.0)
        .collect();
    assert!(long.len() >= 3, "{long:?}");
    // A short segment shares a vertex with a long one, at both ends of the sawtooth.
    let meetings = short
        .iter()
        .filter(|s| long.iter().any(|l| s.iter().any(|v| l.contains(v))))
        .count();
    assert_eq!(meetings, 2);
}

#[test]
fn every_example_resolves_by_name_and_is_written_as_a_poly_file() {
    for name in PSLG_EXAMPLES {
        assert_eq!(datasets::by_name(name).ok(), Some(example(name).pslg));
        assert_eq!(datasets::file_name(name).ok(), Some(format!("{name}.poly")));
        assert_eq!(datasets::describe(name), example(name).tests);
    }
}

/// Our mesher keeps what it promises on every example: valid, conforming, and the Sec. 6
/// bounds on the triangles that touch no segment (paper Sec. 7).
#[test]
fn hex_meshes_every_example_valid_conforming_within_its_interior_bounds() {
    use hexmesh::Mesher;
    let bounds = hexmesh::registry::bounds("hex").expect("hex bounds");
    for e in datasets::pslg_examples() {
        let run = hexmesh::hex::extended::Hex
            .mesh(&e.pslg, &Params::default())
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
        assert!(run.complete, "{}", e.name);
        let v = verdict(&run.mesh, Some(&e.pslg), Some(&bounds));
        assert!(v.passed(), "{}: {v}", e.name);
        assert!(
            (run.mesh.area() - e.area).abs() < 1e-9 * e.area,
            "{}: {} vs {}",
            e.name,
            run.mesh.area(),
            e.area
        );
    }
}
