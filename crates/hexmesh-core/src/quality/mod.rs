//! Checks and figures for triangle meshes: is the mesh valid, how good
//! are its triangles, and does it keep what its mesher promises.

/// What meshers promise, as checkable bounds; `hex`'s criteria.
pub mod bounds;
/// d_min, the closest pair of input points, in O(n log n).
pub mod closest_pair;
/// Input corners sharper than a minimum angle, taken whole.
mod corners;
/// Longest-side bisection's descent bound: each triangle against the initial one it lies in.
pub mod descent;
/// d_min of a domain: the closest pair of input features that share no point.
pub mod feature_gap;
/// Angles, radius ratio, edge ratio, shortest edge / d_min, Delaunay counts.
pub mod metrics;
/// The rounding allowance of every bound: how far f64 vertices may move a figure.
pub mod rounding;
/// Every structural invariant a mesh must meet, each broken one named.
pub mod validate;
/// Validity plus bounds, as a table and as JSON.
pub mod verdict;

pub use bounds::{
    Bounds, HexCriteria, ANGLE_SLACK_DEG, GENERIC_BOUNDS, HEX, LSB_ADAPTIVE_RATIO, LSB_FAMILY_RATIO,
};
pub use closest_pair::{closest_pair, ClosestPair};
pub use descent::{descent, Descent};
pub use feature_gap::{feature_gap, Feature, FeatureGap};
pub use metrics::{
    metrics, metrics_split, on_segment_tolerance, triangle_shape, DelaunayEdge, Metrics,
    SplitMetrics, TriangleShape, Worst, DELAUNAY_ANGLE_SLACK_DEG,
};
pub use validate::{triangle_regions, validate, Numbering, ValidateOptions, Violation};

/// A coordinate or area as text that names its f64 exactly (both forms are Rust's shortest
/// round-trip output) and stays short: plain decimals for magnitudes in [1e-5, 1e16), which
/// is how most meshes read, exponent form beyond, where plain decimals run to hundreds of
/// digits (1e100 would print as a 1 and a hundred zeros).
pub(crate) fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
pub use verdict::{verdict, Check, Rounding, Status, Verdict, WorstTriangle};
