//! The `gmsh` reference mesher: Gmsh's 2D Frontal-Delaunay algorithm (`Mesh.Algorithm = 6`),
//! run as Debian's `gmsh` program (`make deps` installs it) on a `.geo` script of the domain,
//! its binary MSH 4.1 output read back with the library's reader (`io::read_msh`) so that
//! every coordinate comes back with all its bits.
//!
//! - The domain is the one every reference meshes (`Pslg::reference_domain`): for a point set
//!   the bounding hexagon with the points embedded in its surface (`Point{..} In Surface`),
//!   for a PSLG one plane surface per region its segments bound, holes as inner curve loops,
//!   the other segments and points embedded ([`geo`]).
//! - Sizes: at each point the length of its shortest edge in the domain's constrained Delaunay
//!   triangulation (its nearest neighbour along the domain), interpolated by Gmsh; with a
//!   maximum area A, at most the side of the equilateral triangle of area A. Gmsh's sizes are
//!   targets, not bounds: a triangle may exceed A.
//! - Gmsh has no angle bound: its promise is a valid, conforming mesh keeping every input
//!   point; a requested minimum angle is ignored (and `settings` says so).
//! - `Geometry.AutoCoherence = 0`: Gmsh would otherwise merge points closer than its
//!   geometric tolerance (1e-8 of the model's size), losing input points.
//! - One thread (`General.NumThreads = 1`), so that a run gives the same mesh every time.
//! - A time budget kills the program; vertex and step budgets cannot be passed to it.

mod geo;

use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use super::{check_params, check_scale};
use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{MeshRun, Mesher, Params, StopReason};
use crate::quality::Bounds;

const NAME: &str = "gmsh";

/// The program run: `HEXMESH_GMSH` when set, else `gmsh` on the PATH.
fn program() -> PathBuf {
    std::env::var_os("HEXMESH_GMSH")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("gmsh"))
}

/// The options every run sets, as the script's first lines.
const OPTIONS: &str = "\
Geometry.AutoCoherence = 0;
General.NumThreads = 1;
General.Verbosity = 2;
Mesh.Algorithm = 6;
Mesh.MeshSizeFromPoints = 1;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 1;
";

/// Gmsh's version as `gmsh --version` prints it, or why it cannot be run.
fn gmsh_version() -> &'static std::result::Result<String, String> {
    static VERSION: OnceLock<std::result::Result<String, String>> = OnceLock::new();
    VERSION.get_or_init(|| {
        let out = Command::new(program())
            .arg("--version")
            .stdin(Stdio::null())
            .output()
            .map_err(|e| {
                format!(
                    "cannot run {}: {e} (`make deps` installs Debian's gmsh)",
                    program().display()
                )
            })?;
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let version = text.trim().to_string();
        if out.status.success() && !version.is_empty() {
            Ok(version)
        } else {
            Err(format!(
                "{} --version failed: {}",
                program().display(),
                version
            ))
        }
    })
}

/// The side of the equilateral triangle of area `area`.
fn edge_for_area(area: f64) -> f64 {
    (4.0 * area / 3f64.sqrt()).sqrt()
}

/// Gmsh's Frontal-Delaunay 2D mesher as a `Mesher`.
#[derive(Debug, Clone, Copy, Default)]
pub struct GmshMesher;

impl Mesher for GmshMesher {
    fn name(&self) -> &'static str {
        NAME
    }

    fn version(&self) -> String {
        match gmsh_version() {
            Ok(v) => format!("Gmsh {v} ({})", program().display()),
            Err(e) => format!("Gmsh unavailable: {e}"),
        }
    }

    fn settings(&self, params: &Params) -> String {
        let mut s = String::from(
            "Mesh.Algorithm=6 (Frontal-Delaunay), sizes from each point's shortest domain edge",
        );
        if let Some(a) = params.max_area {
            s.push_str(&format!(
                ", at most {:.6e} (the equilateral triangle of area {a})",
                edge_for_area(a)
            ));
        }
        if let Some(l) = params.max_edge {
            s.push_str(&format!(", at most the maximum edge {l}"));
        }
        s.push_str(", AutoCoherence=0, 1 thread, binary msh 4.1");
        if let Some(a) = params.min_angle {
            s.push_str(&format!(
                "; minimum angle {a}° ignored (Gmsh has no angle bound)"
            ));
        }
        let b = params.budget;
        if b.max_steps.is_some() || b.max_vertices.is_some() {
            s.push_str("; step and vertex budgets not enforced (time only)");
        }
        s
    }

    fn supports_segments(&self) -> bool {
        true
    }

    fn promise(&self, _params: &Params) -> Bounds {
        Bounds::validity(NAME)
    }

    fn mesh(&self, input: &Pslg, params: &Params) -> Result<MeshRun> {
        input.validate_input()?;
        check_params(NAME, params)?;
        let domain = input.reference_domain();
        check_scale(NAME, &domain)?;
        gmsh_version()
            .as_ref()
            .map_err(|e| Error::mesher(NAME, e.clone()))?;
        // The regions' area limits, as a size target: the smallest of them everywhere; a
        // maximum edge length is a size target as well, the smaller one wins.
        let area = input.smallest_area_limit(params.max_area);
        let size = area
            .map(edge_for_area)
            .into_iter()
            .chain(params.max_edge)
            .reduce(f64::min);
        let script = geo::script(input, size, OPTIONS)?;
        let dir = Scratch::new()?;
        let geo_path = dir.path.join("domain.geo");
        let msh_path = dir.path.join("domain.msh");
        std::fs::write(&geo_path, &script.text).map_err(|e| Error::Io {
            path: geo_path.clone(),
            source: e,
        })?;
        let start = Instant::now();
        let finished = run(&geo_path, &msh_path, params.budget.max_time)?;
        let elapsed = start.elapsed();
        if let Some(after) = finished {
            return Ok(MeshRun {
                mesh: TriMesh::default(),
                complete: false,
                stop_reason: Some(StopReason::Time(after)),
                steps: 0,
                elapsed,
            });
        }
        let read = crate::io::read_msh(&msh_path)?;
        let mesh = inputs_first(&input.points, read.mesh);
        let steps = mesh.vertices.len().saturating_sub(script.points.len()) as u64;
        Ok(MeshRun {
            mesh,
            complete: true,
            stop_reason: None,
            steps,
            elapsed,
        })
    }
}

/// Runs Gmsh on `geo`, writing `msh`. Returns `Some(limit)` when the time limit killed it.
/// Gmsh's own errors (a line starting "Error") fail the run, quoted.
fn run(geo: &Path, msh: &Path, limit: Option<Duration>) -> Result<Option<Duration>> {
    let mut command = Command::new(program());
    command
        .arg(geo)
        .args(["-2", "-nopopup", "-o"])
        .arg(msh)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: the closure runs in the forked child before exec and only calls prctl,
        // which is async-signal-safe; it touches no memory of the parent.
        unsafe {
            command.pre_exec(|| {
                // Gmsh dies with the process that runs it: a timeout that kills an isolated
                // child (`isolate::run_isolated`) must not leave Gmsh running.
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL) == -1 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
    let mut child = command
        .spawn()
        .map_err(|e| Error::mesher(NAME, format!("cannot run {}: {e}", program().display())))?;
    let out = drain(child.stdout.take());
    let err = drain(child.stderr.take());
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child
            .try_wait()
            .map_err(|e| Error::mesher(NAME, e.to_string()))?
        {
            break status;
        }
        if let Some(limit) = limit.filter(|&l| start.elapsed() >= l) {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(Some(limit));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let text = format!(
        "{}{}",
        out.join().unwrap_or_default(),
        err.join().unwrap_or_default()
    );
    let errors: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("Error"))
        .collect();
    if !status.success() || !errors.is_empty() || !msh.exists() {
        let said = if errors.is_empty() {
            text.trim().to_string()
        } else {
            errors.join("; ")
        };
        return Err(Error::mesher(
            NAME,
            format!("Gmsh failed ({status}): {said}"),
        ));
    }
    Ok(None)
}

/// Reads all of `source` on a thread of its own, so that neither pipe fills up and blocks Gmsh.
fn drain<R: Read + Send + 'static>(source: Option<R>) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut buf = String::new();
        if let Some(mut s) = source {
            let _ = s.read_to_string(&mut buf);
        }
        buf
    })
}

/// `mesh` renumbered so that `points` (bit-exact) are its first vertices, in order, and the
/// other vertices follow in the order Gmsh wrote them. An input point Gmsh left out (outside
/// the domain) is kept as a vertex no triangle uses, so that the check names it.
fn inputs_first(points: &[[f64; 2]], mesh: TriMesh) -> TriMesh {
    let bits = |p: [f64; 2]| (p[0].to_bits(), p[1].to_bits());
    let input_index: HashMap<(u64, u64), u32> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (bits(p), i as u32))
        .collect();
    let mut vertices = points.to_vec();
    let new_index: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|&p| match input_index.get(&bits(p)) {
            Some(&i) => i,
            None => {
                vertices.push(p);
                vertices.len() as u32 - 1
            }
        })
        .collect();
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| new_index[v as usize]))
        .collect();
    TriMesh {
        vertices,
        triangles,
    }
}

/// A directory of its own under the system's temporary directory, removed when dropped.
struct Scratch {
    path: PathBuf,
}

impl Scratch {
    fn new() -> Result<Scratch> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let k = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("hexmesh-gmsh-{}-{k}", std::process::id()));
        std::fs::create_dir_all(&path).map_err(|e| Error::Io {
            path: path.clone(),
            source: e,
        })?;
        Ok(Scratch { path })
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_points_come_first_in_input_order_and_a_lost_one_stays_unused() {
        let mesh = TriMesh {
            vertices: vec![[5.0, 5.0], [1.0, 0.0], [0.0, 0.0], [0.0, 1.0]],
            triangles: vec![[2, 1, 3], [1, 0, 3]],
        };
        let points = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [9.0, 9.0]];
        let m = inputs_first(&points, mesh);
        assert_eq!(
            m.vertices,
            vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [9.0, 9.0], [5.0, 5.0]]
        );
        assert_eq!(m.triangles, vec![[0, 1, 2], [1, 4, 2]]);
    }

    #[test]
    fn the_size_for_an_area_is_the_side_of_the_equilateral_triangle_of_that_area() {
        let h = edge_for_area(3f64.sqrt() / 4.0);
        assert!((h - 1.0).abs() < 1e-15, "{h}");
    }
}
