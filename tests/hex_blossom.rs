//! The local coarsening of paper 000 Sec. 5.3 (`hexmesh::hex::blossom`): 37 hexagons of level
//! k + 1 become 7 of level k where every hexagon within the 4-ring is FIXED_CENTER_REGULAR; the
//! seven form a blossom (six MOVED_CENTER_3 hexagons around their top) whose 60 triangles meet
//! the Sec. 6 bounds; anything but a plain region within the 4-ring prevents it; the datasets
//! get blossoms and keep every bound.

use hexmesh::geom::{dist, Point};
use hexmesh::hex::blossom::{can_form, candidate_tops, coarsen, coarsen_in_order};
use hexmesh::hex::classify::{classify, rings, Class};
use hexmesh::hex::dual::{extract_patched, first_inverted, Placement};
use hexmesh::hex::extended::{delaunay_violations, mesh_extended, relocations};
use hexmesh::hex::lattice::{Key, Lattice};
use hexmesh::hex::mc3::{verdict, Chain, Verdict};
use hexmesh::hex::{Cell, Hierarchy};
use hexmesh::mesher::Budget;
use hexmesh::quality::verdict as quality_verdict;
use hexmesh::{Hexagon, Params};

/// The lattice of the unit hexagon at the origin.
fn unit_lattice() -> Lattice {
    Lattice::new(Hexagon::new([0.0, 0.0], 1.0))
}

/// A hierarchy whose leaves are all of level `level` (no points).
fn uniform(level: u8) -> Hierarchy {
    uniform_with(level, Vec::new())
}

/// `uniform` with the input points `points`.
fn uniform_with(level: u8, points: Vec<hexmesh::Point>) -> Hierarchy {
    let mut h = Hierarchy::new(unit_lattice(), points, Budget::default());
    for k in 0..level {
        let span = 2i64 << k;
        for i in -span..=span {
            for j in -span..=span {
                let key = Key::new(k, i, j);
                if key.inside() && h.is_full_leaf(key) {
                    h.subdivide(key).expect("subdivides");
                }
            }
        }
    }
    h
}

/// The full unsubdivided hexagons of `h`, sorted.
fn full_leaf_keys(h: &Hierarchy) -> Vec<Key> {
    h.leaves()
        .into_iter()
        .filter(|(_, c)| *c == Cell::Full { subdivided: false })
        .map(|(k, _)| k)
        .collect()
}

fn full_leaves(h: &Hierarchy) -> usize {
    full_leaf_keys(h).len()
}

fn radius_ratio(t: [Point; 3]) -> f64 {
    let (a, b, c) = (dist(t[1], t[2]), dist(t[0], t[2]), dist(t[0], t[1]));
    let s = (a + b + c) / 2.0;
    let area = (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt();
    a * b * c / (4.0 * area) / (2.0 * area / s)
}

#[test]
fn a_plain_region_coarsens_into_a_blossom_of_seven_hexagons_with_sixty_triangles() {
    let mut h = uniform(4);
    let top = Key::new(3, 0, 0);
    let r = rings(&h);
    assert!(can_form(&h, &r, top));
    let before = full_leaves(&h);
    let merged = coarsen(&mut h, &r, &[top]);
    assert_eq!(merged.len(), 7);
    assert_eq!(before - full_leaves(&h), 30, "37 hexagons become 7");
    h.check_invariants().expect("balanced");
    let r = rings(&h);
    for d in 0..6 {
        let n = top.neighbor(d);
        assert!(h.is_full_leaf(n));
        let (class, strip) = classify(&h, &r, n);
        assert_eq!(class, Class::MovedCenter3, "neighbour {d}");
        assert_eq!(n.neighbor(strip.expect("a strip").top()), top);
    }
    assert_eq!(
        verdict(&h, &r, top),
        Verdict::Chain(Chain {
            top,
            start: 0,
            len: 6
        })
    );
    // The dual around the blossom: 60 triangles touching its fins, its six centres or its top,
    // every one within the bounds of Sec. 6.
    let (moved, patch) = relocations(&h, &r);
    let (mesh, keys) = extract_patched(&h, Placement::Relocated, &moved, &patch);
    let mut watched: Vec<Key> = patch.fin_owner.keys().copied().collect();
    watched.push(top.canonical());
    watched.extend((0..6).map(|d| top.neighbor(d).canonical()));
    let touches = |t: usize| {
        mesh.triangles[t]
            .iter()
            .any(|&v| watched.contains(&keys[v as usize]))
    };
    let lo = hexmesh::quality::HEX.min_angle - 1e-6;
    let mut count = 0;
    for t in (0..mesh.triangles.len()).filter(|&t| touches(t)) {
        let [a, b, c] = mesh.corners(t);
        for (p, q, s) in [(a, b, c), (b, c, a), (c, a, b)] {
            let x = hexmesh::geom::angle_deg(p, q, s);
            assert!((lo..=90.0 + 1e-6).contains(&x), "triangle {t}: {x}°");
        }
        assert!(radius_ratio([a, b, c]) <= 1.20787);
        count += 1;
    }
    assert_eq!(count, 60);
    assert!(first_inverted(&mesh).is_none());
    assert!(delaunay_violations(&mesh).is_empty());
}

#[test]
fn anything_but_a_plain_region_within_the_four_ring_prevents_the_blossom() {
    let top = Key::new(3, 0, 0);
    let c = top.central_child();
    // A subdivided cell at distance 5 of the centre gives a fin to a cell at distance 4.
    let mut h = uniform(4);
    h.subdivide(Key::new(4, c.i + 5, c.j)).expect("subdivides");
    assert!(!can_form(&h, &rings(&h), top), "a fin in the 4-ring");
    // At distance 6 the fins fall outside the 4-ring.
    let mut h = uniform(4);
    h.subdivide(Key::new(4, c.i + 6, c.j)).expect("subdivides");
    assert!(can_form(&h, &rings(&h), top), "fins beyond the 4-ring");
    // A point in the 4-ring: occupied and ringed cells are not FIXED_CENTER_REGULAR.
    let far = unit_lattice().center(Key::new(4, c.i + 4, c.j));
    let h = uniform_with(4, vec![far]);
    assert!(h.is_occupied(Key::new(4, c.i + 4, c.j)));
    assert!(!can_form(&h, &rings(&h), top), "a point in the 4-ring");
    // A top whose neighbour is not subdivided has no 37 cells to coarsen.
    let h = uniform(3);
    assert!(!can_form(&h, &rings(&h), top));
}

#[test]
fn candidates_are_tried_in_key_order_and_blossoms_never_overlap() {
    let mut h = uniform(5);
    let r = rings(&h);
    let tops = candidate_tops(&h, &r, full_leaf_keys(&h));
    let merged = coarsen(&mut h, &r, &tops);
    assert!(merged.len() >= 14, "a level-5 plane holds several blossoms");
    let mut unique = merged.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), merged.len(), "blossoms share no hexagon");
    h.check_invariants().expect("balanced");
    // The same tops in another order give the same blossoms.
    let mut again = uniform(5);
    let mut reversed = tops.clone();
    reversed.reverse();
    assert_eq!(coarsen(&mut again, &r, &reversed), merged);
}

#[test]
fn coarsening_over_threads_forms_the_blossoms_of_trying_each_top_in_order() {
    // A level-8 plane (more than 8,192 candidate tops: split over threads) with a few
    // points, whose rings keep blossoms away from them; neighbouring tops both pass the
    // condition at first, and only the first in key order may form.
    let points: Vec<hexmesh::Point> = (0..12)
        .map(|n| {
            let a = n as f64 * 0.9;
            [0.6 * a.cos() * (n as f64 / 12.0), 0.5 * a.sin()]
        })
        .collect();
    for threads in [1, 2, 3] {
        let mut h = uniform_with(8, points.clone());
        h.set_threads(threads);
        let r = rings(&h);
        let tops = candidate_tops(&h, &r, full_leaf_keys(&h));
        assert!(tops.len() > 8192, "{} tops", tops.len());
        let mut reference = h.clone();
        let want = coarsen_in_order(&mut reference, &r, &tops);
        let got = coarsen(&mut h, &r, &tops);
        assert!(want.len() > 7 * 100, "{} hexagons merged", want.len());
        // Compared whole, reported by length: the lists run to thousands of keys.
        assert!(
            got == want,
            "{threads} threads: {} hexagons merged, {} when tried in order",
            got.len(),
            want.len()
        );
        assert!(h.leaves() == reference.leaves(), "{threads} threads");
    }
}

#[test]
fn the_random_datasets_get_blossoms_and_keep_every_hex_bound() {
    for name in ["plane-100", "plane-1k"] {
        let input = hexmesh::datasets::by_name(name).expect("dataset");
        let run = mesh_extended(&input, &Params::default()).expect("meshes");
        assert!(run.stats.blossoms > 0, "{name}: no blossom formed");
        let bounds = hexmesh::registry::bounds("hex").expect("bounds");
        let v = quality_verdict(&run.mesh, Some(&input), Some(&bounds));
        assert!(v.passed(), "{name}: {v}");
    }
}
