//! The domains of the campaign on polygonal domains, drawn from seeded PCG streams: valid
//! domains in the sense of paper 001 (one outer simple polygon of at least four corners,
//! polygonal holes strictly inside it and disjoint from each other, each with a seed inside
//! it, isolated points inside the domain and outside the holes), in the families of
//! `FAMILIES`. Every draw is checked with exact orientation signs (`is_valid_domain`) and
//! for the feature its family is for (`has_feature`); a draw that fails is thrown away and
//! drawn again from the same stream, at most `MAX_REDRAWS` times.

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::geom::{orient2d, Point};
use crate::mesh::Pslg;

/// The families of generated domains, in the order cases cycle through them.
pub const FAMILIES: [&str; 8] = [
    "simple-polygon",
    "star",
    "sharp-corner",
    "holes",
    "interior-points",
    "thin-slit",
    "short-long",
    "large-coordinates",
];

/// Most points in one generated domain (corners of every ring and isolated points).
pub const MAX_POINTS: usize = 60;

/// Draws thrown away before a case gives up and takes `fallback_domain` instead.
pub const MAX_REDRAWS: u32 = 200;

/// The smallest angle two segments may make at a corner of a generated domain, and the
/// smallest tip `sharp-corner` draws, in degrees.
pub const SHARP_MIN_DEG: f64 = 1.0;

/// The largest tip `sharp-corner` draws, in degrees.
pub const SHARP_MAX_DEG: f64 = 30.0;

/// The narrowest slit or slot and the shortest segment beside its neighbour, as a fraction of
/// the domain's size or of the neighbour's length.
pub const THINNEST: f64 = 1e-3;

/// One generated domain.
#[derive(Debug, Clone, PartialEq)]
pub struct DomainCase {
    pub family: &'static str,
    pub input: Pslg,
    /// Draws thrown away before this one; `MAX_REDRAWS` means the generator gave up and the
    /// input is `fallback_domain`.
    pub redraws: u32,
}

/// The domain of case `case` of a campaign seeded `seed`: the family cycles with the case
/// number, the rest comes from a PCG stream of its own.
pub fn generate_case(seed: u64, case: u64) -> DomainCase {
    let family = FAMILIES[(case % FAMILIES.len() as u64) as usize];
    generate_family_case(seed, case, family)
}

/// The domain of family `family` drawn from the PCG stream of case `case` of seed `seed`
/// (what `generate_case` gives when the case falls on that family). An unknown family name
/// draws simple polygons.
pub fn generate_family_case(seed: u64, case: u64, family: &str) -> DomainCase {
    let family = FAMILIES
        .iter()
        .copied()
        .find(|&f| f == family)
        .unwrap_or(FAMILIES[0]);
    let mut rng = Pcg64::new(seed as u128, case as u128);
    for redraws in 0..MAX_REDRAWS {
        let domain = draw(&mut rng, family);
        if is_valid_domain(&domain) && has_feature(family, &domain) {
            let input = domain.to_pslg();
            if input.check().is_ok() {
                return DomainCase {
                    family,
                    input,
                    redraws,
                };
            }
        }
    }
    DomainCase {
        family,
        input: fallback_domain().to_pslg(),
        redraws: MAX_REDRAWS,
    }
}

/// The domain a case takes when every draw failed: the square [-1, 1]².
fn fallback_domain() -> Domain {
    Domain {
        outer: vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
        ..Domain::default()
    }
}

/// A domain before it becomes a `Pslg`: rings of corners (the outer one counter-clockwise,
/// holes either way), one seed per hole, isolated points.
#[derive(Debug, Clone, Default)]
struct Domain {
    outer: Vec<Point>,
    holes: Vec<Vec<Point>>,
    seeds: Vec<Point>,
    points: Vec<Point>,
}

impl Domain {
    /// The outer ring's corners first, then each hole's, then the isolated points; each ring
    /// closed by segments in order.
    fn to_pslg(&self) -> Pslg {
        let mut pslg = Pslg::default();
        for ring in std::iter::once(&self.outer).chain(&self.holes) {
            let base = pslg.points.len() as u32;
            let n = ring.len() as u32;
            pslg.points.extend_from_slice(ring);
            pslg.segments
                .extend((0..n).map(|k| [base + k, base + (k + 1) % n]));
        }
        pslg.points.extend_from_slice(&self.points);
        pslg.holes = self.seeds.clone();
        pslg
    }

    fn point_count(&self) -> usize {
        self.outer.len() + self.holes.iter().map(Vec::len).sum::<usize>() + self.points.len()
    }

    /// Every point and seed mapped by `f`.
    fn map(mut self, f: impl Fn(Point) -> Point) -> Domain {
        for p in self
            .outer
            .iter_mut()
            .chain(self.holes.iter_mut().flatten())
            .chain(&mut self.seeds)
            .chain(&mut self.points)
        {
            *p = f(*p);
        }
        self
    }
}

// ---------------------------------------------------------------------------------------
// Drawing domains. Sizes are about 2 (coordinates in [-1, 1]) but for large-coordinates.

fn draw(rng: &mut Pcg64, family: &str) -> Domain {
    let mut d = match family {
        "star" => Domain {
            outer: star(rng),
            ..Domain::default()
        },
        "sharp-corner" => Domain {
            outer: spiked(rng),
            ..Domain::default()
        },
        "holes" => {
            let outer = outer_polygon(rng);
            with_holes(rng, outer, 1)
        }
        "interior-points" => interior_points(rng),
        "thin-slit" => thin_slit(rng),
        "short-long" => short_long(rng),
        "large-coordinates" => {
            let inner = FAMILIES[rng.random_range(0..FAMILIES.len() - 1)];
            let d = draw(rng, inner);
            projected(rng, d)
        }
        _ => Domain {
            outer: untangled(rng),
            ..Domain::default()
        },
    };
    if d.outer.len() == 3 {
        // Paper 001's domains have at least four corners: a triangle gets one on its
        // longest edge.
        let k = (0..3)
            .max_by(|&i, &j| {
                length(d.outer[i], d.outer[(i + 1) % 3])
                    .total_cmp(&length(d.outer[j], d.outer[(j + 1) % 3]))
            })
            .unwrap_or(0);
        let (a, b) = (d.outer[k], d.outer[(k + 1) % 3]);
        d.outer
            .insert(k + 1, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
    }
    d
}

fn length(a: Point, b: Point) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

fn polar(centre: Point, radius: f64, angle: f64) -> Point {
    [
        centre[0] + radius * angle.cos(),
        centre[1] + radius * angle.sin(),
    ]
}

fn uniform(rng: &mut Pcg64, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// 10^x for x uniform in [lo, hi]: log-uniform between 10^lo and 10^hi.
fn log_uniform(rng: &mut Pcg64, lo: f64, hi: f64) -> f64 {
    10f64.powf(uniform(rng, lo, hi))
}

/// A ring star-shaped around `centre`: `n` corners at increasing angles (even steps, each
/// moved by up to `jitter` of a step), at radii in [r_lo, r_hi]; counter-clockwise.
fn star_ring(
    rng: &mut Pcg64,
    centre: Point,
    n: usize,
    r_lo: f64,
    r_hi: f64,
    jitter: f64,
) -> Vec<Point> {
    let step = std::f64::consts::TAU / n as f64;
    let turn = uniform(rng, 0.0, std::f64::consts::TAU);
    (0..n)
        .map(|k| {
            let angle = turn + step * (k as f64 + jitter * uniform(rng, -1.0, 1.0));
            polar(centre, uniform(rng, r_lo, r_hi), angle)
        })
        .collect()
}

/// A random simple polygon: random points in [-1, 1]² in random order, untangled by 2-opt
/// moves (reversing the path between two crossing edges shortens it, so the moves end); at
/// most a bounded number of moves, after which the validity check rejects what is left.
fn untangled(rng: &mut Pcg64) -> Vec<Point> {
    let n = rng.random_range(4..=24usize);
    let mut ring: Vec<Point> = (0..n)
        .map(|_| [uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)])
        .collect();
    for _ in 0..4 * n * n {
        let crossing = (0..n).find_map(|i| {
            (i + 2..n)
                .filter(|&j| (j + 1) % n != i)
                .find(|&j| segments_meet(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n]))
                .map(|j| (i, j))
        });
        match crossing {
            Some((i, j)) => ring[i + 1..=j].reverse(),
            None => break,
        }
    }
    counter_clockwise(ring)
}

/// The ring in counter-clockwise order (by its shoelace area).
fn counter_clockwise(mut ring: Vec<Point>) -> Vec<Point> {
    let n = ring.len();
    let twice_area: f64 = (0..n)
        .map(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    if twice_area < 0.0 {
        ring.reverse();
    }
    ring
}

/// The outer ring of the families that add something inside it: a star-shaped ring or an
/// untangled random polygon.
fn outer_polygon(rng: &mut Pcg64) -> Vec<Point> {
    if rng.random_bool(0.5) {
        // A triangle now and then, which `draw` gives a fourth corner.
        let n = rng.random_range(3..=16usize);
        let jitter = if n == 3 { 0.2 } else { 0.3 };
        star_ring(rng, [0.0, 0.0], n, 0.6, 1.0, jitter)
    } else {
        untangled(rng)
    }
}

/// A star: 3 to 12 spikes, tips and valleys alternating around the origin.
fn star(rng: &mut Pcg64) -> Vec<Point> {
    let spikes = rng.random_range(3..=12usize);
    let step = std::f64::consts::PI / spikes as f64;
    let turn = uniform(rng, 0.0, std::f64::consts::TAU);
    let depth = uniform(rng, 0.1, 0.7);
    (0..2 * spikes)
        .map(|k| {
            let angle = turn + step * (k as f64 + uniform(rng, -0.3, 0.3));
            let radius = if k % 2 == 0 {
                uniform(rng, 0.7, 1.0)
            } else {
                uniform(rng, 0.5, 1.0) * depth
            };
            polar([0.0, 0.0], radius, angle)
        })
        .collect()
}

/// A ring star-shaped around the origin with one spike whose tip makes an angle drawn
/// log-uniformly in [SHARP_MIN_DEG, SHARP_MAX_DEG]: the tip's neighbours lie at radius r,
/// ±δ around the spike's direction, and the tip at height h = r·sin δ / tan(θ/2) above the
/// chord between them.
fn spiked(rng: &mut Pcg64) -> Vec<Point> {
    let theta = log_uniform(rng, SHARP_MIN_DEG.log10(), SHARP_MAX_DEG.log10()).to_radians();
    let r = uniform(rng, 0.3, 0.6);
    let h = uniform(rng, 0.4, 1.4);
    let delta = (h * (0.5 * theta).tan() / r).min(0.95).asin();
    let h = r * delta.sin() / (0.5 * theta).tan();
    let dir = uniform(rng, 0.0, std::f64::consts::TAU);
    let mut ring = vec![
        polar([0.0, 0.0], r, dir - delta),
        polar([0.0, 0.0], r * delta.cos() + h, dir),
        polar([0.0, 0.0], r, dir + delta),
    ];
    let others = rng.random_range(3..=14usize);
    let span = std::f64::consts::TAU - 2.0 * delta;
    let step = span / (others + 1) as f64;
    for k in 1..=others {
        let angle = dir + delta + step * (k as f64 + uniform(rng, -0.3, 0.3));
        ring.push(polar([0.0, 0.0], uniform(rng, 0.4, 1.0), angle));
    }
    ring
}

/// `outer` with at least `least` (and up to three) holes, each a small star-shaped ring of 3
/// to 8 corners seeded at its centre, placed where it lies strictly inside the outer ring and
/// apart from the other holes (up to twenty tries each).
fn with_holes(rng: &mut Pcg64, outer: Vec<Point>, least: usize) -> Domain {
    let mut d = Domain {
        outer,
        ..Domain::default()
    };
    let wanted = rng.random_range(least..=3);
    for _ in 0..20 * wanted {
        if d.holes.len() == wanted {
            break;
        }
        let centre = [uniform(rng, -0.7, 0.7), uniform(rng, -0.7, 0.7)];
        let radius = log_uniform(rng, -1.5, -0.5);
        let n = rng.random_range(3..=8usize);
        let jitter = if n == 3 { 0.2 } else { 0.3 };
        let mut trial = d.clone();
        trial
            .holes
            .push(star_ring(rng, centre, n, 0.5 * radius, radius, jitter));
        trial.seeds.push(centre);
        if is_valid_domain(&trial) {
            d = trial;
        }
    }
    d
}

/// An outer polygon (with a hole half the time) and 1 to 10 isolated points: uniform in the
/// domain, or a little inside an edge (down to 1e-3 of the size from it).
fn interior_points(rng: &mut Pcg64) -> Domain {
    let outer = outer_polygon(rng);
    let mut d = if rng.random_bool(0.5) {
        with_holes(rng, outer, 0)
    } else {
        Domain {
            outer,
            ..Domain::default()
        }
    };
    let wanted = rng.random_range(1..=10usize);
    for _ in 0..20 * wanted {
        if d.points.len() == wanted || d.point_count() >= MAX_POINTS {
            break;
        }
        let p = if rng.random_bool(0.3) {
            // Near the middle of an outer edge, on its inner side (counter-clockwise ring).
            let k = rng.random_range(0..d.outer.len());
            let (a, b) = (d.outer[k], d.outer[(k + 1) % d.outer.len()]);
            let gap = 2.0 * log_uniform(rng, -3.0, -1.0);
            let len = length(a, b);
            let t = uniform(rng, 0.2, 0.8);
            [
                a[0] + t * (b[0] - a[0]) - gap * (b[1] - a[1]) / len,
                a[1] + t * (b[1] - a[1]) + gap * (b[0] - a[0]) / len,
            ]
        } else {
            [uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)]
        };
        let mut trial = d.clone();
        trial.points.push(p);
        if is_valid_domain(&trial) {
            d = trial;
        }
    }
    d
}

/// A quadrilateral about [-1, 1]² with a narrow notch cut into its lower edge, or with a
/// narrow slot as a hole; the width is 1e-1 to `THINNEST` of the size (2), the notch may lean.
fn thin_slit(rng: &mut Pcg64) -> Domain {
    let mut jit = || uniform(rng, -0.2, 0.2);
    let quad = [
        [-1.0 + jit(), -1.0 + jit()],
        [1.0 + jit(), -1.0 + jit()],
        [1.0 + jit(), 1.0 + jit()],
        [-1.0 + jit(), 1.0 + jit()],
    ];
    let width = 2.0 * log_uniform(rng, THINNEST.log10(), -1.0);
    if rng.random_bool(0.5) {
        let (a, b) = (quad[0], quad[1]);
        let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        let t = uniform(rng, 0.2, 0.7);
        let dt = width / length(a, b);
        let depth = uniform(rng, 0.3, 1.5);
        let lean = uniform(rng, -0.4, 0.4);
        let (p, q) = (at(t), at(t + dt));
        Domain {
            outer: vec![
                a,
                p,
                [p[0] + lean, p[1] + depth],
                [q[0] + lean, q[1] + depth],
                q,
                b,
                quad[2],
                quad[3],
            ],
            ..Domain::default()
        }
    } else {
        let centre = [uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3)];
        let half = 0.5 * uniform(rng, 0.3, 1.0);
        let angle = uniform(rng, 0.0, std::f64::consts::PI);
        let (u, v) = ([angle.cos(), angle.sin()], [-angle.sin(), angle.cos()]);
        let corner = |s: f64, w: f64| {
            [
                centre[0] + s * half * u[0] + w * 0.5 * width * v[0],
                centre[1] + s * half * u[1] + w * 0.5 * width * v[1],
            ]
        };
        Domain {
            outer: quad.to_vec(),
            holes: vec![vec![
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ]],
            seeds: vec![centre],
            points: Vec::new(),
        }
    }
}

/// An outer polygon with one to three short segments: a corner put a little way along an
/// edge, 1e-1 down to `THINNEST` of the edge's length (exactly 1e-3 a quarter of the time),
/// turned off the edge by up to 60°, so that a short segment meets a long one.
fn short_long(rng: &mut Pcg64) -> Domain {
    let mut outer = outer_polygon(rng);
    for _ in 0..rng.random_range(1..=3usize) {
        let n = outer.len();
        let k = rng.random_range(0..n);
        let (a, b) = (outer[k], outer[(k + 1) % n]);
        let ratio = if rng.random_bool(0.25) {
            THINNEST
        } else {
            log_uniform(rng, THINNEST.log10(), -1.0)
        };
        let turn = uniform(rng, -60f64, 60.0).to_radians();
        let (c, s) = (turn.cos(), turn.sin());
        let (dx, dy) = (ratio * (b[0] - a[0]), ratio * (b[1] - a[1]));
        outer.insert(k + 1, [a[0] + c * dx - s * dy, a[1] + s * dx + c * dy]);
    }
    Domain {
        outer,
        ..Domain::default()
    }
}

/// A domain moved to projected map coordinates (x ≈ 5e5, y ≈ 5e6, whole metres) and scaled
/// from its size of 2 to 1 m … 10 km.
fn projected(rng: &mut Pcg64, d: Domain) -> Domain {
    let origin = [
        uniform(rng, 4e5, 6e5).floor(),
        uniform(rng, 4e6, 6e6).floor(),
    ];
    let scale = 0.5 * log_uniform(rng, 0.0, 4.0);
    d.map(|p| [origin[0] + scale * p[0], origin[1] + scale * p[1]])
}

/// The shortest segment of the outer ring over the longer of its two neighbours, at most
/// which a `short-long` domain must have one.
pub const SHORT_LONG_RATIO: f64 = 0.125;

/// True when a draw of `family` has what the family is for: a hole, an isolated point, a
/// corner of [SHARP_MIN_DEG, SHARP_MAX_DEG] on the domain's side, or a segment at most
/// `SHORT_LONG_RATIO` of a neighbour's length (the other families have theirs by
/// construction).
fn has_feature(family: &str, d: &Domain) -> bool {
    let ring = &d.outer;
    let n = ring.len();
    match family {
        "holes" => !d.holes.is_empty(),
        "interior-points" => !d.points.is_empty(),
        "sharp-corner" => (0..n).any(|k| {
            let (u, v, w) = (ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]);
            // A convex corner of the counter-clockwise ring: its angle is the domain's.
            orient2d(u, v, w) > 0.0
                && (SHARP_MIN_DEG..=SHARP_MAX_DEG).contains(&corner_deg(u, v, w))
        }),
        "short-long" => (0..n).any(|k| {
            let len = |i: usize| length(ring[i % n], ring[(i + 1) % n]);
            len(k) <= SHORT_LONG_RATIO * len(k + 1).max(len(k + n - 1))
        }),
        _ => true,
    }
}

// ---------------------------------------------------------------------------------------
// The validity of a domain, decided with exact orientation signs.

/// Where a point lies with respect to a ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Place {
    Inside,
    Outside,
    Boundary,
}

/// True when q lies on the closed segment ab (exact).
fn on_segment(a: Point, b: Point, q: Point) -> bool {
    orient2d(a, b, q) == 0.0
        && q[0] >= a[0].min(b[0])
        && q[0] <= a[0].max(b[0])
        && q[1] >= a[1].min(b[1])
        && q[1] <= a[1].max(b[1])
}

fn opposite(x: f64, y: f64) -> bool {
    (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0)
}

/// True when the closed segments ab and cd share a point (exact).
fn segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool {
    let proper = opposite(orient2d(a, b, c), orient2d(a, b, d))
        && opposite(orient2d(c, d, a), orient2d(c, d, b));
    proper
        || on_segment(a, b, c)
        || on_segment(a, b, d)
        || on_segment(c, d, a)
        || on_segment(c, d, b)
}

/// Where `p` lies with respect to the closed ring (crossings of the ray to +x, exact).
fn locate(p: Point, ring: &[Point]) -> Place {
    let n = ring.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (ring[k], ring[(k + 1) % n]);
        if on_segment(a, b, p) {
            return Place::Boundary;
        }
        if (a[1] > p[1]) != (b[1] > p[1]) {
            // The edge crosses the line y = p.y to the right of p when p lies left of an
            // upward edge or right of a downward one.
            let left = orient2d(a, b, p) > 0.0;
            if (b[1] > a[1]) == left {
                inside = !inside;
            }
        }
    }
    if inside {
        Place::Inside
    } else {
        Place::Outside
    }
}

/// The angle between the two segments at corner `v` (between v→u and v→w), in degrees.
fn corner_deg(u: Point, v: Point, w: Point) -> f64 {
    let (e, f) = ([u[0] - v[0], u[1] - v[1]], [w[0] - v[0], w[1] - v[1]]);
    (e[0] * f[1] - e[1] * f[0])
        .abs()
        .atan2(e[0] * f[0] + e[1] * f[1])
        .to_degrees()
}

/// True when `d` is a domain of paper 001 that this campaign may hand out: at most
/// `MAX_POINTS` finite, distinct points; an outer ring of at least four corners and holes of
/// at least three; no two segments meeting except consecutive ones of a ring at their shared
/// corner (and those not folding back over each other); every corner's angle at least
/// `SHARP_MIN_DEG`; every hole strictly inside the outer ring and outside the other holes,
/// with its seed strictly inside it; every isolated point strictly inside the outer ring,
/// outside every hole and on no segment.
fn is_valid_domain(d: &Domain) -> bool {
    if d.outer.len() < 4
        || d.holes.iter().any(|h| h.len() < 3)
        || d.seeds.len() != d.holes.len()
        || d.point_count() > MAX_POINTS
    {
        return false;
    }
    let rings: Vec<&[Point]> = std::iter::once(d.outer.as_slice())
        .chain(d.holes.iter().map(Vec::as_slice))
        .collect();
    let all: Vec<Point> = rings
        .iter()
        .flat_map(|r| r.iter().copied())
        .chain(d.points.iter().copied())
        .collect();
    if all
        .iter()
        .chain(&d.seeds)
        .any(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        return false;
    }
    let mut keys: Vec<[u64; 2]> = all
        .iter()
        .map(|p| [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits()])
        .collect();
    keys.sort_unstable();
    if keys.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    // Segments as (ring, index of the first corner).
    let segs: Vec<(usize, usize)> = rings
        .iter()
        .enumerate()
        .flat_map(|(r, ring)| (0..ring.len()).map(move |k| (r, k)))
        .collect();
    let ends = |(r, k): (usize, usize)| (rings[r][k], rings[r][(k + 1) % rings[r].len()]);
    for (i, &s) in segs.iter().enumerate() {
        let (a, b) = ends(s);
        for &t in &segs[i + 1..] {
            let (c, e) = ends(t);
            let n = rings[s.0].len();
            let meets = if s.0 == t.0 && (s.1 + 1) % n == t.1 {
                // t starts where s ends: neither may run back along the other.
                on_segment(a, b, e) || on_segment(c, e, a)
            } else if s.0 == t.0 && (t.1 + 1) % n == s.1 {
                on_segment(a, b, c) || on_segment(c, e, b)
            } else {
                segments_meet(a, b, c, e)
            };
            if meets {
                return false;
            }
        }
        if d.points.iter().any(|&p| on_segment(a, b, p)) {
            return false;
        }
    }
    let sharp = rings.iter().any(|ring| {
        let n = ring.len();
        (0..n)
            .any(|k| corner_deg(ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]) < SHARP_MIN_DEG)
    });
    if sharp {
        return false;
    }
    let holes_placed = d.holes.iter().enumerate().all(|(i, hole)| {
        hole.iter().all(|&p| locate(p, &d.outer) == Place::Inside)
            && locate(d.seeds[i], hole) == Place::Inside
            && d.holes
                .iter()
                .enumerate()
                .all(|(j, other)| j == i || locate(hole[0], other) == Place::Outside)
    });
    holes_placed
        && d.points.iter().all(|&p| {
            locate(p, &d.outer) == Place::Inside
                && d.holes.iter().all(|h| locate(p, h) == Place::Outside)
        })
}
