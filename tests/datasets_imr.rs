//! The `imr` letters are a sound PSLG: every outline a simple closed loop, the letters apart,
//! and the R's hole seed inside its counter and outside the letters' material. Every sign
//! here is an exact orientation test (`geom::orient2d`).

use hexmesh::datasets;
use hexmesh::geom::orient2d;
use hexmesh::{Point, Pslg};

fn imr() -> Pslg {
    datasets::by_name("imr").expect("imr is a dataset")
}

/// The closed loops of a PSLG whose every vertex has exactly one outgoing and one incoming
/// segment, each as its vertex indices in order, or a message naming what breaks that.
fn loops(pslg: &Pslg) -> Result<Vec<Vec<usize>>, String> {
    let n = pslg.points.len();
    let mut next = vec![None; n];
    let mut incoming = vec![0usize; n];
    for (i, s) in pslg.segments.iter().enumerate() {
        let (a, b) = (s[0] as usize, s[1] as usize);
        if next[a].replace(b).is_some() {
            return Err(format!("vertex {a} starts two segments (second: {i})"));
        }
        incoming[b] += 1;
    }
    if let Some(v) = (0..n).find(|&v| incoming[v] != 1 || next[v].is_none()) {
        return Err(format!("vertex {v} is not on exactly one loop"));
    }
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    for start in 0..n {
        if seen[start] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut v = start;
        while !seen[v] {
            seen[v] = true;
            cycle.push(v);
            v = next[v].ok_or("broken loop")?;
        }
        if v != start {
            return Err(format!("the walk from {start} does not return to it"));
        }
        out.push(cycle);
    }
    Ok(out)
}

fn polygon(pslg: &Pslg, cycle: &[usize]) -> Vec<Point> {
    cycle.iter().map(|&i| pslg.points[i]).collect()
}

/// Winding number of `q` about the closed polygon, from exact orientation signs (Sunday's
/// crossing rule: upward edges with q strictly left, downward edges with q strictly right).
/// `None` when q lies on the boundary.
fn winding(poly: &[Point], q: Point) -> Option<i32> {
    let mut w = 0;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let o = orient2d(a, b, q);
        let within_x = q[0] >= a[0].min(b[0]) && q[0] <= a[0].max(b[0]);
        let within_y = q[1] >= a[1].min(b[1]) && q[1] <= a[1].max(b[1]);
        if o == 0.0 && within_x && within_y {
            return None;
        }
        if a[1] <= q[1] && b[1] > q[1] && o > 0.0 {
            w += 1;
        } else if a[1] > q[1] && b[1] <= q[1] && o < 0.0 {
            w -= 1;
        }
    }
    Some(w)
}

/// Twice the signed area (positive for counter-clockwise).
fn twice_area(poly: &[Point]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

/// True when segments ab and cd share a point (exact), endpoints included.
fn segments_touch(a: Point, b: Point, c: Point, d: Point) -> bool {
    let on = |p: Point, q: Point, r: Point| {
        orient2d(p, q, r) == 0.0
            && r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    (o1 * o2 < 0.0 && o3 * o4 < 0.0) || on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b)
}

/// A polygon is simple when no two of its edges meet except neighbours at their shared
/// corner, and no two neighbours fold back onto each other.
fn is_simple(poly: &[Point]) -> bool {
    let n = poly.len();
    let edge = |i: usize| (poly[i], poly[(i + 1) % n]);
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            if neighbours {
                // Neighbours share exactly one corner; they must not be collinear and overlap.
                let (shared, far_i, far_j) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                if orient2d(far_i, shared, far_j) == 0.0
                    && (far_j[0] - shared[0]) * (far_i[0] - shared[0])
                        + (far_j[1] - shared[1]) * (far_i[1] - shared[1])
                        > 0.0
                {
                    return false;
                }
            } else if segments_touch(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

#[test]
fn imr_passes_the_input_check() {
    assert_eq!(imr().check(), Ok(()));
}

#[test]
fn imr_is_four_simple_counter_clockwise_closed_loops() {
    let pslg = imr();
    let cycles = loops(&pslg).expect("segments form closed loops");
    assert_eq!(cycles.len(), 4, "I, M, R and the R's counter");
    for (k, cycle) in cycles.iter().enumerate() {
        let poly = polygon(&pslg, cycle);
        assert!(is_simple(&poly), "loop {k} crosses itself");
        assert!(twice_area(&poly) > 0.0, "loop {k} is not counter-clockwise");
    }
}

#[test]
fn imr_detail_rises_from_i_to_r() {
    let pslg = imr();
    let cycles = loops(&pslg).expect("loops");
    let sizes: Vec<usize> = cycles.iter().map(Vec::len).collect();
    let (i, m, r, counter) = (sizes[0], sizes[1], sizes[2], sizes[3]);
    assert!((10..=14).contains(&i), "I has {i} vertices");
    assert!((13..=20).contains(&m), "M has {m} vertices");
    assert!(i < m && m < r, "detail must rise: {sizes:?}");
    assert!(
        r - 8 >= 30,
        "the R bowl's arc has at least 30 points: {sizes:?}"
    );
    assert!(
        counter >= 30,
        "the counter's arc is sampled finely: {sizes:?}"
    );
}

#[test]
fn imr_letters_are_about_one_unit_high_and_stand_apart() {
    let pslg = imr();
    let cycles = loops(&pslg).expect("loops");
    let bbox = |cycle: &Vec<usize>| {
        let poly = polygon(&pslg, cycle);
        let xs = poly.iter().map(|p| p[0]);
        let ys = poly.iter().map(|p| p[1]);
        (
            xs.clone().fold(f64::INFINITY, f64::min),
            xs.fold(f64::NEG_INFINITY, f64::max),
            ys.clone().fold(f64::INFINITY, f64::min),
            ys.fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let boxes: Vec<_> = cycles[..3].iter().map(bbox).collect();
    for b in &boxes {
        assert!((b.3 - b.2 - 1.0).abs() < 1e-12, "height {}", b.3 - b.2);
    }
    // Left to right, with a gap: no outline of one letter can meet another's.
    assert!(
        boxes[0].1 < boxes[1].0 && boxes[1].1 < boxes[2].0,
        "{boxes:?}"
    );
    // The counter lies inside the R's box.
    let c = bbox(&cycles[3]);
    assert!(c.0 > boxes[2].0 && c.1 < boxes[2].1 && c.2 > boxes[2].2 && c.3 < boxes[2].3);
}

#[test]
fn the_r_hole_seed_is_in_the_counter_and_outside_the_material() {
    let pslg = imr();
    assert_eq!(pslg.holes.len(), 1);
    let seed = pslg.holes[0];
    let cycles = loops(&pslg).expect("loops");
    let w: Vec<Option<i32>> = cycles
        .iter()
        .map(|c| winding(&polygon(&pslg, c), seed))
        .collect();
    assert_eq!(w, [Some(0), Some(0), Some(1), Some(1)], "I, M, R, counter");
    // Material is where the winding numbers sum to an odd count.
    let total: i32 = w.iter().flatten().sum();
    assert_eq!(total % 2, 0);
}

#[test]
fn the_counter_lies_inside_the_r_material_and_touches_nothing() {
    let pslg = imr();
    let cycles = loops(&pslg).expect("loops");
    let r = polygon(&pslg, &cycles[2]);
    let counter = polygon(&pslg, &cycles[3]);
    for (k, &p) in counter.iter().enumerate() {
        assert_eq!(winding(&r, p), Some(1), "counter vertex {k}");
    }
    for i in 0..counter.len() {
        let (a, b) = (counter[i], counter[(i + 1) % counter.len()]);
        for j in 0..r.len() {
            let (c, d) = (r[j], r[(j + 1) % r.len()]);
            assert!(
                !segments_touch(a, b, c, d),
                "counter edge {i} meets R edge {j}"
            );
        }
    }
}

#[test]
fn the_winding_test_can_fail() {
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    assert_eq!(winding(&square, [0.5, 0.5]), Some(1));
    assert_eq!(winding(&square, [1.5, 0.5]), Some(0));
    assert_eq!(winding(&square, [1.0, 0.5]), None);
    let bow_tie = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
    assert!(!is_simple(&bow_tie));
    assert!(is_simple(&square));
}
