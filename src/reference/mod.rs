//! Reference meshers: other projects' meshers behind the `Mesher` trait, for comparison.

#[cfg(feature = "cgal")]
pub mod cgal;
