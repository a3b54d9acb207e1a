//! The meshers' machinery, for the harness, the tests and research: the hexagon hierarchy,
//! its rules, relocations and PSLG path (`hex`), the rhomb quad-tree (`rhomb`), Saalfeld's
//! refinement and longest-side bisection (`refine`). A mesh user needs none of it: the
//! meshers themselves, [`crate::Hex`], [`crate::HexSimple`], [`crate::Rhomb`],
//! [`crate::Saalfeld`] and [`crate::Lsb`], are at the crate root, behind [`crate::mesh()`],
//! [`crate::mesh_domain`] and [`crate::Mesher`]. These paths may change between versions.
//!
//! The folders keep their place in the source tree (`src/hex/`, `src/rhomb/`,
//! `src/refine/`); inside the crate they are also reachable as `crate::hex` and so on.

#[path = "hex/mod.rs"]
pub mod hex;
#[path = "refine/mod.rs"]
pub mod refine;
#[path = "rhomb/mod.rs"]
pub mod rhomb;
