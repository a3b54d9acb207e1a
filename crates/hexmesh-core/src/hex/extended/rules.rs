//! The extended rules of paper 000 (Sußner & Greiner 2009) Sec. 5.2 on the classified
//! hexagons: which hexagons to subdivide or make full (`extended_actions`), with the
//! departures listed in the module docs of `extended` (boundary fins, spread MOVED_CENTER
//! triangles), and the cells whose rules a batch of subdivisions can change (`around`).

use super::check::breaks_bounds;
use crate::geom::Point;
use crate::hex::classify::{
    classify, fin_class, subdivided_and_neighbours, Class, FinStrip, Rings,
};
use crate::hex::lattice::{FxHashSet, Key, KeySet};
use crate::hex::mc3;
use crate::hex::parallel::{in_parallel_from, PARALLEL_MIN};
use crate::hex::subdivision::Hierarchy;
use crate::quality::HEX;

/// The hexagons the extended rules of Sec. 5.2 (with the departures of the module docs) want
/// subdivided or made full, sorted.
pub(crate) fn extended_actions(h: &Hierarchy, r: &Rings, candidates: &KeySet) -> Vec<(Key, Why)> {
    let mut acts: Vec<(Key, Why)> = r.conflicts.iter().map(|&k| (k, Why::Other)).collect();
    // Only an unsubdivided cell with a subdivided neighbour (a full leaf with fins) has a rule
    // here, and most candidates have none: a whole block of candidates is sifted with its
    // subdivided cells and theirs beside it at once (`Hierarchy::subdivided_block`), and only
    // what is left is examined cell by cell. What is left is split evenly over the machine's
    // threads (read-only): the blocks themselves are not, since the finer levels' blocks keep
    // several times as many cells (at plane-100k the second of two halves of the blocks held
    // five times the cells of the first). The result is sorted, the same for any split.
    let mut keys = Vec::new();
    for (b, word) in candidates.blocks() {
        let (subdivided, beside) = h.subdivided_block(b);
        let mut left = word & !subdivided & beside;
        while left != 0 {
            let n = left.trailing_zeros() as i64;
            left &= left - 1;
            keys.push(KeySet::cell_in_block(b, n));
        }
    }
    let parts = in_parallel_from(h.threads(), &keys, PARALLEL_MIN / 4, |chunk| {
        actions_of(h, r, chunk)
    });
    for part in parts {
        acts.extend(part);
    }
    acts.sort_unstable_by_key(|a| (a.0.packed(), a.1));
    acts.dedup_by_key(|a| a.0);
    acts
}

/// The actions of `extended_actions` for some of the candidates, unsorted.
pub(super) fn actions_of(h: &Hierarchy, r: &Rings, candidates: &[Key]) -> Vec<(Key, Why)> {
    let mut acts = Vec::new();
    for &key in candidates {
        // Only full leaves with fins have rules here: the fins (the cell and its neighbours
        // from one block lookup, mostly) rule most candidates out before the parents are
        // looked at.
        if !key.inside() {
            continue;
        }
        let (subdivided, mask) = subdivided_and_neighbours(h, key);
        if subdivided || mask == 0 || !h.is_full_leaf(key) {
            continue;
        }
        let (class, strip) = fin_class(mask);
        // SUBDIVIDE, and MOVED_CENTER_3 (departure, module docs).
        if class == Class::Subdivide {
            acts.push((key, Why::Other));
            continue;
        }
        // A moved centre in the 1-ring of OCCUPIED_1 or the 1- or 2-ring of OCCUPIED_2; and
        // (departure) a hexagon with fins centred on the boundary of the bounding hexagon,
        // whose centre cannot move inwards without spoiling the boundary triangles.
        if (r.marked.contains(&key) && r.roles.contains_key(&key)) || key.on_boundary() {
            acts.push((key, Why::Other));
            continue;
        }
        // Every full hexagon adjacent to a fin must have a fixed centre.
        let Some(strip) = strip else { continue };
        let fixed_beyond = (0..strip.len).all(|t| {
            let d = (strip.first + t) % 6;
            let n = key.neighbor(d);
            [
                n.central_child(),
                n.edge_child((d + 2) % 6),
                n.edge_child((d + 4) % 6),
            ]
            .into_iter()
            .filter(|&c| h.is_full_leaf(c))
            .all(|c| {
                // `mc3::is_mc4` without classifying twice: MOVED_CENTER_4 is a regular
                // full leaf below which a MOVED_CENTER_3 hexagon lies.
                let class = classify(h, r, c).0;
                class.is_fixed()
                    && !(class == Class::FixedCenterRegular && mc3::mc3_below(h, r, c) != 0)
            })
        });
        if !fixed_beyond {
            acts.push((key, Why::Other));
            continue;
        }
        // Departure (found by the self-check, which subdivided such hexagons on every
        // random set): three mutually adjacent MOVED_CENTER_1/2 hexagons whose fins point
        // different ways (a strip of one level between finer regions on both sides, or a
        // corner of a transition) move apart, and their triangle drops to 35°-40°. Sec. 5.4
        // derives each relocation with fixed hexagons beside the moved one. The triangle is
        // measured here, with the relocations of Sec. 5.4, and its smallest key subdivided,
        // as the self-check would, before any dual is built.
        if let Some(k) = spread_moved_triangle(h, key, class, strip) {
            acts.push((k, Why::Other));
            continue;
        }
        // The rules on MOVED_CENTER_3 hexagons and their top neighbour (Sec. 5.2, `mc3`).
        if class == Class::MovedCenter3 {
            acts.extend(
                mc3::actions_for(h, r, key)
                    .into_iter()
                    .map(|k| (k, Why::Mc3)),
            );
        }
    }
    acts
}

/// Which rule asked for a subdivision (for `ExtendedStats`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Why {
    /// A MOVED_CENTER_3 rule.
    Mc3,
    Other,
}

/// The cells whose extended rules can change when the hexagons `subdivided` are split: the
/// next level around each (its children and the rings of a point moved into them), its own
/// level (neighbours that got fins, rings that lost their point), and the level above (hexagons
/// whose fins border those neighbours). As a block set: at plane-1m a round's candidates are
/// tens of millions of cells, a few bytes each here against 24 in a list of keys.
pub(crate) fn around(subdivided: &[Key]) -> KeySet {
    // A disc of radius R around a cell lies inside the union of the discs of radius R around
    // its six neighbours (a step from the cell towards any point of the disc brings it within
    // R of that neighbour), and the same holds for the discs around central children (radius
    // 4 around 2c is covered by the discs around the 2n). So a source whose six neighbours
    // are sources of the same kind adds nothing and is skipped; the rest are unioned with a
    // block bitset (`KeySet::insert_disc`), a few table lookups per disc.
    let own: FxHashSet<Key> = subdivided.iter().copied().collect();
    let parents: FxHashSet<Key> = subdivided
        .iter()
        .filter(|s| s.k > 0)
        .map(|s| Key::new(s.k - 1, s.i.div_euclid(2), s.j.div_euclid(2)))
        .collect();
    let interior = |set: &FxHashSet<Key>, c: Key| (0..6).all(|d| set.contains(&c.neighbor(d)));
    let mut cells = KeySet::with_capacity(4 * subdivided.len() + 64);
    for &s in subdivided {
        if !interior(&own, s) {
            cells.insert_disc(s.central_child(), 4);
            cells.insert_disc(s, 3);
        }
    }
    for &p in &parents {
        if !interior(&parents, p) {
            cells.insert_disc(p, 3);
        }
    }
    cells
}

/// The centre of a MOVED_CENTER_1 or MOVED_CENTER_2 full leaf relocated as in Sec. 5.4:
/// Ĉ = 5/6·C + 1/6·C_f0 towards the full hexagon beyond the fin, or Ĉ = 3/5·C + 2/5·C_f01
/// towards the full hexagon between the two fins.
pub(super) fn moved_centre(
    h: &Hierarchy,
    key: Key,
    class: Class,
    strip: FinStrip,
) -> Option<Point> {
    let c = h.lattice.center(key);
    let lerp = |a: Point, b: Point, t: f64| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
    match class {
        Class::MovedCenter1 => Some(lerp(
            c,
            h.lattice.center(key.neighbor(strip.first)),
            1.0 / 6.0,
        )),
        Class::MovedCenter2 => {
            let a = key.neighbor(strip.first);
            let b = key.neighbor((strip.first + 1) % 6);
            let m = Key::new(key.k + 1, a.i + b.i, a.j + b.j);
            Some(lerp(c, h.lattice.center(m), 2.0 / 5.0))
        }
        _ => None,
    }
}

/// The MOVED_CENTER_1/2 full leaf with fins of `key`'s level adjacent to it, with its class
/// and strip.
pub(super) fn moved_neighbour(h: &Hierarchy, n: Key) -> Option<(Class, FinStrip)> {
    if !n.inside() {
        return None;
    }
    let (subdivided, mask) = subdivided_and_neighbours(h, n);
    if subdivided || mask == 0 || !h.is_full_leaf(n) {
        return None;
    }
    match fin_class(mask) {
        (c @ (Class::MovedCenter1 | Class::MovedCenter2), Some(s)) => Some((c, s)),
        _ => None,
    }
}

/// A triangle of `key` (MOVED_CENTER_1/2 with `strip`) and two adjacent MOVED_CENTER_1/2
/// neighbours whose relocated centres break the angle bounds of the self-check: the key to
/// subdivide (the smallest of the three, as the self-check picks), if any.
pub(super) fn spread_moved_triangle(
    h: &Hierarchy,
    key: Key,
    class: Class,
    strip: FinStrip,
) -> Option<Key> {
    let here = moved_centre(h, key, class, strip)?;
    let near: Vec<Option<(Key, Point)>> = (0..6)
        .map(|d| {
            let n = key.neighbor(d);
            let (c, s) = moved_neighbour(h, n)?;
            Some((n, moved_centre(h, n, c, s)?))
        })
        .collect();
    let filter = HEX.angle_filter();
    for d in 0..6 {
        let (Some((a, pa)), Some((b, pb))) = (near[d], near[(d + 1) % 6]) else {
            continue;
        };
        let t = [here, pa, pb];
        if filter.clearly_within(&t) {
            continue;
        }
        if breaks_bounds(&t) {
            return [key, a, b].into_iter().min_by_key(|k| (k.k, *k));
        }
    }
    None
}
