//! A seeded fuzz campaign for the hexagonal meshers: random point sets of the families that
//! stress paper 000's guarantees (uniform, clustered, collinear, near-duplicates, extreme
//! scales, far translations, points exactly on hexagon centres, edges and corners), each meshed
//! and checked against the bounds the mesher promises (Sec. 4.3 for `hex-simple`, Sec. 6 for
//! `hex`). The first failing case is written out as a Triangle .node file.

use std::path::PathBuf;

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::error::{Error, InputError};
use crate::geom::{orient2d, Hexagon, Point};
use crate::hex::lattice::{Key, Lattice};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{Mesher, Params};
use crate::quality;

/// What a campaign found.
#[derive(Debug, Clone, PartialEq)]
pub struct FuzzSummary {
    pub mesher: String,
    pub seed: u64,
    pub cases: u64,
    /// Cases refused with `InputError::Range` (points too close for f64 at that scale).
    pub refused: u64,
    pub failures: u64,
    /// The smallest and largest angle seen over all meshes, in degrees.
    pub worst_min_angle: f64,
    pub worst_max_angle: f64,
    pub max_triangles: usize,
    pub first_failure: Option<FuzzFailure>,
}

/// The first failing case of a campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct FuzzFailure {
    pub case: u64,
    pub family: &'static str,
    pub message: String,
    /// Where the input was written (a Triangle .node file), when writing worked.
    pub path: Option<PathBuf>,
}

/// The families of generated point sets, in the order cases cycle through them.
pub const FAMILIES: [&str; 7] = [
    "uniform",
    "clustered",
    "collinear",
    "near-duplicates",
    "scaled",
    "translated",
    "lattice",
];

/// The angle bounds (degrees) a mesher promises, for the meshers this campaign knows.
pub fn angle_bounds(mesher: &str) -> Option<(f64, f64)> {
    match mesher {
        "hex-simple" => Some((30.0, 120.0)),
        "hex" => Some(((5.0 / (3.0 * 3f64.sqrt())).atan().to_degrees(), 90.0)),
        _ => None,
    }
}

/// Runs `cases` random cases through the mesher `mesher` (any registered name, or
/// `hex-simple`), seeded by `seed`; `progress` is called after each case with the number done.
pub fn fuzz_campaign(
    mesher: &str,
    cases: u64,
    seed: u64,
    mut progress: impl FnMut(u64),
) -> FuzzSummary {
    let mut summary = FuzzSummary {
        mesher: mesher.to_string(),
        seed,
        cases: 0,
        refused: 0,
        failures: 0,
        worst_min_angle: f64::INFINITY,
        worst_max_angle: f64::NEG_INFINITY,
        max_triangles: 0,
        first_failure: None,
    };
    let m: Box<dyn Mesher> = match mesher {
        "hex-simple" => Box::new(super::HexSimple),
        "hex" => Box::new(super::extended::Hex),
        other => match crate::registry::mesher(other) {
            Ok(m) => m,
            Err(e) => {
                summary.failures = 1;
                summary.first_failure = Some(FuzzFailure {
                    case: 0,
                    family: "none",
                    message: e.to_string(),
                    path: None,
                });
                return summary;
            }
        },
    };
    let bounds = angle_bounds(mesher);
    for case in 0..cases {
        let (family, input) = generate_case(seed, case);
        let outcome = match m.mesh(&input, &Params::default()) {
            Ok(run) if !run.complete => Err(format!(
                "stopped early without a budget: {:?}",
                run.stop_reason
            )),
            Ok(run) => check_mesh(&run.mesh, &input.points, bounds)
                .and_then(|stats| {
                    // The harness's own checks too: validity, one disc, and every bound the
                    // mesher promises (radius ratio, shortest edge, Delaunay for `hex`).
                    let promised = quality::Bounds::parse(mesher).ok();
                    let v = quality::verdict(&run.mesh, Some(&input), promised.as_ref());
                    if v.passed() {
                        Ok(stats)
                    } else {
                        Err(format!("quality verdict failed:\n{v}"))
                    }
                })
                .map(|stats| {
                    summary.worst_min_angle = summary.worst_min_angle.min(stats.min_angle);
                    summary.worst_max_angle = summary.worst_max_angle.max(stats.max_angle);
                    summary.max_triangles = summary.max_triangles.max(run.mesh.triangles.len());
                }),
            Err(Error::Input {
                problem: InputError::Range { .. },
                ..
            }) => {
                summary.refused += 1;
                Ok(())
            }
            Err(e) => Err(e.to_string()),
        };
        summary.cases += 1;
        if let Err(message) = outcome {
            summary.failures += 1;
            if summary.first_failure.is_none() {
                let path = write_failure(mesher, seed, case, family, &input).ok();
                summary.first_failure = Some(FuzzFailure {
                    case,
                    family,
                    message,
                    path,
                });
            }
        }
        progress(case + 1);
    }
    summary
}

/// The input of case `case` of a campaign seeded `seed`: the family cycles with the case
/// number, the rest comes from a PCG stream of its own.
pub fn generate_case(seed: u64, case: u64) -> (&'static str, Pslg) {
    let mut rng = Pcg64::new(seed as u128, case as u128);
    let family = FAMILIES[(case % FAMILIES.len() as u64) as usize];
    let n = rng.random_range(1..=80usize);
    let unit = |rng: &mut Pcg64| [rng.random::<f64>(), rng.random::<f64>()];
    let mut points: Vec<Point> = match family {
        "uniform" => (0..n).map(|_| unit(&mut rng)).collect(),
        "clustered" => {
            let centres: Vec<Point> = (0..rng.random_range(1..=4))
                .map(|_| unit(&mut rng))
                .collect();
            let spread = 10f64.powf(-rng.random_range(1.0..5.0));
            (0..n)
                .map(|t| {
                    let c = centres[t % centres.len()];
                    [
                        c[0] + spread * (rng.random::<f64>() - 0.5),
                        c[1] + spread * (rng.random::<f64>() - 0.5),
                    ]
                })
                .collect()
        }
        "collinear" => {
            let a = unit(&mut rng);
            let dir = [rng.random::<f64>() - 0.5, rng.random::<f64>() - 0.5];
            // Small-integer steps keep the points exactly collinear in some cases.
            let exact = rng.random_bool(0.5);
            (0..n)
                .map(|t| {
                    if exact {
                        [t as f64, 0.37 * t as f64]
                    } else {
                        let s = rng.random::<f64>();
                        [a[0] + s * dir[0], a[1] + s * dir[1]]
                    }
                })
                .collect()
        }
        "near-duplicates" => {
            let base: Vec<Point> = (0..n.div_ceil(2)).map(|_| unit(&mut rng)).collect();
            let mut v = Vec::new();
            for p in base {
                let gap = 10f64.powf(-rng.random_range(2.0..9.0));
                let angle = rng.random::<f64>() * std::f64::consts::TAU;
                v.push(p);
                v.push([p[0] + gap * angle.cos(), p[1] + gap * angle.sin()]);
            }
            v
        }
        "scaled" => {
            let s = 10f64.powf(rng.random_range(-6.0..6.0));
            (0..n)
                .map(|_| {
                    let p = unit(&mut rng);
                    [p[0] * s, p[1] * s]
                })
                .collect()
        }
        "translated" => {
            let s = 10f64.powf(rng.random_range(-1.0..6.0));
            (0..n)
                .map(|_| {
                    let p = unit(&mut rng);
                    [1e7 + p[0] * s, -1e7 + p[1] * s]
                })
                .collect()
        }
        _ => lattice_points(&mut rng, n),
    };
    dedup(&mut points);
    let mut input = Pslg::from_points(points);
    if family == "lattice" {
        input.hexagon = Some(unit_hexagon());
    }
    (family, input)
}

/// The regular hexagon of circumradius 1 at the origin.
pub fn unit_hexagon() -> Hexagon {
    Hexagon {
        center: [0.0, 0.0],
        circumradius: 1.0,
    }
}

/// Points exactly on hexagon centres, edge midpoints and corners of levels 1–6 of the unit
/// hexagon (constructed with the mesher's own formula, so bit-identical to its lattice), kept
/// only when strictly inside the bounding hexagon.
fn lattice_points(rng: &mut Pcg64, n: usize) -> Vec<Point> {
    let lat = Lattice::new(unit_hexagon());
    let root = unit_hexagon();
    let mut v = Vec::new();
    while v.len() < n {
        let k = rng.random_range(1..=6u8);
        let span = 1i64 << k;
        let key = Key::new(
            k,
            rng.random_range(-span..=span),
            rng.random_range(-span..=span),
        );
        let p = match rng.random_range(0..3) {
            0 => lat.center(key),
            1 => lat.corner(key, rng.random_range(0..6)),
            _ => lat.center(key.edge_child(rng.random_range(0..6))),
        };
        if root.contains_strictly(p) {
            v.push(p);
        }
    }
    v
}

fn dedup(points: &mut Vec<Point>) {
    let mut seen: Vec<Point> = Vec::with_capacity(points.len());
    points.retain(|p| {
        let key = [p[0] + 0.0, p[1] + 0.0];
        if seen.contains(&key) {
            false
        } else {
            seen.push(key);
            true
        }
    });
}

/// Facts about a checked mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshStats {
    pub min_angle: f64,
    pub max_angle: f64,
    pub triangles: usize,
}

/// Checks a mesh against what every hexagonal mesher promises: triangles strictly
/// counter-clockwise (exact), every directed edge used once and every edge by at most two
/// triangles, no duplicate vertices, input point i is vertex i bit for bit, and (when given)
/// every angle within the bounds with 1e-6° slack.
pub fn check_mesh(
    mesh: &TriMesh,
    points: &[Point],
    bounds: Option<(f64, f64)>,
) -> Result<MeshStats, String> {
    if mesh.triangles.is_empty() {
        return Err("the mesh has no triangles".into());
    }
    for (i, p) in points.iter().enumerate() {
        if mesh.vertices.get(i) != Some(p) {
            return Err(format!(
                "input point {i} ({}, {}) is not vertex {i}",
                p[0], p[1]
            ));
        }
    }
    let nv = mesh.vertices.len() as u32;
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v >= nv) {
            return Err(format!("triangle {t} names a missing vertex"));
        }
        let [a, b, c] = mesh.corners(t);
        if orient2d(a, b, c) <= 0.0 {
            return Err(format!("triangle {t} {tri:?} is not counter-clockwise"));
        }
        for e in 0..3 {
            edges.push((tri[e], tri[(e + 1) % 3]));
        }
    }
    edges.sort_unstable();
    if let Some(w) = edges.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!("directed edge {:?} is used twice", w[0]));
    }
    let mut vs: Vec<[u64; 2]> = mesh
        .vertices
        .iter()
        .map(|p| [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits()])
        .collect();
    vs.sort_unstable();
    if vs.windows(2).any(|w| w[0] == w[1]) {
        return Err("two vertices coincide".into());
    }
    let used = {
        let mut u = vec![false; mesh.vertices.len()];
        for t in &mesh.triangles {
            for &v in t {
                u[v as usize] = true;
            }
        }
        u
    };
    if let Some(v) = used.iter().position(|&u| !u) {
        return Err(format!("vertex {v} is in no triangle"));
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for t in 0..mesh.triangles.len() {
        let c = mesh.corners(t);
        for m in 0..3 {
            let a = angle_deg(c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
            lo = lo.min(a);
            hi = hi.max(a);
            if let Some((min, max)) = bounds {
                if a < min - 1e-6 || a > max + 1e-6 {
                    return Err(format!(
                        "triangle {t} {:?} has an angle of {a:.9}° outside [{min:.6}°, {max}°]",
                        mesh.triangles[t]
                    ));
                }
            }
        }
    }
    Ok(MeshStats {
        min_angle: lo,
        max_angle: hi,
        triangles: mesh.triangles.len(),
    })
}

/// The angle at `a` of triangle (a, b, c), in degrees.
pub fn angle_deg(a: Point, b: Point, c: Point) -> f64 {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let (vx, vy) = (c[0] - a[0], c[1] - a[1]);
    (ux * vy - uy * vx)
        .abs()
        .atan2(ux * vx + uy * vy)
        .to_degrees()
}

/// Writes the points of a failing case as a Triangle .node file under `fuzz-failures/`.
pub fn write_failure(
    mesher: &str,
    seed: u64,
    case: u64,
    family: &str,
    input: &Pslg,
) -> std::io::Result<PathBuf> {
    let dir = PathBuf::from("fuzz-failures");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join(format!("{mesher}-seed{seed}-case{case}-{family}.node"));
    let mut s = format!("# fuzz case {case} of seed {seed} ({family}) that failed {mesher}\n");
    if let Some(h) = input.hexagon {
        // The directive `io::read_input` understands.
        s.push_str(&format!(
            "# hexmesh: hexagon {} {} {}\n",
            h.center[0], h.center[1], h.circumradius
        ));
    }
    s.push_str(&format!("{} 2 0 0\n", input.points.len()));
    for (i, p) in input.points.iter().enumerate() {
        s.push_str(&format!("{} {} {}\n", i + 1, p[0], p[1]));
    }
    std::fs::write(&path, s)?;
    Ok(path)
}
