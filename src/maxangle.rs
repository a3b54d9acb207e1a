//! The maximum-angle protocol of paper 000 Sec. 8 "Results" (Table 1: "we increase the angle
//! by 0.25 degrees step by step until the program fails"): ask a mesher for a minimum angle
//! of 20°, then 20° + step, ... until it fails, and report the last angle it met. A step fails on an error, a budget stop, a timeout, an invalid mesh, or a mesh whose
//! measured smallest angle is below the request by more than 1e-6° (`ANGLE_TOLERANCE`).
//! Every step runs isolated (`isolate::run_isolated`), since a reference may hang or exit.

use std::fmt;
use std::path::Path;
use std::time::Duration;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::isolate::run_isolated;
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Params;
use crate::quality::{metrics, validate, Numbering, ValidateOptions};

/// The paper's first requested angle, in degrees.
pub const DEFAULT_START: f64 = 20.0;
/// The paper's step, in degrees.
pub const DEFAULT_STEP: f64 = 0.25;
/// Rounding allowance on a measured angle, in degrees: a request met but for the last bits
/// of the computed angle counts as met.
pub const ANGLE_TOLERANCE: f64 = 1e-6;
/// No triangle has all angles above 60°: the protocol stops before asking for that.
pub const CEILING: f64 = 60.0;

/// The outcome of the protocol for one mesher on one input.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MaxAngle {
    pub mesher: String,
    /// The largest requested angle the mesher met; `None` when even the first request failed.
    pub angle: Option<f64>,
    /// The measured smallest angle of that mesh, in degrees.
    pub measured_min_angle: Option<f64>,
    /// Triangles of that mesh.
    pub triangles: usize,
    /// Time of that meshing call, in seconds.
    pub seconds: f64,
    /// The request that failed.
    pub failed_at: f64,
    /// Why it failed.
    pub failure: String,
    /// Meshing calls made.
    pub attempts: usize,
    /// The mesher's effective settings (`Mesher::settings`) for the last good request, or for
    /// the failed one when none was good, and the per-request timeout of the isolated child.
    pub settings: String,
}

impl fmt::Display for MaxAngle {
    /// One line: a multi-line failure (CGAL's assertion messages) is joined with spaces.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let failure = crate::report::row::one_line(&self.failure);
        match self.angle {
            Some(a) => write!(
                f,
                "{}: max angle {a:.2}° (measured {:.4}°, {} triangles, {:.3} s); {:.2}° failed: {}",
                self.mesher,
                self.measured_min_angle.unwrap_or(f64::NAN),
                self.triangles,
                self.seconds,
                self.failed_at,
                failure
            ),
            None => write!(
                f,
                "{}: no angle met; {:.2}° failed: {}",
                self.mesher, self.failed_at, failure
            ),
        }
    }
}

/// Runs the protocol: requests `start`, `start + step`, ... (each step computed as
/// start + k·step, so the requests carry no accumulated rounding) until one fails.
/// Each call is isolated in a child of `exe` and limited to `timeout`.
pub fn max_angle(
    exe: &Path,
    mesher: &str,
    input: &Pslg,
    step: f64,
    timeout: Duration,
    start: f64,
) -> Result<MaxAngle> {
    if !(step.is_finite() && step > 0.0) {
        return Err(Error::Usage(format!(
            "--step {step} must be a positive number"
        )));
    }
    if !(start.is_finite() && (0.0..CEILING).contains(&start)) {
        return Err(Error::Usage(format!(
            "the start angle {start} must be in [0°, {CEILING}°)"
        )));
    }
    input.validate_input()?;
    let registered = crate::registry::mesher(mesher)?;
    // Only meshers that promise to keep segments are held to conformity: the others mesh
    // the points and are checked for validity alone.
    let conforming = registered.supports_segments();
    let settings = |angle: f64| {
        format!(
            "{}; each request isolated with a {}s timeout",
            registered.settings(&Params::default().with_min_angle(angle)),
            timeout.as_secs_f64()
        )
    };
    let mut best: Option<(f64, f64, usize, f64)> = None;
    let mut attempts = 0;
    for k in 0u32.. {
        let angle = start + f64::from(k) * step;
        if angle >= CEILING {
            let shown = settings(best.map_or(angle, |b| b.0));
            return Ok(finish(
                mesher,
                best,
                angle,
                "reached 60°".into(),
                attempts,
                shown,
            ));
        }
        attempts += 1;
        let params = Params::default().with_min_angle(angle);
        let failure = match run_isolated(exe, mesher, input, &params, timeout) {
            // The mesher failing is the answer; not finding the binary is the caller's error.
            Err(Error::Mesher { message, .. }) => Some(format!("error: {message}")),
            Err(e) => return Err(e),
            Ok(iso) if !iso.run.complete => Some(
                iso.run
                    .stop_reason
                    .map_or_else(|| "stopped early".to_string(), |r| r.to_string()),
            ),
            Ok(iso) => match check_mesh(input, &iso.run.mesh, conforming) {
                Err(problem) => Some(format!("invalid mesh: {problem}")),
                Ok(measured) if measured < angle - ANGLE_TOLERANCE => Some(format!(
                    "measured minimum angle {measured:.6}° is below the request"
                )),
                Ok(measured) => {
                    best = Some((
                        angle,
                        measured,
                        iso.run.mesh.triangles.len(),
                        iso.run.elapsed.as_secs_f64(),
                    ));
                    None
                }
            },
        };
        if let Some(reason) = failure {
            let shown = settings(best.map_or(angle, |b| b.0));
            return Ok(finish(mesher, best, angle, reason, attempts, shown));
        }
    }
    unreachable!("the loop returns once the angle reaches the ceiling")
}

fn finish(
    mesher: &str,
    best: Option<(f64, f64, usize, f64)>,
    failed_at: f64,
    failure: String,
    attempts: usize,
    settings: String,
) -> MaxAngle {
    MaxAngle {
        mesher: mesher.to_string(),
        angle: best.map(|b| b.0),
        measured_min_angle: best.map(|b| b.1),
        triangles: best.map_or(0, |b| b.2),
        seconds: best.map_or(0.0, |b| b.3),
        failed_at,
        failure,
        attempts,
        settings,
    }
}

/// The smallest angle of `mesh` in degrees (`quality::metrics`), once `quality::validate`
/// finds it valid: every input point a vertex bit-exactly, one disc for a point set, and with
/// `conforming` every input segment a chain of mesh edges. The first violation is the error.
pub fn check_mesh(
    input: &Pslg,
    mesh: &TriMesh,
    conforming: bool,
) -> std::result::Result<f64, String> {
    if mesh.triangles.is_empty() {
        return Err("no triangles".into());
    }
    let options = ValidateOptions {
        // The mesh of a point set is one disc (its bounding hexagon), as `verify` holds it.
        single_component: !input.has_segments(),
        conforming: conforming && input.has_segments(),
    };
    if let Some(v) = validate(mesh, Some(input), &options).first() {
        // Numbered as the files `hexmesh mesh` writes and `--out` inputs are written: from 1.
        return Err(v.describe(Numbering::FILES));
    }
    metrics(mesh, Some(input))
        .min_angle
        .map(|w| w.value)
        .ok_or_else(|| "no angle measured".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_angle_of_a_right_isoceles_triangle_is_45() {
        let input = Pslg::from_points(vec![[0.0, 0.0]]);
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        let m = check_mesh(&input, &mesh, true).unwrap();
        assert!((m - 45.0).abs() < 1e-12);
    }

    #[test]
    fn a_clockwise_triangle_is_invalid() {
        let input = Pslg::from_points(vec![[0.0, 0.0]]);
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
            triangles: vec![[0, 1, 2]],
        };
        let err = check_mesh(&input, &mesh, false).unwrap_err();
        assert!(err.contains("clockwise"), "{err}");
    }

    #[test]
    fn a_missing_input_point_is_invalid() {
        let input = Pslg::from_points(vec![[0.5, 0.5]]);
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        let err = check_mesh(&input, &mesh, false).unwrap_err();
        assert!(err.contains("input point 1 "), "{err}");
    }

    #[test]
    fn a_row_names_the_angle_and_the_failure() {
        let row = finish(
            "spade",
            Some((33.5, 33.6, 120, 0.01)),
            33.75,
            "x".into(),
            55,
            "s".into(),
        );
        let text = row.to_string();
        assert!(
            text.contains("33.50°") && text.contains("33.75° failed: x"),
            "{text}"
        );
    }
}
