//! The committed datasets are the same bytes on every machine: SHA-256 of each small
//! dataset's f64 bits, compared with digests committed here (they are generated from fixed seeds).
//! A changed digest means a changed dataset: regenerate `datasets/` and say why in the commit.
//! All six digests were also reproduced by an independent Python implementation (pcg64 from
//! its specification: 128-bit LCG, XSL-RR output; the letters with the same Taylor series).

use hexmesh::datasets::{self, SMALL};
use hexmesh::Pslg;
use sha2::{Digest, Sha256};

/// The digest input: counts as u64, then each point's x and y bits, each segment's two
/// indices, each hole's bits and the given hexagon (centre, circumradius), all little-endian.
fn digest(pslg: &Pslg) -> String {
    let mut h = Sha256::new();
    h.update((pslg.points.len() as u64).to_le_bytes());
    h.update((pslg.segments.len() as u64).to_le_bytes());
    h.update((pslg.holes.len() as u64).to_le_bytes());
    for p in pslg.points.iter().chain(&pslg.holes) {
        h.update(p[0].to_bits().to_le_bytes());
        h.update(p[1].to_bits().to_le_bytes());
    }
    for s in &pslg.segments {
        h.update(s[0].to_le_bytes());
        h.update(s[1].to_le_bytes());
    }
    if let Some(hex) = pslg.hexagon {
        for v in [hex.center[0], hex.center[1], hex.circumradius] {
            h.update(v.to_bits().to_le_bytes());
        }
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

const DIGESTS: &[(&str, &str)] = &[
    (
        "close-pair",
        "7de73506775e4ac88dcd1564a2a801c9ac53ae0cbc356f08a61fb4a2b71dd185",
    ),
    (
        "line-100",
        "c63106e40dfd550ad52878e4ef532ea542b7f9fb200814575d2ba8d6f0a614f4",
    ),
    (
        "plane-100",
        "4c6c5c100254f55c8e16d3ac5781beb16ac4c486618263cf4a13d8a8282360a6",
    ),
    (
        "plane-1k",
        "419753e874d51e556939ecbb2134b353f711d765b46ffe9f17d7b3a4989458e5",
    ),
    (
        "plane-2k",
        "a5d83efe6ca824b52dce023afc437aee3b7cc0f108a21faf2537ab6731f0f542",
    ),
    (
        "imr",
        "2701bb8681cb928c57e35902b5500f0f27ab32f03fb9b8afa619222ad68ad369",
    ),
];

#[test]
fn every_small_dataset_has_its_committed_digest() {
    let names: Vec<&str> = DIGESTS.iter().map(|d| d.0).collect();
    assert_eq!(names, SMALL, "one digest per small dataset, in order");
    let mut wrong = Vec::new();
    for &(name, expected) in DIGESTS {
        let got = digest(&datasets::by_name(name).expect(name));
        if got != expected {
            wrong.push(format!("(\"{name}\", \"{got}\"),"));
        }
    }
    assert!(wrong.is_empty(), "changed digests:\n{}", wrong.join("\n"));
}

#[test]
fn the_digest_sees_a_one_ulp_change() {
    let a = datasets::by_name("plane-100").expect("plane-100");
    let mut b = a.clone();
    b.points[57][1] = f64::from_bits(b.points[57][1].to_bits() + 1);
    assert_ne!(digest(&a), digest(&b));
}
