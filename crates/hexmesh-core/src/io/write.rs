//! Writing a mesh in several formats at once, all or nothing ([`write_mesh_with`]).

use std::path::{Path, PathBuf};

use super::boundary::{derive_boundary, Boundary};
use super::triangle_out::{ele_file, node_file, poly_file, write_edge};
use super::{
    check_mesh, with_suffix, write_ele, write_msh_with, write_node, write_poly, write_svg,
    write_vtk_with, write_vtu_with, Format, SvgOptions,
};
use crate::error::{Error, Result};
use crate::mesh::{Pslg, TriMesh};

/// The files [`write_mesh`] writes for `formats` under `prefix`, in the order it writes them
/// (each format once): PREFIX.node + PREFIX.ele, PREFIX.poly + PREFIX.edge, PREFIX.vtk,
/// PREFIX.vtu, PREFIX.msh, PREFIX.svg, in the order the formats are given. The `.poly` file
/// names no points (they are PREFIX.node's), so [`Format::Poly`] brings [`Format::Triangle`]
/// with it, just before itself, when it is not asked for earlier.
pub fn mesh_files(prefix: &Path, formats: &[Format]) -> Vec<PathBuf> {
    let mut done: Vec<Format> = Vec::new();
    let mut files = Vec::new();
    for &format in formats {
        let implied = (format == Format::Poly).then_some(Format::Triangle);
        for f in implied.into_iter().chain([format]) {
            if !done.contains(&f) {
                done.push(f);
                files.extend(f.extensions().iter().map(|e| with_suffix(prefix, e)));
            }
        }
    }
    files
}

/// Writes `mesh` as [`write_mesh_with`] does, without an input: the labels are the mesh's
/// own (every boundary edge and vertex marked 1, no attributes, no regions).
pub fn write_mesh(prefix: &Path, mesh: &TriMesh, formats: &[Format]) -> Result<Vec<PathBuf>> {
    write_mesh_with(prefix, mesh, None, formats)
}

/// Writes `mesh` in each of `formats` (each once) under `prefix` ([`mesh_files`]), with the
/// labels of `input`, the input it was meshed from, carried to it ([`derive_boundary`]):
/// - [`Format::Triangle`]: PREFIX.node (1-based, header `N 2 A 1`: attributes and boundary
///   markers) and PREFIX.ele (the regional attribute when the input has regions);
/// - [`Format::Poly`]: PREFIX.poly (the boundary and segment edges with their markers, the
///   holes, the regions) and PREFIX.edge (every edge with its marker);
/// - [`Format::Vtk`], [`Format::Vtu`]: cell data `min_angle`, `max_angle`, `radius_ratio`,
///   `region` and point data `boundary_marker`;
/// - [`Format::Msh`]: curves and physical groups for the markers, the outer boundary, each
///   hole, the domain and each region;
/// - [`Format::Svg`]: the picture.
///
/// Returns the files written, in order. A triangle naming a missing vertex, a non-finite
/// vertex or labels that do not fit the input (`Labels::check_fit`) are refused before
/// anything is written.
///
/// All or nothing: every file is first written under a temporary name beside its own
/// (`.NAME.tmp-PID`), and the files are renamed into place only when all of them have been
/// written. When any step fails, the temporaries are removed and the files an earlier run
/// left at these names are put back, so that no output file is created or changed.
///
/// ```
/// use hexmesh_core::io::{write_mesh_with, Format};
/// use hexmesh_core::{Labels, Pslg, TriMesh};
///
/// // The unit square as two triangles, its bottom side marked 7 in the input.
/// let square = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let input = Pslg {
///     points: square.clone(),
///     segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
///     labels: Labels { segment_markers: Some(vec![7, 0, 0, 0]), ..Labels::default() },
///     ..Pslg::default()
/// };
/// let mesh = TriMesh { vertices: square, triangles: vec![[0, 1, 2], [0, 2, 3]] };
/// let dir = std::env::temp_dir().join(format!("hexmesh-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let written = write_mesh_with(&dir.join("sq"), &mesh, Some(&input), &[Format::Poly])?;
/// assert_eq!(written.len(), 4); // sq.node, sq.ele, sq.poly, sq.edge
/// let poly = std::fs::read_to_string(dir.join("sq.poly"))?;
/// // No points (they are sq.node's), then the four sides with Triangle's markers.
/// assert!(poly.starts_with("0 2 0 1\n4 1\n1 1 2 7\n2 2 3 1\n3 3 4 1\n4 4 1 1\n"), "{poly}");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_mesh_with(
    prefix: &Path,
    mesh: &TriMesh,
    input: Option<&Pslg>,
    formats: &[Format],
) -> Result<Vec<PathBuf>> {
    check_mesh(prefix, mesh)?;
    if let Some(input) = input {
        input
            .labels
            .check_fit(input.points.len(), input.segments.len())
            .map_err(|e| {
                super::triangle::invalid(prefix, format!("the input's labels do not fit: {e}"))
            })?;
    }
    let targets = mesh_files(prefix, formats);
    // Only .poly, .edge and .msh files list edges and loops.
    let with_edges = targets.iter().any(|t| {
        matches!(
            t.extension().and_then(|e| e.to_str()),
            Some("poly" | "edge" | "msh")
        )
    });
    let mut boundary: Option<Boundary> = None;
    let write = |target: &Path, path: &Path| -> Result<()> {
        let b = &*boundary.get_or_insert_with(|| match with_edges {
            true => derive_boundary(mesh, input),
            false => super::boundary::derive_labels(mesh, input),
        });
        match target.extension().and_then(|e| e.to_str()) {
            Some("node") => write_node(path, &node_file(mesh, b)),
            Some("ele") => write_ele(path, &ele_file(mesh, b)),
            Some("poly") => write_poly(path, &poly_file(b, input)),
            Some("edge") => write_edge(path, b),
            Some("vtk") => write_vtk_with(path, mesh, b),
            Some("vtu") => write_vtu_with(path, mesh, b),
            Some("msh") => write_msh_with(path, mesh, b),
            _ => write_svg(path, mesh, &SvgOptions::default()),
        }
    };
    write_all_or_nothing(&targets, write)?;
    Ok(targets)
}

/// Writes each of `targets` with `write(target, temporary)` to a temporary file beside it,
/// then renames them all into place; see [`write_mesh`]. On failure nothing is left behind
/// (cleanup is best effort: a failing removal is not reported over the original error).
fn write_all_or_nothing(
    targets: &[PathBuf],
    mut write: impl FnMut(&Path, &Path) -> Result<()>,
) -> Result<()> {
    let untouched = |target: &Path, source: std::io::Error| Error::Io {
        path: target.to_path_buf(),
        source: std::io::Error::new(
            source.kind(),
            format!("{source}; no output file was written or changed"),
        ),
    };
    let remove = |paths: &[PathBuf]| {
        for path in paths {
            let _ = std::fs::remove_file(path);
        }
    };

    // 1. Every file under a temporary name.
    let mut temps: Vec<PathBuf> = Vec::with_capacity(targets.len());
    for target in targets {
        let temp = free_name_beside(target, "tmp");
        temps.push(temp.clone());
        if let Err(e) = write(target, &temp) {
            remove(&temps);
            return Err(match e {
                Error::Io { path, source } if path == temp => untouched(target, source),
                other => other,
            });
        }
    }

    // 2. A link to (or, where links fail, a copy of) every file already at a target name, to
    // put back if a later rename fails. A directory in the way is left to its rename to fail.
    let mut backups: Vec<Option<PathBuf>> = Vec::with_capacity(targets.len());
    for target in targets {
        let in_the_way = std::fs::symlink_metadata(target).is_ok_and(|m| !m.is_dir());
        if !in_the_way {
            backups.push(None);
            continue;
        }
        let backup = free_name_beside(target, "bak");
        let linked = std::fs::hard_link(target, &backup)
            .or_else(|_| std::fs::copy(target, &backup).map(|_| ()));
        if let Err(source) = linked {
            remove(&temps);
            remove(&backups.iter().flatten().cloned().collect::<Vec<_>>());
            let _ = std::fs::remove_file(&backup);
            return Err(untouched(target, source));
        }
        backups.push(Some(backup));
    }

    // 3. Every temporary onto its name; on a failure, the renamed ones are undone.
    for (k, (temp, target)) in temps.iter().zip(targets).enumerate() {
        if let Err(source) = std::fs::rename(temp, target) {
            for (done, backup) in targets[..k].iter().zip(&backups[..k]).rev() {
                let _ = match backup {
                    Some(backup) => std::fs::rename(backup, done),
                    None => std::fs::remove_file(done),
                };
            }
            remove(&temps[k..]);
            remove(&backups[k..].iter().flatten().cloned().collect::<Vec<_>>());
            return Err(untouched(target, source));
        }
    }
    remove(&backups.into_iter().flatten().collect::<Vec<_>>());
    Ok(())
}

/// A name for a hidden scratch file beside `target` (same directory, so a rename onto
/// `target` stays on one file system): `.NAME.TAG-PID`, with a counter when that is taken.
fn free_name_beside(target: &Path, tag: &str) -> PathBuf {
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let pid = std::process::id();
    (0u64..)
        .map(|k| match k {
            0 => target.with_file_name(format!(".{name}.{tag}-{pid}")),
            _ => target.with_file_name(format!(".{name}.{tag}-{pid}-{k}")),
        })
        .find(|p| std::fs::symlink_metadata(p).is_err())
        .unwrap_or_else(|| unreachable!("an unbounded range always yields a free name"))
}
