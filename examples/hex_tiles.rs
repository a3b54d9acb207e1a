//! Measures how local the extended hexagonal mesher (`hex`) is, for the design of a tiled run:
//! `cargo run --release --example hex_tiles DATASET LEVEL HALO [TILES]`.
//!
//! The input points are grouped into tiles: the cells of lattice level LEVEL nearest to them.
//! For TILES tiles spread over the list (default 8), `hex` meshes the tile's own points and
//! those of the tiles at most HALO cells away (0: the tile alone), in the bounding hexagon of
//! the whole input, and the full leaves whose centre lies in the tile are compared with the
//! whole run's: how many differ, how many of the whole run's leaves the tile split further
//! (splits a stitched run would keep), and how far from the tile's edge the farthest
//! difference lies, in radii of the tile's cell. Each line also gives the tile's points and
//! meshing time. Everything runs on one thread.
//!
//! Wrong arguments are named in an error with the usage, exit code 2; a mesher error is
//! printed, exit code 1.

use std::collections::HashSet;
use std::process::ExitCode;

use hexmesh::hex::extended::mesh_extended;
use hexmesh::hex::lattice::Lattice;
use hexmesh::hex::{root_hexagon, Key};
use hexmesh::{Params, Pslg};

// The `hexmesh` command's allocator, set up as it sets it.
#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

const USAGE: &str = "usage: hex_tiles DATASET LEVEL (1 to 12) HALO (0 to 4) [TILES, 1 to 1000]";

/// The arguments: the input, the tile level, the halo in tiles and how many tiles to try.
fn parse(args: &[String]) -> Result<(Pslg, u8, i64, usize), String> {
    if !(3..=4).contains(&args.len()) {
        return Err(format!("{} arguments given, 3 or 4 are taken", args.len()));
    }
    let input = hexmesh::datasets::by_name(&args[0]).map_err(|e| format!("argument 1: {e}"))?;
    let number = |n: usize, lo: i64, hi: i64| -> Result<i64, String> {
        match args[n].parse::<i64>() {
            Ok(v) if (lo..=hi).contains(&v) => Ok(v),
            _ => Err(format!(
                "argument {}: '{}' is not a whole number from {lo} to {hi}",
                n + 1,
                args[n]
            )),
        }
    };
    let level = number(1, 1, 12)? as u8;
    let halo = number(2, 0, 4)?;
    let tiles = if args.len() == 4 {
        number(3, 1, 1000)? as usize
    } else {
        8
    };
    Ok((input, level, halo, tiles))
}

/// Steps between two cells of one level (hexagonal distance on the lattice's axes).
fn steps(a: Key, b: Key) -> i64 {
    let (di, dj) = (a.i - b.i, a.j - b.j);
    (di.abs() + dj.abs() + (di + dj).abs()) / 2
}

fn main() -> ExitCode {
    hexmesh::configure_allocator();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (input, level, halo, wanted) = match parse(&args) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("hex_tiles: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let root = root_hexagon(&input);
    let lattice = Lattice::new(root);
    let one = std::num::NonZeroUsize::MIN;
    let params = Params::default().with_threads(one);
    let start = std::time::Instant::now();
    let whole = match mesh_extended(&input, &params) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("hex_tiles: {}: {e}", args[0]);
            return ExitCode::FAILURE;
        }
    };
    println!(
        "whole input: {} points, {} triangles in {:.2} s",
        input.points.len(),
        whole.mesh.triangles.len(),
        start.elapsed().as_secs_f64()
    );
    let tile_of = |p: [f64; 2]| lattice.nearest(level, p);
    let mut tiles: Vec<Key> = input.points.iter().map(|&p| tile_of(p)).collect();
    tiles.sort_unstable_by_key(|k| k.packed());
    tiles.dedup();
    println!("{} tiles of level {level}, halo {halo}", tiles.len());
    let whole_leaves: Vec<Key> = whole.hierarchy.full_leaves_iter().collect();
    // Distance from `p` to the edge of the tile's cell (the bisectors with its six
    // neighbours), in radii of that cell.
    let to_edge = |tile: Key, p: [f64; 2]| {
        let c = lattice.center(tile);
        let d2 = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
        (0..6)
            .map(|d| {
                let n = lattice.center(tile.neighbor(d));
                (d2(p, n) - d2(p, c)) / (2.0 * d2(n, c).sqrt())
            })
            .fold(f64::INFINITY, f64::min)
            / lattice.radius(level)
    };
    let step = (tiles.len() / wanted).max(1);
    for (n, &tile) in tiles.iter().enumerate().step_by(step).take(wanted) {
        let points: Vec<[f64; 2]> = input
            .points
            .iter()
            .copied()
            .filter(|&p| steps(tile_of(p), tile) <= halo)
            .collect();
        let count = points.len();
        let part = Pslg {
            points,
            hexagon: Some(root),
            ..Pslg::default()
        };
        let start = std::time::Instant::now();
        let run = match mesh_extended(&part, &params) {
            Ok(run) => run,
            Err(e) => {
                eprintln!("hex_tiles: tile {n}: {e}");
                return ExitCode::FAILURE;
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        let inside = |k: &Key| tile_of(lattice.center(*k)) == tile;
        let mine: HashSet<u128> = run
            .hierarchy
            .full_leaves_iter()
            .filter(inside)
            .map(Key::packed)
            .collect();
        let theirs: HashSet<u128> = whole_leaves
            .iter()
            .filter(|k| inside(k))
            .map(|k| k.packed())
            .collect();
        let differ: HashSet<u128> = mine.symmetric_difference(&theirs).copied().collect();
        let split_further = whole_leaves
            .iter()
            .filter(|k| inside(k) && run.hierarchy.is_subdivided(**k))
            .count();
        let farthest = run
            .hierarchy
            .full_leaves_iter()
            .chain(whole_leaves.iter().copied())
            .filter(|k| differ.contains(&k.packed()))
            .map(|k| to_edge(tile, lattice.center(k)))
            .fold(0.0f64, f64::max);
        println!(
            "tile {n} ({}, {}): {count} points, {seconds:.2} s; {} full leaves here against {} \
             in the whole run: {} only here, {} only there, {split_further} of the whole run's \
             split further; farthest difference {farthest:.3} tile radii from the edge",
            tile.i,
            tile.j,
            mine.len(),
            theirs.len(),
            mine.difference(&theirs).count(),
            theirs.difference(&mine).count(),
        );
    }
    ExitCode::SUCCESS
}
