//! The centre relocations of paper 000 (Sußner & Greiner 2009) Sec. 5.4: MOVED_CENTER_1/2
//! centres moved towards the full hexagons beyond their fins, moved ring cells shifted, and
//! the dual rebuilt around MOVED_CENTER_3 hexagons (`mc3`).

use crate::geom::Point;
use crate::hex::classify::{classify, fin_class, fin_mask, Class, Rings, Role};
use crate::hex::lattice::{FxHashMap, Key};
use crate::hex::mc3::{self, Chain, Patch};
use crate::hex::parallel::{each_in_parallel, in_parallel};
use crate::hex::subdivision::Hierarchy;

/// The relocated centres of Sec. 5.4, keyed by `Key::canonical`, and the dual rebuilt around
/// MOVED_CENTER_3 hexagons (`mc3`). Occupied centres are replaced by their points in the dual
/// builder.
pub fn relocations(h: &Hierarchy, r: &Rings) -> (FxHashMap<Key, Point>, Patch) {
    // The relocations of the leaves do not depend on their order (the chains are sorted).
    relocations_of(h, r, h.full_leaves_unordered())
}

/// The relocated centres and the MOVED_CENTER_3 patch of `relocations`, for the full leaves
/// `leaves` only (chains are built for the MOVED_CENTER_3 hexagons among them).
pub fn relocations_of(
    h: &Hierarchy,
    r: &Rings,
    leaves: impl IntoIterator<Item = Key>,
) -> (FxHashMap<Key, Point>, Patch) {
    let leaves: Vec<Key> = leaves.into_iter().collect();
    // Each leaf's relocation depends only on the hierarchy and the rings: computed over
    // threads for long lists, then collected in the order of `leaves`.
    let parts = in_parallel(h.threads(), &leaves, |chunk| {
        let mut out: Vec<(Key, Option<Point>)> = Vec::new();
        for &key in chunk {
            match relocation(h, r, key) {
                Relocation::Stays => {}
                Relocation::At(p) => out.push((key, Some(p))),
                Relocation::Chain => out.push((key, None)),
            }
        }
        out
    });
    drop(leaves);
    // Sized for what was found (the chains add a few centres each).
    let found = parts.iter().flatten().filter(|(_, p)| p.is_some()).count();
    let chained = parts.iter().flatten().count() - found;
    let mut moved = FxHashMap::with_capacity_and_hasher(found + 8 * chained, Default::default());
    let mut mc3_keys = Vec::new();
    for (key, p) in parts.into_iter().flatten() {
        match p {
            Some(p) => {
                moved.insert(key.canonical(), p);
            }
            None => mc3_keys.push(key),
        }
    }
    let mut patch = Patch::default();
    for chain in mc3::chains(h, r, &mc3_keys) {
        mc3::build(h, r, chain, &mut moved, &mut patch);
    }
    (moved, patch)
}

/// `relocations` of the whole subdivision without its table of every moved centre, and
/// without the patch's triangles: only the centres the MOVED_CENTER_3 chains place
/// (`mc3::build`) are in the table, every other relocated centre is `relocated`, computed
/// where the dual asks for it, and the chains are returned for `chain_triangles` to give
/// their triangles when the dual emits them. The dual looks the table up first, as the
/// chains' places replace the others in `relocations`, so it gets the same places, and the
/// triangles come chain by chain in the order of `relocations`' patch. At plane-100k the
/// whole table and the patch's triangles were about 15 and 6 bytes an output triangle at the
/// peak.
pub fn chain_relocations(h: &Hierarchy, r: &Rings) -> (FxHashMap<Key, Point>, Patch, Vec<Chain>) {
    // Only a hexagon with fins can be MOVED_CENTER_3 (`classify` reads its fins first).
    let mc3_keys: Vec<Key> = h.full_leaves_where(|key| {
        let mask = fin_mask(h, key);
        mask != 0 && fin_class(mask).0 == Class::MovedCenter3
    });
    let mut moved = FxHashMap::default();
    let mut patch = Patch::default();
    let chains = mc3::chains(h, r, &mc3_keys);
    for &chain in &chains {
        mc3::build(h, r, chain, &mut moved, &mut patch);
        // Given again, chain by chain, by `chain_triangles`.
        patch.triangles.clear();
    }
    (moved, patch, chains)
}

/// The triangles `mc3::build` makes for each of `chains` in turn, given to `emit` in order
/// (`chain_relocations`): `mc3::build` only adds to the table and the patch it is given, so a
/// chain's triangles do not depend on the chains before it.
///
/// Runs of chains are built over the hierarchy's threads (each run with a table of its own),
/// a few runs a thread at a time, and their triangles given in order.
pub fn chain_triangles(h: &Hierarchy, r: &Rings, chains: &[Chain], emit: &mut dyn FnMut([Key; 3])) {
    const RUN: usize = 2048;
    let runs: Vec<&[Chain]> = chains.chunks(RUN).collect();
    for batch in runs.chunks(4 * h.threads()) {
        let parts = each_in_parallel(h.threads(), batch, |run| {
            let mut scratch = FxHashMap::default();
            let mut patch = Patch::default();
            for &chain in *run {
                mc3::build(h, r, chain, &mut scratch, &mut patch);
            }
            patch.triangles
        });
        for t in parts.into_iter().flatten() {
            emit(t);
        }
    }
}

/// Where Sec. 5.4 puts the dual vertex with canonical key `key`, when it is the centre of a
/// full leaf that moves and is not in a MOVED_CENTER_3 chain: the entry `relocations` has
/// for it, computed alone (`chain_relocations`).
pub fn relocated(h: &Hierarchy, r: &Rings, key: Key) -> Option<Point> {
    let leaf = h.leaf_of_vertex(key);
    if !leaf.inside() || !h.is_full_leaf(leaf) {
        return None;
    }
    match relocation(h, r, leaf) {
        Relocation::At(p) => Some(p),
        Relocation::Stays | Relocation::Chain => None,
    }
}

/// What Sec. 5.4 does with the centre of one full leaf.
enum Relocation {
    /// It stays at the lattice centre (or, occupied, is replaced by its point in the dual).
    Stays,
    /// It moves here.
    At(Point),
    /// A MOVED_CENTER_3 hexagon: placed with its chain (`mc3`).
    Chain,
}

/// The relocation of the full leaf `key`.
fn relocation(h: &Hierarchy, r: &Rings, key: Key) -> Relocation {
    let lerp = |a: Point, b: Point, t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    let c = h.lattice.center(key);
    let (class, strip) = classify(h, r, key);
    match (class, strip) {
        (Class::MovedCenterInRing, _) => match r.roles.get(&key) {
            Some(Role::Moved { shift, .. }) => Relocation::At([c[0] + shift[0], c[1] + shift[1]]),
            _ => Relocation::Stays,
        },
        // Ĉ = 5/6·C + 1/6·C_f0, towards the full hexagon beyond the fin.
        (Class::MovedCenter1, Some(s)) => {
            Relocation::At(lerp(c, h.lattice.center(key.neighbor(s.first)), 1.0 / 6.0))
        }
        // Ĉ = 3/5·C + 2/5·C_f01, towards the full hexagon between the two fins.
        (Class::MovedCenter2, Some(s)) => {
            let a = key.neighbor(s.first);
            let b = key.neighbor((s.first + 1) % 6);
            let m = Key::new(key.k + 1, a.i + b.i, a.j + b.j);
            Relocation::At(lerp(c, h.lattice.center(m), 2.0 / 5.0))
        }
        // MOVED_CENTER_3 hexagons go to the chains (`mc3`).
        (Class::MovedCenter3, _) => Relocation::Chain,
        _ => Relocation::Stays,
    }
}
