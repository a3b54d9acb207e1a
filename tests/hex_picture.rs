//! The `--hexagons` picture of the extended refinement (`hex`): full hexagons coloured by their
//! class of paper 000 Sec. 5.1, with a legend, as in the paper's Figs. 5 and 7.

use hexmesh::hex::classify::Class;
use hexmesh::hex::picture::{full_leaf_classes, write_extended_hexagons_svg, CLASS_COLOURS};
use hexmesh::Params;

fn colour(class: Class) -> &'static str {
    CLASS_COLOURS.iter().find(|(c, _)| *c == class).unwrap().1
}

#[test]
fn every_class_has_its_own_colour() {
    let mut colours: Vec<&str> = CLASS_COLOURS.iter().map(|(_, c)| *c).collect();
    colours.sort();
    colours.dedup();
    assert_eq!(colours.len(), CLASS_COLOURS.len());
}

#[test]
fn the_close_pair_picture_colours_its_hexagons_by_class_with_a_legend() {
    let input = hexmesh::datasets::by_name("close-pair").unwrap();
    let path = std::env::temp_dir().join(format!("hexmesh-hex-picture-{}.svg", std::process::id()));
    write_extended_hexagons_svg(&input, &Params::default(), &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();

    let run = hexmesh::hex::extended::mesh_extended(&input, &Params::default()).unwrap();
    let classes = full_leaf_classes(&run.hierarchy);
    // The two close points sit in occupied hexagons, each inside rings of fixed centres, and
    // the grading away from them leaves hexagons with fins.
    let occupied = classes
        .values()
        .filter(|c| matches!(c, Class::Occupied1 | Class::Occupied2))
        .count();
    assert_eq!(occupied, 2, "{classes:?}");
    for (class, n) in CLASS_COLOURS
        .iter()
        .map(|&(c, _)| (c, classes.values().filter(|&&x| x == c).count()))
    {
        let entry = format!("{} ({n})", class.name());
        assert_eq!(svg.contains(&entry), n > 0, "legend entry {entry}");
        if n > 0 {
            assert!(
                svg.contains(&format!(r#"fill="{}""#, colour(class))),
                "{class:?}"
            );
        }
    }
    assert!(classes.values().any(|c| c.has_fins()), "fins drawn");
    assert!(svg.matches("<polygon").count() > run.mesh.triangles.len());
}
