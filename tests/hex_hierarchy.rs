//! The hexagon hierarchy (paper 000 Sec. 3) and the point-location rule: splits, joins,
//! balancing, and exact, deterministic assignment of points on hexagon edges and corners.

use hexmesh::hex::lattice::Key;
use hexmesh::hex::{mesh_with_hierarchy, Cell, Hierarchy, Lattice};
use hexmesh::{Budget, Hexagon, Params, Pslg};

fn unit() -> Hexagon {
    Hexagon::new([0.0, 0.0], 1.0)
}

fn hierarchy(points: Vec<[f64; 2]>) -> Hierarchy {
    Hierarchy::new(Lattice::new(unit()), points, Budget::default())
}

#[test]
fn splitting_the_root_gives_a_central_hexagon_and_six_virtual_full_boundary_hexagons() {
    let mut h = hierarchy(vec![]);
    h.subdivide(Key::ROOT).unwrap();
    assert_eq!(
        h.cell(Key::ROOT.central_child()),
        Cell::Full { subdivided: false }
    );
    for d in 0..6 {
        let c = Key::ROOT.edge_child(d);
        assert!(c.on_boundary());
        assert_eq!(h.cell(c), Cell::Full { subdivided: false }, "direction {d}");
    }
}

#[test]
fn splitting_one_hexagon_makes_fins_and_splitting_its_neighbour_joins_them() {
    let mut h = hierarchy(vec![]);
    h.subdivide(Key::ROOT).unwrap();
    let a = Key::ROOT.central_child();
    h.subdivide(a).unwrap();
    let b = a.neighbor(0);
    let between = a.edge_child(0);
    assert_eq!(between, b.edge_child(3));
    assert_eq!(
        h.cell(between),
        Cell::Semi {
            owner: a,
            fin_of: b
        }
    );
    h.subdivide(b).unwrap();
    assert_eq!(h.cell(between), Cell::Full { subdivided: false });
    assert_eq!(between.split_counter(), 0);
    assert_eq!(a.central_child().split_counter(), 2);
    h.check_invariants().unwrap();
}

#[test]
fn balancing_splits_the_coarser_neighbour_before_a_level_gap_of_two() {
    let mut h = hierarchy(vec![]);
    h.subdivide(Key::ROOT).unwrap();
    let a = Key::ROOT.central_child();
    h.subdivide(a).unwrap();
    // The central child of `a` is surrounded by semi-hexagons (fins of a's neighbours);
    // splitting it must first join them by splitting those neighbours.
    h.subdivide(a.central_child()).unwrap();
    for d in 0..6 {
        assert!(
            h.is_subdivided(a.neighbor(d)),
            "neighbour {d} was not split"
        );
    }
    h.check_invariants().unwrap();
}

#[test]
fn a_point_on_a_shared_edge_goes_to_the_lower_lattice_index() {
    let lat = Lattice::new(unit());
    let mut h = Hierarchy::new(lat, vec![], Budget::default());
    h.subdivide(Key::ROOT).unwrap();
    // The edge between edge children (1, 1, 0) and (1, 0, 1): (0, 1) < (1, 0).
    let p = lat.center(Key::new(2, 1, 1));
    assert_eq!(h.leaf_of(p), Key::new(1, 0, 1));
    // The edge between the central child and edge child (1, 1, 0): (0, 0) wins.
    let q = lat.center(Key::new(2, 1, 0));
    assert_eq!(h.leaf_of(q), Key::new(1, 0, 0));
}

#[test]
fn a_point_on_a_corner_of_three_hexagons_goes_to_the_lowest_lattice_index() {
    let lat = Lattice::new(unit());
    let mut h = Hierarchy::new(lat, vec![], Budget::default());
    h.subdivide(Key::ROOT).unwrap();
    let centre = Key::ROOT.central_child();
    // Corner 0 of the central child is shared with (1, 1, 0) and (1, 1, -1).
    assert_eq!(h.leaf_of(lat.corner(centre, 0)), centre);
    // One level down, corner 2 of (2, 1, 0) is shared with (2, 1, 1) and (2, 0, 1): (0, 1) wins.
    h.subdivide(centre).unwrap();
    let corner = lat.corner(Key::new(2, 1, 0), 2);
    assert_eq!(corner, lat.corner(Key::new(2, 0, 1), 0));
    assert_eq!(h.leaf_of(corner), Key::new(2, 0, 1));
}

#[test]
fn points_on_edges_and_corners_end_in_the_hexagon_the_rule_names_after_refinement() {
    let lat = Lattice::new(unit());
    let pts = vec![
        lat.corner(Key::new(3, 1, 0), 2),
        lat.center(Key::new(4, 3, 1)),
        lat.center(Key::new(2, 1, 1)),
        lat.corner(Key::new(5, -4, 7), 5),
    ];
    let input = Pslg {
        points: pts,
        hexagon: Some(unit()),
        ..Pslg::default()
    };
    let (h, stop) = mesh_with_hierarchy(&input, &Params::default()).unwrap();
    assert!(stop.is_none());
    h.check_invariants().unwrap();
    h.check_refined().unwrap();
}

#[test]
fn refinement_ends_with_each_point_alone_in_a_ring_of_empty_full_hexagons() {
    let mut pts = Vec::new();
    for t in 0..300 {
        let s = t as f64 * 0.618_033_988_749_895;
        pts.push([s.fract(), (s * 1.7).fract() * 0.3]);
    }
    let (h, stop) = mesh_with_hierarchy(&Pslg::from_points(pts), &Params::default()).unwrap();
    assert!(stop.is_none());
    h.check_invariants().unwrap();
    h.check_refined().unwrap();
}

#[test]
fn the_leaves_listed_over_threads_and_the_central_leaves_come_in_the_order_of_the_iterator() {
    // Enough points that the subdivided set has more than the 1,024 blocks from which
    // `full_leaves_where` splits them over threads.
    let pts: Vec<[f64; 2]> = (0..6000)
        .map(|t| {
            let s = t as f64 * 0.618_033_988_749_895;
            [s.fract() * 0.9, (s * 1.7).fract() * 0.4]
        })
        .collect();
    let params = Params::default().with_threads(std::num::NonZeroUsize::new(3).unwrap());
    let (h, _) = mesh_with_hierarchy(&Pslg::from_points(pts), &params).unwrap();
    let all: Vec<Key> = h.full_leaves_iter().collect();
    assert_eq!(all.len(), h.full_leaves);
    assert_eq!(h.full_leaves_where(|_| true), all);
    let odd = |c: &Key| (c.i + c.j) % 3 == 1;
    let some: Vec<Key> = all.iter().copied().filter(odd).collect();
    assert_eq!(h.full_leaves_where(|c| odd(&c)), some);
    // A central child (k + 1, 2i, 2j) has both coordinates even; an edge child has one odd.
    let from_all: Vec<Key> = all
        .iter()
        .copied()
        .filter(|c| c.k > 0 && c.i % 2 == 0 && c.j % 2 == 0)
        .collect();
    let central: Vec<Key> = h.central_leaves_iter().collect();
    assert!(central.len() > 10_000, "{}", central.len());
    assert_eq!(central, from_all);
}
