//! The one interface every mesher sits behind, ours and the references, so that the CLI and
//! the harness loop over names. Input loading and output writing stay outside `mesh`.

use std::time::Duration;

use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};
use crate::progress::Progress;
use crate::quality::Bounds;

/// The largest rounding allowance, in degrees, that a mesh of ours may use before its input is
/// refused (`Params::max_rounding`; `quality::rounding` explains the allowance).
pub const DEFAULT_MAX_ROUNDING_DEG: f64 = 0.01;

/// Limits that bound every refinement loop. `None` means no limit of that kind.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Budget {
    /// Refinement steps (what a step is depends on the mesher: a split, an insertion, ...).
    pub max_steps: Option<u64>,
    /// Output vertices.
    pub max_vertices: Option<usize>,
    /// Wall-clock time of the meshing call.
    pub max_time: Option<Duration>,
}

/// What a mesher is asked for. Meshers ignore what does not apply to them and say so in
/// `Mesher::settings`. Not `Copy`: it carries the mesher's own option string.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Params {
    /// Requested minimum angle in degrees (references; our meshers have fixed bounds).
    pub min_angle: Option<f64>,
    /// Requested maximum triangle area.
    pub max_area: Option<f64>,
    /// Requested maximum edge length.
    pub max_edge: Option<f64>,
    /// The largest rounding allowance (degrees) a mesh of ours may use before the input is
    /// refused (`quality::rounding`); `None`: `DEFAULT_MAX_ROUNDING_DEG`.
    pub max_rounding: Option<f64>,
    /// The limits every refinement loop stops at (none by default).
    pub budget: Budget,
    /// The mesher's own options, passed through as given (Triangle's command-line switches
    /// for `triangle`); a mesher without such options refuses them (`refuse_switches`).
    pub switches: Option<String>,
    /// How many threads a mesher that splits its work over threads may use (`hex`,
    /// `hex-simple`, `rhomb` on a domain); `None`: as many as the machine has (`available_parallelism`). The mesh
    /// is the same bytes for every count.
    pub threads: Option<std::num::NonZeroUsize>,
    /// Who is told what the mesher is doing while it runs (`progress`); `None`: nobody, and
    /// the reports cost nothing. The mesh is the same bytes either way.
    pub progress: Option<Progress>,
}

impl Params {
    /// These parameters asking for a minimum angle of `degrees` (the references' request).
    pub fn with_min_angle(mut self, degrees: f64) -> Params {
        self.min_angle = Some(degrees);
        self
    }

    /// These parameters asking for triangles of at most `area`.
    pub fn with_max_area(mut self, area: f64) -> Params {
        self.max_area = Some(area);
        self
    }

    /// These parameters asking for edges of at most `length`.
    pub fn with_max_edge(mut self, length: f64) -> Params {
        self.max_edge = Some(length);
        self
    }

    /// The size limits as given, checked: each must be a positive finite number (a usage
    /// error naming it otherwise).
    pub fn size_limits(&self) -> Result<(Option<f64>, Option<f64>)> {
        for (name, v) in [("max-area", self.max_area), ("max-edge", self.max_edge)] {
            if let Some(v) = v {
                if !(v > 0.0 && v.is_finite()) {
                    return Err(Error::Usage(format!(
                        "--{name} must be a positive finite number, not {v}"
                    )));
                }
            }
        }
        Ok((self.max_area, self.max_edge))
    }

    /// Refuses, as a usage error naming `mesher`, a maximum edge length for a mesher that
    /// cannot keep one: it must be kept or refused, never ignored.
    pub fn refuse_max_edge(&self, mesher: &str, why: &str) -> Result<()> {
        match self.max_edge {
            Some(l) => Err(Error::Usage(format!(
                "mesher {mesher} cannot keep --max-edge {l}: {why}"
            ))),
            None => Ok(()),
        }
    }

    /// These parameters allowing meshes to use at most `degrees` of rounding allowance.
    pub fn with_max_rounding(mut self, degrees: f64) -> Params {
        self.max_rounding = Some(degrees);
        self
    }

    /// The largest rounding allowance a mesh may use, in degrees.
    pub fn max_rounding_deg(&self) -> f64 {
        self.max_rounding.unwrap_or(DEFAULT_MAX_ROUNDING_DEG)
    }

    /// These parameters with the limits `budget`.
    pub fn with_budget(mut self, budget: Budget) -> Params {
        self.budget = budget;
        self
    }

    /// These parameters passing the mesher its own options `switches`.
    pub fn with_switches(mut self, switches: impl Into<String>) -> Params {
        self.switches = Some(switches.into());
        self
    }

    /// These parameters letting the mesher use at most `threads` threads.
    pub fn with_threads(mut self, threads: std::num::NonZeroUsize) -> Params {
        self.threads = Some(threads);
        self
    }

    /// These parameters telling `progress` what the mesher is doing while it runs.
    pub fn with_progress(mut self, progress: Progress) -> Params {
        self.progress = Some(progress);
        self
    }

    /// The threads a mesher may use: `threads`, or as many as the machine has (1 where that
    /// is unknown).
    pub fn thread_count(&self) -> usize {
        self.threads
            .or_else(|| std::thread::available_parallelism().ok())
            .map_or(1, std::num::NonZeroUsize::get)
    }

    /// Refuses, as a usage error naming `mesher`, options of its own (`switches`) for a mesher
    /// that has none: they would otherwise be ignored without a word.
    pub fn refuse_switches(&self, mesher: &str) -> Result<()> {
        match &self.switches {
            Some(s) => Err(Error::Usage(format!(
                "mesher {mesher} takes no options of its own, but was given the switches \"{s}\""
            ))),
            None => Ok(()),
        }
    }
}

/// Why a mesher stopped before it finished. A budget of [`Params::budget`] ran out, a limit of
/// the mesher's own did, the harness ended the run, or a reference said so in its own words.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum StopReason {
    /// [`Budget::max_steps`]: this many refinement steps were taken.
    Steps(u64),
    /// [`Budget::max_vertices`]: the mesh reached this many vertices.
    Vertices(usize),
    /// [`Budget::max_time`] ran out.
    Time(Duration),
    /// The mesh would need `needed` vertices (`usize::MAX`: more than a count holds), above
    /// the `limit` of the vertex budget or of the mesher itself, so it was not started.
    VertexLimit {
        /// Vertices the mesh would need.
        needed: usize,
        /// The most it may have.
        limit: usize,
    },
    /// A limit of the mesher itself ran out: this many rounds of Saalfeld's refinement.
    Rounds(u32),
    /// The mesher could make no further progress, for the reason given.
    Stalled(String),
    /// The run was killed after this long (the harness's isolation timeout).
    Timeout(Duration),
    /// A reference mesher stopped early and said why, in its words.
    Reported(String),
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Steps(max) => write!(f, "step budget of {max} reached"),
            StopReason::Vertices(max) => write!(f, "vertex budget of {max} reached"),
            StopReason::Time(max) => write!(f, "time budget of {max:?} reached"),
            StopReason::VertexLimit { needed, limit } if *needed == usize::MAX => {
                write!(
                    f,
                    "needs more vertices than a count holds, above the limit of {limit}"
                )
            }
            StopReason::VertexLimit { needed, limit } => {
                write!(f, "needs {needed} vertices, above the limit of {limit}")
            }
            StopReason::Rounds(max) => write!(f, "round limit of {max} reached"),
            StopReason::Stalled(why) => write!(f, "stalled: {why}"),
            StopReason::Timeout(after) => write!(f, "timeout after {}s", after.as_secs_f64()),
            StopReason::Reported(words) => f.write_str(words),
        }
    }
}

/// The outcome of one meshing call. Stopping early (a budget ran out) is not an error: the
/// mesh so far is returned with `complete == false` and the reason.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshRun {
    /// The mesh: the input points are its first vertices, in order.
    pub mesh: TriMesh,
    /// False when a budget stopped the mesher before it finished.
    pub complete: bool,
    /// Why the mesher stopped early, when it did.
    pub stop_reason: Option<StopReason>,
    /// Refinement steps taken.
    pub steps: u64,
    /// Time of the meshing call alone.
    pub elapsed: Duration,
}

/// Refuses an input whose regions limit triangle areas, for a mesher without size control
/// (`mesher`): such a limit must be kept or refused, never ignored. The error names the first
/// region with a limit (numbered from 1, as in the file's regions section).
pub fn refuse_area_limits(mesher: &str, input: &Pslg) -> Result<()> {
    let regions = &input.labels.regions;
    match regions.iter().position(|r| r.area_limit().is_some()) {
        None => Ok(()),
        Some(k) => {
            let r = &regions[k];
            Err(crate::error::Error::mesher(
                mesher,
                format!(
                    "region {} at ({:?}, {:?}) limits triangle areas to {:?}, and {mesher} has no \
                     size control: mesh the input with triangle, cgal, spade, gmsh, lsb, hex, \
                     hex-simple or rhomb, or drop the area limits",
                    k + 1,
                    r.point[0],
                    r.point[1],
                    r.area_limit().unwrap_or(f64::NAN)
                ),
            ))
        }
    }
}

/// A 2D mesher.
pub trait Mesher: Send + Sync {
    /// The name used on the command line, in reports and by `registry::mesher`.
    fn name(&self) -> &'static str;

    /// The version of the implementation (a crate version, a library version).
    fn version(&self) -> String;

    /// The effective settings a call with `params` uses, spelled in the mesher's own terms
    /// (e.g. Triangle's switches, CGAL's b = sin²θ), for report rows.
    fn settings(&self, params: &Params) -> String;

    /// True when the mesher keeps input segments as chains of mesh edges.
    fn supports_segments(&self) -> bool;

    /// What a finished mesh of a call with `params` keeps, as the bounds `quality::verdict`
    /// checks it against (a reference: the minimum angle it was asked for, or its default).
    fn promise(&self, params: &Params) -> Bounds;

    /// Meshes the input. The input has passed `Pslg::check`.
    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun>;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mesher_without_options_refuses_switches_naming_itself_and_them() {
        assert!(Params::default().refuse_switches("hex").is_ok());
        let e = Params::default()
            .with_switches("q25")
            .refuse_switches("hex")
            .unwrap_err()
            .to_string();
        assert!(e.contains("hex") && e.contains("q25"), "{e}");
    }

    #[test]
    fn a_stop_reason_names_the_limit_and_its_figure() {
        assert_eq!(
            StopReason::Steps(40).to_string(),
            "step budget of 40 reached"
        );
        assert_eq!(
            StopReason::Vertices(1000).to_string(),
            "vertex budget of 1000 reached"
        );
        assert_eq!(
            StopReason::Timeout(Duration::from_millis(500)).to_string(),
            "timeout after 0.5s"
        );
        assert_eq!(
            StopReason::Reported("CGAL ran out".into()).to_string(),
            "CGAL ran out"
        );
    }
}
