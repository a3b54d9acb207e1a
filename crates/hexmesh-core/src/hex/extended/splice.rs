//! The splice: not in paper 000 (engineering). After local repairs the whole dual is put
//! together from the last complete dual and the dual of the repaired region instead of
//! extracted a second time, checking that the two meet along the same seam.

use super::ExtendedStats;
use crate::geom::Point;
use crate::hex::lattice::{FxHashMap, FxHashSet, Key};
use crate::hex::parallel::{fill_in_parallel, PARALLEL_MIN};
use crate::hex::region::Region;
use crate::hex::subdivision::Hierarchy;
use crate::mesh::TriMesh;

/// The whole dual once a check has passed. After a complete check (no `inner` region) it is
/// the checked `mesh`; after local checks, `splice` of the complete dual kept then (`base`)
/// and the region's `mesh`, whose `keys` get back the ones `blamed` replaced. `None` when
/// there is no complete dual to splice into (incremental insertion) or the seam does not
/// close: the caller extracts it whole.
pub(super) fn whole_dual(
    h: &Hierarchy,
    stats: &mut ExtendedStats,
    base: Option<(TriMesh, Vec<Key>)>,
    mesh: TriMesh,
    keys: &mut [Key],
    blamed: &[(usize, Key)],
    inner: Option<&Region>,
) -> Option<TriMesh> {
    let Some(inner) = inner else {
        return Some(mesh);
    };
    unblame(keys, blamed);
    let whole = splice(h, base?, &mesh, keys, inner);
    match whole {
        Some(_) => stats.spliced += 1,
        None => stats.splice_refused += 1,
    }
    whole
}

/// Gives the vertex keys back that blaming triangles on MOVED_CENTER_3 hexagons replaced.
pub(super) fn unblame(keys: &mut [Key], blamed: &[(usize, Key)]) {
    for &(v, k) in blamed {
        keys[v] = k;
    }
}

/// After a complete check that failed, when local repairs begin: the complete dual and its
/// vertex keys (unblamed) become the `base` that `whole_dual` splices into.
pub(super) fn keep_for_splice(
    base: &mut Option<(TriMesh, Vec<Key>)>,
    mesh: &mut TriMesh,
    keys: &mut Vec<Key>,
    blamed: &[(usize, Key)],
) {
    unblame(keys, blamed);
    *base = Some((std::mem::take(mesh), std::mem::take(keys)));
}

/// The whole dual after local repairs without a second pass over the whole hierarchy: the
/// complete dual `old` (with the canonical key of each vertex) keeps its triangles whose
/// vertices' leaves all lie outside `inner`, and takes from `part` (the dual of the repaired
/// region, with its keys) the triangles with a vertex inside. Beyond the reach of the changed
/// cells nothing changed (`region`), which is what the local checks rely on too; the splice
/// checks it where it matters: the replaced and the new triangles must meet the kept ones
/// along the same seam (their boundary edges between vertices outside `inner`, as directed
/// edges between vertex keys), and every vertex outside `inner` that a new triangle uses must
/// be a vertex of a replaced one, in the same place; the new triangles' other boundary edges
/// must lie on the rim of the bounding hexagon (no hole). `None` when not.
/// Kept triangles and vertices keep their order (the input points stay the first vertices);
/// the new ones follow in the order of `part`.
pub(crate) fn splice(
    h: &Hierarchy,
    old: (TriMesh, Vec<Key>),
    part: &TriMesh,
    part_keys: &[Key],
    inner: &Region,
) -> Option<TriMesh> {
    let (old, old_keys) = old;
    let inside = |k: &Key| inner.contains(h.leaf_of_vertex(*k));
    // Each vertex's leaf looked up over the threads (5.9 million at plane-100k).
    let mut old_in = vec![false; old_keys.len()];
    fill_in_parallel(h.threads(), &mut old_in, PARALLEL_MIN, |v| {
        inside(&old_keys[v])
    });
    let part_in: Vec<bool> = part_keys.iter().map(inside).collect();
    let TriMesh {
        mut vertices,
        mut triangles,
    } = old;
    // The vertices of the replaced triangles by key, and their directed edges. The kept
    // triangles stay in the old array, in order (no second mesh-sized array).
    let mut seam: FxHashMap<Key, u32> = FxHashMap::default();
    let mut replaced: FxHashSet<(Key, Key)> = FxHashSet::default();
    triangles.retain(|t| {
        let gone = t.iter().any(|&v| old_in[v as usize]);
        if gone {
            for e in 0..3 {
                replaced.insert((old_keys[t[e] as usize], old_keys[t[(e + 1) % 3] as usize]));
                seam.insert(old_keys[t[e] as usize], t[e]);
            }
        }
        !gone
    });
    let added: Vec<[u32; 3]> = part
        .triangles
        .iter()
        .filter(|t| t.iter().any(|&v| part_in[v as usize]))
        .copied()
        .collect();
    let mut new_edges: FxHashSet<(Key, Key)> = FxHashSet::default();
    for t in &added {
        for e in 0..3 {
            new_edges.insert((part_keys[t[e] as usize], part_keys[t[(e + 1) % 3] as usize]));
        }
    }
    // The seam: the boundary edges between vertices outside `inner` (an edge at an inside
    // vertex can only be on the boundary of the whole dual, which may change there).
    let boundary = |edges: &FxHashSet<(Key, Key)>| {
        let mut b: Vec<(Key, Key)> = edges
            .iter()
            .filter(|&&(a, b)| !edges.contains(&(b, a)) && !inside(&a) && !inside(&b))
            .copied()
            .collect();
        b.sort_unstable();
        b
    };
    if boundary(&replaced) != boundary(&new_edges) {
        return None;
    }
    // The other boundary edges of the new triangles (at an inside vertex) must lie on the
    // boundary of the whole dual: both ends at hexagons on the rim of the bounding hexagon.
    // Anywhere else such an edge would border a hole, a triangle the region missed.
    let rim = |k: &Key| {
        let leaf = h.leaf_of_vertex(*k);
        leaf.on_boundary() || (0..6).any(|d| !leaf.neighbor(d).inside())
    };
    if new_edges.iter().any(|&(a, b)| {
        !new_edges.contains(&(b, a)) && (inside(&a) || inside(&b)) && !(rim(&a) && rim(&b))
    }) {
        return None;
    }
    let same =
        |a: Point, b: Point| a[0].to_bits() == b[0].to_bits() && a[1].to_bits() == b[1].to_bits();
    let mut map = vec![u32::MAX; part.vertices.len()];
    for t in &added {
        for &v in t {
            let v = v as usize;
            if map[v] != u32::MAX {
                continue;
            }
            let p = part.vertices[v];
            map[v] = match seam.get(&part_keys[v]) {
                Some(&o) if same(vertices[o as usize], p) => o,
                _ if !part_in[v] => return None,
                // An input point whose hexagon was subdivided (its vertex key changed): it
                // keeps its number, as in a whole extraction, where the points come first.
                _ => match h.occupants(h.leaf_of_vertex(part_keys[v])) {
                    &[i] if (i as usize) < h.points.len()
                        && same(vertices[i as usize], p)
                        && same(h.points[i as usize], p) =>
                    {
                        i
                    }
                    _ => {
                        vertices.push(p);
                        (vertices.len() - 1) as u32
                    }
                },
            };
        }
    }
    triangles.extend(added.iter().map(|t| t.map(|v| map[v as usize])));
    // Vertices no triangle uses any more (inside `inner`, replaced) are dropped, the rest
    // renumbered in order.
    let mut used = vec![false; vertices.len()];
    for t in &triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    if used.iter().all(|&u| u) {
        return Some(TriMesh {
            vertices,
            triangles,
        });
    }
    // Compacted in place: `retain` visits the vertices in order, and a kept vertex's new
    // number is the count kept before it.
    let mut renumber = vec![u32::MAX; vertices.len()];
    let (mut v, mut next) = (0, 0);
    vertices.retain(|_| {
        let keep = used[v];
        if keep {
            renumber[v] = next;
            next += 1;
        }
        v += 1;
        keep
    });
    for t in &mut triangles {
        *t = t.map(|v| renumber[v as usize]);
    }
    Some(TriMesh {
        vertices,
        triangles,
    })
}

#[cfg(test)]
mod tests {
    use super::super::mesh_extended;
    use super::super::ExtendedRun;
    use super::*;
    use crate::hex::dual::{self, Placement};
    use crate::hex::extended::relocate::relocations;
    use crate::hex::extended::rings::{apply_placed, rings_with_flips};
    use crate::mesher::Params;

    /// The finished `hex` dual of 100 points spread over the unit square (the R2 sequence:
    /// steps of the plastic number's inverse powers) with its vertex keys, the hierarchy, and
    /// an interior vertex far from the bounding hexagon with its region (reach 2).
    fn plane_100() -> (ExtendedRun, TriMesh, Vec<Key>, usize, Region) {
        let (a1, a2) = (0.754_877_666_246_693, 0.569_840_290_998_053_3);
        let points = (1..=100)
            .map(|i| [(0.5 + a1 * i as f64).fract(), (0.5 + a2 * i as f64).fract()])
            .collect();
        let input = crate::mesh::Pslg::from_points(points);
        let run = mesh_extended(&input, &Params::default()).expect("meshes");
        let h = &run.hierarchy;
        let r = rings_with_flips(h, &run.rings);
        let (mut moved, patch) = relocations(h, &r);
        apply_placed(&mut moved, &run.rings);
        let (mesh, keys) = dual::extract_patched(h, Placement::Relocated, &moved, &patch);
        let centre = [0.5, 0.5];
        let v = (0..mesh.vertices.len())
            .min_by(|&a, &b| {
                crate::geom::dist2(mesh.vertices[a], centre)
                    .total_cmp(&crate::geom::dist2(mesh.vertices[b], centre))
            })
            .expect("vertices");
        let inner = Region::around(&[h.leaf_of_vertex(keys[v])], 2);
        (run, mesh, keys, v, inner)
    }

    #[test]
    fn a_dual_spliced_with_itself_is_itself() {
        let (run, mesh, keys, _, inner) = plane_100();
        let whole = splice(
            &run.hierarchy,
            (mesh.clone(), keys.clone()),
            &mesh,
            &keys,
            &inner,
        )
        .expect("the seam closes");
        assert_eq!(whole.corner_bits_sorted(), mesh.corner_bits_sorted());
        assert_eq!(whole.vertices.len(), mesh.vertices.len());
    }

    #[test]
    fn a_region_missing_a_triangle_is_not_spliced() {
        let (run, mesh, keys, v, inner) = plane_100();
        let mut part = mesh.clone();
        let t = part
            .triangles
            .iter()
            .position(|t| t.contains(&(v as u32)))
            .expect("a triangle at the vertex");
        part.triangles.remove(t);
        assert!(splice(&run.hierarchy, (mesh, keys.clone()), &part, &keys, &inner).is_none());
    }

    #[test]
    fn a_region_that_moves_a_seam_vertex_is_not_spliced() {
        let (run, mesh, keys, _, inner) = plane_100();
        let h = &run.hierarchy;
        let inside = |w: u32| inner.contains(h.leaf_of_vertex(keys[w as usize]));
        // A vertex outside the region on a triangle that has one inside: on the seam.
        let seam = mesh
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&w| inside(w)))
            .flat_map(|t| t.iter().copied())
            .find(|&w| !inside(w))
            .expect("a seam vertex");
        let mut part = mesh.clone();
        part.vertices[seam as usize][0] += 1e-9;
        assert!(splice(h, (mesh, keys.clone()), &part, &keys, &inner).is_none());
    }
}
