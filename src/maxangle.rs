//! The maximum-angle protocol of paper 000 Sec. 8 "Results" (Table 1: "we increase the angle
//! by 0.25 degrees step by step until the program fails"): ask a mesher for a minimum angle
//! of 20°, then 20° + step, ... until it fails, and report the last angle it met. A step fails on an error, a budget stop, a timeout, an invalid mesh, or a mesh whose
//! measured smallest angle is below the request by more than 1e-6° (DESIGN.md "Checks").
//! Every step runs isolated (`isolate::run_isolated`), since a reference may hang or exit.

use std::collections::HashMap;
use std::fmt;
use std::path::Path;
use std::time::Duration;

use serde::Serialize;

use crate::error::{Error, Result};
use crate::geom::orient2d;
use crate::isolate::run_isolated;
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::Params;

/// The paper's first requested angle, in degrees.
pub const DEFAULT_START: f64 = 20.0;
/// The paper's step, in degrees.
pub const DEFAULT_STEP: f64 = 0.25;
/// Rounding allowance on a measured angle, in degrees (DESIGN.md "Checks").
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
}

impl fmt::Display for MaxAngle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.angle {
            Some(a) => write!(
                f,
                "{}: max angle {a:.2}° (measured {:.4}°, {} triangles, {:.3} s); {:.2}° failed: {}",
                self.mesher,
                self.measured_min_angle.unwrap_or(f64::NAN),
                self.triangles,
                self.seconds,
                self.failed_at,
                self.failure
            ),
            None => write!(
                f,
                "{}: no angle met; {:.2}° failed: {}",
                self.mesher, self.failed_at, self.failure
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
    crate::registry::mesher(mesher)?;
    let mut best: Option<(f64, f64, usize, f64)> = None;
    let mut attempts = 0;
    for k in 0u32.. {
        let angle = start + f64::from(k) * step;
        if angle >= CEILING {
            return Ok(finish(mesher, best, angle, "reached 60°".into(), attempts));
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
                    .unwrap_or_else(|| "stopped early".to_string()),
            ),
            Ok(iso) => match check_mesh(input, &iso.run.mesh) {
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
            return Ok(finish(mesher, best, angle, reason, attempts));
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
    }
}

/// The smallest angle of `mesh` in degrees, after the structural checks the protocol needs:
/// a non-empty mesh, indices in range, every triangle counter-clockwise with positive area
/// (exact sign), every edge used at most once per direction and by at most two triangles,
/// and every input point a vertex, bit-exactly. (The `quality` module holds the full checks.)
pub fn check_mesh(input: &Pslg, mesh: &TriMesh) -> std::result::Result<f64, String> {
    if mesh.triangles.is_empty() {
        return Err("no triangles".into());
    }
    let n = mesh.vertices.len();
    let mut edges: HashMap<(u32, u32), u8> = HashMap::with_capacity(3 * mesh.triangles.len());
    let mut min_angle = f64::INFINITY;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tri.iter().any(|&v| v as usize >= n) {
            return Err(format!("triangle {t} names a vertex out of range"));
        }
        let [a, b, c] = mesh.corners(t);
        if orient2d(a, b, c) <= 0.0 {
            return Err(format!("triangle {t} is not counter-clockwise"));
        }
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            let count = edges.entry((u, v)).or_insert(0);
            *count += 1;
            if *count > 1 {
                return Err(format!("edge {u}-{v} is used twice in one direction"));
            }
        }
        min_angle = min_angle.min(smallest_angle(a, b, c));
    }
    let mut bits: Vec<(u64, u64)> = mesh
        .vertices
        .iter()
        .map(|p| (p[0].to_bits(), p[1].to_bits()))
        .collect();
    bits.sort_unstable();
    for (i, p) in input.points.iter().enumerate() {
        if bits
            .binary_search(&(p[0].to_bits(), p[1].to_bits()))
            .is_err()
        {
            return Err(format!("input point {i} is not a vertex"));
        }
    }
    Ok(min_angle)
}

/// The smallest interior angle of triangle abc, in degrees; atan2 of cross and dot keeps it
/// accurate for angles near 0° and 180° alike.
fn smallest_angle(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let angle = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        let (ux, uy) = (q[0] - p[0], q[1] - p[1]);
        let (vx, vy) = (r[0] - p[0], r[1] - p[1]);
        (ux * vy - uy * vx)
            .abs()
            .atan2(ux * vx + uy * vy)
            .to_degrees()
    };
    angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_angle_of_a_right_isoceles_triangle_is_45() {
        let m = smallest_angle([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]);
        assert!((m - 45.0).abs() < 1e-12);
    }

    #[test]
    fn a_clockwise_triangle_is_invalid() {
        let input = Pslg::from_points(vec![[0.0, 0.0]]);
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
            triangles: vec![[0, 1, 2]],
        };
        assert!(check_mesh(&input, &mesh).unwrap_err().contains("counter"));
    }

    #[test]
    fn a_missing_input_point_is_invalid() {
        let input = Pslg::from_points(vec![[0.5, 0.5]]);
        let mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]],
        };
        assert!(check_mesh(&input, &mesh)
            .unwrap_err()
            .contains("input point 0"));
    }

    #[test]
    fn a_row_names_the_angle_and_the_failure() {
        let row = finish(
            "spade",
            Some((33.5, 33.6, 120, 0.01)),
            33.75,
            "x".into(),
            55,
        );
        let text = row.to_string();
        assert!(
            text.contains("33.50°") && text.contains("33.75° failed: x"),
            "{text}"
        );
    }
}
