//! The MOVED_CENTER_3 topology of `hex` (paper 000 Sec. 5.2 and 5.4, `hexmesh::hex::mc3`):
//! every chain of MOVED_CENTER_3 hexagons around a MOVED_CENTER_4 top (n = 1…4) and the
//! blossom (n = 6), built on a real hierarchy, meets the Sec. 6 bounds at every triangle that
//! touches a fin centre, a chain centre or the top; the Fig. 6 rule and the rule on
//! non-consecutive MOVED_CENTER_3 hexagons fire; the datasets' triangle counts do not exceed
//! paper 000 Table 1 where they now are below it.

use hexmesh::geom::{dist, Point};
use hexmesh::hex::classify::rings;
use hexmesh::hex::dual::{extract_patched, Placement};
use hexmesh::hex::extended::{delaunay_violations, mesh_extended, relocations};
use hexmesh::hex::lattice::{Key, Lattice, DIRS};
use hexmesh::hex::mc3::{verdict, Chain, Verdict};
use hexmesh::hex::Hierarchy;
use hexmesh::mesher::Budget;
use hexmesh::{Hexagon, Params};

const LEVEL: u8 = 3;

fn add(a: Key, d: usize) -> Key {
    a.neighbor(d)
}

/// A hierarchy whose leaves are all of level 3 (no points), the top T at the root centre.
fn uniform() -> Hierarchy {
    let lattice = Lattice::new(Hexagon::new([0.0, 0.0], 1.0));
    let mut h = Hierarchy::new(lattice, Vec::new(), Budget::default());
    for k in 0..LEVEL {
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

fn top() -> Key {
    Key::new(LEVEL, 0, 0)
}

/// The subdivided neighbours beyond the fins of the chain T + e_s … T + e_{s+n-1}.
fn beyond_fins(start: usize, n: usize) -> Vec<Key> {
    beyond_fins_of(top(), start, n)
}

fn beyond_fins_of(t: Key, start: usize, n: usize) -> Vec<Key> {
    let mut out = Vec::new();
    for i in 0..n {
        let k = add(t, (start + i) % 6);
        for m in 0..3 {
            out.push(add(k, (start + i + 5 + m) % 6));
        }
    }
    out.sort();
    out.dedup();
    out
}

fn chain_hierarchy(start: usize, n: usize) -> Hierarchy {
    let mut h = uniform();
    for key in beyond_fins(start, n) {
        h.subdivide(key).expect("subdivides");
    }
    h
}

fn radius_ratio(t: [Point; 3]) -> f64 {
    let (a, b, c) = (dist(t[1], t[2]), dist(t[0], t[2]), dist(t[0], t[1]));
    let s = (a + b + c) / 2.0;
    let area = (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt();
    a * b * c / (4.0 * area) / (2.0 * area / s)
}

fn angle(a: Point, b: Point, c: Point) -> f64 {
    hexmesh::geom::angle_deg(a, b, c)
}

/// Builds the relocated dual and checks every triangle touching a vertex of the chain (fin
/// centres, chain centres, the top): angles in [α, 90°] (1e-6° slack), radius ratio at most
/// 1.20787, no exact Delaunay violation among them. Returns how many triangles were checked.
fn assert_chain_bounds(h: &Hierarchy, expect: Chain) -> usize {
    let r = rings(h);
    assert_eq!(verdict(h, &r, expect.top), Verdict::Chain(expect));
    let (moved, patch) = relocations(h, &r);
    let (mesh, keys) = extract_patched(h, Placement::Relocated, &moved, &patch);
    let mut watched: Vec<Key> = patch.fin_owner.keys().copied().collect();
    watched.push(expect.top.canonical());
    for i in 0..expect.len {
        watched.push(add(expect.top, (expect.start + i) % 6).canonical());
    }
    let touches = |t: usize| {
        mesh.triangles[t]
            .iter()
            .any(|&v| watched.contains(&keys[v as usize]))
    };
    let lo = hexmesh::quality::HEX.min_angle - 1e-6;
    let mut checked = 0;
    for t in (0..mesh.triangles.len()).filter(|&t| touches(t)) {
        let [a, b, c] = mesh.corners(t);
        for (p, q, s) in [(a, b, c), (b, c, a), (c, a, b)] {
            let x = angle(p, q, s);
            assert!(
                (lo..=90.0 + 1e-6).contains(&x),
                "chain {expect:?}: triangle {t} has an angle of {x}°"
            );
        }
        let rr = radius_ratio([a, b, c]);
        assert!(rr <= 1.20787, "chain {expect:?}: radius ratio {rr}");
        checked += 1;
    }
    for (t, u) in delaunay_violations(&mesh) {
        assert!(
            !touches(t) && !touches(u),
            "chain {expect:?}: triangles {t} and {u} are not Delaunay"
        );
    }
    assert!(hexmesh::hex::dual::first_inverted(&mesh).is_none());
    checked
}

#[test]
fn a_single_moved_center_3_hexagon_meets_the_bounds_in_every_orientation() {
    for start in 0..6 {
        let h = chain_hierarchy(start, 1);
        let c = Chain {
            top: top(),
            start,
            len: 1,
        };
        // 12 triangles in the rebuilt star, 3 more at the top.
        assert!(assert_chain_bounds(&h, c) >= 15);
    }
}

#[test]
fn chains_of_two_to_four_moved_center_3_hexagons_meet_the_bounds() {
    for n in 2..=4 {
        for start in 0..6 {
            let h = chain_hierarchy(start, n);
            let c = Chain {
                top: top(),
                start,
                len: n,
            };
            assert_chain_bounds(&h, c);
        }
    }
}

#[test]
fn a_blossom_meets_the_bounds_with_sixty_triangles() {
    let h = chain_hierarchy(0, 6);
    let c = Chain {
        top: top(),
        start: 0,
        len: 6,
    };
    assert_eq!(assert_chain_bounds(&h, c), 60);
}

#[test]
fn a_moved_center_2_hexagon_beside_a_pair_gets_its_far_neighbour_subdivided() {
    // Chain T + e_0, T + e_1; its right neighbour R = T + e_2 gets a second fin (MOVED_CENTER_2)
    // from T + 2·e_2.
    let mut h = chain_hierarchy(0, 2);
    let r_end = add(top(), 2);
    h.subdivide(add(r_end, 2)).expect("subdivides");
    let r = rings(&h);
    let far = add(r_end, 3);
    assert_eq!(verdict(&h, &r, top()), Verdict::Subdivide(vec![far]));
    h.subdivide(far).expect("subdivides");
    let r = rings(&h);
    let grown = Chain {
        top: top(),
        start: 0,
        len: 3,
    };
    assert_eq!(verdict(&h, &r, top()), Verdict::Chain(grown));
    assert_chain_bounds(&h, grown);
}

#[test]
fn a_top_of_two_non_consecutive_moved_center_3_hexagons_is_subdivided() {
    let mut h = uniform();
    let mut cells = beyond_fins(0, 1);
    cells.extend(beyond_fins(3, 1));
    for key in cells {
        h.subdivide(key).expect("subdivides");
    }
    let r = rings(&h);
    assert_eq!(verdict(&h, &r, top()), Verdict::Subdivide(vec![top()]));
}

#[test]
fn two_chains_facing_each_other_meet_the_bounds_and_the_exact_empty_circle_test() {
    // Chains of four around T1 and T2 = T1 + e_0 + e_1 share both end neighbours
    // (T1 + e_0, T1 + e_1) and the subdivided hexagons beside them: each shared end is a pair
    // of right triangles on one circle.
    let t1 = top();
    let t2 = add(add(t1, 0), 1);
    let mut h = uniform();
    let mut cells = beyond_fins_of(t1, 2, 4);
    cells.extend(beyond_fins_of(t2, 5, 4));
    for key in cells {
        h.subdivide(key).expect("subdivides");
    }
    for (t, start) in [(t1, 2), (t2, 5)] {
        let c = Chain {
            top: t,
            start,
            len: 4,
        };
        assert_chain_bounds(&h, c);
    }
}

#[test]
fn the_lattice_directions_are_counter_clockwise_as_the_chains_assume() {
    // e_{j} + e_{j+2} = e_{j+1}: the chain construction relies on it.
    for j in 0..6 {
        let (a, b, c) = (DIRS[j], DIRS[(j + 1) % 6], DIRS[(j + 2) % 6]);
        assert_eq!((a.0 + c.0, a.1 + c.1), b);
    }
}

/// The triangle counts of paper 000 Table 1 bound the new counts where they are below them
/// (line-100, about 21,000 against 18,667, is not): close-pair itself, plane-100 as the mean
/// over ten seeds, as the paper's random sets are.
#[test]
fn plane_100_and_close_pair_are_not_above_the_paper_counts() {
    let count = |input: &hexmesh::Pslg| {
        let out = mesh_extended(input, &Params::default()).expect("meshes");
        assert!(out.stop.is_none());
        out.mesh.triangles.len()
    };
    let close = count(&hexmesh::datasets::by_name("close-pair").expect("dataset"));
    assert!(close <= 684, "close-pair: {close} triangles, paper 684");
    let seed = hexmesh::datasets::default_seed("plane-100").expect("random");
    let total: usize = (0..10)
        .map(|t| count(&hexmesh::datasets::random_with_seed("plane-100", seed + t).expect("set")))
        .sum();
    let mean = total as f64 / 10.0;
    assert!(
        mean <= 12_748.0,
        "plane-100: mean {mean} triangles, paper 12,748"
    );
}

#[test]
#[ignore = "a few seconds in a test build"]
fn plane_1k_and_plane_2k_are_not_above_the_paper_counts() {
    for (name, paper) in [("plane-1k", 127_729), ("plane-2k", 268_138)] {
        let input = hexmesh::datasets::by_name(name).expect("dataset");
        let out = mesh_extended(&input, &Params::default()).expect("meshes");
        assert!(out.stop.is_none());
        let n = out.mesh.triangles.len();
        assert!(n <= paper, "{name}: {n} triangles, paper {paper}");
    }
}
