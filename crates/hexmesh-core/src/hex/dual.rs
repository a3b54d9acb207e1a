//! Extraction of the dual triangle mesh, paper 000 Sec. 4.2: an edge joins the centres of
//! adjacent full hexagons, a semi-hexagon neighbour is replaced by the full hexagon opposite
//! it, boundary semi-hexagons count as virtual full hexagons, and the centre of an occupied
//! hexagon is replaced by its input point.
//!
//! The centres of the hexagons of one level form a triangular lattice, and subdividing a hexagon
//! refines the triangles around its centre 1:4 at their midpoints, so the triangles are found as a
//! 1:4 / 1:2 refinement of lattice triangles: the triangle of three mutually adjacent full hexagons
//! A, B, C of level k is split into the four triangles of level k + 1 when all three are
//! subdivided, into two through the midpoint of AB (a full hexagon joined from two semi-hexagons)
//! when exactly A and B are, and is a triangle of the mesh otherwise; the centre of a subdivided
//! hexagon is the centre of its central child. Cells outside the bounding hexagon count as
//! subdivided, and a triangle is kept only when its three centres lie in the closed bounding
//! hexagon. The balancing rule guarantees that the hexagons of a kept triangle are not subdivided
//! further.

use crate::geom::{orient2d, Point};
use crate::hex::lattice::{FxHashMap, FxHashSet, Key, KeyIndex};
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
    extract_all(h, placement, moved, &Patch::default())
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
    extract_all(h, placement, moved, patch)
}

/// A centre's place asked after the table of moved centres, before the lattice centre
/// (`extract_relocated`).
pub type Relocate<'a> = &'a (dyn Fn(Key) -> Option<Point> + Sync);

/// Gives triangles of the patch to the function it is called with, in order, when the dual
/// emits them (`extract_relocated`).
pub type PatchTriangles<'a> = &'a dyn Fn(&mut dyn FnMut([Key; 3]));

/// `extract_patched` in `Relocated` placement, with the centres that `moved` does not hold
/// placed by `relocate` where it gives a place, and the triangles of `later` emitted after
/// those of `patch`: the whole dual without a table of every relocated centre nor a list of
/// the patch's triangles (`extended::chain_relocations`), the places computed as the vertices
/// are met (over the threads of the split descent), the patch's triangles as they are made.
pub fn extract_relocated(
    h: &Hierarchy,
    (moved, relocate): (&FxHashMap<Key, Point>, Relocate<'_>),
    patch: &Patch,
    later: PatchTriangles<'_>,
) -> (TriMesh, Vec<Key>) {
    extract_all_from(
        h,
        (Placement::Relocated, Some(relocate)),
        moved,
        (patch, Some(later)),
        PARALLEL_EXTRACT_MIN,
    )
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
    extract_where(h, placement, moved, &Patch::default(), false, |tri| {
        region.touches(tri)
    })
}

/// `extract_region` of `extract_patched`: the patch triangles with a cell in the region are
/// kept with the others. A centre in `placed` goes there, before `moved` is asked: a large
/// table of places is looked up, not merged into `moved`, for a small region.
pub fn extract_region_patched(
    h: &Hierarchy,
    placement: Placement,
    (placed, moved): (&FxHashMap<Key, Point>, &FxHashMap<Key, Point>),
    patch: &Patch,
    region: &Region,
) -> (TriMesh, Vec<Key>) {
    let mut b = Builder::new(h, placement, moved, &patch.dropped, false);
    b.placed = Some(placed);
    emit_where(h, b, patch, |tri| region.touches(tri))
}

/// The dual recursion, descending only into lattice triangles for which `keep` holds (it must
/// hold for a triangle whenever it holds for one of its sub-triangles), with the triangles of
/// `patch` in place of those around `patch.dropped`.
fn extract_where(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    patch: &Patch,
    whole: bool,
    keep: impl Fn(&[Key; 3]) -> bool,
) -> (TriMesh, Vec<Key>) {
    let b = Builder::new(h, placement, moved, &patch.dropped, whole);
    emit_where(h, b, patch, keep)
}

/// The descent of `extract_where` into the builder `b`.
fn emit_where(
    h: &Hierarchy,
    mut b: Builder<'_>,
    patch: &Patch,
    keep: impl Fn(&[Key; 3]) -> bool,
) -> (TriMesh, Vec<Key>) {
    descend(h, root_triangles(h), &keep, &mut |tri| b.emit(tri));
    for tri in patch.triangles.iter().filter(|t| keep(t)) {
        b.emit_patch(*tri);
    }
    b.finish()
}

/// `extract_where` of the whole dual, with the descent split over threads for a large
/// hierarchy. The output is the serial one, byte for byte: the lattice triangles of the first
/// levels are expanded in emission order into independent subtrees (the depth-first descent
/// emits each subtree whole before the next), each part numbers the vertices it meets in the
/// order it meets them, and the parts are merged in order, a vertex taking the next number
/// where it is first met: the order of the serial descent.
fn extract_all(
    h: &Hierarchy,
    placement: Placement,
    moved: &FxHashMap<Key, Point>,
    patch: &Patch,
) -> (TriMesh, Vec<Key>) {
    extract_all_from(
        h,
        (placement, None),
        moved,
        (patch, None),
        PARALLEL_EXTRACT_MIN,
    )
}

/// `extract_all`, split over threads from `min_leaves` full leaves on, with the centres
/// `moved` does not hold placed by the `Relocate` given, if any, and the `PatchTriangles`
/// given, if any, after the patch's own (`extract_relocated`).
fn extract_all_from(
    h: &Hierarchy,
    (placement, relocate): (Placement, Option<Relocate<'_>>),
    moved: &FxHashMap<Key, Point>,
    (patch, later): (&Patch, Option<PatchTriangles<'_>>),
    min_leaves: usize,
) -> (TriMesh, Vec<Key>) {
    let mut b = Builder::new(h, placement, moved, &patch.dropped, true);
    b.relocate = relocate;
    // `later`'s triangles, when they were built to find the centres they use (once is
    // enough: they are emitted from this list in the order `later` gave them).
    let mut later_triangles: Option<Vec<[Key; 3]>> = None;
    if h.full_leaves < min_leaves {
        descend(h, root_triangles(h), &|_| true, &mut |tri| b.emit(tri));
    } else {
        // The centres the patch's triangles use: the parts' vertices among them go into the
        // index, where `emit_patch` finds them.
        let mut wanted: FxHashSet<Key> = FxHashSet::default();
        wanted.extend(patch.triangles.iter().flatten().map(|c| c.canonical()));
        if let Some(later) = later {
            let mut triangles = Vec::new();
            later(&mut |tri| {
                wanted.extend(tri.map(|c| c.canonical()));
                triangles.push(tri);
            });
            later_triangles = Some(triangles);
        }
        b = emit_split(h, b, &wanted);
    }
    for tri in &patch.triangles {
        b.emit_patch(*tri);
    }
    match (later_triangles, later) {
        (Some(triangles), _) => {
            for tri in triangles {
                b.emit_patch(tri);
            }
        }
        (None, Some(later)) => later(&mut |tri| b.emit_patch(tri)),
        (None, None) => {}
    }
    b.finish()
}

/// The descent of `extract_all_from` over threads, absorbed into `b` in emission order. Only
/// the vertices two subtrees can share, on the lattice lines of the finest subtree's level
/// (`on_lines`), and those the patch will ask for (`wanted`), go into the builder's index; the
/// others lie inside one subtree, whose part numbers them alone (at plane-100k an index of
/// every vertex was about 14 bytes an output triangle).
fn emit_split<'a>(h: &'a Hierarchy, mut b: Builder<'a>, wanted: &FxHashSet<Key>) -> Builder<'a> {
    let items = expand(h, root_triangles(h), PARALLEL_SUBTREES);
    let finest = items
        .iter()
        .flat_map(|item| match item {
            Item::Emit(tri) => *tri,
            Item::Descend(tri) => tri.map(|c| c.0),
        })
        .map(|c| c.k)
        .max()
        .unwrap_or(0);
    // The parts are made over the threads and absorbed in order as they come, while the
    // threads make the next ones (`each_in_order`). They look vertices up in the index as it
    // was before any part: a vertex that an earlier part added lies on the lattice lines,
    // where `absorb` finds it. Parts are made at most a sixteenth of the subtrees ahead of the
    // one absorbed, so that few are alive beside the growing builder (with all parts at once,
    // the last one alone was about 23 bytes a triangle beside the whole builder at
    // plane-100k).
    let window = items.len().div_ceil(PARALLEL_WINDOWS).max(1);
    let base = b.frozen();
    // Each part's share of the full leaves, if the subtrees share them evenly, with room for
    // an uneven split: reserved but untouched room costs no memory.
    let per_item = h.full_leaves.div_ceil(items.len().max(1));
    let leaves = per_item * 5 / 4;
    // One part a subtree, handed out to the threads as they come free: the subtrees differ
    // several times in size.
    let make = |item: &Item| {
        let mut part = Part {
            index: KeyIndex::with_capacity(leaves),
            vertices: Vec::with_capacity(leaves),
            triangles: Vec::with_capacity(2 * leaves),
        };
        match *item {
            Item::Emit(tri) => part.emit(&base, tri),
            Item::Descend(tri) => descend(h, vec![tri], &|_| true, &mut |t| part.emit(&base, t)),
        }
        // Only the vertices and triangles are merged.
        part.index = KeyIndex::default();
        part
    };
    crate::hex::parallel::each_in_order(h.threads(), &items, window, make, |part| {
        b.absorb(part, |key| on_lines(key, finest) || wanted.contains(&key))
    });
    b
}

/// Hierarchies with at least this many full leaves are extracted over threads.
const PARALLEL_EXTRACT_MIN: usize = 1 << 16;

/// `extract_all` expands the first levels until this many subtrees are pending.
const PARALLEL_SUBTREES: usize = 1024;

/// `extract_all` makes the parts of its subtrees at most one in this many of them ahead of
/// the part it absorbs (`emit_split`).
const PARALLEL_WINDOWS: usize = 16;

/// A lattice triangle of the recursion with whether each of its hexagons is subdivided
/// (outside counts as subdivided).
type StateTri = [(Key, bool); 3];

/// What the recursion does next, in emission order: emit a triangle, or descend into a
/// lattice triangle.
#[derive(Debug, Clone, Copy)]
enum Item {
    Emit([Key; 3]),
    Descend(StateTri),
}

/// The six lattice triangles around the root, as a stack (the first to emit on top),
/// counter-clockwise because the lattice directions are listed counter-clockwise.
fn root_triangles(h: &Hierarchy) -> Vec<StateTri> {
    let state = |c: Key| (c, h.is_subdivided_or_outside(c));
    (0..6)
        .rev()
        .map(|d| {
            [
                state(Key::ROOT),
                state(Key::ROOT.neighbor(d)),
                state(Key::ROOT.neighbor((d + 1) % 6)),
            ]
        })
        .collect()
}

/// One step of the recursion on `tri`: the triangles it emits and the sub-triangles to
/// descend into, in emission order (`descend` pushes the sub-triangles in reverse).
fn step(h: &Hierarchy, tri: StateTri, out: &mut Vec<Item>) {
    if !tri.iter().any(|c| c.0.inside()) {
        return;
    }
    let state = |c: Key| (c, h.is_subdivided_or_outside(c));
    let sub = tri.map(|c| c.1);
    let keys = tri.map(|c| c.0);
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
            out.push(Item::Descend([ca, mab, mca]));
            out.push(Item::Descend([mab, cb, mbc]));
            out.push(Item::Descend([mca, mbc, cc]));
            out.push(Item::Descend([mab, mbc, mca]));
        }
        2 => {
            // Rotate so that the unsubdivided hexagon comes last: (A, B sub, C not).
            let r = (0..3).find(|&r| !sub[(r + 2) % 3]).unwrap_or(0);
            let [a, b2, c] = [keys[r], keys[(r + 1) % 3], keys[(r + 2) % 3]];
            let m = midpoint(a, b2);
            out.push(Item::Emit([m, b2, c]));
            out.push(Item::Emit([a, m, c]));
        }
        _ => out.push(Item::Emit(keys)),
    }
}

/// The depth-first recursion from `stack` (the next triangle on top), giving each dual
/// triangle to `emit` in order and descending only where `keep` holds.
fn descend(
    h: &Hierarchy,
    mut stack: Vec<StateTri>,
    keep: &impl Fn(&[Key; 3]) -> bool,
    emit: &mut impl FnMut([Key; 3]),
) {
    let mut next = Vec::with_capacity(4);
    while let Some(tri) = stack.pop() {
        if !keep(&tri.map(|c| c.0)) {
            continue;
        }
        next.clear();
        step(h, tri, &mut next);
        // A step emits triangles or descends, never both: emitted now, in order, or pushed
        // in reverse so that the first sub-triangle is popped next.
        for &item in &next {
            if let Item::Emit(t) = item {
                emit(t);
            }
        }
        for &item in next.iter().rev() {
            if let Item::Descend(t) = item {
                stack.push(t);
            }
        }
    }
}

/// The recursion from the roots `stack`, one level at a time in emission order, until at
/// least `want` subtrees are pending or nothing is left to expand: a list whose items,
/// each done in turn (a subtree by `descend`), emit what the serial recursion emits.
fn expand(h: &Hierarchy, mut stack: Vec<StateTri>, want: usize) -> Vec<Item> {
    stack.reverse();
    let mut items: Vec<Item> = stack.into_iter().map(Item::Descend).collect();
    loop {
        let pending = items
            .iter()
            .filter(|i| matches!(i, Item::Descend(_)))
            .count();
        if pending == 0 || pending >= want {
            return items;
        }
        let mut next = Vec::with_capacity(4 * items.len());
        for item in items {
            match item {
                Item::Emit(_) => next.push(item),
                Item::Descend(t) => step(h, t, &mut next),
            }
        }
        items = next;
    }
}

/// Whether the cell `key` lies on a line of the lattice of level `k`, that is on an edge of
/// a lattice triangle of that level (every cell of level `k` or coarser does): the lines run
/// along the directions (1, 0), (0, 1) and (-1, 1), where j, i or i + j is a multiple of
/// 2^(key.k - k).
fn on_lines(key: Key, k: u8) -> bool {
    if key.k <= k {
        return true;
    }
    let m = (1i64 << (key.k - k)) - 1;
    key.i & m == 0 || key.j & m == 0 || (key.i + key.j) & m == 0
}

/// The cell at the midpoint of two adjacent cells of the same level.
fn midpoint(a: Key, b: Key) -> Key {
    Key::new(a.k + 1, a.i + b.i, a.j + b.j)
}

/// The index entry of a dropped centre that has no vertex yet (`KeyIndex` keeps `u32::MAX`
/// for empty slots).
const DROPPED: u32 = u32::MAX - 1;

struct Builder<'a> {
    h: &'a Hierarchy,
    /// Places asked before `moved` (`extract_region_patched`).
    placed: Option<&'a FxHashMap<Key, Point>>,
    moved: &'a FxHashMap<Key, Point>,
    /// Places asked after `moved` (`extract_relocated`).
    relocate: Option<Relocate<'a>>,
    /// Centres whose triangles the patch replaces.
    dropped: &'a FxHashSet<Key>,
    /// Every dropped centre is marked `DROPPED` in `index` (none is a vertex yet).
    marked: bool,
    /// Canonical key of each vertex.
    keys: Vec<Key>,
    /// Dual vertex of each canonical centre.
    index: KeyIndex,
    vertices: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    used: Vec<bool>,
    /// For a part of the relocated dual: the input point of each vertex (`u32::MAX`: none).
    /// The index then holds the input points only once met, instead of all of them from the
    /// start (a pass over every point for a few triangles), and `finish` numbers them first.
    points_met: Option<Vec<u32>>,
}

impl<'a> Builder<'a> {
    fn new(
        h: &'a Hierarchy,
        placement: Placement,
        moved: &'a FxHashMap<Key, Point>,
        dropped: &'a FxHashSet<Key>,
        whole: bool,
    ) -> Builder<'a> {
        // About one vertex per full leaf and two triangles per vertex: reserving avoids
        // rehashing a table of millions of entries. A part of the dual (`whole` false) is
        // small: its tables grow as needed.
        let expected = if whole { h.full_leaves } else { 0 } + h.points.len();
        // The dual split over threads indexes few of its vertices (`emit_split`).
        let split = whole && h.full_leaves >= PARALLEL_EXTRACT_MIN;
        let mut index = KeyIndex::with_capacity(if split { h.points.len() } else { expected });
        // The vectors get a quarter more: the dual has more vertices than full leaves (at
        // plane-100k its triangles outgrew twice `expected`), and reserved room that is never
        // written costs no memory.
        let room = if whole { expected + expected / 4 } else { 0 };
        let mut vertices = Vec::with_capacity(room);
        let lazy = placement == Placement::Relocated && !whole;
        if placement == Placement::Relocated && whole {
            vertices = h.points.clone();
            // In any order: the index is the same.
            for key in h.occupied_unordered() {
                if let [p] = h.occupants(key) {
                    if h.is_full_leaf(key) {
                        index.insert(key.canonical(), *p);
                    }
                }
            }
        }
        // The points' copy replaced the reserved vector; every vector that grows by a vertex
        // keeps the reservation, so that it is never copied into a doubled allocation (whose
        // fresh pages the kernel must also clear).
        vertices.reserve(room.saturating_sub(vertices.len()));
        let mut used = Vec::with_capacity(room);
        used.resize(vertices.len(), false);
        let mut keys = Vec::with_capacity(room);
        keys.resize(vertices.len(), Key::ROOT);
        for (key, v) in index.iter() {
            keys[v as usize] = key;
        }
        // Dropped centres are marked in the index: the lookup that finds a vertex also tells
        // a triangle of a dropped star (`emit`); the patch gives them vertices (`vertex`).
        let mut marked = true;
        for &key in dropped {
            if lazy && point_at(h, key).is_some() {
                marked = false;
            } else if index.get_or_insert(key, DROPPED) != DROPPED {
                // A dropped centre that already is a vertex (an input point): test the set.
                marked = false;
            }
        }
        Builder {
            h,
            placed: None,
            moved,
            relocate: None,
            dropped,
            marked,
            keys,
            index,
            vertices,
            triangles: Vec::with_capacity(2 * room),
            used,
            points_met: lazy.then(Vec::new),
        }
    }

    /// A builder that only looks up and places (`Part::emit`): the same sources of places and
    /// dropped centres, and a copy of the index as it is now (at the start of `emit_split`,
    /// the input points and the dropped centres), with nothing emitted.
    fn frozen(&self) -> Builder<'a> {
        Builder {
            h: self.h,
            placed: self.placed,
            moved: self.moved,
            relocate: self.relocate,
            dropped: self.dropped,
            marked: self.marked,
            keys: Vec::new(),
            index: self.index.clone(),
            vertices: Vec::new(),
            triangles: Vec::new(),
            used: Vec::new(),
            points_met: None,
        }
    }

    /// True when the triangle with canonical keys `keys` (found in the index as `found`)
    /// lies around a dropped centre, so that the patch replaces it.
    fn is_dropped(&self, keys: &[Key; 3], found: &[Option<u32>; 3]) -> bool {
        if self.dropped.is_empty() {
            return false;
        }
        if self.marked {
            found.contains(&Some(DROPPED))
        } else {
            keys.iter().any(|k| self.dropped.contains(k))
        }
    }

    /// Where the centre with canonical key `key` goes.
    fn place(&self, key: Key) -> Point {
        if let Some(&p) = self.placed.and_then(|m| m.get(&key)) {
            return p;
        }
        if let Some(&p) = self.moved.get(&key) {
            return p;
        }
        match self.relocate.and_then(|f| f(key)) {
            Some(p) => p,
            None => self.h.lattice.center(key),
        }
    }

    /// The canonical keys of the lattice triangle `tri` and the vertices the index holds for
    /// them, or `None` when it is not a triangle of the dual: a cell lies outside the
    /// bounding hexagon, or the patch replaces it.
    fn lookup(&self, tri: [Key; 3]) -> Option<([Key; 3], [Option<u32>; 3])> {
        if !tri.iter().all(|c| c.inside()) {
            return None;
        }
        let keys = tri.map(|c| c.canonical());
        let found = keys.map(|k| self.index.get(&k));
        (!self.is_dropped(&keys, &found)).then_some((keys, found))
    }

    fn emit(&mut self, tri: [Key; 3]) {
        let Some((keys, found)) = self.lookup(tri) else {
            return;
        };
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
            Some(v) if v != DROPPED => {
                self.used[v as usize] = true;
                v
            }
            _ => self.new_vertex(key),
        }
    }

    /// A new vertex for the canonical key `key` (not in the index, or a dropped centre).
    fn new_vertex(&mut self, key: Key) -> u32 {
        if let Some(met) = &mut self.points_met {
            if let Some(i) = point_at(self.h, key) {
                met.push(i);
                return self.push_vertex(key, self.h.points[i as usize]);
            }
            met.push(u32::MAX);
        }
        let p = self.place(key);
        self.push_vertex(key, p)
    }

    /// A new vertex for `key` at `p`.
    fn push_vertex(&mut self, key: Key, p: Point) -> u32 {
        let v = self.push_unindexed(key, p);
        self.index.insert(key, v);
        v
    }

    /// `push_vertex` of a vertex no later lookup asks for (`absorb`).
    fn push_unindexed(&mut self, key: Key, p: Point) -> u32 {
        let v = self.vertices.len() as u32;
        self.vertices.push(p);
        self.keys.push(key);
        self.used.push(true);
        v
    }

    /// Appends the triangles of `part` (the next part of the recursion in emission order),
    /// numbering its vertices that are new here in the order the part met them. Only the
    /// vertices for which `indexed` holds are looked up in the index and added to it: the
    /// others no other part meets (`emit_split`).
    fn absorb(&mut self, part: Part, indexed: impl Fn(Key) -> bool) {
        let map: Vec<u32> = part
            .vertices
            .iter()
            .map(|&(key, p)| {
                if !indexed(key) {
                    debug_assert!(self.index.get(&key).is_none(), "{key:?} met twice");
                    return self.push_unindexed(key, p);
                }
                match self.index.get(&key) {
                    Some(v) => {
                        debug_assert_ne!(v, DROPPED, "a part used the dropped centre {key:?}");
                        self.used[v as usize] = true;
                        v
                    }
                    None => self.push_vertex(key, p),
                }
            })
            .collect();
        self.triangles.reserve(part.triangles.len());
        for t in part.triangles {
            let t = t.map(|v| {
                if v & LOCAL != 0 {
                    map[(v & !LOCAL) as usize]
                } else {
                    self.used[v as usize] = true;
                    v
                }
            });
            self.triangles.push(t);
        }
    }

    /// Drops vertices no triangle uses (points of an unfinished refinement, all of them in
    /// `Plain` placement) and renumbers.
    fn finish(self) -> (TriMesh, Vec<Key>) {
        if let Some(met) = &self.points_met {
            // Every vertex is used; the input points go first, in their order, as in a
            // builder that started with all of them.
            let mut order: Vec<u32> = (0..self.vertices.len() as u32).collect();
            order.sort_by_key(|&v| (met[v as usize] == u32::MAX, met[v as usize]));
            let mut map = vec![0u32; order.len()];
            for (new, &old) in order.iter().enumerate() {
                map[old as usize] = new as u32;
            }
            let mesh = TriMesh {
                vertices: order.iter().map(|&v| self.vertices[v as usize]).collect(),
                triangles: self
                    .triangles
                    .iter()
                    .map(|t| t.map(|v| map[v as usize]))
                    .collect(),
            };
            let keys = order.iter().map(|&v| self.keys[v as usize]).collect();
            return (mesh, keys);
        }
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

/// The input point whose hexagon is the full leaf with canonical centre `key`, if it holds
/// exactly one: that vertex of the relocated dual is the point itself.
fn point_at(h: &Hierarchy, key: Key) -> Option<u32> {
    let leaf = h.leaf_of_vertex(key);
    match h.occupants(leaf) {
        [p] if h.is_full_leaf(leaf) => Some(*p),
        _ => None,
    }
}

/// Marks a vertex number of a `Part` as its own (the rest are vertices of the builder's
/// index, met before any part: the input points).
const LOCAL: u32 = 1 << 31;

/// The triangles one thread of `extract_all` emits for its subtrees, with the vertices it met
/// that the builder's index did not hold, in the order it met them, with their places.
#[derive(Default)]
struct Part {
    index: KeyIndex,
    vertices: Vec<(Key, Point)>,
    triangles: Vec<[u32; 3]>,
}

impl Part {
    /// `Builder::emit` against the builder's index as it was before any part (`frozen`).
    fn emit(&mut self, base: &Builder, tri: [Key; 3]) {
        let Some((keys, found)) = base.lookup(tri) else {
            return;
        };
        let t = [0, 1, 2].map(|m| match found[m] {
            Some(v) => v,
            None => match self.index.get(&keys[m]) {
                Some(v) => v,
                None => {
                    let v = LOCAL | self.vertices.len() as u32;
                    self.vertices.push((keys[m], base.place(keys[m])));
                    self.index.insert(keys[m], v);
                    v
                }
            },
        });
        self.triangles.push(t);
    }
}

/// The first triangle that is not strictly counter-clockwise under exact orientation, if any.
pub fn first_inverted(mesh: &TriMesh) -> Option<usize> {
    first_inverted_over(mesh, 1)
}

/// `first_inverted` with the triangles looked at over `threads` threads in ranges, the first
/// range's find first: the same answer for every count.
pub fn first_inverted_over(mesh: &TriMesh, threads: usize) -> Option<usize> {
    let n = mesh.triangles.len();
    crate::hex::parallel::ranges_in_parallel(
        threads,
        n,
        crate::hex::parallel::PARALLEL_MIN,
        |range| {
            range.into_iter().find(|&t| {
                let [a, b, c] = mesh.corners(t);
                orient2d(a, b, c) <= 0.0
            })
        },
    )
    .into_iter()
    .flatten()
    .next()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hex::classify::rings;
    use crate::hex::extended::{
        chain_relocations, chain_triangles, mesh_extended, relocated, relocations,
    };
    use crate::hex::key::DIRS;
    use crate::{Params, Pslg};

    #[test]
    fn the_first_inverted_triangle_is_the_same_for_every_thread_count() {
        // 20,000 copies of one counter-clockwise triangle (ranges split from 8,192 on).
        let mut mesh = TriMesh {
            vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            triangles: vec![[0, 1, 2]; 20_000],
        };
        for threads in [1, 2, 3] {
            assert_eq!(first_inverted_over(&mesh, threads), None);
        }
        // Inverted in the last range, then also in the first: the first in order wins.
        for (t, first) in [(19_000, 19_000), (3_000, 3_000)] {
            mesh.triangles[t] = [0, 2, 1];
            for threads in [1, 2, 3] {
                assert_eq!(
                    first_inverted_over(&mesh, threads),
                    Some(first),
                    "{threads}"
                );
            }
        }
    }

    #[test]
    fn a_cell_is_on_the_lines_of_a_level_exactly_when_it_lies_on_an_edge_of_its_triangles() {
        // Level 1 against level 4 (t = 8), every cell of a window, against the edges of the
        // level-1 triangles around it walked one by one.
        let (k, fine, t) = (1u8, 4u8, 8i64);
        let on_an_edge = |i: i64, j: i64| {
            (-4..4i64).any(|a| {
                (-4..4i64).any(|b| {
                    let (pi, pj) = (t * a, t * b);
                    DIRS[..3].iter().any(|&(di, dj)| {
                        // (i, j) = P + λ·t·d with 0 ≤ λ ≤ 1.
                        (0..=t).any(|l| (pi + l * di, pj + l * dj) == (i, j))
                    })
                })
            })
        };
        let mut on = 0;
        for i in -12..12 {
            for j in -12..12 {
                let key = Key::new(fine, i, j);
                assert_eq!(on_lines(key, k), on_an_edge(i, j), "{key:?}");
                on += on_lines(key, k) as usize;
            }
        }
        assert!(on > 0 && on < 24 * 24);
        assert!(on_lines(Key::new(1, 1, 0), 1) && on_lines(Key::ROOT, 2));
    }

    #[test]
    fn the_dual_split_over_threads_is_the_serial_dual_byte_for_byte() {
        // Clustered points (MOVED_CENTER_3 patches, dropped centres, moved ring cells) and
        // a point near the root's edge.
        let mut x: u64 = 0x853c_49e6_748f_ea9b;
        let mut pts = Vec::new();
        for n in 0..120 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let (u, v) = (
                (x >> 11) as f64 / (1u64 << 53) as f64,
                (x % 1000) as f64 / 1000.0,
            );
            let s = if n % 3 == 0 { 0.05 } else { 1.0 };
            pts.push([u * s, v * s]);
        }
        pts.push([0.999, 0.5]);
        let run = mesh_extended(&Pslg::from_points(pts), &Params::default()).expect("meshes");
        let h = &run.hierarchy;
        let (moved, patch) = relocations(h, &rings(h));
        assert!(
            !patch.triangles.is_empty(),
            "the input makes MOVED_CENTER_3 patches"
        );
        for placement in [Placement::Relocated, Placement::Plain] {
            let serial = extract_where(h, placement, &moved, &patch, true, |_| true);
            let split = extract_all_from(h, (placement, None), &moved, (&patch, None), 0);
            assert!(!serial.0.triangles.is_empty());
            assert_eq!(serial.0.triangles, split.0.triangles, "{placement:?}");
            assert_eq!(serial.1, split.1, "{placement:?}");
            let bits = |m: &TriMesh| -> Vec<[u64; 2]> {
                m.vertices
                    .iter()
                    .map(|p| [p[0].to_bits(), p[1].to_bits()])
                    .collect()
            };
            assert_eq!(bits(&serial.0), bits(&split.0), "{placement:?}");
        }
        // The relocated centres computed as the dual meets them, with only the chains' in a
        // table, give the same dual as the table of every relocated centre, serial or split.
        let r = rings(h);
        let (chained, chain_patch, chains) = chain_relocations(h, &r);
        assert!(
            chained.len() < moved.len(),
            "the table holds the chains only"
        );
        assert!(chain_patch.triangles.is_empty());
        assert_eq!(chain_patch.dropped, patch.dropped);
        let mut streamed = Vec::new();
        chain_triangles(h, &r, &chains, &mut |t| streamed.push(t));
        assert_eq!(streamed, patch.triangles);
        let relocate = |k: Key| relocated(h, &r, k);
        let later = |emit: &mut dyn FnMut([Key; 3])| chain_triangles(h, &r, &chains, emit);
        let table = extract_where(h, Placement::Relocated, &moved, &patch, true, |_| true);
        for min in [0, usize::MAX] {
            let lazy = extract_all_from(
                h,
                (Placement::Relocated, Some(&relocate)),
                &chained,
                (&chain_patch, Some(&later)),
                min,
            );
            assert_eq!(table.0.triangles, lazy.0.triangles, "split from {min}");
            assert_eq!(table.1, lazy.1, "split from {min}");
            let bits = |m: &TriMesh| -> Vec<u64> {
                m.vertices
                    .iter()
                    .flat_map(|p| [p[0].to_bits(), p[1].to_bits()])
                    .collect()
            };
            assert_eq!(bits(&table.0), bits(&lazy.0), "split from {min}");
        }
    }
}
