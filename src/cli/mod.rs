//! The `hexmesh` command line (`hexmesh --help`; reads Triangle .node/.poly files, writes
//! Triangle, VTK, Gmsh and SVG). Exit codes: 0 when all is
//! well, 1 when `verify` finds a failed check or a mesher stops short, 2 on bad input or usage.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use clap::{Args, Parser, Subcommand};

use crate::error::{Error, Result};
use crate::mesh::Pslg;
use crate::mesher::{Budget, Mesher, Params};
use crate::quality::{Bounds, Numbering};

mod mesh_progress;

#[derive(Parser)]
#[command(
    name = "hexmesh",
    version,
    about = "Hexagonal Delaunay meshing with guaranteed quality, and a harness that checks and compares 2D meshers"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write the paper's datasets as Triangle .node/.poly files, and the PSLG examples
    /// (pslg-holes, pslg-wedge-5, pslg-slit, pslg-nested, pslg-short-long) as .poly files.
    Datasets {
        /// Output directory.
        #[arg(long, default_value = "datasets")]
        out: PathBuf,
        /// Also write the scaling series (plane-10k, plane-100k, plane-1m).
        #[arg(long)]
        scaling: bool,
    },
    /// List the registered meshers with their versions, then the variants reachable by name.
    Meshers,
    /// Mesh a .node/.poly file (or a dataset by name) with one mesher.
    Mesh(MeshArgs),
    /// Check a mesh (Triangle's PREFIX.node + PREFIX.ele, Gmsh .msh, VTK .vtk or .vtu):
    /// validity, and with --bounds a mesher's promises.
    Verify(VerifyArgs),
    /// The paper's protocol: raise the requested minimum angle from 20° by --step until the
    /// mesher fails; print the last good angle, its triangle count and time.
    MaxAngle(MaxAngleArgs),
    /// Fuzz a mesher's promises on generated point sets (uniform, clustered, collinear,
    /// near-duplicates, scaled, translated, lattice-aligned), or with --domains on generated
    /// polygonal domains; exit 1 on any failure.
    Fuzz(FuzzArgs),
    /// Run every mesher on every dataset, check and time them, and regenerate the reports
    /// directory whole (results.csv, table1.md, plots, pictures, README.md).
    Report(ReportArgs),
}

#[derive(Args)]
struct ReportArgs {
    /// Datasets, comma-separated (default: the small ones and every PSLG example). PSLG
    /// examples named here go to pslg.csv, the others to results.csv.
    #[arg(long, value_delimiter = ',')]
    datasets: Vec<String>,
    /// Meshers, comma-separated (default: every registered mesher).
    #[arg(long, value_delimiter = ',')]
    meshers: Vec<String>,
    /// Runs per case; times are the median, min and max.
    #[arg(long, default_value_t = 3)]
    runs: usize,
    /// Add plane-1m to the scaling series (plane-1k to plane-100k are always run and plotted;
    /// with --datasets, add plane-10k, plane-100k and plane-1m).
    #[arg(long)]
    scaling: bool,
    /// The reports directory (its generated files are replaced).
    #[arg(long, default_value = "reports")]
    out: PathBuf,
    /// Seconds one meshing call may take before it becomes an error row.
    #[arg(long, default_value_t = 180.0)]
    timeout: f64,
    /// Seconds each request of the max-angle protocol may take.
    #[arg(long, default_value_t = 10.0)]
    max_angle_timeout: f64,
    /// Skip the max-angle protocol (Table 1's reference columns).
    #[arg(long)]
    no_max_angle: bool,
    /// Triangle's command-line switches for the triangle rows of results.csv and pslg.csv
    /// (as `mesh --triangle-switches`; without q, which the report sets), recorded in their
    /// settings column.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    triangle_switches: Option<String>,
}

#[derive(Args)]
struct FuzzArgs {
    /// The mesher (hex-simple, hex, or any registered name; with --domains, one that keeps
    /// segments).
    #[arg(long)]
    mesher: String,
    /// Generate polygonal domains instead of point sets: simple polygons, stars, sharp corners
    /// down to 1°, holes, interior points, thin slits, short segments beside long ones, map
    /// coordinates. Refusals are counted by reason, not failed.
    #[arg(long)]
    domains: bool,
    /// Number of generated cases.
    #[arg(long, default_value_t = 10_000)]
    cases: u64,
    /// Seed of the case generator: the same seed gives the same cases.
    #[arg(long, default_value_t = 20_261_123)]
    seed: u64,
    /// The number of the first case: `--first N --cases 1` runs case N of the campaign of
    /// that seed alone, as the whole campaign meshes and checks it.
    #[arg(long, default_value_t = 0, value_name = "N")]
    first: u64,
    /// Directory the input of each failing case is written into, as a Triangle .node file
    /// (a .poly file with --domains; created if missing; at most a hundred files). Without it no files are written: the
    /// failing cases are only reported, and `--seed` with the case number reproduces them.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// With --domains: how many cases are meshed side by side, each on one thread (the
    /// summary is the same for any number but for the times).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=1024))]
    jobs: u64,
}

#[derive(Args)]
struct MaxAngleArgs {
    /// A Triangle .node or .poly file, or the name of a dataset or PSLG example.
    input: String,
    /// The mesher (see `hexmesh meshers`).
    #[arg(long)]
    mesher: String,
    /// Degrees added at each attempt.
    #[arg(long, default_value_t = crate::maxangle::DEFAULT_STEP)]
    step: f64,
    /// Seconds each attempt may take before it counts as a failure.
    #[arg(long, default_value_t = 10.0)]
    timeout: f64,
    /// The first requested angle.
    #[arg(long, default_value_t = crate::maxangle::DEFAULT_START)]
    start: f64,
    /// Print only the JSON object (the row goes to stderr).
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct MeshArgs {
    /// A Triangle .node or .poly file, or the name of a dataset or PSLG example (see
    /// `hexmesh datasets`).
    input: String,
    /// The mesher (see `hexmesh meshers`).
    #[arg(long)]
    mesher: String,
    /// Requested minimum angle in degrees (reference meshers; ours have fixed bounds).
    #[arg(long)]
    min_angle: Option<f64>,
    /// Requested maximum triangle area. hex, hex-simple and rhomb keep it by refining
    /// further (their angle bounds unchanged); a .poly region's area limit is kept too.
    #[arg(long)]
    max_area: Option<f64>,
    /// Requested maximum edge length: kept by hex, hex-simple, rhomb, lsb, cgal and gmsh;
    /// refused (exit 2, naming the mesher) by the others, which have no such control.
    #[arg(long, value_name = "L")]
    max_edge: Option<f64>,
    /// Triangle's command-line switches (e.g. q25D), passed to the triangle mesher as given
    /// after its fixed pzAQa (README "Command line"); refused for other meshers, and j, r and the
    /// switches that change what Triangle outputs are refused. A q or a number after a here
    /// cannot be combined with --min-angle or --max-area.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    triangle_switches: Option<String>,
    /// Our meshers (hex, hex-simple, rhomb) refuse an input, naming its two closest points,
    /// rather than hand out a mesh that rounding to f64 moves beyond a bound by more than
    /// this many degrees (README "Checks").
    #[arg(long, value_name = "DEG")]
    max_rounding: Option<f64>,
    /// Threads hex and hex-simple may split their work over (default: as many as the
    /// machine has); the mesh is the same bytes for every count. The other meshers run on one.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// Output prefix: writes PREFIX.node and PREFIX.ele (and the other --format files), with
    /// the input's markers, attributes and regions carried to the mesh.
    #[arg(short = 'o', long = "out")]
    prefix: PathBuf,
    /// Output formats, comma-separated: node (.node/.ele), poly (.poly/.edge, with .node/.ele),
    /// vtk, vtu, msh, svg.
    #[arg(long, value_delimiter = ',', default_value = "node")]
    format: Vec<String>,
    /// Also draw the hexagon subdivision with its dual mesh (hex meshers) as an SVG file.
    #[arg(long)]
    hexagons: Option<PathBuf>,
    /// Budget: at most this many refinement steps.
    #[arg(long)]
    max_steps: Option<u64>,
    /// Budget: at most this many output vertices.
    #[arg(long)]
    max_vertices: Option<usize>,
    /// Budget: seconds. The mesher runs in a child process of this program, which is killed
    /// when time is up (Triangle and spade cannot be stopped any other way).
    #[arg(long, default_value_t = 600.0)]
    timeout: f64,
    /// Do not check the mesh against the mesher's promises (and the requested minimum angle)
    /// before exiting; by default a mesh that fails them is written but exits 1.
    #[arg(long)]
    no_check: bool,
    /// Mesh a .poly input inside its convex hull (Triangle's -c): the hull's edges are added
    /// as segments after the file's (split at every point on the hull), for every mesher
    /// alike, and the mesh is checked against that input. Without it, segments that enclose
    /// no region are refused (exit 2), as is a segment or point outside the region they
    /// enclose. A point set keeps its bounding hexagon.
    #[arg(long)]
    convex_hull: bool,
}

#[derive(Args)]
struct VerifyArgs {
    /// The mesh, chosen by extension: FILE.msh (Gmsh MSH 4.1 or 2.2, ASCII or binary),
    /// FILE.vtk (VTK legacy UNSTRUCTURED_GRID or POLYDATA, ASCII or BINARY), FILE.vtu (VTK
    /// XML: ascii, base64 or appended data, plain or zlib-compressed, as meshio writes it),
    /// or else PREFIX for Triangle's PREFIX.node and PREFIX.ele. Only 3-node triangles in
    /// the plane z = 0 are read: points and lines are skipped, quadrangles and higher-order
    /// triangles refused. Messages number vertices and triangles in the order the file lists
    /// them, from the .node file's first index, from 1 for .msh (the text output then ends
    /// with the node and element tags of those it names), from 0 for VTK (its point and cell
    /// ids).
    #[arg(value_name = "MESH")]
    prefix: PathBuf,
    /// The input the mesh was made from (.node/.poly, or a dataset or PSLG example name): every
    /// input point must be a vertex, and every segment a chain of edges where the bounds ask
    /// for conformity.
    #[arg(long)]
    input: Option<String>,
    /// A mesher's name, `delaunay`, or `min-angle=DEG`. Without it, validity only.
    #[arg(long)]
    bounds: Option<String>,
    /// Print the verdict as JSON.
    #[arg(long)]
    json: bool,
    /// With --input: check against the input inside its convex hull (the hull's edges added
    /// as segments after the file's), as `mesh --convex-hull` meshed it.
    #[arg(long)]
    convex_hull: bool,
    /// Check every triangle's area against this limit (and, with --input, each region's own
    /// limit), as `mesh --max-area` asked; with a mesher's --bounds, its promise under it.
    #[arg(long)]
    max_area: Option<f64>,
    /// Check every edge's length against this limit, as `mesh --max-edge` asked.
    #[arg(long, value_name = "L")]
    max_edge: Option<f64>,
}

/// Runs the command line; `main` returns this.
pub fn main() -> ExitCode {
    crate::isolate::running_as_cli();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli.command) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("hexmesh: error: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(command: Command) -> Result<ExitCode> {
    match command {
        Command::Datasets { out, scaling } => datasets(&out, scaling),
        Command::Meshers => {
            for m in crate::registry::meshers() {
                println!("{:<16} {}", m.name(), m.version());
            }
            for m in crate::registry::variants() {
                println!(
                    "{:<16} {} (variant, not in the default report)",
                    m.name(),
                    m.version()
                );
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Mesh(args) => mesh(&args),
        Command::Verify(args) => verify(&args),
        Command::MaxAngle(args) => max_angle(&args),
        Command::Fuzz(args) => fuzz(&args),
        Command::Report(args) => {
            crate::report::run_report(&crate::report::ReportOptions {
                datasets: args.datasets,
                meshers: args.meshers,
                runs: args.runs,
                scaling: args.scaling,
                out: args.out,
                timeout: seconds("--timeout", args.timeout)?,
                max_angle_timeout: seconds("--max-angle-timeout", args.max_angle_timeout)?,
                max_angle: !args.no_max_angle,
                triangle_switches: args.triangle_switches,
                ..crate::report::ReportOptions::default()
            })?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Reads INPUT: a file when it exists or has an extension, else a dataset or PSLG example name.
fn load_input(input: &str) -> Result<Pslg> {
    load_input_numbered(input, false).map(|(pslg, _)| pslg)
}

/// [`load_input`], inside its convex hull when `convex_hull` is set (`Pslg::with_convex_hull`),
/// checked (`Pslg::check`), and the number of the input's first point: the file's, or 1 for a
/// dataset (as `hexmesh datasets` writes it).
fn load_input_numbered(input: &str, convex_hull: bool) -> Result<(Pslg, u32)> {
    let path = Path::new(input);
    if path.exists() || path.extension().is_some() {
        crate::io::read_input_enclosed(path, convex_hull)
    } else {
        let pslg = crate::datasets::by_name(input)?;
        let pslg = if convex_hull {
            pslg.with_convex_hull()
        } else {
            pslg
        };
        pslg.validate_input()?;
        Ok((pslg, 1))
    }
}

fn datasets(out: &Path, scaling: bool) -> Result<ExitCode> {
    std::fs::create_dir_all(out).map_err(|source| Error::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let names = crate::datasets::SMALL
        .iter()
        .chain(crate::datasets::PSLG_EXAMPLES)
        .chain(if scaling {
            crate::datasets::SCALING
        } else {
            &[]
        });
    for name in names {
        let pslg = crate::datasets::by_name(name)?;
        let path = out.join(crate::datasets::file_name(name)?);
        crate::io::write_pslg(&path, &pslg)?;
        println!(
            "{}: {} points, {} segments",
            path.display(),
            pslg.points.len(),
            pslg.segments.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// `--threads`: a positive count, or none given.
fn thread_count(threads: Option<usize>) -> Result<Option<std::num::NonZeroUsize>> {
    threads
        .map(|n| {
            std::num::NonZeroUsize::new(n).ok_or_else(|| {
                Error::Usage("--threads must be at least 1 (give none for all)".into())
            })
        })
        .transpose()
}

fn mesh(args: &MeshArgs) -> Result<ExitCode> {
    let (input, input_base) = load_input_numbered(&args.input, args.convex_hull)?;
    input.validate_input()?;
    let mesher = crate::registry::mesher(&args.mesher)?;
    let formats = args
        .format
        .iter()
        .map(|f| crate::io::Format::parse(f))
        .collect::<Result<Vec<_>>>()?;
    refuse_to_overwrite_input(args, &formats)?;
    positive(&[
        ("--min-angle", args.min_angle),
        ("--max-area", args.max_area),
        ("--max-edge", args.max_edge),
        ("--max-rounding", args.max_rounding),
    ])?;
    if args.hexagons.is_some() && !matches!(mesher.name(), "hex-simple" | "hex") {
        return Err(Error::Usage(format!(
            "--hexagons draws the hexagon subdivision of hex-simple or hex, not of {}",
            mesher.name()
        )));
    }
    let timeout = seconds("--timeout", args.timeout)?;
    let params = Params {
        min_angle: args.min_angle,
        max_area: args.max_area,
        max_edge: args.max_edge,
        max_rounding: args.max_rounding,
        budget: Budget {
            max_steps: args.max_steps,
            max_vertices: args.max_vertices,
            max_time: Some(timeout),
        },
        switches: args.triangle_switches.clone(),
        threads: thread_count(args.threads)?,
        progress: None,
    };
    check_triangle_switches(mesher.name(), &params)?;
    let exe = crate::isolate::find_exe()?;
    let mut progress = mesh_progress::MeshProgress::new(mesher.name());
    // Off a terminal nothing is drawn, and the child is not asked for its progress.
    let isolated = if progress.draws() {
        crate::isolate::run_isolated_watched(
            &exe,
            mesher.name(),
            &input,
            &params,
            timeout,
            &mut |watch| progress.meshing(watch),
        )
    } else {
        crate::isolate::run_isolated(&exe, mesher.name(), &input, &params, timeout)
    };
    let run = match isolated {
        Ok(isolated) => isolated.run,
        // A refusal naming input points names them by the lines of the file they came from.
        Err(Error::Input { problem, .. }) if Path::new(&args.input).exists() => {
            return Err(crate::io::locate_input_error(
                Path::new(&args.input),
                problem,
            ))
        }
        Err(e) => return Err(e),
    };
    if !run.complete {
        eprintln!(
            "hexmesh: mesher {} stopped early: {}; no mesh written",
            mesher.name(),
            run.stop_reason
                .as_ref()
                .map_or("budget exhausted".into(), ToString::to_string)
        );
        return Ok(ExitCode::from(1));
    }
    progress.phase("writing the files");
    let written = crate::io::write_mesh_with(&args.prefix, &run.mesh, Some(&input), &formats);
    progress.clear();
    let written = written?;
    eprintln!(
        "{}: {} vertices, {} triangles in {:.3} s ({})",
        mesher.name(),
        run.mesh.vertices.len(),
        run.mesh.triangles.len(),
        run.elapsed.as_secs_f64(),
        mesher.settings(&params)
    );
    // On a domain, the shape bounds of a promise kept away from the segments (paper 000
    // Sec. 7) are not the mesh's: the figures beside the segments are stated apart, with what
    // is promised there (hex: `Bounds::near_segment_angles`) or as measured only.
    let promise = mesher.promise(&params);
    if input.has_segments() && promise.interior_only_on_segments {
        let band = crate::quality::on_segment_tolerance(&input);
        let split = crate::quality::metrics_split(&run.mesh, &input, band);
        let range = |m: &crate::quality::Metrics| match (&m.min_angle, &m.max_angle) {
            (Some(lo), Some(hi)) => format!("angles {:.4}-{:.4} deg", lo.value, hi.value),
            _ => "no angles".to_string(),
        };
        let near = match promise.near_segment_angles {
            Some((lo, hi)) => format!(
                "promised {lo}-{hi} deg but at input corners sharper than {lo} deg, taken whole"
            ),
            None => "measured, not promised".to_string(),
        };
        eprintln!(
            "{}: its bounds hold away from the segments ({} triangles, {}); the {} triangles \
             touching a segment have {} ({near})",
            mesher.name(),
            split.interior.triangles,
            range(&split.interior),
            split.near.triangles,
            range(&split.near)
        );
    }
    for path in written {
        println!("{}", path.display());
    }
    let failed = if args.no_check {
        None
    } else {
        progress.phase("checking the mesh against its promise");
        failed_promise(mesher.as_ref(), &params, (&input, input_base), &run.mesh)
    };
    progress.finish();
    if let Some(path) = &args.hexagons {
        match mesher.name() {
            "hex-simple" => crate::hex::write_hexagons_svg(&input, &params, path)?,
            "hex" => crate::hex::picture::write_extended_hexagons_svg(&input, &params, path)?,
            other => {
                return Err(Error::Usage(format!(
                    "--hexagons draws the hexagon subdivision of hex-simple or hex, not of {other}"
                )))
            }
        }
        println!("{}", path.display());
    }
    if let Some((bounds, problem)) = failed {
        eprintln!(
            "hexmesh: the {} mesh fails --bounds {bounds}: {problem}; it is written for \
             inspection (`hexmesh verify {} --input {}{} --bounds {bounds}` lists every \
             failure)",
            mesher.name(),
            args.prefix.display(),
            args.input,
            if args.convex_hull {
                " --convex-hull"
            } else {
                ""
            }
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// Refuses `--triangle-switches` for a mesher other than `triangle`, and for `triangle`
/// switches it refuses or that clash with `--min-angle`/`--max-area`, before a child runs.
fn check_triangle_switches(mesher: &str, params: &Params) -> Result<()> {
    if params.switches.is_none() {
        return Ok(());
    }
    if mesher != "triangle" {
        return Err(Error::Usage(format!(
            "--triangle-switches passes switches to the triangle mesher, not to {mesher}"
        )));
    }
    crate::reference::triangle::user_switches(params).map(|_| ())
}

/// Refuses, before anything runs, a `mesh` whose outputs (the `-o` files and the `--hexagons`
/// picture) would replace a file INPUT is read from (`io::input_files`). The mesh files are
/// written all or nothing by `io::write_mesh`.
fn refuse_to_overwrite_input(args: &MeshArgs, formats: &[crate::io::Format]) -> Result<()> {
    let path = Path::new(&args.input);
    // As `load_input` decides: a dataset or example name reads no file.
    if !(path.exists() || path.extension().is_some()) {
        return Ok(());
    }
    let mut outputs = crate::io::mesh_files(&args.prefix, formats);
    outputs.extend(args.hexagons.iter().cloned());
    crate::io::refuse_to_overwrite(&outputs, &crate::io::input_files(path))
}

/// What `mesh` holds a finished mesh to: what the mesher promises for the run's parameters
/// (`Mesher::promise`; a reference: the minimum angle it was asked for, its default one when
/// none was). Returns the bounds' name and the first problem when the mesh fails them: no
/// mesh is passed on as good without being checked. The problem numbers vertices and
/// triangles as the written files do (from 1), input items as the input file does.
fn failed_promise(
    mesher: &dyn Mesher,
    params: &Params,
    (input, input_base): (&Pslg, u32),
    mesh: &crate::mesh::TriMesh,
) -> Option<(String, String)> {
    let bounds = mesher.promise(params);
    let verdict = crate::quality::verdict(mesh, Some(input), Some(&bounds)).numbered(Numbering {
        mesh: 1,
        input: input_base,
    });
    (!verdict.passed()).then(|| (verify_name(&bounds), crate::report::first_problem(&verdict)))
}

/// The `verify --bounds` name that checks what `bounds` check: `min-angle=DEG` when that is
/// all they are besides area limits (a reference's promise, which its own name gives only at
/// its default angle), otherwise the mesher's name. (No name carries an area limit asked for
/// on the command line; the first problem `mesh` prints names a failed one.)
fn verify_name(bounds: &Bounds) -> String {
    if let Some(angle) = bounds.min_angle {
        let generic = format!("min-angle={angle}");
        let as_generic = Bounds {
            name: generic.clone(),
            max_area: None,
            max_edge: None,
            region_area_limits: false,
            ..bounds.clone()
        };
        if Bounds::named(&generic).is_ok_and(|g| g == as_generic) {
            return generic;
        }
    }
    bounds.name.clone()
}

fn verify(args: &VerifyArgs) -> Result<ExitCode> {
    let loaded = crate::io::read_any_mesh(&args.prefix)?;
    let mesh = &loaded.mesh;
    if args.convex_hull && args.input.is_none() {
        return Err(Error::Usage(
            "--convex-hull encloses the input given with --input; there is none".into(),
        ));
    }
    let input = args
        .input
        .as_deref()
        .map(|i| load_input_numbered(i, args.convex_hull))
        .transpose()?;
    let numbering = Numbering {
        mesh: loaded.first_index,
        input: input.as_ref().map_or(1, |(_, base)| *base),
    };
    let input = input.map(|(pslg, _)| pslg);
    let bounds = verify_bounds(args)?;
    let verdict =
        crate::quality::verdict(mesh, input.as_ref(), bounds.as_ref()).numbered(numbering);
    if args.json {
        let json = serde_json::to_string_pretty(&verdict)
            .map_err(|e| Error::Usage(format!("cannot render the verdict as JSON: {e}")))?;
        println!("{json}");
    } else {
        print!("{verdict}");
        if let Some(note) = tag_note(&args.prefix, &loaded, &verdict) {
            println!("{note}");
        }
    }
    Ok(if verdict.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// A usage error naming the first option given whose value is not a positive finite number.
fn positive(options: &[(&str, Option<f64>)]) -> Result<()> {
    match options
        .iter()
        .find_map(|&(what, v)| v.filter(|v| !v.is_finite() || *v <= 0.0).map(|v| (what, v)))
    {
        Some((what, v)) => Err(Error::Usage(format!(
            "{what} must be a positive number, not {v}"
        ))),
        None => Ok(()),
    }
}

/// What `verify` checks: the bounds named by --bounds, with the size limits given. A
/// mesher's bounds under a limit are its promise for a run with that limit (hex gives up the
/// Sec. 6.3 shortest edge under one); other bounds, or validity alone, get the limits added.
fn verify_bounds(args: &VerifyArgs) -> Result<Option<Bounds>> {
    positive(&[("--max-area", args.max_area), ("--max-edge", args.max_edge)])?;
    let named = args.bounds.as_deref();
    if args.max_area.is_none() && args.max_edge.is_none() {
        return named.map(crate::registry::bounds).transpose();
    }
    if let Some(m) = named.and_then(|n| crate::registry::mesher(n).ok()) {
        let params = Params {
            max_area: args.max_area,
            max_edge: args.max_edge,
            ..Params::default()
        };
        let promise = m.promise(&params);
        return Ok(Some(promise.with_size_limits(args.max_area, args.max_edge)));
    }
    let base = match named {
        Some(n) => crate::registry::bounds(n)?,
        None => Bounds::validity("valid"),
    };
    Ok(Some(base.with_size_limits(args.max_area, args.max_edge)))
}

/// For a file with its own node and element tags (Gmsh), the tags of the vertices and
/// triangles the verdict names by their positions (numbered from the file's first index);
/// `None` when it names none.
fn tag_note(
    path: &std::path::Path,
    loaded: &crate::io::LoadedMesh,
    verdict: &crate::quality::Verdict,
) -> Option<String> {
    const SHOWN: usize = 20;
    let mut vertices: Vec<usize> = Vec::new();
    let mut triangles: Vec<usize> = Vec::new();
    for violation in &verdict.violations {
        let (v, t) = violation.named();
        vertices.extend(v);
        triangles.extend(t);
    }
    triangles.extend(
        verdict
            .checks
            .iter()
            .filter_map(|c| c.worst.map(|w| w.triangle)),
    );
    let list = |named: &mut Vec<usize>, tags: Option<&Vec<u64>>, what: &str, tag: &str| {
        let tags = tags?;
        named.sort_unstable();
        named.dedup();
        let shown: Vec<String> = named
            .iter()
            .filter_map(|&i| {
                let numbered = i as u64 + u64::from(loaded.first_index);
                tags.get(i)
                    .map(|t| format!("{what} {numbered} is {tag} {t}"))
            })
            .take(SHOWN)
            .collect();
        let more = named.len().saturating_sub(SHOWN);
        (!shown.is_empty()).then(|| {
            let tail = if more > 0 {
                format!(", and {more} more")
            } else {
                String::new()
            };
            format!("{}{tail}", shown.join(", "))
        })
    };
    let parts: Vec<String> = [
        list(&mut vertices, loaded.vertex_tags.as_ref(), "vertex", "node"),
        list(
            &mut triangles,
            loaded.triangle_tags.as_ref(),
            "triangle",
            "element",
        ),
    ]
    .into_iter()
    .flatten()
    .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "vertices and triangles above are numbered from {} in file order; in {}: {}",
            loaded.first_index,
            path.display(),
            parts.join("; ")
        )
    })
}

/// A positive, finite number of seconds.
fn seconds(option: &str, value: f64) -> Result<Duration> {
    if value.is_finite() && value > 0.0 {
        Ok(Duration::from_secs_f64(value))
    } else {
        Err(Error::Usage(format!(
            "{option} must be a positive number of seconds, not {value}"
        )))
    }
}

fn max_angle(args: &MaxAngleArgs) -> Result<ExitCode> {
    let input = load_input(&args.input)?;
    input.validate_input()?;
    crate::registry::mesher(&args.mesher)?;
    let timeout = seconds("--timeout", args.timeout)?;
    let exe = crate::isolate::find_exe()?;
    let result =
        crate::maxangle::max_angle(&exe, &args.mesher, &input, args.step, timeout, args.start)?;
    let json = serde_json::to_string(&result)
        .map_err(|e| Error::Usage(format!("cannot render the result as JSON: {e}")))?;
    if args.json {
        eprintln!("{result}");
    } else {
        println!("{result}");
    }
    println!("{json}");
    Ok(if result.angle.is_some() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn fuzz(args: &FuzzArgs) -> Result<ExitCode> {
    if args.domains {
        return fuzz_domains(args);
    }
    if args.jobs > 1 {
        return Err(Error::Usage(
            "--jobs runs cases side by side only in a campaign on domains (--domains); a \
             campaign on point sets runs one case at a time"
                .to_string(),
        ));
    }
    if !matches!(args.mesher.as_str(), "hex" | "hex-simple" | "hex-tiled") {
        crate::registry::mesher(&args.mesher)?;
    }
    if args.mesher == "triangle" {
        // The campaign (crate::fuzz) calls meshers in this process; Triangle exits the process
        // on some inputs and segfaults on others (lattice case 60 of seed 5:
        // tests/fixtures/refs/lattice_triangle_segfault.node), which would end the campaign
        // with no summary and no failure written.
        return Err(Error::Usage(
            "fuzz runs the mesher inside this process, and Triangle can exit or crash it: fuzz \
             triangle case by case with `hexmesh mesh` (isolated, with --timeout) or `hexmesh \
             report`"
                .into(),
        ));
    }
    let cases = case_range(args)?;
    let bar = fuzz_progress(args.cases)?;
    let summary = crate::fuzz::fuzz_campaign(
        &args.mesher,
        cases,
        args.seed,
        args.out.as_deref(),
        |done| bar.set(done),
    );
    bar.finish();
    println!(
        "fuzz {}: {} cases{} (seed {}), {} refused as too close for f64 at their coordinates, {} failed",
        summary.mesher,
        summary.cases,
        crate::fuzz::from_case(summary.first),
        summary.seed,
        summary.refused,
        summary.failures
    );
    println!(
        "worst angles seen: min {:.9}°, max {:.9}°; largest mesh {} triangles",
        summary.worst_min_angle, summary.worst_max_angle, summary.max_triangles
    );
    println!(
        "worst radius ratio {:.7}, worst shortest edge / d_min {:.7}, most exact Delaunay \
         violations in one mesh {}",
        summary.worst_radius_ratio, summary.worst_edge_over_d_min, summary.max_delaunay_violations
    );
    println!(
        "meshes by the largest rounding allowance used (degrees beyond the bounds): {}",
        crate::fuzz::ROUNDING_BINS
            .iter()
            .zip(summary.rounding_used)
            .map(|(bin, n)| format!("{bin} {n}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for f in &summary.families {
        println!(
            "  {:<16} {:>7} cases, {:>6} refused, {:>5} failed",
            f.family, f.cases, f.refused, f.failures
        );
    }
    if let Some(f) = &summary.first_failure {
        println!(
            "first failure: case {} ({}): {}",
            f.case, f.family, f.message
        );
        if let Some(path) = &f.path {
            println!("input written to {}", path.display());
        }
    }
    if summary.failed.len() > 1 {
        println!("all {} failing cases:", summary.failed.len());
        for (case, family, path) in &summary.failed {
            match path {
                Some(p) => println!("  case {case} ({family}): {}", p.display()),
                None => println!("  case {case} ({family})"),
            }
        }
    }
    Ok(if summary.failures == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// A campaign's progress: a bar on a terminal, otherwise a line every twentieth of the cases.
struct FuzzProgress {
    bar: Option<indicatif::ProgressBar>,
    cases: u64,
}

impl FuzzProgress {
    fn set(&self, done: u64) {
        match &self.bar {
            Some(bar) => bar.set_position(done),
            None if done % (self.cases / 20).max(1) == 0 => {
                eprintln!("{done}/{} cases", self.cases)
            }
            None => {}
        }
    }

    fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

/// The numbers of a campaign's cases: `--cases` of them from `--first`.
fn case_range(args: &FuzzArgs) -> Result<std::ops::Range<u64>> {
    match args.first.checked_add(args.cases) {
        Some(end) => Ok(args.first..end),
        None => Err(Error::Usage(format!(
            "--first {} with --cases {} runs past the last case number ({})",
            args.first,
            args.cases,
            u64::MAX
        ))),
    }
}

/// Refuses a campaign of no cases, and starts its progress display.
fn fuzz_progress(cases: u64) -> Result<FuzzProgress> {
    use std::io::IsTerminal;
    if cases == 0 {
        return Err(Error::Usage(
            "--cases must be at least 1: a campaign of no cases shows nothing".into(),
        ));
    }
    let bar = if std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(cases);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} cases, eta {eta}",
            )
            .map_err(|e| Error::Usage(format!("progress bar: {e}")))?,
        );
        Some(bar)
    } else {
        None
    };
    Ok(FuzzProgress { bar, cases })
}

/// `fuzz --domains`: the campaign of `crate::fuzz_domains`, any mesher that keeps segments
/// (Triangle, CGAL and hex each case in a child process).
fn fuzz_domains(args: &FuzzArgs) -> Result<ExitCode> {
    let runner = crate::fuzz_domains::runner_for(&args.mesher)?;
    let cases = case_range(args)?;
    let bar = fuzz_progress(args.cases)?;
    let summary = crate::fuzz_domains::domain_campaign(
        &args.mesher,
        cases,
        args.seed,
        args.out.as_deref(),
        &runner,
        args.jobs as usize,
        |done| bar.set(done),
    );
    bar.finish();
    let summary = summary?;
    print!("{summary}");
    Ok(if summary.failures == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
