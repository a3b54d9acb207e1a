//! The cyclic ladder of `fill` solved in pieces (ours, engineering of steps 11 and 16): the
//! chain is cut at anchor rungs, each the perpendicular from a front corner to its own foot
//! on a side, away from the polygon's corners, as the paper's border-boxes are bounded; the
//! ladder (`boxes::ladder`) runs on each piece alone and its result is kept by the piece's
//! content (`Pieces`). An erosion then costs the pieces it changes, not the whole polygon:
//! a front of 20,000 corners was solved again whole, 300 times, in a failing run.
//!
//! Pieces not solved before are solved over the threads first (`solve`), each from its
//! content alone, so the mesh is the same bytes for every thread count.
//!
//! A piece that keeps no ladder in bounds is merged with its neighbours (the anchors between
//! them dropped), one more on each side at a time up to `MERGE`, before the failure is
//! reported: the anchors then only restrict a ladder where it also fails with more room.

use super::boxes::{ladder, Failure, Vertex};
use crate::geom::Point;
use crate::hex::fxhash::{FxHashMap, FxHashSet};
use crate::hex::parallel::each_in_parallel;

/// Pieces merged on each side of a failing one, at most, before the failure stands.
const MERGE: usize = 2;

/// A solved piece: its smallest margin and its triangles (local indices), or its failure.
type Solved = Result<(f64, Vec<[Vertex; 3]>), Failure>;

/// The pieces solved so far, by their content (kept from one erosion to the next).
#[derive(Debug, Default)]
pub struct Pieces {
    solved: FxHashMap<Words, Solved>,
    /// The threads the pieces may be solved on (`solve`; 0 or 1: in order, on this one).
    pub threads: usize,
}

/// The link of a ladder (`boxes::ladder`: a side's key, `boxes::key_of`), shared by the
/// threads that solve pieces.
pub type Link<'l> = &'l (dyn Fn(usize, usize) -> Option<f64> + Sync);

/// A long key of words (a piece's content, a wedge's points), hashed a word at a time: as
/// a `Vec<u64>` it reaches the hasher as bytes, one multiplication each in `FxHasher`, and
/// SipHash cost a twentieth of a large domain's run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Words(pub Vec<u64>);

impl std::hash::Hash for Words {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        h.write_u64(self.0.len() as u64);
        for &w in &self.0 {
            h.write_u64(w);
        }
    }
}

/// A polygon's cyclic ladder as `boxes::ladder` takes it (the whole chain), with what the
/// pieces' keys need besides the points: `tags` per inner point (words naming what `link`
/// reads of the point) and `salt` (the polygon).
pub struct Chain<'c> {
    pub front: &'c [Point],
    pub inner: &'c [Point],
    pub window: &'c [(usize, usize)],
    pub back: &'c [usize],
    pub tags: &'c [[u64; 4]],
    pub salt: u64,
}

/// The ladder of `chain` through the rungs `anchors` ((front index, inner index), both
/// increasing; the first is (0, 0), the last the chain's end): the smallest margin and the
/// triangles, as `ladder` gives them for the whole chain.
///
/// With more than one thread (`Pieces::threads`), the pieces not solved before are solved
/// first over the threads, each on its own: a piece's ladder depends on its content only,
/// so the result is the same for every thread count. This solves the pieces past a failing
/// one too, which a single thread leaves for a later fill.
pub fn solve(
    chain: &Chain,
    anchors: &[(usize, usize)],
    link: Link,
    pieces: &mut Pieces,
) -> Result<(f64, Vec<[Vertex; 3]>), Failure> {
    let count = anchors.len() - 1;
    if pieces.threads > 1 {
        let mut todo: Vec<(usize, Local)> = Vec::new();
        let mut listed = FxHashSet::default();
        for p in 0..count {
            let l = local(chain, anchors[p], anchors[p + 1]);
            if !pieces.solved.contains_key(&l.key) && listed.insert(l.key.clone()) {
                todo.push((p, l));
            }
        }
        let solved = each_in_parallel(pieces.threads, &todo, |(p, l)| {
            run(chain, l, anchors[*p], anchors[*p + 1], link)
        });
        for ((_, l), s) in todo.into_iter().zip(solved) {
            pieces.solved.insert(l.key, s);
        }
    }
    // The solved stretches in order: (first anchor, margin, triangles).
    let mut done: Vec<(usize, f64, Vec<[Vertex; 3]>)> = Vec::new();
    let mut p = 0;
    while p < count {
        let mut solved = piece(chain, anchors[p], anchors[p + 1], link, pieces);
        let (mut from, mut end) = (p, p + 1);
        // Merge with the pieces around it, giving back the earlier ones' triangles.
        let mut wide = 0;
        while solved.is_err() && wide < MERGE && (from > 0 || end < count) {
            wide += 1;
            // Back to the start of the solved stretch holding that anchor (stretches run
            // on from anchor 0 without a gap, and one is never cut).
            let lo = p.saturating_sub(wide);
            from = done
                .iter()
                .map(|d| d.0)
                .filter(|&s| s <= lo)
                .max()
                .unwrap_or(lo);
            end = (p + 1 + wide).min(count);
            solved = piece(chain, anchors[from], anchors[end], link, pieces);
        }
        let (v, tris) = solved?;
        while done.last().is_some_and(|d| d.0 >= from) {
            done.pop();
        }
        done.push((from, v, tris));
        p = end;
    }
    let value = done.iter().map(|d| d.1).fold(f64::INFINITY, f64::min);
    Ok((value, done.into_iter().flat_map(|d| d.2).collect()))
}

/// A piece as `ladder` takes it: the windows and backs in its own indices, and its key.
struct Local {
    key: Words,
    window: Vec<(usize, usize)>,
    back: Vec<usize>,
}

/// The piece of `chain` between rungs a and b in its own indices, with its key (its content).
fn local(chain: &Chain, (ia, xa): (usize, usize), (ib, xb): (usize, usize)) -> Local {
    let front = &chain.front[ia..=ib];
    let inner = &chain.inner[xa..=xb];
    let last = xb - xa;
    let mut window: Vec<(usize, usize)> = chain.window[ia..=ib]
        .iter()
        .map(|&(lo, hi)| (lo.clamp(xa, xb) - xa, hi.clamp(xa, xb) - xa))
        .collect();
    let m = window.len();
    window[0].0 = 0;
    window[m - 1].1 = last;
    for i in 1..m {
        window[i].0 = window[i].0.max(window[i - 1].0).min(window[i - 1].1);
    }
    for i in (0..m - 1).rev() {
        window[i].1 = window[i].1.min(window[i + 1].1).max(window[i + 1].0);
    }
    let back: Vec<usize> = chain.back[xa..=xb]
        .iter()
        .map(|&b| b.max(xa) - xa)
        .collect();
    let mut key = vec![chain.salt, front.len() as u64, inner.len() as u64];
    key.extend(front.iter().flat_map(|p| p.map(f64::to_bits)));
    for (p, tag) in inner.iter().zip(&chain.tags[xa..=xb]) {
        key.extend(p.map(f64::to_bits));
        key.extend(tag);
    }
    key.extend(window.iter().flat_map(|w| [w.0 as u64, w.1 as u64]));
    key.extend(back.iter().map(|&b| b as u64));
    Local {
        key: Words(key),
        window,
        back,
    }
}

/// The ladder of piece `l`, between rungs a and b, in its own indices.
fn run(
    chain: &Chain,
    l: &Local,
    (ia, xa): (usize, usize),
    (ib, xb): (usize, usize),
    link: Link,
) -> Solved {
    let local_link = |k0: usize, k1: usize| link(xa + k0, xa + k1);
    let inner = &chain.inner[xa..=xb];
    ladder(
        &chain.front[ia..=ib],
        inner,
        &l.window,
        (inner.len(), &l.back),
        &local_link,
    )
}

/// The ladder between rungs a and b alone, in the chain's indices (kept by content).
fn piece(
    chain: &Chain,
    a: (usize, usize),
    b: (usize, usize),
    link: Link,
    pieces: &mut Pieces,
) -> Solved {
    let l = local(chain, a, b);
    if let Some(found) = pieces.solved.get(&l.key) {
        return shifted(found.clone(), a.0, a.1);
    }
    let solved = run(chain, &l, a, b, link);
    pieces.solved.insert(l.key, solved.clone());
    shifted(solved, a.0, a.1)
}

/// A piece's result in the chain's indices.
fn shifted(solved: Solved, ia: usize, xa: usize) -> Solved {
    match solved {
        Ok((v, tris)) => Ok((
            v,
            tris.into_iter()
                .map(|t| {
                    t.map(|v| match v {
                        Vertex::Front(i) => Vertex::Front(ia + i),
                        Vertex::Segment(k) => Vertex::Segment(xa + k),
                    })
                })
                .collect(),
        )),
        Err(Failure::Bounds { at, margin }) => Err(Failure::Bounds {
            at: ia + at,
            margin,
        }),
        #[cfg(test)]
        Err(Failure::Front(i)) => Err(Failure::Front(ia + i)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::orient2d;

    /// A strip's front, inner points, windows and back.
    type Strip = (Vec<Point>, Vec<Point>, Vec<(usize, usize)>, Vec<usize>);

    /// A straight strip: front corners one apart at height √3/2 above the x axis, and on the
    /// axis each corner's foot and the midpoints between feet (inner point 2i is corner i's
    /// foot). Returns the front, inner points, windows and back.
    fn strip(m: usize) -> Strip {
        let h = 3f64.sqrt() / 2.0;
        let front: Vec<Point> = (0..m).map(|i| [i as f64, h]).collect();
        let inner: Vec<Point> = (0..2 * m - 1).map(|k| [k as f64 / 2.0, 0.0]).collect();
        let n = inner.len();
        let window = (0..m)
            .map(|i| ((2 * i).saturating_sub(4), (2 * i + 4).min(n - 1)))
            .collect();
        let back = (0..n).map(|k| k.saturating_sub(48)).collect();
        (front, inner, window, back)
    }

    /// The strip's chain, every inner point of one kind.
    fn chain<'c>(
        front: &'c [Point],
        inner: &'c [Point],
        window: &'c [(usize, usize)],
        back: &'c [usize],
        tags: &'c [[u64; 4]],
    ) -> Chain<'c> {
        Chain {
            front,
            inner,
            window,
            back,
            tags,
            salt: 0,
        }
    }

    /// Anchors at every fifth front corner's foot of a strip of `m` corners.
    fn every_fifth_foot(m: usize) -> Vec<(usize, usize)> {
        (0..m).step_by(5).map(|i| (i, 2 * i)).collect()
    }

    fn area(t: [Point; 3]) -> f64 {
        orient2d(t[0], t[1], t[2]) / 2.0
    }

    #[test]
    fn a_strip_solved_in_pieces_is_covered_in_bounds_and_solved_again_from_the_kept_pieces() {
        let m = 31;
        let (front, inner, window, back) = strip(m);
        let tags = vec![[0; 4]; inner.len()];
        let chain = chain(&front, &inner, &window, &back, &tags);
        let anchors = every_fifth_foot(m);
        assert_eq!(anchors.last(), Some(&(30, 60)));
        let link = |k0: usize, k1: usize| (k1 > k0).then_some(f64::INFINITY);
        let mut pieces = Pieces::default();
        let (margin, triangles) = solve(&chain, &anchors, &link, &mut pieces).unwrap();
        assert!(margin >= -super::super::boxes::SLACK, "{margin}");
        let at = |v: Vertex| match v {
            Vertex::Front(i) => front[i],
            Vertex::Segment(k) => inner[k],
        };
        // Counter-clockwise, in bounds, and covering the strip once.
        let mut total = 0.0;
        for t in &triangles {
            let p = t.map(at);
            assert!(area(p) > 0.0, "{t:?}");
            let g = super::super::boxes::score(p[0], p[1], p[2]).unwrap();
            assert!(g >= -super::super::boxes::SLACK, "{t:?}: {g}");
            total += area(p);
        }
        let strip_area = (m - 1) as f64 * 3f64.sqrt() / 2.0;
        assert!((total - strip_area).abs() < 1e-9, "{total} vs {strip_area}");
        // Each piece was kept; solving again reads them and gives the same triangles.
        assert_eq!(pieces.solved.len(), anchors.len() - 1);
        let again = solve(&chain, &anchors, &link, &mut pieces).unwrap();
        assert_eq!(again.1, triangles);
        assert_eq!(pieces.solved.len(), anchors.len() - 1);
    }

    #[test]
    fn a_piece_that_fails_with_its_neighbours_names_its_front_corner_in_the_chain() {
        let m = 31;
        let (mut front, inner, window, back) = strip(m);
        // Corner 17 far above the others: no triangle at it keeps 30°.
        front[17][1] = 6.0;
        let tags = vec![[0; 4]; inner.len()];
        let chain = chain(&front, &inner, &window, &back, &tags);
        let anchors = every_fifth_foot(m);
        let link = |k0: usize, k1: usize| (k1 > k0).then_some(f64::INFINITY);
        let err = solve(&chain, &anchors, &link, &mut Pieces::default()).unwrap_err();
        assert!((16..=18).contains(&err.at()), "{err:?}");
    }
}
