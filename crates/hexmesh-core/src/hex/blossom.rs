//! Local coarsening into blossoms, paper 000 Sec. 5.3: "all of the hexagons in the 4-ring of
//! h_i must be of type FIXED_CENTER_REGULAR. By this operation 37 hexagons are replaced by 7.
//! In the dual mesh a blossom is represented by 60 triangles instead of 96."
//!
//! In the integer lattice of `lattice` (cells (k, i, j)) a blossom is one subdivided hexagon T of level k and its six
//! subdivided neighbours N_0 … N_5 made leaves again. Before, the level-(k+1) cells within
//! lattice distance 3 of c = T's central child are 37 full leaves: the central children of T
//! and N_d (distance 0 and 2), the cells between T and N_d (1), between N_d and N_{d+1} (2),
//! and the 18 between N_d and the twelve hexagons R of T's 2-ring (3). After, T and the N_d
//! are the 7 full leaves of level k there; the cells between N_d and R are halves of R, three
//! fins of each N_d, so every N_d is MOVED_CENTER_3 with top neighbour T, and T is
//! MOVED_CENTER_4 of a ring of six: the blossom that `mc3` builds (60 triangles, T unmoved).
//!
//! The condition, read in these terms ("h_i" is c; its 4-ring is every cell within distance
//! 4 of it): the 61 level-(k+1) cells within distance 4 of c are full leaves inside the
//! bounding hexagon, off its boundary, FIXED_CENTER_REGULAR (no fin, no point, no ring role)
//! and not MOVED_CENTER_4. The 37 inner ones are the cells replaced; the 24 at distance 4 are
//! the central children of the R and the cells between two R: the full hexagons next to the
//! new fins, which Sec. 5.2 wants FIXED_CENTER_x, with no finer hexagon next to a fin
//! (Sec. 3.3). The split counters of Sec. 3.2 allow the operation on such leaves: the 7
//! central children merge up (their counter `Key::split_counter` is at least 1) and the 30
//! other cells are joined cells (counter 0), which may be broken.
//!
//! Departure from the paper: Sec. 5.3 examines "each hexagon h_i with a split-counter of 0";
//! a central child c never has counter 0, so the condition is read as above, on every
//! subdivided T. Candidates are tried once each, in key order, on the state left by the
//! blossoms already formed, so that blossoms never overlap and the result is deterministic.

use crate::hex::classify::{classify, Class, Rings};
use crate::hex::lattice::Key;
use crate::hex::mc3;
use crate::hex::parallel::in_parallel;
use crate::hex::subdivision::Hierarchy;

/// The cells within lattice distance `radius` of `c`, at its level.
fn disc(c: Key, radius: i64) -> impl Iterator<Item = Key> {
    (-radius..=radius).flat_map(move |di| {
        (-radius..=radius)
            .filter(move |dj| (di + dj).abs() <= radius)
            .map(move |dj| Key::new(c.k, c.i + di, c.j + dj))
    })
}

/// True when the subdivided hexagon `top` and its six neighbours can be made a blossom.
/// A blossom makes `top` and its neighbours leaves of `top`'s level, so none is formed
/// coarser than the size level (`hex::size`).
pub fn can_form(h: &Hierarchy, r: &Rings, top: Key) -> bool {
    if top.k < h.size_level()
        || !h.is_subdivided(top)
        || (0..6).any(|d| !h.is_subdivided(top.neighbor(d)))
    {
        return false;
    }
    disc(top.central_child(), 4).all(|x| {
        x.inside()
            && !x.on_boundary()
            && h.is_full_leaf(x)
            && classify(h, r, x).0 == Class::FixedCenterRegular
            && !mc3::is_mc4(h, r, x)
    })
}

/// Forms every blossom the condition allows among the subdivided hexagons `tops` (tried in
/// key order), on `h` as it stands with the rings `r`, and returns the hexagons made leaves
/// (seven per blossom): the blossoms of `coarsen_in_order`, found with most of the work
/// shared over the hierarchy's threads.
///
/// The condition is first read for every top on the state before any blossom, over the
/// threads; then, in key order, the tops that passed are read again on the state the
/// blossoms before them left. A top that failed at first fails then too. Key order goes
/// level by level, coarsest first, and a blossom of level k only takes its seven hexagons
/// out of the subdivided set. The condition of a top of level k reads which hexagons of
/// levels k and k + 1 are subdivided (the top and its neighbours; the parents of the cells
/// of level k + 1 it tests for full leaves; their fins and MOVED_CENTER_3 neighbours), so a
/// coarser blossom changes nothing it reads, and one of its own level can only turn its
/// reads from true to false (hexagons no longer subdivided, cells below them no longer full
/// leaves) but one: a cell x of the 4-ring whose MOVED_CENTER_3 neighbour n stops being a
/// full leaf stops being MOVED_CENTER_4. n would be a child of the blossom's hexagons, which
/// that blossom's condition required to be FIXED_CENTER_REGULAR, hence not MOVED_CENTER_3.
/// At plane-100k 21,597 of 1,056,401 tops pass the first reading and 6,225 blossoms form.
pub fn coarsen(h: &mut Hierarchy, r: &Rings, tops: &[Key]) -> Vec<Key> {
    let mut tops = tops.to_vec();
    tops.sort_unstable_by_key(|k| k.packed());
    tops.dedup();
    let before = &*h;
    let passed: Vec<Key> = in_parallel(before.threads(), &tops, |chunk| {
        chunk
            .iter()
            .copied()
            .filter(|&t| can_form(before, r, t))
            .collect::<Vec<Key>>()
    })
    .concat();
    form_in_order(h, r, passed)
}

/// `coarsen` as the paper states it: every top in key order, its condition read on the
/// state the blossoms before it left. The reference the tests hold `coarsen` to.
pub fn coarsen_in_order(h: &mut Hierarchy, r: &Rings, tops: &[Key]) -> Vec<Key> {
    let mut tops = tops.to_vec();
    tops.sort_unstable_by_key(|k| k.packed());
    tops.dedup();
    form_in_order(h, r, tops)
}

/// Forms the blossom of each top of `tops` (sorted) whose condition holds when its turn
/// comes; the hexagons made leaves, the top first.
fn form_in_order(h: &mut Hierarchy, r: &Rings, tops: Vec<Key>) -> Vec<Key> {
    let mut merged = Vec::new();
    for top in tops {
        if can_form(h, r, top) {
            h.merge_blossom(top);
            merged.push(top);
            merged.extend((0..6).map(|d| top.neighbor(d)));
        }
    }
    merged
}

/// The subdivided hexagons whose central child is a full leaf of class FIXED_CENTER_REGULAR:
/// the only possible blossom tops, found from the leaves of the hierarchy, in their order.
/// The leaves that are central children are listed, then classified over the hierarchy's
/// threads (at plane-100k a million of them, half a second on one thread).
pub fn candidate_tops(h: &Hierarchy, r: &Rings, leaves: impl IntoIterator<Item = Key>) -> Vec<Key> {
    let tops: Vec<Key> = leaves
        .into_iter()
        .filter(|c| c.k > 0 && c.i % 2 == 0 && c.j % 2 == 0)
        .map(|c| Key::new(c.k - 1, c.i / 2, c.j / 2))
        .collect();
    in_parallel(h.threads(), &tops, |chunk| {
        chunk
            .iter()
            .copied()
            .filter(|t| {
                let c = t.central_child();
                h.is_full_leaf(c) && classify(h, r, c).0 == Class::FixedCenterRegular
            })
            .collect::<Vec<Key>>()
    })
    .concat()
}
