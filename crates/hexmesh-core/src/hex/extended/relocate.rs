//! The centre relocations of paper 000 (Sußner & Greiner 2009) Sec. 5.4: MOVED_CENTER_1/2
//! centres moved towards the full hexagons beyond their fins, moved ring cells shifted, and
//! the dual rebuilt around MOVED_CENTER_3 hexagons (`mc3`).

use crate::geom::Point;
use crate::hex::classify::{classify, Class, Rings, Role};
use crate::hex::lattice::{FxHashMap, Key};
use crate::hex::mc3::{self, Patch};
use crate::hex::parallel::in_parallel;
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
    let lerp = |a: Point, b: Point, t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    // Each leaf's relocation depends only on the hierarchy and the rings: computed over
    // threads for long lists, then collected in the order of `leaves`.
    let parts = in_parallel(&leaves, |chunk| {
        let mut out: Vec<(Key, Option<Point>)> = Vec::new();
        for &key in chunk {
            let c = h.lattice.center(key);
            let (class, strip) = classify(h, r, key);
            let p = match (class, strip) {
                (Class::MovedCenterInRing, _) => match r.roles.get(&key) {
                    Some(Role::Moved { shift, .. }) => [c[0] + shift[0], c[1] + shift[1]],
                    _ => continue,
                },
                // Ĉ = 5/6·C + 1/6·C_f0, towards the full hexagon beyond the fin.
                (Class::MovedCenter1, Some(s)) => {
                    lerp(c, h.lattice.center(key.neighbor(s.first)), 1.0 / 6.0)
                }
                // Ĉ = 3/5·C + 2/5·C_f01, towards the full hexagon between the two fins.
                (Class::MovedCenter2, Some(s)) => {
                    let a = key.neighbor(s.first);
                    let b = key.neighbor((s.first + 1) % 6);
                    let m = Key::new(key.k + 1, a.i + b.i, a.j + b.j);
                    lerp(c, h.lattice.center(m), 2.0 / 5.0)
                }
                // MOVED_CENTER_3 hexagons go to the chains (`mc3`).
                (Class::MovedCenter3, _) => {
                    out.push((key, None));
                    continue;
                }
                _ => continue,
            };
            out.push((key, Some(p)));
        }
        out
    });
    drop(leaves);
    // Sized for what was found (the chains add a few centres each): a table sized for half
    // the leaves was mostly empty, but the kernel still cleared most of its pages.
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
