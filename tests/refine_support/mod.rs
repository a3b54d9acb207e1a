//! Checks shared by the refine tests: mesh validity, exact Delaunay violations, input points
//! as vertices, segment chains, and the inputs the tests mesh. Written against the exchange
//! types only, so they judge the meshers independently of the meshers' own bookkeeping.
#![allow(dead_code)]

use std::collections::{HashMap, HashSet};

use hexmesh::geom::{dist, incircle, orient2d};
use hexmesh::{Point, Pslg, TriMesh};

/// Every triangle counter-clockwise with positive area (exact), every directed edge used once,
/// no duplicate vertices, every vertex used. The first problem found, or Ok.
pub fn validate(mesh: &TriMesh) -> Result<(), String> {
    let n = mesh.vertices.len();
    let mut directed = HashSet::new();
    let mut used = vec![false; n];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= n) {
            return Err(format!("triangle {t} names a missing vertex"));
        }
        let [a, b, c] = mesh.corners(t);
        if orient2d(a, b, c) <= 0.0 {
            return Err(format!("triangle {t} {tri:?} is not counter-clockwise"));
        }
        for k in 0..3 {
            used[tri[k] as usize] = true;
            if !directed.insert((tri[k], tri[(k + 1) % 3])) {
                return Err(format!("edge {}->{} used twice", tri[k], tri[(k + 1) % 3]));
            }
        }
    }
    if let Some(v) = used.iter().position(|u| !u) {
        return Err(format!("vertex {v} is used by no triangle"));
    }
    let mut seen = HashSet::new();
    for (i, p) in mesh.vertices.iter().enumerate() {
        if !seen.insert([p[0].to_bits(), p[1].to_bits()]) {
            return Err(format!("vertex {i} at {p:?} is a duplicate"));
        }
    }
    Ok(())
}

/// Interior edges whose opposite vertex lies strictly inside the circumcircle (exact test).
pub fn delaunay_violations(mesh: &TriMesh) -> usize {
    let mut by_edge: HashMap<(u32, u32), u32> = HashMap::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            by_edge.insert((tri[k], tri[(k + 1) % 3]), tri[(k + 2) % 3]);
        }
    }
    let p = |v: u32| mesh.vertices[v as usize];
    by_edge
        .iter()
        .filter(|(&(a, b), &c)| {
            a < b
                && by_edge
                    .get(&(b, a))
                    .is_some_and(|&d| incircle(p(a), p(b), p(c), p(d)) > 0.0)
        })
        .count()
}

/// The set of undirected mesh edges.
pub fn edges(mesh: &TriMesh) -> HashSet<(u32, u32)> {
    mesh.triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect()
}

/// Index of the vertex bit-identical to `p`.
pub fn vertex_of(mesh: &TriMesh, p: Point) -> Option<u32> {
    mesh.vertices
        .iter()
        .position(|q| q[0].to_bits() == p[0].to_bits() && q[1].to_bits() == p[1].to_bits())
        .map(|i| i as u32)
}

/// Checks that `chain` represents segment ab: it starts at a and ends at b bit-exactly, every
/// consecutive pair is a mesh edge, and the inner vertices advance along ab while staying within
/// `tol` (relative to the coordinates' magnitude) of the segment's line. Returns the largest
/// deviation from the line, relative to that magnitude.
pub fn check_chain(
    mesh: &TriMesh,
    chain: &[u32],
    a: Point,
    b: Point,
    tol: f64,
) -> Result<f64, String> {
    let e = edges(mesh);
    let v = |i: u32| mesh.vertices[i as usize];
    if chain.len() < 2 {
        return Err("chain shorter than two vertices".into());
    }
    if v(chain[0]) != a || v(*chain.last().unwrap_or(&0)) != b {
        return Err(format!(
            "chain ends {:?}..{:?} are not {a:?}..{b:?}",
            v(chain[0]),
            v(chain[chain.len() - 1])
        ));
    }
    let scale = a[0]
        .abs()
        .max(a[1].abs())
        .max(b[0].abs())
        .max(b[1].abs())
        .max(dist(a, b));
    let len = dist(a, b);
    let mut last_t = -1.0;
    let mut worst: f64 = 0.0;
    for w in chain.windows(2) {
        if !e.contains(&(w[0].min(w[1]), w[0].max(w[1]))) {
            return Err(format!("chain piece {}-{} is not a mesh edge", w[0], w[1]));
        }
    }
    for &i in chain {
        let p = v(i);
        let dev = orient2d(a, b, p).abs() / len / scale;
        worst = worst.max(dev);
        if dev > tol {
            return Err(format!(
                "chain vertex {i} at {p:?} is {dev:e} off the segment"
            ));
        }
        let t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / (len * len);
        if t <= last_t {
            return Err(format!(
                "chain vertex {i} does not advance along the segment"
            ));
        }
        last_t = t;
    }
    Ok(worst)
}

/// Signed area of a polygon given by its vertices.
pub fn polygon_area(p: &[Point]) -> f64 {
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        / 2.0
}

/// Appends a closed polygon to `pslg`.
pub fn add_loop(pslg: &mut Pslg, pts: &[Point]) {
    let base = pslg.points.len() as u32;
    let n = pts.len() as u32;
    pslg.points.extend_from_slice(pts);
    pslg.segments
        .extend((0..n).map(|i| [base + i, base + (i + 1) % n]));
}

/// The unit square with a square hole [0.4, 0.6]².
pub fn square_with_hole() -> Pslg {
    let mut p = Pslg::default();
    add_loop(&mut p, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    add_loop(&mut p, &[[0.4, 0.4], [0.4, 0.6], [0.6, 0.6], [0.6, 0.4]]);
    p.holes.push([0.5, 0.5]);
    p
}

/// A polygon with an interior slit: a segment from a boundary vertex into the interior.
pub fn polygon_with_slit() -> Pslg {
    let mut p = Pslg::default();
    add_loop(
        &mut p,
        &[
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 0.5],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.0, 0.3],
        ],
    );
    p.points.push([0.3, 0.52]);
    p.segments.push([2, 6]);
    p
}

/// A deterministic pseudo-random point set in the unit square (a small LCG, so the tests do
/// not depend on a generator's version).
pub fn random_points(n: usize, seed: u64) -> Vec<Point> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| [next(), next()]).collect()
}

/// A random PSLG in the unit square: the square's outline, `n` random interior points, and
/// up to `tries` random segments between them, each kept only if the input check accepts it
/// (no crossing, no overlap, no point inside a segment). Dangling segments, chains and
/// closed cycles all occur. With `hole`, the square [0.4, 0.6]² is a hole (points inside it
/// are left out: they would lie outside the domain).
pub fn random_pslg(seed: u64, n: usize, tries: usize, hole: bool) -> Pslg {
    let mut u = random_points(2 * n + 2 * tries, seed).into_iter().flatten();
    let mut next = move || u.next().unwrap_or(0.5);
    let mut p = Pslg::default();
    add_loop(&mut p, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    if hole {
        add_loop(&mut p, &[[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]]);
        p.holes.push([0.5, 0.5]);
    }
    for _ in 0..n {
        let q = [0.01 + 0.98 * next(), 0.01 + 0.98 * next()];
        if hole && (0.39..0.61).contains(&q[0]) && (0.39..0.61).contains(&q[1]) {
            continue;
        }
        p.points.push(q);
        if p.check().is_err() {
            p.points.pop();
        }
    }
    let m = p.points.len();
    for _ in 0..tries {
        let a = ((next() * m as f64) as usize).min(m - 1) as u32;
        let b = ((next() * m as f64) as usize).min(m - 1) as u32;
        if a == b {
            continue;
        }
        // A segment between two of the hole's corners would cut the hole and put its seed
        // on a segment: which side is removed would then be up to the mesher.
        let mid = [
            (p.points[a as usize][0] + p.points[b as usize][0]) / 2.0,
            (p.points[a as usize][1] + p.points[b as usize][1]) / 2.0,
        ];
        if hole && (0.4..=0.6).contains(&mid[0]) && (0.4..=0.6).contains(&mid[1]) {
            continue;
        }
        p.segments.push([a, b]);
        if p.check().is_err() {
            p.segments.pop();
        }
    }
    p
}

/// A fan of `k` segments from (0.1, 0.1) inside the square [0, 2]², consecutive ones `deg`
/// degrees apart: input angles as small as f64 lets them be.
pub fn fan(k: usize, deg: f64) -> Pslg {
    let mut p = Pslg::default();
    add_loop(&mut p, &[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    let o = p.points.len() as u32;
    p.points.push([0.1, 0.1]);
    for i in 0..k {
        let t = (10.0 + i as f64 * deg).to_radians();
        p.points.push([0.1 + 1.8 * t.cos(), 0.1 + 1.8 * t.sin()]);
        p.segments.push([o, o + 1 + i as u32]);
    }
    p
}

/// Collinear points and segments: points on the line y = 0.3 inside the unit square, every
/// other gap a segment, plus points on the same line's extension outside the segments and
/// a column of collinear points on x = 0.7 crossing nothing.
pub fn collinear_pslg(k: usize) -> Pslg {
    let mut p = Pslg::default();
    add_loop(&mut p, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let base = p.points.len() as u32;
    for i in 0..k {
        p.points.push([0.05 + 0.6 * i as f64 / k as f64, 0.3]);
    }
    for i in (0..k.saturating_sub(1)).step_by(2) {
        p.segments.push([base + i as u32, base + i as u32 + 1]);
    }
    for i in 0..k {
        p.points.push([0.7, 0.05 + 0.9 * i as f64 / k as f64]);
    }
    p
}

/// The smallest angle, in degrees, between two segments of `p` that share an endpoint
/// (180° when no two do).
pub fn smallest_segment_angle(p: &Pslg) -> f64 {
    let mut best: f64 = 180.0;
    for (i, s) in p.segments.iter().enumerate() {
        for t in &p.segments[i + 1..] {
            let Some(&apex) = s.iter().find(|v| t.contains(v)) else {
                continue;
            };
            let other = |x: &[u32; 2]| if x[0] == apex { x[1] } else { x[0] };
            let (o, a, b) = (
                p.points[apex as usize],
                p.points[other(s) as usize],
                p.points[other(t) as usize],
            );
            let (u, v) = ([a[0] - o[0], a[1] - o[1]], [b[0] - o[0], b[1] - o[1]]);
            let ang = (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(u[0] * v[0] + u[1] * v[1])
                .to_degrees();
            best = best.min(ang);
        }
    }
    best
}

/// The input's smallest feature, relative: the smallest of the angles between segments that
/// share an endpoint (radians) and the distances from a point to a segment it is not on,
/// over that segment's length.
pub fn smallest_feature(p: &Pslg) -> f64 {
    let mut f = smallest_segment_angle(p).to_radians();
    for (i, &q) in p.points.iter().enumerate() {
        for s in &p.segments {
            if s.contains(&(i as u32)) {
                continue;
            }
            let (a, b) = (p.points[s[0] as usize], p.points[s[1] as usize]);
            let l = dist(a, b);
            let t = ((q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1])) / (l * l);
            let d = if t <= 0.0 {
                dist(q, a)
            } else if t >= 1.0 {
                dist(q, b)
            } else {
                orient2d(a, b, q).abs() / l
            };
            f = f.min(d / l);
        }
    }
    f
}
