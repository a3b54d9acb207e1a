//! A seeded fuzz campaign for the hexagonal meshers: random point sets of the families that
//! stress paper 000's guarantees (uniform, clustered, collinear, near-duplicates, extreme
//! scales, far translations, points exactly on hexagon centres, edges and corners), each meshed
//! and checked by `quality::verdict` against the bounds the mesher promises
//! (`Mesher::promise`: Sec. 4.3 for `hex-simple`, Sec. 6 for `hex`). Failing cases are
//! written out as Triangle .node files when the campaign is given a directory for them.

use std::ops::Range;
use std::path::{Path, PathBuf};

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::error::{Error, InputError};
use crate::geom::{Hexagon, Point};
use crate::hex::lattice::{Key, Lattice};
use crate::mesh::Pslg;
use crate::mesher::{Mesher, Params};
use crate::quality;

/// What a campaign found.
#[derive(Debug, Clone, PartialEq)]
pub struct FuzzSummary {
    pub mesher: String,
    pub seed: u64,
    /// The first case's number (0 unless the campaign was asked to start later).
    pub first: u64,
    pub cases: u64,
    /// Cases refused as too close for f64 at their coordinates (`InputError::Rounding`,
    /// `NearBoundary` or `Range`).
    pub refused: u64,
    /// Finished meshes (failing ones too) by the largest rounding allowance one of their
    /// angles uses (degrees beyond the promised angle bounds, `quality::rounding`, as the
    /// verdict's angle checks report it), in the bins of `ROUNDING_BINS`; none are counted
    /// for a mesher that promises no angles.
    pub rounding_used: [u64; ROUNDING_BINS.len()],
    pub failures: u64,
    /// The smallest and largest angle seen over all meshes that passed, in degrees.
    pub worst_min_angle: f64,
    pub worst_max_angle: f64,
    /// The most triangles in one mesh that passed.
    pub max_triangles: usize,
    /// The largest radius ratio R/(2r) seen over every finished mesh (failing ones too).
    pub worst_radius_ratio: f64,
    /// The smallest shortest-edge / d_min seen (inputs with at least two points, failing
    /// meshes too).
    pub worst_edge_over_d_min: f64,
    /// The largest number of exact empty-circle violations in one mesh (failing ones too).
    pub max_delaunay_violations: usize,
    /// Cases, refusals and failures per family, in the order of `FAMILIES`.
    pub families: Vec<FamilyCounts>,
    pub first_failure: Option<FuzzFailure>,
    /// Every failing case (case number, family, where its input was written), so that a long
    /// campaign names all it found, not only the first.
    pub failed: Vec<(u64, &'static str, Option<PathBuf>)>,
}

/// The bins of `FuzzSummary::rounding_used`: none used, then at most 1e-9°, 1e-6°, 1e-4°,
/// 1e-3°, 1e-2° and more.
pub const ROUNDING_BINS: [&str; 7] = [
    "0",
    "≤1e-9°",
    "≤1e-6°",
    "≤1e-4°",
    "≤1e-3°",
    "≤1e-2°",
    ">1e-2°",
];

/// The bin of `ROUNDING_BINS` an allowance of `used` degrees falls in.
pub fn rounding_bin(used: f64) -> usize {
    [0.0, 1e-9, 1e-6, 1e-4, 1e-3, 1e-2]
        .iter()
        .position(|&top| used <= top)
        .unwrap_or(ROUNDING_BINS.len() - 1)
}

/// What a campaign found in one family of point sets.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyCounts {
    pub family: &'static str,
    pub cases: u64,
    pub refused: u64,
    pub failures: u64,
}

/// The first failing case of a campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct FuzzFailure {
    pub case: u64,
    pub family: &'static str,
    pub message: String,
    /// Where the input was written (a Triangle .node file), when the campaign had a directory
    /// for it and writing worked.
    pub path: Option<PathBuf>,
}

/// Records a failing case in a campaign's list and, when it is the first, as its first
/// failure; `write` puts its input into the campaign's directory (given one), for the first
/// hundred failures.
pub(crate) fn record_failure<E, W: FnOnce() -> Result<PathBuf, E>>(
    failed: &mut Vec<(u64, &'static str, Option<PathBuf>)>,
    first: &mut Option<FuzzFailure>,
    mut failure: FuzzFailure,
    write: Option<W>,
) {
    failure.path = write.filter(|_| failed.len() < 100).and_then(|w| w().ok());
    failed.push((failure.case, failure.family, failure.path.clone()));
    first.get_or_insert(failure);
}

/// The families of generated point sets, in the order cases cycle through them.
/// The first seven are the original families, whose point sets are generated as before but
/// for near-duplicates, which reach 1e-11 of their coordinates apart (they stopped at 1e-9);
/// the families appended later only renumber the cases.
pub const FAMILIES: [&str; 10] = [
    "uniform",
    "clustered",
    "collinear",
    "near-duplicates",
    "scaled",
    "translated",
    "lattice",
    "cocircular",
    "grid",
    "projected",
];

/// Runs the random cases numbered `cases` (`0..n` is a campaign of n, `k..k + 1` its case k
/// alone) through the mesher `mesher` (any registered name, or `hex-simple`, or `hex-tiled`:
/// `hex` with tiles of 16 points), seeded by `seed`; `progress` is called after each case
/// with the number done.
/// The input of each failing case is written into `out` (`write_failure`) when it is given;
/// without it nothing is written and the failures are only reported.
pub fn fuzz_campaign(
    mesher: &str,
    cases: Range<u64>,
    seed: u64,
    out: Option<&Path>,
    progress: impl FnMut(u64),
) -> FuzzSummary {
    fuzz_campaign_sized(mesher, cases, seed, MAX_POINTS, out, progress)
}

/// What a campaign's summary line says of where its cases start: nothing from case 0,
/// else " from case N".
pub fn from_case(first: u64) -> String {
    if first > 0 {
        format!(" from case {first}")
    } else {
        String::new()
    }
}

/// Most points in one generated case (before duplicates are dropped).
pub const MAX_POINTS: usize = 80;

/// The figures of one finished mesh the summary keeps, read off its verdict.
struct Figures {
    min_angle: Option<f64>,
    max_angle: Option<f64>,
    radius_ratio: Option<f64>,
    edge_over_d_min: Option<f64>,
    delaunay_violations: usize,
    /// The largest rounding allowance an angle used against the angle bounds, when the
    /// bounds have any.
    rounding_used: Option<f64>,
}

impl Figures {
    fn of(v: &quality::Verdict) -> Figures {
        let m = &v.metrics;
        // The verdict checks the smallest and the largest angle apart; an angle uses
        // allowance against one of them at most, so the larger of the two is what it uses
        // against both.
        let rounding_used = v
            .checks
            .iter()
            .filter(|c| c.what == "min angle (deg)" || c.what == "max angle (deg)")
            .filter_map(|c| c.rounding.map(|r| r.used))
            .reduce(f64::max);
        Figures {
            min_angle: m.min_angle.map(|w| w.value),
            max_angle: m.max_angle.map(|w| w.value),
            radius_ratio: m.radius_ratio_max.map(|w| w.value),
            edge_over_d_min: m.shortest_edge_over_d_min,
            delaunay_violations: m.delaunay_violations,
            rounding_used,
        }
    }
}

/// `fuzz_campaign` with at most `max_points` points per case (`generate_sized_case`): small
/// sets mesh fast enough for a test of a thousand cases.
pub fn fuzz_campaign_sized(
    mesher: &str,
    cases: Range<u64>,
    seed: u64,
    max_points: usize,
    out: Option<&Path>,
    mut progress: impl FnMut(u64),
) -> FuzzSummary {
    let mut summary = FuzzSummary {
        mesher: mesher.to_string(),
        seed,
        first: cases.start,
        cases: 0,
        refused: 0,
        rounding_used: [0; ROUNDING_BINS.len()],
        failures: 0,
        worst_min_angle: f64::INFINITY,
        worst_max_angle: f64::NEG_INFINITY,
        max_triangles: 0,
        worst_radius_ratio: f64::NEG_INFINITY,
        worst_edge_over_d_min: f64::INFINITY,
        max_delaunay_violations: 0,
        families: FAMILIES
            .iter()
            .map(|&family| FamilyCounts {
                family,
                cases: 0,
                refused: 0,
                failures: 0,
            })
            .collect(),
        first_failure: None,
        failed: Vec::new(),
    };
    let m: Box<dyn Mesher> = match mesher {
        "hex-simple" => Box::new(crate::hex::HexSimple),
        "hex" => Box::new(crate::hex::extended::Hex),
        // `hex` with tiles of 16 points, so that these small sets are meshed in tiles as
        // large inputs are (`HexInTiles`).
        "hex-tiled" => Box::new(crate::hex::extended::HexInTiles(16)),
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
    // What the mesher promises for the parameters of the campaign (`verify --bounds NAME`).
    let promised = Some(m.promise(&Params::default()));
    let first = cases.start;
    for case in cases {
        let (family, input) = generate_sized_case(seed, case, max_points);
        let fam = FAMILIES.iter().position(|&f| f == family).unwrap_or(0);
        summary.families[fam].cases += 1;
        let outcome = match m.mesh(&input, &Params::default()) {
            Ok(run) if !run.complete => Err(format!(
                "stopped early without a budget: {:?}",
                run.stop_reason
            )),
            Ok(run) => {
                // Validity (one disc, every input point a vertex bit for bit) and every bound
                // the mesher promises, each angle and ratio up to its rounding allowance.
                let v = quality::verdict(&run.mesh, Some(&input), promised.as_ref())
                    .numbered(quality::Numbering::FILES);
                let f = Figures::of(&v);
                if let Some(used) = f.rounding_used {
                    summary.rounding_used[rounding_bin(used)] += 1;
                }
                if let Some(w) = f.radius_ratio {
                    summary.worst_radius_ratio = summary.worst_radius_ratio.max(w);
                }
                if let Some(e) = f.edge_over_d_min {
                    summary.worst_edge_over_d_min = summary.worst_edge_over_d_min.min(e);
                }
                summary.max_delaunay_violations =
                    summary.max_delaunay_violations.max(f.delaunay_violations);
                if v.passed() {
                    if let Some(a) = f.min_angle {
                        summary.worst_min_angle = summary.worst_min_angle.min(a);
                    }
                    if let Some(a) = f.max_angle {
                        summary.worst_max_angle = summary.worst_max_angle.max(a);
                    }
                    summary.max_triangles = summary.max_triangles.max(run.mesh.triangles.len());
                    Ok(())
                } else {
                    Err(format!("quality verdict failed:\n{v}"))
                }
            }
            Err(Error::Input {
                problem:
                    InputError::Range { .. }
                    | InputError::Rounding { .. }
                    | InputError::NearBoundary { .. },
                ..
            }) => {
                summary.refused += 1;
                summary.families[fam].refused += 1;
                Ok(())
            }
            Err(e) => Err(e.to_string()),
        };
        summary.cases += 1;
        if let Err(message) = outcome {
            summary.failures += 1;
            summary.families[fam].failures += 1;
            // Every failing input is written when there is a directory for them (up to a
            // hundred files).
            record_failure(
                &mut summary.failed,
                &mut summary.first_failure,
                FuzzFailure {
                    case,
                    family,
                    message,
                    path: None,
                },
                out.map(|dir| move || write_failure(dir, mesher, seed, case, family, &input)),
            );
        }
        progress(case + 1 - first);
    }
    summary
}

/// The input of case `case` of a campaign seeded `seed`: the family cycles with the case
/// number, the rest comes from a PCG stream of its own.
pub fn generate_case(seed: u64, case: u64) -> (&'static str, Pslg) {
    generate_sized_case(seed, case, MAX_POINTS)
}

/// `generate_case` with 1 to `max_points` points drawn instead of 1 to `MAX_POINTS` (the same
/// cases when `max_points == MAX_POINTS`).
pub fn generate_sized_case(seed: u64, case: u64, max_points: usize) -> (&'static str, Pslg) {
    let family = FAMILIES[(case % FAMILIES.len() as u64) as usize];
    (family, sized_family_case(seed, case, family, max_points))
}

/// The input of family `family` drawn from the PCG stream of case `case` of seed `seed`: the
/// point set `generate_case` gives when the case falls on that family. Keeps a case found
/// under an older family cycle reproducible. An unknown family name gives lattice points.
pub fn generate_family_case(seed: u64, case: u64, family: &str) -> Pslg {
    sized_family_case(seed, case, family, MAX_POINTS)
}

fn sized_family_case(seed: u64, case: u64, family: &str, max_points: usize) -> Pslg {
    let mut rng = Pcg64::new(seed as u128, case as u128);
    let n = rng.random_range(1..=max_points.max(1));
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
                // From 1e-2 down to 1e-11 of the point's own coordinates.
                let gap = p[0].max(p[1]) * 10f64.powf(-rng.random_range(2.0..11.0));
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
        "cocircular" => cocircular_points(&mut rng, n),
        "projected" => projected_points(&mut rng, n),
        "grid" => grid_points(&mut rng, n),
        _ => lattice_points(&mut rng, n),
    };
    dedup(&mut points);
    let mut input = Pslg::from_points(points);
    if family == "lattice" {
        input.hexagon = Some(unit_hexagon());
    }
    input
}

/// Points on one circle, many of them exactly: the circle has an integer centre and a radius
/// 65·2^e, and the points c + R·(a/h, b/h) of the Pythagorean triples (3, 4, 5), (5, 12, 13)
/// and (33, 56, 65) (all sign and swap symmetries, and the four axis points) are exact in
/// f64, so the 4, 8 or 12 points of a circle are cocircular to the bit. Some sets add points
/// at random angles (cocircular up to rounding) or a few points inside the circle.
fn cocircular_points(rng: &mut Pcg64, n: usize) -> Vec<Point> {
    let centre = [
        rng.random_range(-8i32..=8) as f64,
        rng.random_range(-8i32..=8) as f64,
    ];
    let radius = 65.0 * 2f64.powi(rng.random_range(-10..=4));
    let mut dirs: Vec<(f64, f64)> = vec![(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
    let triples: [(f64, f64, f64); 3] = [(3.0, 4.0, 5.0), (5.0, 12.0, 13.0), (33.0, 56.0, 65.0)];
    let used = rng.random_range(0..=triples.len());
    for &(a, b, h) in &triples[..used] {
        for (x, y) in [(a, b), (b, a)] {
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
                dirs.push((sx * x / h, sy * y / h));
            }
        }
    }
    let mut v: Vec<Point> = dirs
        .iter()
        .map(|&(c, s)| [centre[0] + radius * c, centre[1] + radius * s])
        .collect();
    match rng.random_range(0..3) {
        0 => {}
        1 => {
            for _ in 0..n.min(40) {
                let a = rng.random::<f64>() * std::f64::consts::TAU;
                v.push([centre[0] + radius * a.cos(), centre[1] + radius * a.sin()]);
            }
        }
        _ => {
            for _ in 0..rng.random_range(1..=4) {
                let (x, y) = (rng.random::<f64>() - 0.5, rng.random::<f64>() - 0.5);
                v.push([centre[0] + radius * x, centre[1] + radius * y]);
            }
        }
    }
    v
}

/// Points in projected map coordinates (UTM metres: x in [4e5, 6e5], y in [4e6, 6e6]) as a
/// survey or a LiDAR tile gives them: a patch of 1 m to 10 km, its points uniform, on a
/// 1 cm grid, or with a few pairs down to 1 mm apart.
fn projected_points(rng: &mut Pcg64, n: usize) -> Vec<Point> {
    let origin = [
        rng.random_range(4e5..6e5f64).floor(),
        rng.random_range(4e6..6e6f64).floor(),
    ];
    let size = 10f64.powf(rng.random_range(0.0..4.0));
    let mut v: Vec<Point> = (0..n)
        .map(|_| {
            let p = [
                origin[0] + size * rng.random::<f64>(),
                origin[1] + size * rng.random::<f64>(),
            ];
            match rng.random_range(0..3) {
                // Centimetres, as survey exports round them.
                0 => [
                    (p[0] * 100.0).round() / 100.0,
                    (p[1] * 100.0).round() / 100.0,
                ],
                _ => p,
            }
        })
        .collect();
    if rng.random_bool(0.5) {
        for k in 0..v.len().min(4) {
            let gap = 10f64.powf(-rng.random_range(0.0..3.0));
            let angle = rng.random::<f64>() * std::f64::consts::TAU;
            let p = v[k];
            v.push([p[0] + gap * angle.cos(), p[1] + gap * angle.sin()]);
        }
    }
    v
}

/// An exact integer grid (spacing a power of two), unshifted, shifted by half a spacing, or
/// shifted by a random offset (which rounding makes only nearly regular).
fn grid_points(rng: &mut Pcg64, n: usize) -> Vec<Point> {
    let cols = rng.random_range(1..=10usize);
    let rows = n.div_ceil(cols).clamp(1, 10);
    let h = 2f64.powi(rng.random_range(-8..=8));
    let shift = match rng.random_range(0..3) {
        0 => [0.0, 0.0],
        1 => [0.5 * h, 0.5 * h],
        _ => [rng.random::<f64>() * 100.0, rng.random::<f64>() * 100.0],
    };
    let mut v = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in 0..cols {
            v.push([shift[0] + c as f64 * h, shift[1] + r as f64 * h]);
        }
    }
    v
}

/// The regular hexagon of circumradius 1 at the origin.
pub fn unit_hexagon() -> Hexagon {
    Hexagon::new([0.0, 0.0], 1.0)
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

/// Writes the points of a failing case as a Triangle .node file into `dir` (created if
/// missing), named after the mesher, seed, case and family; returns its path.
pub fn write_failure(
    dir: &Path,
    mesher: &str,
    seed: u64,
    case: u64,
    family: &str,
    input: &Pslg,
) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join(format!("{mesher}-seed{seed}-case{case}-{family}.node"));
    let mut s = format!("# fuzz case {case} of seed {seed} ({family}) that failed {mesher}\n");
    if let Some(h) = input.hexagon {
        // The directive `io::read_input` understands.
        s.push_str(&crate::io::triangle::hexagon_directive_text(&h));
        s.push('\n');
    }
    s.push_str(&format!("{} 2 0 0\n", input.points.len()));
    for (i, p) in input.points.iter().enumerate() {
        s.push_str(&format!("{} {} {}\n", i + 1, p[0], p[1]));
    }
    std::fs::write(&path, s)?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failing_case_is_written_into_the_given_directory_and_reads_back() {
        let dir = std::env::temp_dir()
            .join(format!("hexmesh-fuzz-{}", std::process::id()))
            .join("failures");
        // A lattice case: its bounding hexagon is written as a directive too.
        let input = generate_family_case(7, 6, "lattice");
        let path = write_failure(&dir, "hex", 7, 6, "lattice", &input).expect("written");
        assert_eq!(path, dir.join("hex-seed7-case6-lattice.node"));
        let back = crate::io::read_input(&path).expect("reads back");
        assert_eq!(back.points, input.points);
        assert_eq!(back.hexagon, input.hexagon);
        std::fs::remove_dir_all(dir.parent().unwrap()).ok();
    }
}
