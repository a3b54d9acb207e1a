//! Extraction of the dual triangle mesh, paper 000 Sec. 4.2: an edge joins the centres of
//! adjacent full hexagons, a semi-hexagon neighbour is replaced by the full hexagon opposite
//! it, boundary semi-hexagons count as virtual full hexagons, and the centre of an occupied
//! hexagon is replaced by its input point.
//!
//! The triangles are found as a 1:4 / 1:2 refinement of lattice triangles (DESIGN.md): the
//! triangle of three mutually adjacent full hexagons A, B, C of level k is split into the four
//! triangles of level k + 1 when all three are subdivided, into two through the midpoint of AB
//! (a full hexagon joined from two semi-hexagons) when exactly A and B are, and is a triangle of
//! the mesh otherwise; the centre of a subdivided hexagon is the centre of its central child.
//! Cells outside the bounding hexagon count as subdivided, and a triangle is kept only when its
//! three centres lie in the closed bounding hexagon. The balancing rule guarantees that the
//! hexagons of a kept triangle are not subdivided further.

use crate::geom::{orient2d, Point};
use crate::hex::lattice::{FxHashMap, FxHashSet, Key};
use crate::hex::mc3::Patch;
use crate::hex::region::Region;
use crate::hex::subdivision::Hierarchy;
use crate::mesh::TriMesh;

/// How centres are placed in the output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placement {
    /// Occupied centres replaced by their input point (Sec. 4.2), input point i is vertex i.
    Relocated,
    /// Plain lattice centres only: the mesh of an unfinished refinement.
    Plain,
}

/// The dual mesh of the hierarchy's current subdivision.
pub fn extract(h: &Hierarchy, placement: Placement) -> TriMesh {
    extract_moved(h, placement, &FxHashMap::default()).0
}

/// The dual mesh with the centres in `moved` (keyed by `Key::canonical`) placed there instead
/// of at the lattice centre (Sec. 5.4), and the canonical key of each vertex (input points
/// carry the key of their hexagon).
pub fn extract_moved(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
) -> (TriMesh, Vec<Key>) {
    extract_where(h, placement, moved, &Patch::default(), |_| true)
}

/// `extract_moved`, with the triangles around the centres `patch.dropped` replaced by
/// `patch.triangles` (the MOVED_CENTER_3 topology of Sec. 5.4, `mc3`), which are emitted after
/// the others in their order.
pub fn extract_patched(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    patch: &Patch,
) -> (TriMesh, Vec<Key>) {
    extract_where(h, placement, moved, patch, |_| true)
}

/// The triangles of `extract_moved` that lie in lattice triangles touching `region` (with
/// the vertices they use): the part of the dual a local change can have altered, found by
/// descending only into the lattice triangles that touch the region.
pub fn extract_region(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    region: &Region,
) -> (TriMesh, Vec<Key>) {
    extract_where(h, placement, moved, &Patch::default(), |tri| {
        region.touches(tri)
    })
}

/// `extract_region` of `extract_patched`: the patch triangles with a cell in the region are
/// kept with the others.
pub fn extract_region_patched(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    patch: &Patch,
    region: &Region,
) -> (TriMesh, Vec<Key>) {
    extract_where(h, placement, moved, patch, |tri| region.touches(tri))
}

/// The dual recursion, descending only into lattice triangles for which `keep` holds (it must
/// hold for a triangle whenever it holds for one of its sub-triangles), with the triangles of
/// `patch` in place of those around `patch.dropped`.
fn extract_where(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    patch: &Patch,
    keep: impl Fn(&[Key; 3]) -> bool,
) -> (TriMesh, Vec<Key>) {
    let mut b = Builder::new(h, placement, moved, &patch.dropped);
    // Each entry carries whether its three hexagons are subdivided (outside counts as
    // subdivided), looked up once per distinct hexagon when the parent is split.
    let state = |c: Key| (c, h.is_subdivided_or_outside(c));
    let mut stack: Vec<[(Key, bool); 3]> = Vec::new();
    // The six lattice triangles around the root, counter-clockwise because the lattice
    // directions are listed counter-clockwise.
    for d in (0..6).rev() {
        stack.push([
            state(Key::ROOT),
            state(Key::ROOT.neighbor(d)),
            state(Key::ROOT.neighbor((d + 1) % 6)),
        ]);
    }
    while let Some(tri) = stack.pop() {
        if !tri.iter().any(|c| c.0.inside()) {
            continue;
        }
        let sub = tri.map(|c| c.1);
        let keys = tri.map(|c| c.0);
        if !keep(&keys) {
            continue;
        }
        match sub.iter().filter(|&&s| s).count() {
            3 => {
                let [a, b2, c] = keys;
                let (mab, mbc, mca) = (
                    state(midpoint(a, b2)),
                    state(midpoint(b2, c)),
                    state(midpoint(c, a)),
                );
                let (ca, cb, cc) = (
                    state(a.central_child()),
                    state(b2.central_child()),
                    state(c.central_child()),
                );
                // Pushed in reverse so that they are emitted in this order.
                stack.push([mab, mbc, mca]);
                stack.push([mca, mbc, cc]);
                stack.push([mab, cb, mbc]);
                stack.push([ca, mab, mca]);
            }
            2 => {
                // Rotate so that the unsubdivided hexagon comes last: (A, B sub, C not).
                let r = (0..3).find(|&r| !sub[(r + 2) % 3]).unwrap_or(0);
                let [a, b2, c] = [keys[r], keys[(r + 1) % 3], keys[(r + 2) % 3]];
                let m = midpoint(a, b2);
                b.emit([m, b2, c]);
                b.emit([a, m, c]);
            }
            _ => b.emit(keys),
        }
    }
    for tri in patch.triangles.iter().filter(|t| keep(t)) {
        b.emit_patch(*tri);
    }
    b.finish()
}

/// The cell at the midpoint of two adjacent cells of the same level.
fn midpoint(a: Key, b: Key) -> Key {
    Key::new(a.k + 1, a.i + b.i, a.j + b.j)
}

/// The index entry of a dropped centre that has no vertex yet.
const DROPPED: u32 = u32::MAX;

struct Builder<'a> {
    h: &'a Hierarchy,
    moved: &'a FxHashMap<Key, Point>,
    /// Centres whose triangles the patch replaces.
    dropped: &'a FxHashSet<Key>,
    /// Every dropped centre is marked `DROPPED` in `index` (none is a vertex yet).
    marked: bool,
    /// Canonical key of each vertex.
    keys: Vec<Key>,
    /// Dual vertex of each canonical centre.
    index: FxHashMap<Key, u32>,
    vertices: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    used: Vec<bool>,
}

impl<'a> Builder<'a> {
    fn new(
        h: &'a Hierarchy,
        placement: Placement,
        moved: &'a FxHashMap<Key, Point>,
        dropped: &'a FxHashSet<Key>,
    ) -> Builder<'a> {
        // About one vertex per full leaf and two triangles per vertex: reserving avoids
        // rehashing a table of millions of entries.
        let expected = h.full_leaves + h.points.len();
        let mut index = FxHashMap::with_capacity_and_hasher(expected, Default::default());
        let mut vertices = Vec::with_capacity(expected);
        if placement == Placement::Relocated {
            vertices = h.points.clone();
            for key in h.occupied_sorted() {
                if let [p] = h.occupants(key) {
                    if h.is_full_leaf(key) {
                        index.insert(key.canonical(), *p);
                    }
                }
            }
        }
        let used = vec![false; vertices.len()];
        let mut keys = vec![Key::ROOT; vertices.len()];
        for (&key, &v) in &index {
            keys[v as usize] = key;
        }
        // Dropped centres are marked in the index: the lookup that finds a vertex also tells
        // a triangle of a dropped star (`emit`); the patch gives them vertices (`vertex`).
        let mut marked = true;
        for &key in dropped {
            if *index.entry(key).or_insert(DROPPED) != DROPPED {
                // A dropped centre that already is a vertex (an input point): test the set.
                marked = false;
            }
        }
        Builder {
            h,
            moved,
            dropped,
            marked,
            keys,
            index,
            vertices,
            triangles: Vec::with_capacity(2 * expected),
            used,
        }
    }

    fn emit(&mut self, tri: [Key; 3]) {
        if !tri.iter().all(|c| c.inside()) {
            return;
        }
        let keys = tri.map(|c| c.canonical());
        let found = keys.map(|k| self.index.get(&k).copied());
        if !self.dropped.is_empty() {
            let dropped = if self.marked {
                found.contains(&Some(DROPPED))
            } else {
                keys.iter().any(|k| self.dropped.contains(k))
            };
            if dropped {
                return;
            }
        }
        let t = [0, 1, 2].map(|m| match found[m] {
            Some(v) => {
                self.used[v as usize] = true;
                v
            }
            None => self.new_vertex(keys[m]),
        });
        self.triangles.push(t);
    }

    fn emit_patch(&mut self, tri: [Key; 3]) {
        if tri.iter().all(|c| c.inside()) {
            let t = tri.map(|c| self.vertex(c));
            self.triangles.push(t);
        }
    }

    fn vertex(&mut self, cell: Key) -> u32 {
        let key = cell.canonical();
        match self.index.get(&key) {
            Some(&v) if v != DROPPED => {
                self.used[v as usize] = true;
                v
            }
            _ => self.new_vertex(key),
        }
    }

    /// A new vertex for the canonical key `key` (not in the index, or a dropped centre).
    fn new_vertex(&mut self, key: Key) -> u32 {
        let v = self.vertices.len() as u32;
        let p = match self.moved.get(&key) {
            Some(&p) => p,
            None => self.h.lattice.center(key),
        };
        self.vertices.push(p);
        self.keys.push(key);
        self.used.push(true);
        self.index.insert(key, v);
        v
    }

    /// Drops vertices no triangle uses (points of an unfinished refinement, all of them in
    /// `Plain` placement) and renumbers.
    fn finish(self) -> (TriMesh, Vec<Key>) {
        if self.used.iter().all(|&u| u) {
            let mesh = TriMesh {
                vertices: self.vertices,
                triangles: self.triangles,
            };
            return (mesh, self.keys);
        }
        let mut map = vec![u32::MAX; self.vertices.len()];
        let mut vertices = Vec::new();
        let mut keys = Vec::new();
        for (v, &u) in self.used.iter().enumerate() {
            if u {
                map[v] = vertices.len() as u32;
                vertices.push(self.vertices[v]);
                keys.push(self.keys[v]);
            }
        }
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|v| map[v as usize]))
            .collect();
        (
            TriMesh {
                vertices,
                triangles,
            },
            keys,
        )
    }
}

/// The first triangle that is not strictly counter-clockwise under exact orientation, if any.
pub fn first_inverted(mesh: &TriMesh) -> Option<usize> {
    (0..mesh.triangles.len()).find(|&t| {
        let [a, b, c] = mesh.corners(t);
        orient2d(a, b, c) <= 0.0
    })
}
