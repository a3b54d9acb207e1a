//! Steps 8–9 of paper 001 (Sec. 4) on the triangulated quad-tree: the lattice's triangles
//! that a boundary segment touches are deleted with everything outside the domain (step 9),
//! the corners next to them are moved away from the boundary (Sec. 5.2), and what is kept
//! ends at fronts, one closed loop around each polygon, which `fill` joins to the segments.
//!
//! Moves (Sec. 5.2 case 1, generalised): a kept corner p whose nearest boundary crossing
//! along its edges (p, a) lies within half of that edge goes to the midpoint of the edge
//! (p, b) most nearly opposite (at least 150° from (p, a)); for four equal rhombs this is
//! the paper's move to (p, a_{j+3})/2. A corner with no such edge is deleted. Departure
//! (ours): at rhombs of different sizes the paper's case 2 (and its neighbours' moves) is
//! replaced by the same rule, and every kept triangle a move leaves outside [30°, 90°] is
//! deleted too, so the front recedes there. A moved corner left closer than 3/4 of its side
//! to another front corner loses its triangles as well (`drop_short_fronts`).
//!
//! A front must be a simple loop: a corner where the kept region touches itself (two front
//! edges leave it) has its triangles deleted, as have the corners `eroded` by `fill` where
//! a ladder failed, and those within `clear` lattice sides of an input corner (where `fill`
//! builds the corner's own triangles).

use crate::hex::fxhash::FxHashMap;

pub use super::input::bbox;
use super::input::{self, Domain};
use super::near::meets;
use crate::geom::{angle_deg, dist, orient2d, Point};
use crate::mesh::TriMesh;

/// The boundary segments bucketed in a uniform grid over their bounding box.
pub struct Segments {
    /// Each segment's ends and (polygon, side).
    pub ends: Vec<[Point; 2]>,
    pub owner: Vec<(usize, usize)>,
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl Segments {
    pub fn new(domain: &Domain) -> Segments {
        let mut ends = Vec::new();
        let mut owner = Vec::new();
        for (k, poly) in domain.polygons.iter().enumerate() {
            let n = poly.corners.len();
            for s in 0..n {
                let (a, b) = (poly.corners[s], poly.corners[(s + 1) % n]);
                ends.push([domain.points[a as usize], domain.points[b as usize]]);
                owner.push((k, s));
            }
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for e in &ends {
            for p in e {
                for d in 0..2 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let per_side = ((ends.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
        let cell = span / per_side as f64;
        let (nx, ny) = (
            ((hi[0] - lo[0]) / cell) as usize + 1,
            ((hi[1] - lo[1]) / cell) as usize + 1,
        );
        let mut grid = Segments {
            ends,
            owner,
            origin: lo,
            cell,
            nx,
            ny,
            cells: vec![Vec::new(); nx * ny],
        };
        for k in 0..grid.ends.len() {
            for c in grid.cells_of(bbox(&grid.ends[k])) {
                grid.cells[c].push(k as u32);
            }
        }
        grid
    }

    fn cells_of(&self, b: [f64; 4]) -> Vec<usize> {
        let index =
            |x: f64, o: f64, n: usize| (((x - o) / self.cell).floor().max(0.0) as usize).min(n - 1);
        let (x0, x1) = (
            index(b[0], self.origin[0], self.nx),
            index(b[2], self.origin[0], self.nx),
        );
        let (y0, y1) = (
            index(b[1], self.origin[1], self.ny),
            index(b[3], self.origin[1], self.ny),
        );
        if b[2] < self.origin[0] || b[3] < self.origin[1] {
            return Vec::new();
        }
        let mut out = Vec::new();
        for y in y0..=y1 {
            for x in x0..=x1 {
                out.push(y * self.nx + x);
            }
        }
        out
    }

    /// The distance from `p` to the nearest segment (every segment looked at: for the
    /// few points that ask).
    pub fn distance(&self, p: Point) -> f64 {
        self.ends
            .iter()
            .map(|&[a, b]| crate::quality::metrics::point_segment(p, a, b))
            .fold(f64::INFINITY, f64::min)
    }

    /// The segments whose cells meet the box [x0, y0, x1, y1], each once, ascending.
    pub fn near(&self, b: [f64; 4]) -> Vec<u32> {
        let mut out: Vec<u32> = self
            .cells_of(b)
            .into_iter()
            .flat_map(|c| self.cells[c].iter().copied())
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// Whether segment ab touches the closed triangle t (counter-clockwise).
pub fn touches(t: [Point; 3], a: Point, b: Point) -> bool {
    let within = |p: Point| (0..3).all(|k| orient2d(t[k], t[(k + 1) % 3], p) >= 0.0);
    within(a) || within(b) || (0..3).any(|k| meets(t[k], t[(k + 1) % 3], a, b))
}

/// What steps 8–9 keep of the lattice mesh.
pub struct Cut<'a> {
    /// Every lattice vertex, moved where Sec. 5.2 moves it.
    pub position: &'a [Point],
    /// Each lattice vertex's local side: the mean length of its edges before moving.
    pub side: &'a [f64],
    /// The kept triangles, counter-clockwise.
    pub kept: Vec<[u32; 3]>,
    /// The fronts: closed loops of lattice vertices, the kept region on the left.
    pub loops: Vec<Vec<u32>>,
}

/// A cut's kept triangles and fronts apart from the positions: moving a corner (`relax`)
/// changes neither, so its trials fill the same shape again.
pub struct Shape {
    kept: Vec<[u32; 3]>,
    loops: Vec<Vec<u32>>,
}

impl<'a> Cut<'a> {
    /// The kept triangles and fronts, the positions let go.
    pub fn into_shape(self) -> Shape {
        Shape {
            kept: self.kept,
            loops: self.loops,
        }
    }

    /// `shape` over the positions `prep` has now.
    pub fn over(prep: &'a Prepared, shape: Shape) -> Cut<'a> {
        Cut {
            position: &prep.position,
            side: &prep.side,
            kept: shape.kept,
            loops: shape.loops,
        }
    }
}

/// What does not change while `fill` erodes: the adjacency, the moves, and the triangles
/// kept before any erosion (inside the domain and untouched by it, no corner deleted, in
/// bounds after the moves, no moved corner on a short front edge: `drop_short_fronts`).
pub struct Prepared {
    edge: Edges,
    /// Per triangle and side (from corner e to e + 1), the triangle across it, or
    /// `u32::MAX`: a cut reads it three times a triangle in each pass (it looked the edges
    /// up in `edge`, a sixth of a large domain's run).
    across: Vec<[u32; 3]>,
    neighbours: Vec<Vec<u32>>,
    position: Vec<Point>,
    side: Vec<f64>,
    kept: Vec<bool>,
}

impl Prepared {
    /// Lattice vertex `v` where the cut has it (moved or not).
    pub fn position(&self, v: u32) -> Point {
        self.position[v as usize]
    }

    /// Lattice vertex `v`'s local side.
    pub fn side(&self, v: u32) -> f64 {
        self.side[v as usize]
    }

    /// Whether triangle `t` of the lattice is kept before any erosion.
    pub fn is_kept(&self, t: usize) -> bool {
        self.kept[t]
    }

    /// The lattice triangles at vertex `v` (by index, in the order of its neighbours), each
    /// found by its edge leaving `v`.
    pub fn triangles_at(&self, v: u32) -> impl Iterator<Item = usize> + '_ {
        self.neighbours[v as usize]
            .iter()
            .filter_map(move |&b| self.edge.get(v, b))
    }

    /// Moves lattice vertex `v` to `p` (`relax`, which keeps its triangles in bounds).
    pub fn relocate(&mut self, v: u32, p: Point) {
        self.position[v as usize] = p;
    }
}

/// The triangle of each directed lattice edge, by the edge's first corner (rows in
/// triangle order): a look-up scans a row of about six. It replaced a hash map of the
/// edges, whose millions of inserts and look-ups were a tenth of a large domain's run.
#[derive(Debug)]
struct Edges {
    start: Vec<u32>,
    entries: Vec<(u32, u32)>,
}

impl Edges {
    fn new(nv: usize, triangles: &[[u32; 3]]) -> Edges {
        let mut start = vec![0u32; nv + 1];
        for t in triangles {
            for &a in t {
                start[a as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut entries = vec![(0u32, 0u32); 3 * triangles.len()];
        for (k, t) in triangles.iter().enumerate() {
            for e in 0..3 {
                let a = t[e] as usize;
                entries[fill[a] as usize] = (t[(e + 1) % 3], k as u32);
                fill[a] += 1;
            }
        }
        Edges { start, entries }
    }

    /// The triangle with directed edge (a, b) (the last in triangle order, should two have
    /// it), if any.
    fn get(&self, a: u32, b: u32) -> Option<usize> {
        let row =
            &self.entries[self.start[a as usize] as usize..self.start[a as usize + 1] as usize];
        row.iter().rev().find(|e| e.0 == b).map(|e| e.1 as usize)
    }
}

/// Prepares the cut of `mesh` (the quad-tree's triangulation, `fixed` vertices never moved:
/// the single points) by the domain's boundary.
pub fn prepare(
    mesh: &TriMesh,
    domain: &Domain,
    segments: &Segments,
    fixed: &[bool],
    clear: f64,
) -> Prepared {
    let nv = mesh.vertices.len();
    let nt = mesh.triangles.len();
    // Edge adjacency and the neighbours of every vertex.
    let edge = Edges::new(nv, &mesh.triangles);
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); nv];
    let mut side = vec![0.0; nv];
    for t in &mesh.triangles {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            neighbours[a as usize].push(b);
            let l = dist(mesh.vertices[a as usize], mesh.vertices[b as usize]);
            side[a as usize] += l;
        }
    }
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
    }
    let across: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            [0, 1, 2].map(|e| {
                edge.get(t[(e + 1) % 3], t[e])
                    .map_or(u32::MAX, |o| o as u32)
            })
        })
        .collect();
    // Mean edge length: each vertex's outgoing edges were summed once per triangle.
    let mut out_count = vec![0usize; nv];
    for t in &mesh.triangles {
        for &v in t {
            out_count[v as usize] += 1;
        }
    }
    for v in 0..nv {
        if out_count[v] > 0 {
            side[v] /= out_count[v] as f64;
        }
    }
    // Triangles a boundary segment touches are deleted (step 8: edges cutting the boundary
    // go; step 9: the rest outside is found region by region).
    let touched: Vec<bool> = (0..nt)
        .map(|k| {
            let t = mesh.corners(k);
            segments.near(bbox(&t)).into_iter().any(|s| {
                touches(
                    t,
                    segments.ends[s as usize][0],
                    segments.ends[s as usize][1],
                )
            })
        })
        .collect();
    let rings: Vec<Vec<Point>> = domain
        .polygons
        .iter()
        .map(|p| {
            p.corners
                .iter()
                .map(|&c| domain.points[c as usize])
                .collect()
        })
        .collect();
    let mut region = vec![usize::MAX; nt];
    let mut inside_region: Vec<bool> = Vec::new();
    for start in 0..nt {
        if touched[start] || region[start] != usize::MAX {
            continue;
        }
        let r = inside_region.len();
        let t = mesh.corners(start);
        let centroid = [
            (t[0][0] + t[1][0] + t[2][0]) / 3.0,
            (t[0][1] + t[1][1] + t[2][1]) / 3.0,
        ];
        let odd = rings
            .iter()
            .filter(|ring| input::inside(centroid, ring))
            .count()
            % 2
            == 1;
        inside_region.push(odd);
        let mut stack = vec![start];
        region[start] = r;
        while let Some(k) = stack.pop() {
            let t = mesh.triangles[k];
            for e in 0..3 {
                if let Some(o) = edge.get(t[(e + 1) % 3], t[e]) {
                    if !touched[o] && region[o] == usize::MAX {
                        region[o] = r;
                        stack.push(o);
                    }
                }
            }
        }
    }
    let mut keep: Vec<bool> = (0..nt)
        .map(|k| !touched[k] && inside_region[region[k]])
        .collect();
    // Moves: a kept corner next to a deleted triangle, its nearest crossing within half an
    // edge, goes halfway along the most nearly opposite edge.
    let mut position = mesh.vertices.clone();
    let mut near_boundary = vec![false; nv];
    let mut stuck = vec![false; nv];
    for (t, _) in mesh.triangles.iter().zip(&keep).filter(|x| !*x.1) {
        for &v in t {
            near_boundary[v as usize] = true;
        }
    }
    for v in 0..nv {
        if !near_boundary[v] || fixed[v] {
            continue;
        }
        let p = mesh.vertices[v];
        let mut nearest: Option<(f64, u32)> = None;
        for &a in &neighbours[v] {
            let q = mesh.vertices[a as usize];
            for s in segments.near(bbox(&[p, q])) {
                let [b, c] = segments.ends[s as usize];
                if !meets(p, q, b, c) {
                    continue;
                }
                let (op, oq) = (orient2d(b, c, p), orient2d(b, c, q));
                let t = if op == oq { 0.0 } else { op / (op - oq) };
                if nearest.is_none_or(|(u, _)| t < u) {
                    nearest = Some((t, a));
                }
            }
        }
        let Some((t, a)) = nearest else { continue };
        if t >= 0.5 {
            continue;
        }
        let toward = mesh.vertices[a as usize];
        let opposite = neighbours[v]
            .iter()
            .map(|&b| (angle_deg(p, toward, mesh.vertices[b as usize]), b))
            .fold(None, |best: Option<(f64, u32)>, x| match best {
                Some(b) if b.0 >= x.0 => Some(b),
                _ => Some(x),
            });
        match opposite {
            Some((angle, b)) if angle >= 150.0 => {
                let q = mesh.vertices[b as usize];
                position[v] = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
            }
            // No edge leads away (a splitting point): too close to stay, it goes.
            _ => stuck[v] = true,
        }
    }
    // Deleted besides: corners within `clear` sides of an input corner, and those too close
    // to the boundary to stay (no edge to move along).
    let near_corner = |v: usize| {
        let p = position[v];
        let r = clear * side[v];
        segments
            .near([p[0] - r, p[1] - r, p[0] + r, p[1] + r])
            .into_iter()
            .any(|s| segments.ends[s as usize].iter().any(|&c| dist(c, p) < r))
    };
    let gone: Vec<bool> = (0..nv)
        .map(|v| stuck[v] || (near_boundary[v] && !fixed[v] && near_corner(v)))
        .collect();
    // Deleted besides: triangles at those corners and triangles a move left outside the
    // bounds, by more than placing their corners explains (`placed`).
    for (t, kept) in mesh.triangles.iter().zip(keep.iter_mut()).filter(|x| *x.1) {
        let p = t.map(|v| position[v as usize]);
        // The placement's share is computed only for the few triangles past `SLACK`.
        let bounded = super::boxes::score(p[0], p[1], p[2])
            .is_some_and(|g| g >= -super::boxes::SLACK || g >= -placed(p));
        if t.iter().any(|&v| gone[v as usize]) || !bounded {
            *kept = false;
        }
    }
    drop_short_fronts(mesh, &edge, &neighbours, &position, &side, &mut keep);
    Prepared {
        edge,
        across,
        neighbours,
        position,
        side,
        kept: keep,
    }
}

/// How far (degrees) the angles of lattice triangle `t`, its corners where the cut has
/// them, may lie beyond [30°, 90°] and still count as in bounds: `boxes::SLACK` plus what
/// placing its corners by one rounding each explains (`rounding::placement_allowance`, the
/// largest of its three angles'). The lattice's own triangles are in bounds in real
/// arithmetic, but where they are small against their coordinates their angles come out
/// beyond `SLACK` alone: a right triangle of a size change, sides 4e-6 to 8e-6 at
/// x ≈ −0.78, measured 90.0000000015° (fuzz case 54 of seed 1). Deleted, it left a hole in
/// the kept lattice, an island whose erosions grew it a ring a round (3, 9, 17, 23 corners)
/// on every lattice the run made, until the ladders beside the short segment failed: cases
/// 46, 54 and 118 of seed 1 failed so after three finer bands, and mesh with none.
fn placed(t: [Point; 3]) -> f64 {
    use crate::quality::rounding::placement_allowance;
    let most = (0..3)
        .map(|m| placement_allowance(t[m], t[(m + 1) % 3], t[(m + 2) % 3]))
        .fold(0.0, f64::max);
    super::boxes::SLACK + most
}

/// Departure (ours): a moved corner with a front edge shorter than `SHORT_FRONT` of its
/// local side loses its triangles, and so on until none is left. Two neighbours moved
/// toward each other, or a corner moved halfway along its edge to one that stays, end half
/// a side apart on the front; facing a gap of up to a side, no triangle from so short an
/// edge to the boundary reaches 30°. The fill named such a corner and eroded it, a round at
/// a time: imr took 110 fills (erosions and `relax`'s trials), pslg-short-long 63. With the
/// corners dropped first (963 of them on imr), every report domain keeps the bounds on its
/// first fill, and so does fuzz case 1 (a six-point star that needed a finer band before).
/// The paper deletes a fine neighbour of a moved corner in a like place (Sec. 5.2 case 2,
/// a_{j-1}).
///
/// Rounds: a corner is looked at again only next to one that lost its triangles, the only
/// place where front edges change.
fn drop_short_fronts(
    mesh: &TriMesh,
    edge: &Edges,
    neighbours: &[Vec<u32>],
    position: &[Point],
    side: &[f64],
    keep: &mut [bool],
) {
    let moved = |v: usize| position[v] != mesh.vertices[v];
    let short_front = |v: usize, keep: &[bool]| {
        neighbours[v].iter().any(|&b| {
            let kept = |(a, b): (u32, u32)| edge.get(a, b).is_some_and(|k| keep[k]);
            let b = b as usize;
            kept((v as u32, b as u32)) != kept((b as u32, v as u32))
                && dist(position[v], position[b]) < SHORT_FRONT * side[v].min(side[b])
        })
    };
    let mut candidates: Vec<usize> = (0..position.len()).filter(|&v| moved(v)).collect();
    while !candidates.is_empty() {
        let doomed: Vec<usize> = candidates
            .into_iter()
            .filter(|&v| short_front(v, keep))
            .collect();
        let mut next = Vec::new();
        for &v in &doomed {
            for &b in &neighbours[v] {
                if let Some(k) = edge.get(v as u32, b) {
                    keep[k] = false;
                }
                if moved(b as usize) {
                    next.push(b as usize);
                }
            }
        }
        next.sort_unstable();
        next.dedup();
        candidates = next;
    }
}

/// How short a front edge at a moved corner may be, against the smaller local side of its
/// ends, before the corner loses its triangles (`drop_short_fronts`).
const SHORT_FRONT: f64 = 0.75;

/// Cuts the prepared lattice: deletes the triangles at `eroded` corners, then the pinches,
/// and traces the fronts.
pub fn cut<'a>(mesh: &TriMesh, prep: &'a Prepared, eroded: &[bool]) -> Cut<'a> {
    let (nv, nt) = (mesh.vertices.len(), mesh.triangles.len());
    let (across, position, side) = (&prep.across, &prep.position[..], &prep.side[..]);
    let mut keep = prep.kept.clone();
    for (t, kept) in mesh.triangles.iter().zip(keep.iter_mut()).filter(|x| *x.1) {
        if t.iter().any(|&v| eroded[v as usize]) {
            *kept = false;
        }
    }
    // The kept triangles' sides whose other side is not kept, the kept region on the left.
    let front_edges = |keep: &[bool]| -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for ((t, o), _) in mesh.triangles.iter().zip(across).zip(keep).filter(|x| *x.1) {
            for e in 0..3 {
                if o[e] == u32::MAX || !keep[o[e] as usize] {
                    out.push((t[e], t[(e + 1) % 3]));
                }
            }
        }
        out
    };
    // Pinches: a corner with two front edges leaving it loses its triangles, until none.
    loop {
        let mut leaving = vec![0u8; nv];
        for (a, _) in front_edges(&keep) {
            leaving[a as usize] += 1;
        }
        let mut changed = false;
        for (t, kept) in mesh.triangles.iter().zip(keep.iter_mut()) {
            if *kept && t.iter().any(|&v| leaving[v as usize] > 1) {
                *kept = false;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let kept: Vec<[u32; 3]> = (0..nt)
        .filter(|&k| keep[k])
        .map(|k| mesh.triangles[k])
        .collect();
    let next: FxHashMap<u32, u32> = front_edges(&keep).into_iter().collect();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut seen = vec![false; nv];
    let mut loops = Vec::new();
    for s in starts {
        if seen[s as usize] {
            continue;
        }
        let mut l = Vec::new();
        let mut v = s;
        while !seen[v as usize] {
            seen[v as usize] = true;
            l.push(v);
            v = next[&v];
        }
        loops.push(l);
    }
    Cut {
        position,
        side,
        kept,
        loops,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edge_is_found_in_the_triangle_that_has_it_and_the_last_of_two_wins() {
        // Two triangles sharing edge 1-2, and a third repeating the first's edge 0-1.
        let triangles = [[0, 1, 2], [2, 1, 3], [0, 1, 4]];
        let edges = Edges::new(5, &triangles);
        assert_eq!(edges.get(1, 2), Some(0));
        assert_eq!(edges.get(2, 1), Some(1));
        assert_eq!(edges.get(3, 2), Some(1));
        assert_eq!(edges.get(2, 3), None);
        assert_eq!(edges.get(0, 1), Some(2));
        assert_eq!(edges.get(4, 0), Some(2));
        assert_eq!(edges.get(4, 3), None);
    }

    #[test]
    fn a_lattice_right_triangle_rounded_past_90_degrees_is_in_bounds_within_its_placement() {
        // The lattice triangle of fuzz case 54 of seed 1 (a size change's 30-60-90, sides
        // 4.1e-6 to 8.2e-6 at x ≈ −0.78) that `SLACK` alone deleted: its right angle measures
        // 90.0000000015°.
        let t = [
            [-0.784835287049825, -0.20438435694255125],
            [-0.784837339496637, -0.20438791188470976],
            [-0.7848311821562006, -0.20439146682686823],
        ];
        let g = crate::rhomb::domain::boxes::score(t[0], t[1], t[2]).expect("counter-clockwise");
        assert!(g < -crate::rhomb::domain::boxes::SLACK, "{g}");
        assert!(g >= -placed(t), "{g} against {}", placed(t));
        // Still a fraction of a millionth of a degree, as the finished mesh's check allows.
        assert!(placed(t) < 1e-7, "{}", placed(t));
        // A triangle moved out of bounds for real is not excused: the same one with its
        // right-angled corner moved a thousandth of the way to the hypotenuse's midpoint.
        let mid = [(t[0][0] + t[2][0]) / 2.0, (t[0][1] + t[2][1]) / 2.0];
        let mut out = t;
        out[1] = [
            t[1][0] + (mid[0] - t[1][0]) / 1000.0,
            t[1][1] + (mid[1] - t[1][1]) / 1000.0,
        ];
        let g = crate::rhomb::domain::boxes::score(out[0], out[1], out[2]).unwrap();
        assert!(g < -placed(out), "{g}");
    }
}
