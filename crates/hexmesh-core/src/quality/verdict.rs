//! The verdict on one mesh: validity plus every bound of a `Bounds`, each with its value, its
//! limit and, when it fails, the worst triangle — what `hexmesh verify` prints as a table and,
//! with `--json`, as serde JSON.

use std::fmt;

use crate::geom::Point;
use crate::mesh::{Pslg, TriMesh};
use crate::quality::bounds::Bounds;
use crate::quality::descent::descent;
use crate::quality::metrics::{
    metrics_split_with, metrics_with, triangle_shape, Metrics, SplitMetrics,
};
use crate::quality::rounding::{self, angle_fit, angle_uses, fit_of, Fit, Use, ANGLE_FLOOR_DEG};
use crate::quality::validate::{topology, validate_with, Numbering, ValidateOptions, Violation};

/// The outcome of one check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Status {
    /// The bound holds (up to the rounding allowance).
    Ok,
    /// The bound fails.
    Fail,
    /// The check needs something that is missing (e.g. the input, for d_min).
    Skipped,
}

/// A triangle named in a failed check, with its corners.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct WorstTriangle {
    /// The triangle's 0-based index.
    pub triangle: usize,
    /// Its corners, in the triangle's (counter-clockwise) order.
    pub corners: [Point; 3],
    /// The figure at that triangle (angle, ratio, ...).
    pub value: f64,
}

/// One row of the verdict table.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Check {
    /// What was checked, with its unit.
    pub what: String,
    /// The measured figure; `None` when there is none (no triangles, or skipped).
    pub value: Option<f64>,
    /// "≥", "≤" or "=".
    pub relation: String,
    /// The bound the figure is held to, in the unit of `what`.
    pub limit: f64,
    /// The outcome.
    pub status: Status,
    /// For a failed bound: the triangle where it fails worst.
    pub worst: Option<WorstTriangle>,
    /// For a bound checked with the rounding allowance: the largest allowance a figure uses.
    pub rounding: Option<Rounding>,
    /// Why a check was skipped, or which part of the mesh it covers.
    pub note: Option<String>,
}

/// The largest allowance a figure of a mesh uses against its bound, and the allowance that
/// figure has (`quality::rounding`): both in the unit of the figure.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Rounding {
    /// How far the figure lies beyond its bound.
    pub used: f64,
    /// How far rounding of its corners may move it.
    pub allowance: f64,
}

/// Validity, bounds and figures of one mesh.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Verdict {
    /// The name of the bounds checked, if any.
    pub bounds: Option<String>,
    /// The validity checks run (one disc, conformity to the segments).
    pub options: ValidateOptions,
    /// Every validity violation found; empty when the mesh is valid.
    pub violations: Vec<Violation>,
    /// The rows: validity first, then one per bound.
    pub checks: Vec<Check>,
    /// The figures of the whole mesh.
    pub metrics: Metrics,
    /// Near-segment and interior figures apart, for inputs with segments.
    pub split: Option<SplitMetrics>,
    /// How the printed verdict numbers vertices, triangles and input items (from 0, the
    /// library's indices, unless set with [`Verdict::numbered`]); the indices in the fields
    /// above stay 0-based.
    pub numbering: Numbering,
}

impl Verdict {
    /// The same verdict, printed with `numbering`: the first index of the files the mesh and
    /// the input were read from.
    pub fn numbered(mut self, numbering: Numbering) -> Verdict {
        self.numbering = numbering;
        self
    }

    /// The rows that failed, in table order.
    pub fn failed(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| c.status == Status::Fail)
    }

    /// True when the mesh is valid and no bound fails (skipped checks do not fail).
    pub fn passed(&self) -> bool {
        self.violations.is_empty() && self.checks.iter().all(|c| c.status != Status::Fail)
    }
}

/// Validates `mesh` and checks it against `bounds`. Without bounds, only validity (with
/// conformity off) is decided and the figures are reported. The one-disc rule applies when
/// `input` is a point set: without it, a mesh with holes may be the mesh of a domain.
pub fn verdict(mesh: &TriMesh, input: Option<&Pslg>, bounds: Option<&Bounds>) -> Verdict {
    let options = ValidateOptions {
        // The mesh of a point set is one disc, whatever the bounds: a second boundary loop is a
        // hole the mesher had no business making. Without the input nothing says the mesh is
        // of a point set, and a mesh of a domain may have holes.
        single_component: input.is_some_and(|i| !i.has_segments()),
        conforming: bounds.is_some_and(|b| b.conforming),
    };
    // The edge structure, which the validity checks and the figures both read: built once.
    let topo = topology(mesh);
    let split = input.filter(|i| i.has_segments()).map(|i| {
        metrics_split_with(
            mesh,
            i,
            crate::quality::metrics::on_segment_tolerance(i),
            &topo,
        )
    });
    // The triangles the shape bounds cover: away from the segments when the bounds say so
    // (out-of-range corners are validate's business).
    let interior_only = bounds.is_some_and(|b| b.interior_only_on_segments) && split.is_some();
    let mut part = vec![true; mesh.triangles.len()];
    if let (Some(s), true) = (&split, interior_only) {
        for &t in &s.near_triangles {
            part[t] = false;
        }
    }
    // Validity, the figures and the rounding fits are independent passes over the mesh: they
    // run side by side, each whole on one thread, so the verdict does not depend on the
    // machine (at plane-100k, hex's 11.7 M triangles, they took 5, 5 and 7 s one after the
    // other).
    let (violations, all, fits) = std::thread::scope(|scope| {
        let violations = scope.spawn(|| validate_with(mesh, input, &options, &topo));
        let fits = bounds.map(|b| {
            let part = &part;
            (
                scope.spawn(move || angle_fits(mesh, input, b, part)),
                scope.spawn(move || size_fits(mesh, input, b, part)),
            )
        });
        let all = metrics_with(mesh, input, &topo);
        let fits = fits.map(|(angles, sizes)| ShapeFits {
            angles: join(angles),
            sizes: join(sizes),
        });
        (join(violations), all, fits)
    });

    let mut checks = vec![Check {
        what: "validity violations".to_string(),
        value: Some(violations.len() as f64),
        relation: "=".to_string(),
        limit: 0.0,
        status: if violations.is_empty() {
            Status::Ok
        } else {
            Status::Fail
        },
        worst: None,
        rounding: None,
        note: None,
    }];
    if let (Some(b), Some(fits)) = (bounds, fits) {
        let (m, note) = match (&split, interior_only) {
            (Some(s), true) => (&s.interior, Some("away from segments".to_string())),
            _ => (&all, None),
        };
        // A figure with its limit, in the part of the mesh the shape bounds cover (`fit_check`).
        let mut bound = |what: &str, value: Option<f64>, ge: bool, limit: f64, fit: Option<Fit>| {
            checks.push(fit_check(mesh, what, (value, ge, limit), fit, note.clone()));
        };
        let mut exempt_corners = 0usize;
        if let (Some(limit), Some((fit, smallest, exempt))) = (b.min_angle, fits.angles.min) {
            let value = if fits.angles.whole_corners {
                smallest
            } else {
                m.min_angle.map(|w| w.value)
            };
            bound("min angle (deg)", value, true, limit, fit);
            exempt_corners = exempt;
        }
        if let (Some(limit), Some(fit)) = (b.max_angle, fits.angles.max) {
            bound(
                "max angle (deg)",
                m.max_angle.map(|w| w.value),
                false,
                limit,
                fit,
            );
        }
        if let (Some(limit), Some(fit)) = (b.max_radius_ratio, fits.sizes.radius_ratio) {
            bound(
                "radius ratio R/(2r)",
                m.radius_ratio_max.map(|w| w.value),
                false,
                limit,
                fit,
            );
        }
        // A size limit of the input's regions sets the edge scale where it is finer than the
        // points: the shortest edge relative to d_min (hex's Sec. 6.3) is then not promised
        // (`Mesher::promise` drops it for `--max-area`/`--max-edge`, which it sees).
        let sized = b.region_area_limits && input.is_some_and(Pslg::has_area_limits);
        if let Some(limit) = b.min_edge_over_dmin {
            let skipped = |note: &str| Check {
                what: "shortest edge / d_min".to_string(),
                value: None,
                relation: "≥".to_string(),
                limit,
                status: Status::Skipped,
                worst: None,
                rounding: None,
                note: Some(note.to_string()),
            };
            match (m.shortest_edge, m.d_min) {
                _ if sized => checks.push(skipped(
                    "the input's regional area limits set the edge lengths",
                )),
                (Some(s), Some(d)) if d > 0.0 => {
                    // `size_fits` measured the edges against the same d_min.
                    let fit = fits.sizes.edge.flatten();
                    bound("shortest edge / d_min", Some(s.value / d), true, limit, fit);
                }
                (None, _) => bound("shortest edge / d_min", None, true, limit, None),
                _ => checks.push(skipped("needs the input points (two or more)")),
            }
        }
        if exempt_corners > 0 {
            if let Some(check) = checks.iter_mut().find(|c| c.what == "min angle (deg)") {
                let words = format!(
                    "{exempt_corners} angle{} at input corners sharper than the bound, taken \
                     whole, left out",
                    if exempt_corners == 1 { "" } else { "s" }
                );
                check.note = Some(match check.note.take() {
                    Some(n) => format!("{n}; {words}"),
                    None => words,
                });
            }
        }
        if let (Some((lo, hi)), Some(s), Some(i), true) =
            (b.near_segment_angles, &split, input, interior_only)
        {
            checks.extend(near_segment_checks(mesh, i, s, lo, hi));
        }
        if let (true, Some(i)) = (b.constrained_delaunay && b.delaunay, input) {
            if i.has_segments() {
                checks.push(constrained_delaunay_check(mesh, i));
            }
        }
        if let Some(r) = b.min_angle_over_ancestor {
            checks.push(descent_check(mesh, input, r));
        }
        let regional = b.region_area_limits && input.is_some_and(Pslg::has_area_limits);
        if b.max_area.is_some() || regional {
            checks.push(area_check(mesh, input.filter(|_| regional), b.max_area));
        }
        if let Some(limit) = b.max_edge {
            checks.push(edge_check(mesh, limit));
        }
        if b.delaunay {
            let what = "non-Delaunay edges (exact)";
            let (count, first) = (m.delaunay_violations, m.delaunay_first);
            checks.push(delaunay_check(mesh, what, count, first, note.clone()));
        }
    }
    Verdict {
        bounds: bounds.map(|b| b.name.clone()),
        options,
        violations,
        checks,
        metrics: all,
        split,
        numbering: Numbering::default(),
    }
}

/// What a scoped thread returned; its panic goes on in the caller.
fn join<T>(handle: std::thread::ScopedJoinHandle<'_, T>) -> T {
    match handle.join() {
        Ok(r) => r,
        Err(panic) => std::panic::resume_unwind(panic),
    }
}

/// The rounding fits of a verdict's shape bounds (`fit_check`), computed beside its other
/// passes.
struct ShapeFits {
    angles: AngleFits,
    sizes: SizeFits,
}

/// The fits of the angle bounds: each `None` when the bounds have no such limit.
struct AngleFits {
    /// The min-angle fit, the smallest angle kept and how many angles at whole sharp input
    /// corners were left out (`min_angle_fit`).
    min: Option<(Option<Fit>, Option<f64>, usize)>,
    /// Whether the min-angle fit left out the whole sharp corners (the bound says so and the
    /// input has segments): its smallest angle is then the figure reported.
    whole_corners: bool,
    max: Option<Option<Fit>>,
}

/// The fits of the radius ratio and of the shortest edge over d_min: each `None` when the
/// bounds have no such limit (the edge's also without a positive d_min).
struct SizeFits {
    radius_ratio: Option<Option<Fit>>,
    edge: Option<Option<Fit>>,
}

/// The triangles `part` marks whose corners are all vertices of `mesh`, with their corners.
fn covered<'a>(
    mesh: &'a TriMesh,
    part: &'a [bool],
) -> impl Iterator<Item = (usize, [Point; 3])> + 'a {
    let n = mesh.vertices.len();
    (0..mesh.triangles.len())
        .filter(move |&t| part[t] && mesh.triangles[t].iter().all(|&v| (v as usize) < n))
        .map(move |t| (t, mesh.corners(t)))
}

/// The fits of the min- and max-angle bounds of `b` over the triangles `part` marks.
fn angle_fits(mesh: &TriMesh, input: Option<&Pslg>, b: &Bounds, part: &[bool]) -> AngleFits {
    // Input corners sharper than the bound, taken whole, are the input's, not the mesher's
    // (`quality::corners`): their angles are left out, and counted.
    let corners = input
        .filter(|i| b.whole_sharp_corners && i.has_segments())
        .map(super::corners::InputCorners::new);
    AngleFits {
        min: b
            .min_angle
            .map(|limit| min_angle_fit(covered(mesh, part), limit, corners.as_ref())),
        whole_corners: corners.is_some(),
        max: b
            .max_angle
            .map(|limit| angle_fit(covered(mesh, part), 0.0, limit)),
    }
}

/// The fits of the radius-ratio bound of `b` and of its shortest edge over d_min (the
/// closest input points or features, as `metrics` takes it) over the triangles `part` marks.
fn size_fits(mesh: &TriMesh, input: Option<&Pslg>, b: &Bounds, part: &[bool]) -> SizeFits {
    let radius_ratio = b.max_radius_ratio.map(|limit| {
        fit_of(covered(mesh, part).map(|(t, c)| {
            let shape = triangle_shape(c);
            let allowance = rounding::radius_ratio_allowance(c, shape.angles, shape.radius_ratio);
            Use {
                used: (shape.radius_ratio - limit).max(0.0),
                allowance,
                value: shape.radius_ratio,
                triangle: t,
            }
        }))
    });
    let d_min = input
        .and_then(crate::quality::feature_gap)
        .map(|c| c.distance)
        .filter(|&d| d > 0.0);
    let edge = b.min_edge_over_dmin.zip(d_min).map(|(limit, d)| {
        fit_of(covered(mesh, part).flat_map(|(t, c)| {
            (0..3).map(move |e| {
                let (p, q) = (c[e], c[(e + 1) % 3]);
                let ratio = crate::geom::dist_scaled(p, q) / d;
                Use {
                    used: (limit - ratio).max(0.0),
                    allowance: rounding::edge_allowance(p, q) / d,
                    value: ratio,
                    triangle: t,
                }
            })
        }))
    });
    SizeFits { radius_ratio, edge }
}

/// The smallest angle of the triangles `tris` against `limit` with the rounding allowance,
/// leaving out the angles at input corners sharper than the limit taken whole (`corners`):
/// the fit, the smallest angle kept and how many were left out. Streamed, as `angle_fit` is:
/// a mesh of 10^8 triangles has 3·10^8 angles.
fn min_angle_fit(
    tris: impl Iterator<Item = (usize, [Point; 3])>,
    limit: f64,
    corners: Option<&super::corners::InputCorners>,
) -> (Option<Fit>, Option<f64>, usize) {
    let exempt = std::cell::Cell::new(0usize);
    let smallest = std::cell::Cell::new(None::<f64>);
    let kept = tris
        .flat_map(|(t, c)| {
            let uses = angle_uses(t, c, limit, 180.0);
            (0..3).map(move |k| (uses[k], [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]))
        })
        .filter_map(|(u, [a, b, c])| {
            if u.value < limit && corners.is_some_and(|k| k.whole_at(a, b, c)) {
                exempt.set(exempt.get() + 1);
                None
            } else {
                smallest.set(Some(smallest.get().map_or(u.value, |s| s.min(u.value))));
                Some(u)
            }
        });
    let fit = fit_of(kept);
    (fit, smallest.get(), exempt.get())
}

/// The rows of the near-segment angle bound (`Bounds::near_segment_angles`): the triangles
/// touching a segment (`split.near_triangles`) have every angle in [lo, hi] with the rounding
/// allowance, but the angles at input corners sharper than lo taken whole.
fn near_segment_checks(
    mesh: &TriMesh,
    input: &Pslg,
    split: &SplitMetrics,
    lo: f64,
    hi: f64,
) -> [Check; 2] {
    let n = mesh.vertices.len();
    let near = || {
        split
            .near_triangles
            .iter()
            .copied()
            .filter(|&t| mesh.triangles[t].iter().all(|&v| (v as usize) < n))
            .map(|t| (t, mesh.corners(t)))
    };
    let corners = super::corners::InputCorners::new(input);
    let (low_fit, smallest, exempt) = min_angle_fit(near(), lo, Some(&corners));
    let high_fit = angle_fit(near(), 0.0, hi);
    let note = "touching a segment".to_string();
    let low_note = match exempt {
        0 => note.clone(),
        1 => format!("{note}; 1 whole sharp input corner left out"),
        k => format!("{note}; {k} whole sharp input corners left out"),
    };
    let row = |what: &str, value: Option<f64>, ge: bool, limit: f64, fit: Option<Fit>, note| {
        fit_check(mesh, what, (value, ge, limit), fit, Some(note))
    };
    [
        row(
            "min angle near segments (deg)",
            smallest,
            true,
            lo,
            low_fit,
            low_note,
        ),
        row(
            "max angle near segments (deg)",
            split.near.max_angle.map(|w| w.value),
            false,
            hi,
            high_fit,
            note,
        ),
    ]
}

/// The constrained Delaunay property over the whole mesh (`Bounds::constrained_delaunay`):
/// no edge off the input segments fails the exact empty-circle test.
fn constrained_delaunay_check(mesh: &TriMesh, input: &Pslg) -> Check {
    let (count, first) = crate::quality::metrics::off_segment_delaunay_violations(mesh, input);
    let what = "non-Delaunay edges off the segments (exact)";
    delaunay_check(mesh, what, count, first, Some("whole mesh".to_string()))
}

/// The row of a figure held to a limit with the rounding allowance (`value` ≥ or ≤ `limit`,
/// as `ge` says): it fails when some triangle uses more than its allowance (`fit.nearest`,
/// the one nearest to breaking it, is then named); `fit.most` is the largest allowance used.
fn fit_check(
    mesh: &TriMesh,
    what: &str,
    (value, ge, limit): (Option<f64>, bool, f64),
    fit: Option<Fit>,
    note: Option<String>,
) -> Check {
    let failed = fit.is_some_and(|f| !f.holds());
    Check {
        what: what.to_string(),
        value,
        relation: if ge { "≥" } else { "≤" }.to_string(),
        limit,
        status: if failed { Status::Fail } else { Status::Ok },
        worst: fit.filter(|_| failed).map(|f| WorstTriangle {
            triangle: f.nearest.triangle,
            corners: mesh.corners(f.nearest.triangle),
            value: f.nearest.value,
        }),
        rounding: fit.map(|f| Rounding {
            used: f.most.used,
            allowance: f.most.allowance,
        }),
        note,
    }
}

/// The row of a count of edges that fail the exact empty-circle test, which must be 0; a
/// triangle of the first such edge is named when it fails.
fn delaunay_check(
    mesh: &TriMesh,
    what: &str,
    count: usize,
    first: Option<crate::quality::DelaunayEdge>,
    note: Option<String>,
) -> Check {
    let failed = count > 0;
    Check {
        what: what.to_string(),
        value: Some(count as f64),
        relation: "=".to_string(),
        limit: 0.0,
        status: if failed { Status::Fail } else { Status::Ok },
        worst: first.filter(|_| failed).map(|e| WorstTriangle {
            triangle: e.triangles[0],
            corners: mesh.corners(e.triangles[0]),
            value: count as f64,
        }),
        rounding: None,
        note,
    }
}

/// The descent bound of longest-side bisection (`quality::descent`): every triangle's
/// smallest angle at least `r` times that of the initial triangle (the constrained Delaunay
/// triangulation of the input's domain, as `lsb` starts from) it lies in, less the angle slack.
fn descent_check(mesh: &TriMesh, input: Option<&Pslg>, r: f64) -> Check {
    let what = "smallest angle / ancestor's (lsb descent)".to_string();
    let skipped = |note: String| Check {
        what: what.clone(),
        value: None,
        relation: "≥".to_string(),
        limit: r,
        status: Status::Skipped,
        worst: None,
        rounding: None,
        note: Some(note),
    };
    let Some(input) = input else {
        return skipped("needs the input (--input) to build the initial triangulation".into());
    };
    let initial = match crate::refine::Lsb::initial(input) {
        Ok((initial, _)) => initial,
        Err(e) => return skipped(format!("no initial triangulation: {e}")),
    };
    let d = descent(&initial, mesh, r);
    let corners = |t: usize, value: f64| WorstTriangle {
        triangle: t,
        corners: mesh.corners(t),
        value,
    };
    let (status, worst, note) = match (d.first_unlocated, d.min_margin) {
        (Some(t), _) => (
            Status::Fail,
            Some(corners(t, f64::NAN)),
            Some("a triangle lies outside the initial triangulation".to_string()),
        ),
        (None, Some((margin, t))) if margin < -ANGLE_FLOOR_DEG => (
            Status::Fail,
            Some(corners(t, d.min_ratio.map_or(f64::NAN, |(v, _)| v))),
            None,
        ),
        _ => (Status::Ok, None, None),
    };
    Check {
        what,
        value: d.min_ratio.map(|(v, _)| v),
        relation: "≥".to_string(),
        limit: r,
        status,
        worst,
        rounding: None,
        note,
    }
}

/// The relative slack of the area check: a mesher compares areas computed in f64, which may
/// differ from ours in the last bits.
const AREA_SLACK: f64 = 1.0 / (1u64 << 40) as f64;

/// Every triangle's area against its limit: `max_area` everywhere and, with `input`, the
/// limit of the region it lies in (`triangle_regions`). The figure is the largest area over
/// limit; it passes up to 1 + 2^-40.
fn area_check(mesh: &TriMesh, input: Option<&Pslg>, max_area: Option<f64>) -> Check {
    let regions = input.map(|i| crate::quality::triangle_regions(mesh, i));
    let mut worst: Option<(f64, usize)> = None;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= mesh.vertices.len()) {
            continue;
        }
        let regional = match (&regions, input) {
            (Some(r), Some(i)) => r[t].and_then(|k| i.labels.regions[k].area_limit()),
            _ => None,
        };
        let Some(limit) = regional.into_iter().chain(max_area).reduce(f64::min) else {
            continue;
        };
        let [a, b, c] = mesh.corners(t);
        let ratio = 0.5 * crate::geom::orient2d(a, b, c) / limit;
        if worst.is_none_or(|(w, _)| ratio > w) {
            worst = Some((ratio, t));
        }
    }
    let note = match (max_area, input.is_some()) {
        (Some(a), true) => format!("--max-area {a} and the input's regional limits"),
        (Some(a), false) => format!("--max-area {a}"),
        (None, _) => "the input's regional limits".to_string(),
    };
    ratio_check(mesh, "triangle area / its limit", worst, note)
}

/// The row of a size limit: `worst` is the largest figure over its limit and the triangle it
/// belongs to; it fails beyond 1 + 2^-40 (`AREA_SLACK`).
fn ratio_check(mesh: &TriMesh, what: &str, worst: Option<(f64, usize)>, note: String) -> Check {
    let failed = worst.is_some_and(|(w, _)| w > 1.0 + AREA_SLACK);
    Check {
        what: what.to_string(),
        value: worst.map(|(w, _)| w),
        relation: "≤".to_string(),
        limit: 1.0,
        status: if failed { Status::Fail } else { Status::Ok },
        worst: worst.filter(|_| failed).map(|(w, t)| WorstTriangle {
            triangle: t,
            corners: mesh.corners(t),
            value: w,
        }),
        rounding: None,
        note: Some(note + "; up to 1 + 2^-40"),
    }
}

/// Every edge's length against `limit` (`--max-edge`). The figure is the longest edge over
/// its limit; it passes up to 1 + 2^-40, the area check's slack (`AREA_SLACK`).
fn edge_check(mesh: &TriMesh, limit: f64) -> Check {
    let mut worst: Option<(f64, usize)> = None;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= mesh.vertices.len()) {
            continue;
        }
        let c = mesh.corners(t);
        for e in 0..3 {
            let ratio = crate::geom::dist(c[e], c[(e + 1) % 3]) / limit;
            if worst.is_none_or(|(w, _)| ratio > w) {
                worst = Some((ratio, t));
            }
        }
    }
    ratio_check(
        mesh,
        "longest edge / its limit",
        worst,
        format!("--max-edge {limit}"),
    )
}

fn number(v: Option<f64>) -> String {
    match v {
        None => "-".to_string(),
        Some(v) if v.fract() == 0.0 && v.abs() < 1e15 => format!("{v:.0}"),
        // Seven decimals say nothing about 1e-9 and run long for 1e20: seven digits instead.
        Some(v) if v.is_finite() && (v.abs() < 1e-4 || v.abs() >= 1e15) => format!("{v:.6e}"),
        Some(v) => format!("{v:.7}"),
    }
}

/// A small non-negative figure in three significant digits (0 as 0).
fn short(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v:.2e}")
    }
}

fn point(p: Point) -> String {
    format!("({}, {})", super::show(p[0]), super::show(p[1]))
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = &self.metrics;
        writeln!(
            f,
            "bounds: {}   ({} vertices, {} triangles, covered area {})",
            self.bounds.as_deref().unwrap_or("none (validity only)"),
            m.vertices,
            m.triangles,
            super::show(m.covered_area)
        )?;
        let label = |c: &Check| match &c.note {
            Some(n) if c.status != Status::Skipped => format!("{} [{n}]", c.what),
            _ => c.what.clone(),
        };
        let width = self
            .checks
            .iter()
            .map(|c| label(c).chars().count())
            .max()
            .unwrap_or(0)
            .max(5);
        writeln!(
            f,
            "{:<width$} {:>14} {:>16}  {:>25}  result",
            "check", "value", "limit", "rounding used (allowed)"
        )?;
        for c in &self.checks {
            let what = label(c);
            let result = match c.status {
                Status::Ok => "ok".to_string(),
                Status::Fail => "FAIL".to_string(),
                Status::Skipped => format!("skipped: {}", c.note.as_deref().unwrap_or("")),
            };
            let rounding = c.rounding.map_or(String::new(), |r| {
                format!("{} ({})", short(r.used), short(r.allowance))
            });
            writeln!(
                f,
                "{:<width$} {:>14} {:>16}  {rounding:>25}  {result}",
                what,
                number(c.value),
                format!("{} {}", c.relation, number(Some(c.limit)))
            )?;
        }
        writeln!(
            f,
            "a figure may lie beyond its bound by its rounding allowance (for an angle at a of \
             abc: {ANGLE_FLOOR_DEG}° + (δa + δb)/|ab| + (δa + δc)/|ac|, δv = 2^-50·max(|xv|, |yv|)); \
             \"rounding used\" is the most any figure lies beyond, with that figure's allowance; \
             radius ratio is Verdict's R/(2r)"
        )?;
        for c in self.checks.iter().filter(|c| c.status == Status::Fail) {
            if let Some(w) = &c.worst {
                writeln!(
                    f,
                    "FAIL {}: worst triangle {} {} {} {}: {} {} {} fails",
                    c.what,
                    self.numbering.mesh_index(w.triangle as u64),
                    point(w.corners[0]),
                    point(w.corners[1]),
                    point(w.corners[2]),
                    number(Some(w.value)),
                    c.relation,
                    number(Some(c.limit))
                )?;
            }
        }
        if !self.violations.is_empty() {
            writeln!(f, "validity violations ({}):", self.violations.len())?;
            for v in &self.violations {
                writeln!(f, "  {}", v.describe(self.numbering))?;
            }
        }
        if let Some(s) = &self.split {
            for (part, pm) in [("near segments", &s.near), ("interior", &s.interior)] {
                writeln!(
                    f,
                    "{part}: {} triangles, angles {}–{} deg, radius ratio max {}",
                    pm.triangles,
                    number(pm.min_angle.map(|w| w.value)),
                    number(pm.max_angle.map(|w| w.value)),
                    number(pm.radius_ratio_max.map(|w| w.value))
                )?;
            }
        }
        writeln!(f, "{}", if self.passed() { "PASSED" } else { "FAILED" })
    }
}
