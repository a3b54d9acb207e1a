//! The `triangle` reference mesher: Shewchuk's Triangle 1.6 (constrained Delaunay
//! refinement, Shewchuk 2002 "Delaunay refinement algorithms for triangular mesh
//! generation") through tritet 3.4.0's `Trigen::generate_mesh`.
//!
//! What tritet really asks Triangle for (c_code/interface_triangle.c, `tri_run_triangulate`):
//! the switch string is `pzA` + `Q` (quiet) + `a%.15f` (or a bare `a`) + `q%.15f` (or a bare
//! `q`), with `o2` only for quadratic elements and `Y` only when boundary Steiner points are
//! forbidden; this mesher asks for neither. So:
//! - `p` PSLG, `z` zero-based numbering, `A` regional attributes (harmless: no regions);
//! - no `j`: input vertices come back first, in input order, with their exact bits;
//! - no `c`: triangles outside the segments' region are eaten, as are seeded holes;
//! - the angle is always a `q` switch: no request means a bare `q`, Triangle's 20°, and a
//!   request of 0° would also read as a bare `q`, so 0° is sent as 1e-15°;
//! - the area goes through `%.15f`, fifteen decimals: it is rounded (shown in `settings`),
//!   an area below 5e-16 would print as zero, on which Triangle calls `exit(1)`, and one of
//!   1e14 or more does not fit tritet's 32-byte buffer: both are refused here;
//! - no `S`: tritet has no way to cap Steiner points, so `Budget` is not enforced in-process;
//!   run through `isolate::run_isolated` to bound the time.
//!
//! Triangle calls `exit()` (`triexit`) instead of returning on: an input of fewer than three
//! points or all-identical points, a zero area, running out of memory, "Ran out of precision"
//! while splitting segments (tiny features), and internal errors; it may also not terminate
//! for angles above about 34°. `Pslg::check` plus the checks here rule out the input errors;
//! the rest can still end or hang the process, which is why the harness isolates it.
//! Triangle keeps global predicate state, so calls are serialized with a process-wide mutex.

use std::sync::Mutex;
use std::time::Instant;

use tritet::Trigen;

use super::check_params;
use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params};
use crate::quality::Bounds;

const NAME: &str = "triangle";

/// The angle sent when 0° is requested, so that tritet does not fall back to a bare `q`.
const ZERO_ANGLE: f64 = 1e-15;

/// Triangle's default minimum angle for a bare `q` switch.
pub const DEFAULT_MIN_ANGLE: f64 = 20.0;

static TRIANGLE_LOCK: Mutex<()> = Mutex::new(());

/// Shewchuk's Triangle as a `Mesher`.
#[derive(Debug, Clone, Copy, Default)]
pub struct TriangleMesher;

/// The values handed to `Trigen::generate_mesh` for `params`.
fn requested(params: &Params) -> (Option<f64>, Option<f64>) {
    let angle = params
        .min_angle
        .map(|a| if a == 0.0 { ZERO_ANGLE } else { a });
    (params.max_area, angle)
}

/// The exact switch string tritet 3.4.0 passes to Triangle's `triangulate()` for `params`,
/// rebuilt the way `tri_run_triangulate` builds it. Errors for an area that Triangle would
/// read as zero (it would `exit(1)`) or that does not fit tritet's buffer.
pub fn triangle_switches(params: &Params) -> Result<String> {
    check_params(NAME, params)?;
    let (area, angle) = requested(params);
    let mut s = String::from("pzAQ");
    match area {
        Some(a) => {
            let text = format!("{a:.15}");
            if text.len() + 1 >= 32 {
                return Err(Error::mesher(
                    NAME,
                    format!("maximum area {a} is too large for tritet's switch buffer (< 1e14)"),
                ));
            }
            if text.bytes().all(|b| b == b'0' || b == b'.') {
                return Err(Error::mesher(
                    NAME,
                    format!("maximum area {a} prints as zero with tritet's 15 decimals (Triangle would exit)"),
                ));
            }
            s.push('a');
            s.push_str(&text);
        }
        None => s.push('a'),
    }
    match angle {
        Some(a) => {
            s.push('q');
            s.push_str(&format!("{a:.15}"));
        }
        None => s.push('q'),
    }
    Ok(s)
}

impl Mesher for TriangleMesher {
    fn name(&self) -> &'static str {
        NAME
    }

    fn version(&self) -> String {
        "Triangle 1.6 via tritet 3.4.0".to_string()
    }

    fn settings(&self, params: &Params) -> String {
        let budget = if params.budget == Default::default() {
            ""
        } else {
            "; budget not enforced in-process (tritet has no -S), bounded by isolation's timeout"
        };
        match triangle_switches(params) {
            Ok(s) => {
                let q = if params.min_angle.is_none() {
                    " (bare q = 20°)"
                } else {
                    ""
                };
                format!("triangulate(\"{s}\"){q}{budget}")
            }
            Err(e) => format!("invalid: {e}"),
        }
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, params: &Params) -> Bounds {
        super::asked_angle(self.name(), params, DEFAULT_MIN_ANGLE)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        // Triangle exits the process on inputs it rejects: check everything first.
        input.validate_input()?;
        triangle_switches(params)?;
        let domain = input.reference_domain();
        super::check_scale(NAME, &domain)?;
        if domain.points.len() < 3 {
            return Err(Error::mesher(NAME, "Triangle needs at least three points"));
        }
        if domain.segments.len() < 3 {
            return Err(Error::mesher(
                NAME,
                "a PSLG needs at least three segments to bound a region",
            ));
        }
        // Triangle computes buffer sizes in `int` bytes (points × 2 × 8 and the like),
        // which overflows beyond 2^31 / 16 items.
        let limit = i32::MAX as usize / 16;
        if domain.points.len() > limit
            || domain.segments.len() > limit
            || domain.holes.len() > limit
        {
            return Err(Error::mesher(
                NAME,
                format!("input too large for Triangle's int sizes (at most {limit} points)"),
            ));
        }
        let tritet_err = |e: &str| Error::mesher(NAME, format!("tritet: {e}"));
        let holes = (!domain.holes.is_empty()).then_some(domain.holes.len());
        let mut gen = Trigen::new(
            domain.points.len(),
            Some(domain.segments.len()),
            None,
            holes,
        )
        .map_err(tritet_err)?;
        for (i, p) in domain.points.iter().enumerate() {
            gen.set_point(i, 0, p[0], p[1]).map_err(tritet_err)?;
        }
        for (i, s) in domain.segments.iter().enumerate() {
            gen.set_segment(i, 0, s[0] as usize, s[1] as usize)
                .map_err(tritet_err)?;
        }
        for (i, h) in domain.holes.iter().enumerate() {
            gen.set_hole(i, h[0], h[1]).map_err(tritet_err)?;
        }
        let (area, angle) = requested(params);
        let start = Instant::now();
        {
            // A poisoned lock only means another call panicked; Triangle's state is reset
            // at the start of every call, so it is safe to go on.
            let _guard = TRIANGLE_LOCK.lock().unwrap_or_else(|p| p.into_inner());
            gen.generate_mesh(false, false, true, area, angle)
                .map_err(tritet_err)?;
        }
        let elapsed = start.elapsed();
        let n = gen.out_npoint();
        if n < domain.points.len() {
            return Err(Error::mesher(
                NAME,
                format!(
                    "Triangle returned {n} points for {} input points",
                    domain.points.len()
                ),
            ));
        }
        let vertices: Vec<[f64; 2]> = (0..n)
            .map(|i| [gen.out_point(i, 0), gen.out_point(i, 1)])
            .collect();
        if let Some(i) = (0..domain.points.len()).find(|&i| {
            vertices[i][0].to_bits() != domain.points[i][0].to_bits()
                || vertices[i][1].to_bits() != domain.points[i][1].to_bits()
        }) {
            return Err(Error::mesher(
                NAME,
                format!("Triangle moved input point {} (numbered from 1)", i + 1),
            ));
        }
        let triangles: Vec<[u32; 3]> = (0..gen.out_ncell())
            .map(|t| {
                [
                    gen.out_cell_point(t, 0) as u32,
                    gen.out_cell_point(t, 1) as u32,
                    gen.out_cell_point(t, 2) as u32,
                ]
            })
            .collect();
        Ok(MeshRun {
            mesh: TriMesh {
                vertices,
                triangles,
            },
            complete: true,
            stop_reason: None,
            steps: (n - domain.points.len()) as u64,
            elapsed,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switches_follow_tritets_format() {
        let p = Params::default().with_min_angle(30.0).with_max_area(0.5);
        assert_eq!(
            triangle_switches(&p).unwrap(),
            "pzAQa0.500000000000000q30.000000000000000"
        );
        assert_eq!(triangle_switches(&Params::default()).unwrap(), "pzAQaq");
    }

    #[test]
    fn an_area_on_a_rounding_tie_prints_as_glibcs_printf_does() {
        // 2^-16 = 0.0000152587890625 ends in a tie at 15 decimals; glibc's "%.15f" rounds it
        // to even, and so must the string documented here.
        let p = Params::default().with_max_area(1.0 / 65536.0);
        assert_eq!(triangle_switches(&p).unwrap(), "pzAQa0.000015258789062q");
    }

    #[test]
    fn zero_angle_is_not_sent_as_a_bare_q() {
        let p = Params::default().with_min_angle(0.0);
        assert_eq!(triangle_switches(&p).unwrap(), "pzAQaq0.000000000000001");
    }

    #[test]
    fn areas_triangle_would_exit_on_are_refused() {
        assert!(triangle_switches(&Params::default().with_max_area(1e-17)).is_err());
        assert!(triangle_switches(&Params::default().with_max_area(1e15)).is_err());
        assert!(triangle_switches(&Params::default().with_max_area(1e13)).is_ok());
    }

    #[test]
    fn two_segments_are_refused_before_triangle_sees_them() {
        let input = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            segments: vec![[0, 1], [1, 2]],
            ..Pslg::default()
        };
        assert!(TriangleMesher.mesh(&input, &Params::default()).is_err());
    }
}
