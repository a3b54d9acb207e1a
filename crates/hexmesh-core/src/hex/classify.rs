//! Classification of full hexagons, paper 000 Sec. 5.1: by their fins (MOVED_CENTER_1/2/3,
//! SUBDIVIDE) with left, right and top neighbours, and, without fins, by the input points
//! around them (OCCUPIED_1/2, FIXED_CENTER_IN_RING, MOVED_CENTER_IN_RING, MOVED_CENTER_4,
//! FIXED_CENTER_REGULAR).

use crate::geom::{dist2, Point};
use crate::hex::lattice::{FxHashMap, Key, KeySet};
use crate::hex::subdivision::Hierarchy;

/// The classes of Sec. 5.1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Class {
    /// One fin; the centre moves towards the hexagon across it (Sec. 5.4).
    MovedCenter1,
    /// Two consecutive fins.
    MovedCenter2,
    /// Three consecutive fins; the fins' centres enter the dual (Sec. 5.4).
    MovedCenter3,
    /// Fins that are not one run of one to three: the hexagon must be subdivided (Sec. 5.2).
    Subdivide,
    /// No fins; holds an input point inside its closed half-sized hexagon (central child).
    Occupied1,
    /// No fins; holds an input point outside its half-sized hexagon.
    Occupied2,
    /// No fins; in the 1-ring of an OCCUPIED_1 or the 2-ring of an OCCUPIED_2 hexagon. Its
    /// centre stays.
    FixedCenterInRing,
    /// No fins; in the 1-ring of an OCCUPIED_2 hexagon, whose ring shift moves its centre.
    MovedCenterInRing,
    /// No fins; the top neighbour of a MOVED_CENTER_3 hexagon.
    MovedCenter4,
    /// No fins and none of the above: the centre stays.
    FixedCenterRegular,
}

impl Class {
    /// The paper's name.
    pub fn name(self) -> &'static str {
        match self {
            Class::MovedCenter1 => "MOVED_CENTER_1",
            Class::MovedCenter2 => "MOVED_CENTER_2",
            Class::MovedCenter3 => "MOVED_CENTER_3",
            Class::Subdivide => "SUBDIVIDE",
            Class::Occupied1 => "OCCUPIED_1",
            Class::Occupied2 => "OCCUPIED_2",
            Class::FixedCenterInRing => "FIXED_CENTER_IN_RING",
            Class::MovedCenterInRing => "MOVED_CENTER_IN_RING",
            Class::MovedCenter4 => "MOVED_CENTER_4",
            Class::FixedCenterRegular => "FIXED_CENTER_REGULAR",
        }
    }

    /// FIXED_CENTER_x: the centre stays where the lattice puts it.
    pub fn is_fixed(self) -> bool {
        matches!(self, Class::FixedCenterInRing | Class::FixedCenterRegular)
    }

    /// A hexagon with fins: MOVED_CENTER_1, _2, _3 or SUBDIVIDE.
    pub fn has_fins(self) -> bool {
        matches!(
            self,
            Class::MovedCenter1 | Class::MovedCenter2 | Class::MovedCenter3 | Class::Subdivide
        )
    }
}

/// The fins of a full hexagon as one run of consecutive directions `first, first + 1, …`
/// (mod 6), `len` long. The left neighbour lies in direction `first - 1`, the right one in
/// `first + len`, and for three fins the top neighbour in `first + 4`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FinStrip {
    /// The direction of the first fin, an index into `lattice::DIRS` (0..6).
    pub first: usize,
    /// How many fins, 1 to 5.
    pub len: usize,
}

impl FinStrip {
    /// The direction of the left neighbour, the one before the first fin.
    pub fn left(self) -> usize {
        (self.first + 5) % 6
    }

    /// The direction of the right neighbour, the one after the last fin.
    pub fn right(self) -> usize {
        (self.first + self.len) % 6
    }

    /// The direction of the top neighbour of a strip of three fins: opposite the middle fin.
    pub fn top(self) -> usize {
        (self.first + 4) % 6
    }
}

/// The directions in which the full leaf `key` has fins, as a bit mask.
///
/// The edge child towards neighbour n of an unsubdivided hexagon is a fin exactly when n lies
/// inside the bounding hexagon and is subdivided (`refine::is_fin`: a semi-hexagon owned by a
/// hexagon inside), so one lookup per direction decides it.
pub fn fin_mask(h: &Hierarchy, key: Key) -> u8 {
    debug_assert!(h.is_full_leaf(key), "fin_mask of {key:?}, not a full leaf");
    subdivided_and_neighbours(h, key).1
}

/// Whether `key` is subdivided, and the directions in which its neighbour lies inside the
/// bounding hexagon and is subdivided, as a bit mask (the fins of `key` when it is a full
/// leaf), from the same lookups.
pub fn subdivided_and_neighbours(h: &Hierarchy, key: Key) -> (bool, u8) {
    let (own, mut mask) = h.subdivided_neighbourhood(key);
    let mut rest = mask;
    while rest != 0 {
        let d = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        if !key.neighbor(d).inside() {
            mask &= !(1 << d);
        }
    }
    (own, mask)
}

/// The mask as one cyclic run of 1 to 5 directions, or `None` (no fins, all six, or several
/// runs: the hexagon is of type SUBDIVIDE).
pub fn fin_strip(mask: u8) -> Option<FinStrip> {
    let len = mask.count_ones() as usize;
    if len == 0 || len == 6 {
        return None;
    }
    let first = (0..6).find(|&d| mask & (1 << d) != 0 && mask & (1 << ((d + 5) % 6)) == 0)?;
    let run = (0..6)
        .take_while(|&t| mask & (1 << ((first + t) % 6)) != 0)
        .count();
    (run == len).then_some(FinStrip { first, len })
}

/// What the rings around the occupied hexagons ask of a hexagon (Sec. 5.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Role {
    /// FIXED_CENTER_IN_RING.
    Fixed,
    /// MOVED_CENTER_IN_RING of the OCCUPIED_2 hexagon `owner`, shifted by `shift` (Sec. 5.4).
    Moved {
        /// The OCCUPIED_2 hexagon whose 1-ring the cell is in.
        owner: Key,
        /// What is added to the cell's centre: half the vector from `owner`'s centre to its
        /// corner nearest the point (`ring_shift`), in input coordinates.
        shift: Point,
    },
}

/// The ring roles of all hexagons around occupied hexagons, and the occupied hexagons whose
/// rings collide with another point's rings close enough to it that splitting both keeps
/// the shortest edge of Sec. 6.3 (they must be subdivided).
#[derive(Debug, Clone, Default)]
pub struct Rings {
    /// The role of each cell in a ring of an occupied hexagon; a cell not listed has none.
    pub roles: FxHashMap<Key, Role>,
    /// Cells claimed by the fixed ring of one point and the moved 1-ring of another, with the
    /// moved role they lost (Sec. 5.1 lists FIXED_CENTER_IN_RING first), and cells of two
    /// moved 1-rings of points too far apart to split, with the second one's role.
    pub contested: FxHashMap<Key, Role>,
    /// The occupied hexagons, each with its class (OCCUPIED_1 or OCCUPIED_2).
    pub occupied: FxHashMap<Key, Class>,
    /// The occupied hexagons to subdivide because their rings collide, sorted by
    /// `Key::packed`, without repeats.
    pub conflicts: Vec<Key>,
    /// The keys each cell's claims put into `conflicts` (so that `update` can redo a cell).
    pub conflict_at: FxHashMap<Key, Vec<Key>>,
    /// Every key ever put into `roles` or `occupied` (never taken out): `classify` asks it
    /// first, and most cells, far from any point, are FIXED_CENTER_REGULAR after one lookup
    /// in this table of 8 × 8 blocks, several times smaller than `roles`, instead of two
    /// missed lookups in the large tables (cache misses on big inputs).
    pub marked: KeySet,
}

/// The cells at lattice distance exactly `radius` (1 or 2) from `key`, inside the domain.
pub fn ring(key: Key, radius: i64) -> Vec<Key> {
    let mut out = Vec::new();
    for di in -radius..=radius {
        for dj in -radius..=radius {
            let dist = di.abs().max(dj.abs()).max((di + dj).abs());
            if dist == radius {
                let c = Key::new(key.k, key.i + di, key.j + dj);
                if c.inside() {
                    out.push(c);
                }
            }
        }
    }
    out
}

/// OCCUPIED_1 when the point lies in the (closed) half-sized hexagon, else OCCUPIED_2.
pub fn occupied_class(h: &Hierarchy, key: Key, p: Point) -> Class {
    if h.closed_contains(key.central_child(), p) {
        Class::Occupied1
    } else {
        Class::Occupied2
    }
}

/// Half the vector from the centre of an OCCUPIED_2 hexagon to its corner nearest the point
/// (Sec. 5.4, "Centers of MOVED_CENTER_IN_RING-hexagons"); ties go to the lower corner index.
pub fn ring_shift(h: &Hierarchy, key: Key, p: Point) -> Point {
    ring_shift_ranked(h, key, p, 0)
}

/// Half the vector from the centre of an OCCUPIED_2 hexagon to its corner of rank `rank` in
/// distance from the point (0: the nearest, as Sec. 5.4; 1: the second nearest, the
/// alternative `extended` tries for a point near the border of two corners' regions); ties
/// go to the lower corner index.
pub fn ring_shift_ranked(h: &Hierarchy, key: Key, p: Point, rank: usize) -> Point {
    let c = h.lattice.center(key);
    let corners = h.lattice.corners(key);
    let mut order: Vec<usize> = (0..6).collect();
    order.sort_by(|&a, &b| {
        dist2(corners[a], p)
            .total_cmp(&dist2(corners[b], p))
            .then(a.cmp(&b))
    });
    let best = order[rank.min(5)];
    [
        (corners[best][0] - c[0]) / 2.0,
        (corners[best][1] - c[1]) / 2.0,
    ]
}

/// Splitting a pair gives hexagons of radius r/2, and a moved ring cell can lie (3√3/4)·(r/2)
/// from an OCCUPIED_2 point on its hexagon's edge: that keeps the shortest edge
/// l_min = √7/(12√3)·d of Sec. 6.3 only for points at most (3√3/4)/(√7/(12√3))/2·r ≈ 5.10·r
/// apart. Farther apart the pair is not split and `extended::settle_contested` places the
/// cells its rings share.
fn splittable(h: &Hierarchy, key: Key, other: Key) -> bool {
    let reach = 3.0 * 3f64.sqrt() / 4.0 / (7f64.sqrt() / (12.0 * 3f64.sqrt())) / 2.0;
    let p = h.points[h.occupants(key)[0] as usize];
    let q = h.points[h.occupants(other)[0] as usize];
    dist2(p, q).sqrt() <= reach * h.lattice.radius(key.k)
}

/// The role the occupied hexagon `key` (of class `class`) gives the cells of its 1-ring.
fn first_role(h: &Hierarchy, key: Key, class: Class) -> Role {
    match class {
        Class::Occupied1 => Role::Fixed,
        _ => Role::Moved {
            owner: key,
            shift: ring_shift(h, key, h.points[h.occupants(key)[0] as usize]),
        },
    }
}

/// The claim of the occupied hexagon `key` on `cell`, one of its ring cells: the rules of
/// Sec. 5.1 in the order of `rings`. Each cell's roles, contests and conflicts depend only on
/// the claims on that cell, in the order of the claimants' keys.
fn claim(h: &Hierarchy, r: &mut Rings, key: Key, cell: Key, role: Role) {
    if r.occupied.contains_key(&cell) {
        if splittable(h, key, cell) {
            r.conflict_at.entry(cell).or_default().extend([key, cell]);
        }
        return;
    }
    match (r.roles.get(&cell).copied(), role) {
        (None, _) => {
            r.marked.insert(cell);
            r.roles.insert(cell, role);
        }
        // FIXED_CENTER_IN_RING comes first in the classification of Sec. 5.1: a cell in the
        // fixed ring of one point and the moved 1-ring of another keeps its centre. Sec. 6.3
        // lets OCCUPIED_2 hexagons three apart share such cells; subdividing them instead
        // would go one level below its r_min.
        (Some(old), Role::Fixed) => {
            if let Role::Moved { .. } = old {
                r.contested.entry(cell).or_insert(old);
            }
            r.roles.insert(cell, Role::Fixed);
        }
        (Some(Role::Fixed), Role::Moved { .. }) => {
            r.contested.entry(cell).or_insert(role);
        }
        (Some(Role::Moved { owner, .. }), Role::Moved { .. }) => {
            // Two moved 1-rings overlap only when the occupied hexagons are two apart, closer
            // than Sec. 6.3 assumes.
            if splittable(h, key, owner) {
                r.conflict_at.entry(cell).or_default().extend([key, owner]);
            } else {
                r.contested.entry(cell).or_insert(role);
            }
        }
    }
}

impl Rings {
    /// The conflict list from the conflicts recorded per cell.
    fn collect_conflicts(&mut self) {
        let mut c: Vec<Key> = self.conflict_at.values().flatten().copied().collect();
        c.sort_unstable_by_key(|k| k.packed());
        c.dedup();
        self.conflicts = c;
    }

    /// Brings the rings up to date with `h` from the hexagons whose occupancy may have
    /// changed since they were made (`Hierarchy::take_occupancy_changes`, in any order, with
    /// repeats), without listing every occupied hexagon: only the cells within two of a
    /// hexagon that stopped or started being occupied are claimed again, by every occupied
    /// hexagon within two of them in key order, which gives each of them what `rings` gives
    /// it.
    pub fn update_changed(&mut self, h: &Hierarchy, mut changed: Vec<Key>) {
        changed.sort_unstable_by_key(|k| k.packed());
        changed.dedup();
        let removed: Vec<Key> = changed
            .iter()
            .copied()
            .filter(|k| self.occupied.contains_key(k) && !h.is_occupied(*k))
            .collect();
        let added: Vec<Key> = changed
            .iter()
            .copied()
            .filter(|k| !self.occupied.contains_key(k) && h.is_occupied(*k))
            .collect();
        if removed.is_empty() && added.is_empty() {
            return;
        }
        for k in &removed {
            self.occupied.remove(k);
        }
        for &k in &added {
            let p = h.points[h.occupants(k)[0] as usize];
            self.marked.insert(k);
            self.occupied.insert(k, occupied_class(h, k, p));
        }
        let mut cells: Vec<Key> = Vec::new();
        for &k in removed.iter().chain(&added) {
            cells.push(k);
            for di in -2i64..=2 {
                for dj in -2i64..=2 {
                    if (di + dj).abs() <= 2 {
                        cells.push(Key::new(k.k, k.i + di, k.j + dj));
                    }
                }
            }
        }
        cells.sort_unstable_by_key(|k| k.packed());
        cells.dedup();
        for &cell in &cells {
            self.roles.remove(&cell);
            self.contested.remove(&cell);
            self.conflict_at.remove(&cell);
        }
        for &cell in &cells {
            if !cell.inside() {
                continue;
            }
            // The occupied hexagons whose 1-ring or 2-ring holds `cell`, in key order.
            let mut claimants: Vec<(Key, i64)> = Vec::new();
            for di in -2i64..=2 {
                for dj in -2i64..=2 {
                    let d = di.abs().max(dj.abs()).max((di + dj).abs());
                    if d == 0 || d > 2 {
                        continue;
                    }
                    let o = Key::new(cell.k, cell.i - di, cell.j - dj);
                    // `marked` holds every key `occupied` ever held: most cells around a
                    // change are ruled out by a word just read instead of a table probe.
                    if self.marked.contains(&o) && self.occupied.contains_key(&o) {
                        claimants.push((o, d));
                    }
                }
            }
            claimants.sort_unstable_by_key(|c| c.0.packed());
            for (o, d) in claimants {
                let class = self.occupied[&o];
                let role = match (d, class) {
                    (1, _) => first_role(h, o, class),
                    (2, Class::Occupied2) => Role::Fixed,
                    _ => continue,
                };
                claim(h, self, o, cell, role);
            }
        }
        self.collect_conflicts();
    }
}

/// Builds the rings of every occupied hexagon (which must be full leaves holding one point).
pub fn rings(h: &Hierarchy) -> Rings {
    let occupied = h.occupied_sorted();
    // Up to 18 ring cells per point: sized once, the table is not rebuilt while it fills.
    let mut r = Rings {
        roles: FxHashMap::with_capacity_and_hasher(18 * occupied.len(), Default::default()),
        occupied: FxHashMap::with_capacity_and_hasher(occupied.len(), Default::default()),
        marked: KeySet::with_capacity(19 * occupied.len()),
        ..Rings::default()
    };
    for &key in &occupied {
        let p = h.points[h.occupants(key)[0] as usize];
        r.marked.insert(key);
        r.occupied.insert(key, occupied_class(h, key, p));
    }
    for &key in &occupied {
        let class = r.occupied[&key];
        let first = first_role(h, key, class);
        for cell in ring(key, 1) {
            claim(h, &mut r, key, cell, first);
        }
        if class == Class::Occupied2 {
            for cell in ring(key, 2) {
                claim(h, &mut r, key, cell, Role::Fixed);
            }
        }
    }
    r.collect_conflicts();
    r
}

/// The class of a full leaf with the (non-empty) fin mask `mask`: MOVED_CENTER_1/2/3 for one
/// run of one to three fins, else SUBDIVIDE (Sec. 5.1).
pub fn fin_class(mask: u8) -> (Class, Option<FinStrip>) {
    debug_assert!(mask != 0);
    match fin_strip(mask) {
        Some(s) if s.len == 1 => (Class::MovedCenter1, Some(s)),
        Some(s) if s.len == 2 => (Class::MovedCenter2, Some(s)),
        Some(s) if s.len == 3 => (Class::MovedCenter3, Some(s)),
        _ => (Class::Subdivide, None),
    }
}

/// The class of a full leaf.
pub fn classify(h: &Hierarchy, rings: &Rings, key: Key) -> (Class, Option<FinStrip>) {
    let mask = fin_mask(h, key);
    if mask != 0 {
        return fin_class(mask);
    }
    if !rings.marked.contains(&key) {
        return (Class::FixedCenterRegular, None);
    }
    if let Some(&c) = rings.occupied.get(&key) {
        return (c, None);
    }
    match rings.roles.get(&key) {
        Some(Role::Fixed) => (Class::FixedCenterInRing, None),
        Some(Role::Moved { .. }) => (Class::MovedCenterInRing, None),
        None => (Class::FixedCenterRegular, None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_run_of_consecutive_fins_is_a_strip_even_across_direction_zero() {
        assert_eq!(fin_strip(0b000001), Some(FinStrip { first: 0, len: 1 }));
        assert_eq!(fin_strip(0b100001), Some(FinStrip { first: 5, len: 2 }));
        assert_eq!(fin_strip(0b000111), Some(FinStrip { first: 0, len: 3 }));
        let s = fin_strip(0b110000).expect("a strip");
        assert_eq!((s.left(), s.right()), (3, 0));
        let t = fin_strip(0b000111).expect("a strip");
        assert_eq!(t.top(), 4);
    }

    #[test]
    fn split_runs_no_fins_and_six_fins_are_not_strips() {
        assert_eq!(fin_strip(0), None);
        assert_eq!(fin_strip(0b000101), None);
        assert_eq!(fin_strip(0b111111), None);
    }

    #[test]
    fn rings_have_six_and_twelve_cells_inside_the_domain() {
        let key = Key::new(4, 1, 2);
        assert_eq!(ring(key, 1).len(), 6);
        assert_eq!(ring(key, 2).len(), 12);
    }
}
