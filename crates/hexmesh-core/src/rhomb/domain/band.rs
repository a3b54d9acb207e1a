//! The rhombs along the boundary (ours, in place of Sec. 5.1's moving conditions and Sec. 5.2
//! case 2, which make corners next to a change of size movable): before the cut, the leaves a
//! segment touches are made one size along each polygon, or graded along it.
//!
//! - **Even** (`Band::Even`): every leaf the boundary touches has first neighbours of its own
//!   size. The fronts the ladder joins are then of one size locally, at the price of the
//!   finest size spreading along the whole boundary: a segment a thousandth of its
//!   neighbours' length makes a million triangles (fuzz case 14 of seed 20261123: 554,470
//!   leaves against 4,528 graded).
//! - **Graded** (`Band::Graded`): no touched leaf has a coarser neighbour off the boundary;
//!   along the boundary two touched leaves may differ 2:1, and a coarse touched leaf may
//!   have finer neighbours off it. The rhombs then change size along a segment, where a
//!   fine front meets a coarse one a row deeper; with an earlier rule the ladder missed
//!   there by 3.3° to 5° on fuzz case 14, and `relax`, moving the corner the ladder names,
//!   mended those steps. Asking also that a touched leaf's finer neighbours off the
//!   boundary take its size spreads the finest size along the whole boundary: at a step,
//!   the fine leaves inside the coarse leaf's fine touched neighbour lie beside it, so that
//!   rule's only tree is the even band (checked: 395 s for the rectangle of the tests,
//!   every touched leaf of one level). A work list that applied it only when a leaf was
//!   made (that earlier rule) reached a graded tree that depended on the order of splits.
//!
//! `choose` evens the band unless that makes the tree more than `GRADED_ABOVE` times the
//! graded one, or more than half the vertices a budget allows (`even_cap`): the even band
//! meshes more of the fuzz domains (where the size changes along a polygon's sides, the
//! graded band's steps fail more often than the even band's finer lattice costs), the
//! graded one the domains the even band cannot afford. A band even only
//! near the input corners and points (within 3 + 1.5 / sin(α/2) leaf sides of a corner of
//! angle α) and graded elsewhere met 71 of the first 100 fuzz domains, against the even
//! band's 88 (METHODOLOGY, 2026-12-07).
//!
//! Where a graded band's fill fails, `finer_near` splits the coarse touched leaves near the
//! failure when a finer leaf lies near it, and grades the band again: the change of size
//! moves along the boundary, a coarse leaf at a time, to where the ladder closes. Of the
//! domain campaign's first 200 cases, it meshes 11 that failed (9 of the 10 short-long
//! failures, one with large coordinates, one with holes; METHODOLOGY, 2026-12-07).
//!
//! Where the cut leaves a single point out of the kept lattice, or on an island of it,
//! `around_single` and `around_island` make the band finer beside the point or the island,
//! so that the point's lattice joins the rest instead of being cut or eroded out of the
//! mesh.

use super::cut;
use crate::rhomb::lattice::{self, Cell, Frame, AROUND};
use crate::rhomb::tree::{Cover, Guard, Stop, Tree};

/// How the band along the boundary is made (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Band {
    Even,
    Graded,
}

/// The even band is chosen when its tree has at most this many times the leaves of the
/// graded one. On the first 100 fuzz domains (seed 20261123) the ratio runs from 1 to over
/// 1,000. Before `finer_near` and the islands' own erosions (`mod.rs`), the even band meshed
/// every domain up to 59 times (case 46, 363,112 leaves) within the fuzz budget but two
/// (cases 72 and 76, at 7 and 37 times), where the graded band failed case 46, and the limit
/// was 100. With them, the graded band meshes case 46, and the even band of case 107 (holes,
/// 43.9 times: 397,630 leaves against 9,061) ran past the campaign's 500,000 vertices where
/// the graded one meshes in 5 s. At 25 the campaign's first 200 cases all mesh, and 50 left
/// case 107 even (METHODOLOGY, 2026-12-07).
const GRADED_ABOVE: usize = 25;

/// Makes the band along the boundary of `tree` (a fresh quad-tree of the domain; `again`
/// builds another) even, or graded where the even one would exceed `GRADED_ABOVE` times the
/// graded one's leaves or half the budget's vertices (`even_cap`), and says which. The even
/// tree is built beside the graded one, and given up as soon as it passes that size (or a
/// budget or the lattice's depth stops it).
pub fn choose(
    tree: &mut Tree,
    again: impl FnOnce() -> Result<Tree, Stop>,
    frame: &Frame,
    segments: &cut::Segments,
    guard: &Guard,
) -> Result<Band, Stop> {
    make(tree, frame, segments, Band::Graded, None, guard)?;
    let cap = even_cap(tree.leaf_count(), guard.max_vertices());
    let mut even = again()?;
    match make(&mut even, frame, segments, Band::Even, Some(cap), guard) {
        Ok(true) => {
            *tree = even;
            Ok(Band::Even)
        }
        Ok(false) | Err(_) => Ok(Band::Graded),
    }
}

/// The most leaves an even band may have beside a graded band of `graded` leaves, under a
/// budget of `max_vertices`: `GRADED_ABOVE` times the graded band, and at most half the
/// budget: a mesh has about as many vertices as its tree has leaves, and the fills may make
/// the tree finer still (`finer`, `fill::Stuck::Finer`), so an even band past half the
/// budget leaves it no room. Case 109 of seed 2 (a thin slit, 3e-3 wide) had an even band
/// of 450,796 leaves, 9.8 times the graded one's 45,841; its fills took it to 905,590
/// leaves and 656,812 vertices, past the campaign's 500,000, in 22 s. The graded band
/// meshes it with 37,846 vertices in 4.4 s.
fn even_cap(graded: usize, max_vertices: Option<usize>) -> usize {
    let cap = GRADED_ABOVE.saturating_mul(graded);
    max_vertices.map_or(cap, |max| cap.min(max / 2))
}

/// Splits leaves until the band along the boundary is `band`; with `cap`, stops (returning
/// false) once the tree has more leaves than that.
///
/// A work list of the touched leaves: a leaf is looked at again only after a split beside
/// it, and a split's new leaves only if they are touched, so the cost follows the splits
/// (a whole-tree pass per round was quadratic where the finest size spreads along a long
/// boundary: minutes on a short segment beside long ones). Splits only make leaves finer,
/// so the least tree with the property is reached whatever the order.
pub fn make(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    band: Band,
    cap: Option<usize>,
    guard: &Guard,
) -> Result<bool, Stop> {
    let touched = |c: Cell| touches_boundary(frame, segments, c);
    let target = |tree: &Tree, c: Cell| match band {
        Band::Even => tree.coarser_neighbour(c),
        Band::Graded => graded_split(tree, &touched, c),
    };
    tree.take_fresh();
    let mut queue: Vec<Cell> = tree.leaves().into_iter().filter(|&c| touched(c)).collect();
    queue.reverse();
    let mut looked = 0u64;
    while let Some(c) = queue.pop() {
        looked += 1;
        if looked % 4096 == 0 {
            guard.check(tree)?;
        }
        if !tree.is_leaf(c) {
            continue;
        }
        if cap.is_some_and(|cap| tree.leaf_count() > cap) {
            return Ok(false);
        }
        let Some(split) = target(tree, c) else {
            continue;
        };
        tree.split(split)?;
        queue.push(c);
        let mut fresh = tree.take_fresh();
        fresh.sort_unstable();
        fresh.reverse();
        queue.extend(fresh.into_iter().filter(|&f| tree.is_leaf(f) && touched(f)));
    }
    guard.check(tree)?;
    Ok(true)
}

/// What the graded band splits next at touched leaf `c`: a coarser first neighbour the
/// boundary does not touch. Splits only make leaves finer, so a leaf looked at when it is
/// made and after each split it asks for never gets such a neighbour later.
fn graded_split(tree: &Tree, touched: &impl Fn(Cell) -> bool, c: Cell) -> Option<Cell> {
    AROUND.iter().find_map(|&(di, dj)| {
        let n = c.offset(di, dj);
        match tree.cover(n) {
            Cover::Leaf(l) if l.level < c.level && !touched(l) => Some(l),
            _ => None,
        }
    })
}

/// Whether a boundary segment touches rhomb `c` (either of its two lattice triangles).
pub fn touches_boundary(frame: &Frame, segments: &cut::Segments, c: Cell) -> bool {
    let corner = |di: i64, dj: i64| frame.point(lattice::key(c.level, c.i + di, c.j + dj));
    let halves = [
        [corner(0, 0), corner(1, 0), corner(0, 1)],
        [corner(1, 0), corner(1, 1), corner(0, 1)],
    ];
    let b = cut::bbox(&[corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)]);
    segments.near(b).into_iter().any(|s| {
        let [p, q] = segments.ends[s as usize];
        halves.iter().any(|&h| cut::touches(h, p, q))
    })
}

/// Departure (ours): where `BAND_EROSIONS` erosions and the moved corners leave no ladder in
/// bounds, every leaf the boundary touches is split and the band made again (`make`), and
/// the method starts over on the finer lattice. A ladder's failure is a coincidence of where
/// the lattice's corners fall against the boundary (a short front edge facing a wide gap, a
/// front corner too near a segment), and eroding more corners there widens the gap: fuzz
/// case 1 (a six-point star) walked its miss from 0.5° to 85° over 300 erosions. Half the
/// size puts the corners elsewhere along the same segments: case 1 meshed on the first finer
/// band, case 11 (holes) on the second; of the first 40 fuzz cases, 30 meshed instead of 25.
/// Since short front edges are dropped (`cut::drop_short_fronts`), case 1 meshes on its
/// first fill; case 20 (interior points) still needs a finer band. A search, not a
/// construction: nothing bounds how many finer bands a domain needs, and `FINER_BANDS` are
/// tried.
pub fn finer(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    band: Band,
    guard: &Guard,
) -> Result<(), Stop> {
    let touched: Vec<Cell> = tree
        .leaves()
        .into_iter()
        .filter(|&c| touches_boundary(frame, segments, c))
        .collect();
    for c in touched {
        guard.check(tree)?;
        tree.split(c)?;
    }
    make(tree, frame, segments, band, None, guard).map(|_| ())
}

/// Departure (ours, where Sec. 5.1 makes the corners at a change of size movable): where
/// a graded band's fill fails at `p`, the touched leaves near `p` coarser than the finest
/// leaf near it are split, and the band graded again; false (nothing split) where no such
/// leaf is near. Near: the leaf holding `p` and those at a half to `NEAR` of its sides
/// from `p` along the lattice's six directions.
///
/// The fronts a graded band leaves where sizes meet defeat the ladder in two ways (the
/// short-long failures of the fuzz, METHODOLOGY 2026-12-07): along the segment, the coarse
/// front recedes a row beside the fine one; across it, a coarse touched leaf over finer
/// leaves leaves a fine front up to two fine sides from the segment. Splitting the coarse
/// touched leaves there moves the change of size along the boundary, a coarse leaf at a
/// time, to where the ladder closes; the split leaves' neighbours are graded as before.
/// Of the ten short-long failures of the campaign's first 200 cases, nine mesh with it
/// (case 166 is the fixture), where making the whole band finer three times meshed none.
/// A search, not the paper's construction: `NEAR_SPLITS` in `mod.rs` caps it.
pub fn finer_near(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    p: crate::geom::Point,
    guard: &Guard,
) -> Result<bool, Stop> {
    let st = frame.locate(p);
    let here = tree.leaf_at(st);
    // A leaf side of `here` in root coordinates, and the lattice's six directions there.
    let d = 0.5f64.powi(i32::from(here.level));
    let directions = [
        (1.0, 0.0),
        (-1.0, 0.0),
        (0.0, 1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (-1.0, 1.0),
    ];
    let mut near = vec![here];
    for step in 1..=2 * NEAR {
        let r = 0.5 * step as f64 * d;
        for (a, b) in directions {
            near.push(tree.leaf_at([st[0] + r * a, st[1] + r * b]));
        }
    }
    near.sort_unstable();
    near.dedup();
    let finest = near.iter().map(|c| c.level).max().unwrap_or(here.level);
    let coarse: Vec<Cell> = near
        .into_iter()
        .filter(|&c| c.level < finest && touches_boundary(frame, segments, c))
        .collect();
    if coarse.is_empty() {
        return Ok(false);
    }
    for c in coarse {
        guard.check(tree)?;
        tree.split(c)?;
    }
    make(tree, frame, segments, Band::Graded, None, guard).map(|_| true)
}

/// Departure (ours): where the cut left single point `p` in no kept triangle, or on an
/// island of kept lattice that no front reaches (`mod.rs`, `lost_singles`), the leaf
/// holding it and the leaves the boundary touches within twice its distance `d` to the
/// boundary are split where their side exceeds `d / SINGLE_SIDES`, and the band is made
/// again; called again while the point is lost, this makes the band beside the point fine
/// enough for the kept lattice to reach it. The corner condition (step 3) keeps the other
/// input points out of a single point's window, not the segments: points 0.0015 to 0.01
/// from a segment in domains two units across, in a band of sides near 0.02 (fuzz cases
/// 4076, 4892, 5228 and 9759 of seed 20261123), were cut out of the mesh; splitting the
/// point's own leaf alone left it on an island inside the gap the fill spans, which the
/// fill covered a second time.
pub fn around_single(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    band: Band,
    p: crate::geom::Point,
    guard: &Guard,
) -> Result<bool, Stop> {
    let d = segments.distance(p);
    let target = d / SINGLE_SIDES;
    let here = tree.leaf_at(frame.locate(p));
    let mut split = Vec::new();
    if leaf_side(frame, here) > target {
        split.push(here);
    }
    touched_near(tree, frame, segments, p, 2.0 * d, target, &mut split);
    split_all(tree, frame, segments, band, split, guard)
}

/// A single point's leaf and the band beside it are split by `around_single` until their
/// side is at most the point's distance to the boundary over this.
const SINGLE_SIDES: f64 = 3.0;

/// Departure (ours): where an island of kept lattice holds a single point (a point in a
/// spike or slot of the domain, whose kept lattice is cut off from the rest where the
/// domain narrows: fuzz case 4076 of seed 20261123; or a point whose finer rhombs
/// `around_single` made end before the band's coarse ones: case 5228), the island is not
/// eroded, which would cut the point out: the leaves the boundary touches within
/// `ISLAND_REACH` leaf sides of each island corner and coarser than that corner's leaf are
/// split, and the band made again, so that the island reaches further at each round until
/// it joins the rest. False where nothing was split.
pub fn around_island(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    band: Band,
    corners: &[crate::geom::Point],
    guard: &Guard,
) -> Result<bool, Stop> {
    let mut split = Vec::new();
    for &p in corners {
        let s = leaf_side(frame, tree.leaf_at(frame.locate(p)));
        touched_near(tree, frame, segments, p, ISLAND_REACH * s, s, &mut split);
    }
    split_all(tree, frame, segments, band, split, guard)
}

/// How far from an island corner, in sides of its leaf, `around_island` looks.
const ISLAND_REACH: f64 = 4.0;

/// The side of leaf `c`.
pub fn leaf_side(frame: &Frame, c: Cell) -> f64 {
    let corner = |di: i64| frame.point(lattice::key(c.level, c.i + di, c.j));
    crate::geom::dist(corner(0), corner(1))
}

/// Adds to `out` the leaves the boundary touches over the disc of radius `r` about `p`
/// whose side exceeds `side` (looked up on a grid of spacing `side / 2`).
fn touched_near(
    tree: &Tree,
    frame: &Frame,
    segments: &cut::Segments,
    p: crate::geom::Point,
    r: f64,
    side: f64,
    out: &mut Vec<Cell>,
) {
    let step = 0.5 * side;
    let n = (r / step).ceil() as i64;
    for a in -n..=n {
        for b in -n..=n {
            let (x, y) = (a as f64 * step, b as f64 * step);
            if x * x + y * y > r * r {
                continue;
            }
            let c = tree.leaf_at(frame.locate([p[0] + x, p[1] + y]));
            if leaf_side(frame, c) > side && touches_boundary(frame, segments, c) {
                out.push(c);
            }
        }
    }
}

/// Splits the leaves `split` (each once) and makes the band again; false where there were
/// none.
fn split_all(
    tree: &mut Tree,
    frame: &Frame,
    segments: &cut::Segments,
    band: Band,
    mut split: Vec<Cell>,
    guard: &Guard,
) -> Result<bool, Stop> {
    split.sort_unstable();
    split.dedup();
    if split.is_empty() {
        return Ok(false);
    }
    for c in split {
        guard.check(tree)?;
        if tree.is_leaf(c) {
            tree.split(c)?;
        }
    }
    make(tree, frame, segments, band, None, guard).map(|_| true)
}

/// How far from a failing corner, in sides of its leaf, `finer_near` looks.
const NEAR: usize = 2;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Pslg;
    use crate::mesher::Budget;
    use crate::rhomb::domain::tests::ring;
    use crate::rhomb::domain::{quad_tree, read};

    /// A 2 × 1 rectangle whose top-right corner is cut by a segment `short` long.
    fn cut_rectangle(short: f64) -> Pslg {
        let mut input = Pslg::default();
        ring(
            &[
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 1.0 - short],
                [2.0 - short, 1.0],
                [0.0, 1.0],
            ],
            &mut input,
        );
        input
    }

    /// The tree of `input` with its band made `band`, and the frame and segments.
    fn banded(input: &Pslg, band: Band) -> (Tree, Frame, cut::Segments) {
        let (domain, classes) = read(input).unwrap();
        let guard = Guard::new(Budget::default());
        let (mut tree, frame) = quad_tree(&domain, &classes, &guard).unwrap();
        let segments = cut::Segments::new(&domain);
        assert!(make(&mut tree, &frame, &segments, band, None, &guard).unwrap());
        (tree, frame, segments)
    }

    #[test]
    fn an_even_band_past_half_the_vertex_budget_is_not_chosen() {
        let input = cut_rectangle(0.05);
        let graded = banded(&input, Band::Graded).0.leaf_count();
        let even = banded(&input, Band::Even).0.leaf_count();
        assert!(
            even > graded && even <= GRADED_ABOVE * graded,
            "{even} {graded}"
        );
        let (domain, classes) = read(&input).unwrap();
        let chosen = |max_vertices: usize| {
            let guard = Guard::new(Budget {
                max_vertices: Some(max_vertices),
                ..Budget::default()
            });
            let (mut tree, frame) = quad_tree(&domain, &classes, &guard).unwrap();
            let fresh = || quad_tree(&domain, &classes, &guard).map(|(t, _)| t);
            let segments = cut::Segments::new(&domain);
            let band = choose(&mut tree, fresh, &frame, &segments, &guard).unwrap();
            let leaves = if band == Band::Even { even } else { graded };
            assert_eq!(tree.leaf_count(), leaves, "{max_vertices}");
            band
        };
        assert_eq!(chosen(2 * even), Band::Even);
        assert_eq!(chosen(2 * even - 2), Band::Graded);
    }

    #[test]
    fn finer_near_splits_where_sizes_meet_keeps_the_band_graded_and_leaves_one_size_alone() {
        let input = cut_rectangle(1e-3);
        let guard = Guard::new(Budget::default());
        let (mut split, mut alone) = (0, 0);
        // Points along the long sides: sizes meet towards the short segment, and far from
        // it the band is of one size.
        for k in 0..=16 {
            for y in [0.0, 1.0] {
                let p = [2.0 * f64::from(k) / 16.0, y];
                let (mut tree, frame, segments) = banded(&input, Band::Graded);
                let before = tree.leaves();
                if finer_near(&mut tree, &frame, &segments, p, &guard).unwrap() {
                    split += 1;
                    assert!(tree.leaf_count() > before.len(), "{p:?}");
                    let touched = |c: Cell| touches_boundary(&frame, &segments, c);
                    for c in tree.leaves().into_iter().filter(|&c| touched(c)) {
                        assert_eq!(graded_split(&tree, &touched, c), None, "{p:?} {c:?}");
                    }
                } else {
                    alone += 1;
                    assert_eq!(tree.leaves(), before, "{p:?}");
                }
            }
        }
        assert!(split > 0 && alone > 0, "{split} split, {alone} left alone");
    }

    #[test]
    fn the_even_band_leaves_no_touched_leaf_beside_a_coarser_one() {
        let (tree, frame, segments) = banded(&cut_rectangle(1e-3), Band::Even);
        let touched: Vec<Cell> = tree
            .leaves()
            .into_iter()
            .filter(|&c| touches_boundary(&frame, &segments, c))
            .collect();
        assert!(!touched.is_empty());
        for c in touched {
            assert_eq!(tree.coarser_neighbour(c), None, "{c:?}");
        }
    }

    #[test]
    fn the_graded_band_leaves_no_touched_leaf_beside_a_coarser_one_off_the_boundary() {
        let (tree, frame, segments) = banded(&cut_rectangle(1e-3), Band::Graded);
        let touched = |c: Cell| touches_boundary(&frame, &segments, c);
        let mut levels = std::collections::BTreeSet::new();
        for c in tree.leaves().into_iter().filter(|&c| touched(c)) {
            levels.insert(c.level);
            assert_eq!(graded_split(&tree, &touched, c), None, "{c:?}");
        }
        // The band is graded: the short segment's leaves are finer than the long ones'.
        assert!(levels.len() >= 4, "{levels:?}");
    }

    #[test]
    fn a_segment_a_thousandth_of_its_neighbours_gets_a_graded_band_and_a_tenth_an_even_one() {
        for (short, want) in [(1e-3, Band::Graded), (1e-1, Band::Even)] {
            let input = cut_rectangle(short);
            let (domain, classes) = read(&input).unwrap();
            let guard = Guard::new(Budget::default());
            let (mut tree, frame) = quad_tree(&domain, &classes, &guard).unwrap();
            let segments = cut::Segments::new(&domain);
            let again = || quad_tree(&domain, &classes, &guard).map(|(t, _)| t);
            let band = choose(&mut tree, again, &frame, &segments, &guard).unwrap();
            assert_eq!(band, want, "short side {short}");
            // The tree kept is the chosen band's.
            let (made, _, _) = banded(&input, band);
            assert_eq!(tree.leaves(), made.leaves(), "short side {short}");
        }
    }
}
