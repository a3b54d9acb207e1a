//! The two exchange types: `Pslg`, what every mesher takes, and `TriMesh`, what every mesher
//! gives back and every check consumes.

use crate::error::{Error, InputError, Result};
use crate::geom::{orient2d, Hexagon, Point};

/// A planar straight-line graph: points, segments between them, and hole seeds as in
/// Triangle's .poly format. A point set is a PSLG without segments.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pslg {
    /// The input points; point i (0-based) is what segments and errors call i.
    pub points: Vec<Point>,
    /// Pairs of 0-based point indices.
    pub segments: Vec<[u32; 2]>,
    /// Seed points: the region around each, bounded by segments, is removed.
    pub holes: Vec<Point>,
    /// The domain of a point set: the bounding hexagon. `None` means fitted to the points
    /// (`Hexagon::fitted`). Ignored when the input has segments.
    pub hexagon: Option<Hexagon>,
    /// What a Triangle `.node`/`.poly` input says about its items beyond geometry: point
    /// markers and attributes, segment markers, regions. The meshers read only the regions'
    /// area limits (kept or refused: [`Region::area_limit`]); the writers carry all of them to
    /// the output mesh (`io::write_mesh_with`). Empty by default.
    pub labels: Labels,
}

/// The labels of an input, as Triangle's `.node` and `.poly` files give them (Triangle 1.6
/// documentation, ".node files", ".poly files", "Boundary markers"). Every field is optional:
/// an absent column is `None` (markers) or empty (attributes, regions), and a point set read
/// from a `.node` file without markers has `Labels::default()`.
///
/// The labels sit beside the geometry in [`Pslg`] rather than in it, so that the meshers,
/// `Pslg::from_points` and `Pslg::check` see the same geometry as without them; a mesher reads
/// only the regions' area limits (`triangle` per region, the others with size control the
/// smallest, the rest refuse them).
/// The output mesh gets its labels from its input afterwards, by position (an input point is
/// the mesh vertex with its exact coordinates; a segment is the chain of mesh edges along it),
/// in `io::boundary`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Labels {
    /// One boundary marker per input point, when the `.node` header's marker flag is 1.
    pub point_markers: Option<Vec<i64>>,
    /// The attributes of each input point: one row per point, all of the same length, or no
    /// rows at all (no attributes).
    pub point_attributes: Vec<Vec<f64>>,
    /// One boundary marker per segment, when the `.poly` segment header's marker flag is 1.
    pub segment_markers: Option<Vec<i64>>,
    /// The regional attributes and area constraints of a `.poly` file, in file order. Each
    /// region is the part of the domain reachable from its point without crossing a segment;
    /// a later region overrides an earlier one, as in Triangle.
    pub regions: Vec<Region>,
}

impl Labels {
    /// True when there is no label at all.
    pub fn is_empty(&self) -> bool {
        self == &Labels::default()
    }

    /// The number of attributes per point (0 without attributes).
    pub fn attribute_count(&self) -> usize {
        self.point_attributes.first().map_or(0, Vec::len)
    }

    /// Checks that the labels fit an input of `points` points and `segments` segments: one
    /// marker per point and per segment when markers are given, one attribute row of the same
    /// length per point when attributes are given, finite attributes and regions. Returns a
    /// description of the first misfit.
    pub fn check_fit(&self, points: usize, segments: usize) -> std::result::Result<(), String> {
        if let Some(m) = &self.point_markers {
            if m.len() != points {
                return Err(format!("{} point markers for {points} points", m.len()));
            }
        }
        if let Some(m) = &self.segment_markers {
            if m.len() != segments {
                return Err(format!(
                    "{} segment markers for {segments} segments",
                    m.len()
                ));
            }
        }
        let width = self.attribute_count();
        if !self.point_attributes.is_empty() && self.point_attributes.len() != points {
            return Err(format!(
                "{} point attribute rows for {points} points",
                self.point_attributes.len()
            ));
        }
        for (k, row) in self.point_attributes.iter().enumerate() {
            if row.len() != width {
                return Err(format!(
                    "point {k} has {} attributes, point 0 has {width}",
                    row.len()
                ));
            }
            if let Some(v) = row.iter().find(|v| !v.is_finite()) {
                return Err(format!("point {k} has the non-finite attribute {v}"));
            }
        }
        for (k, r) in self.regions.iter().enumerate() {
            let values = [r.point[0], r.point[1], r.attribute];
            if values.iter().chain(&r.max_area).any(|v| !v.is_finite()) {
                return Err(format!("region {k} has a non-finite value: {r:?}"));
            }
        }
        Ok(())
    }
}

/// A regional attribute / area constraint row of a `.poly` file. Meshers with size control
/// keep its area limit ([`Region::area_limit`]; `triangle` per region, the others with the
/// smallest limit everywhere, [`Pslg::smallest_area_limit`]) and the rest refuse it; the
/// writers give every triangle the attribute of the region it lies in (`io::boundary`), and a
/// `.poly` file keeps them through a round trip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    /// A point inside the region.
    pub point: Point,
    /// The regional attribute (or, without `max_area`, Triangle's area bound).
    pub attribute: f64,
    /// Triangle uses the attribute as the area bound when this field is missing.
    pub max_area: Option<f64>,
}

impl Region {
    /// The largest triangle area this region allows, as Triangle reads the row: its area
    /// field, or its attribute when the row has no area field; a limit that is not positive
    /// is no limit (Triangle 1.6, ".poly files" and the `-a` switch).
    pub fn area_limit(&self) -> Option<f64> {
        Some(self.max_area.unwrap_or(self.attribute)).filter(|&a| a > 0.0 && a.is_finite())
    }
}

impl Pslg {
    /// A point set, with the bounding hexagon fitted to it.
    pub fn from_points(points: Vec<Point>) -> Pslg {
        Pslg {
            points,
            ..Pslg::default()
        }
    }

    /// True when a region of the input limits the area of its triangles
    /// ([`Region::area_limit`]).
    pub fn has_area_limits(&self) -> bool {
        self.labels.regions.iter().any(|r| r.area_limit().is_some())
    }

    /// The smallest of `max_area` (a limit for the whole domain) and the regions' limits
    /// ([`Region::area_limit`]): the one limit that keeps every region's, for a mesher that
    /// takes a single maximum area.
    pub fn smallest_area_limit(&self, max_area: Option<f64>) -> Option<f64> {
        self.labels
            .regions
            .iter()
            .filter_map(Region::area_limit)
            .chain(max_area)
            .reduce(f64::min)
    }

    /// True when the input has segments, so the domain is what they bound.
    pub fn has_segments(&self) -> bool {
        !self.segments.is_empty()
    }

    /// The bounding hexagon of a point set: given, or fitted (its inscribed circle the
    /// minimum enclosing circle of the points, slightly enlarged: `Hexagon::fitted`). The hex
    /// meshers turn a fitted one for elongated points (`hex::root_hexagon`).
    pub fn bounding_hexagon(&self) -> Hexagon {
        self.hexagon
            .unwrap_or_else(|| Hexagon::fitted(&self.points))
    }

    /// The domain a reference mesher is asked to mesh, so that it covers what ours cover: for
    /// a point set, the bounding hexagon's corners (appended after the input points) and its
    /// six edges as segments; a PSLG is returned unchanged.
    pub fn reference_domain(&self) -> Pslg {
        if self.has_segments() {
            return self.clone();
        }
        let hex = self.bounding_hexagon();
        let mut out = self.clone();
        let base = out.points.len() as u32;
        out.points.extend(hex.corners());
        out.segments = (0..6).map(|i| [base + i, base + (i + 1) % 6]).collect();
        out.hexagon = Some(hex);
        // The labels keep fitting: the corners and the sides get marker 0 and zero attributes.
        let labels = &mut out.labels;
        if let Some(m) = &mut labels.point_markers {
            m.extend([0; 6]);
        }
        let width = labels.attribute_count();
        if width > 0 {
            labels
                .point_attributes
                .extend((0..6).map(|_| vec![0.0; width]));
        }
        if let Some(m) = &mut labels.segment_markers {
            m.clear();
            m.extend([0; 6]);
        }
        out
    }

    /// Checks the input before any mesher sees it: at least one point, finite coordinates,
    /// no duplicate points, segments naming existing distinct vertices, no two segments
    /// crossing or overlapping, no point inside a segment, finite hole seeds, a coordinate
    /// range that f64 can mesh, for a point set every point strictly inside its bounding
    /// hexagon, and for a PSLG a region that the segments enclose with every segment and
    /// point in it ([`Pslg::check_enclosed`]; [`Pslg::with_convex_hull`] encloses an input in
    /// its convex hull). Returns the first problem found, deterministically.
    pub fn check(&self) -> std::result::Result<(), InputError> {
        if self.points.is_empty() {
            return Err(InputError::Empty);
        }
        for (index, &p) in self.points.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(InputError::NonFinite { index, point: p });
            }
        }
        let max_abs = self
            .points
            .iter()
            .flat_map(|p| [p[0].abs(), p[1].abs()])
            .fold(0.0, f64::max);
        if max_abs > 1e150 {
            return Err(InputError::Range {
                detail: format!(
                    "coordinates as large as {max_abs:e} would overflow when squared; scale the input"
                ),
            });
        }
        if let Some((first, second)) = first_duplicate(&self.points) {
            return Err(InputError::Duplicate {
                first,
                second,
                point: self.points[first],
            });
        }
        let n = self.points.len();
        for (segment, s) in self.segments.iter().enumerate() {
            for &v in s {
                if v as usize >= n {
                    return Err(InputError::MissingVertex {
                        segment,
                        vertex: v as i64,
                        count: n,
                    });
                }
            }
            if s[0] == s[1] {
                return Err(InputError::DegenerateSegment { segment });
            }
        }
        for (index, h) in self.holes.iter().enumerate() {
            if !h[0].is_finite() || !h[1].is_finite() {
                return Err(InputError::NonFiniteHole { index });
            }
        }
        if !self.has_segments() {
            // The domain of a point set is its bounding hexagon: every mesher puts the hexagon
            // (or the references its corners) around the points, so a point on or outside it
            // would be a duplicate corner or a point outside the domain.
            let hex = self.bounding_hexagon();
            if let Some(index) = self.points.iter().position(|&p| !hex.contains_strictly(p)) {
                return Err(InputError::OutsideHexagon {
                    index,
                    point: self.points[index],
                    fitted: self.hexagon.is_none(),
                });
            }
        }
        self.check_segment_intersections()?;
        self.check_enclosed()
    }

    /// Segment–segment and point–segment tests with exact orientation signs. A sweep over
    /// x-sorted bounding boxes keeps the usual case near O(n log n).
    fn check_segment_intersections(&self) -> std::result::Result<(), InputError> {
        if self.segments.is_empty() {
            return Ok(());
        }
        let p = &self.points;
        let seg = |s: [u32; 2]| (p[s[0] as usize], p[s[1] as usize]);
        // Items: segments and points, each with an x-interval.
        #[derive(Clone, Copy)]
        enum Item {
            Seg(usize),
            Pt(usize),
        }
        let mut items: Vec<(f64, f64, Item)> = self
            .segments
            .iter()
            .enumerate()
            .map(|(i, &s)| {
                let (a, b) = seg(s);
                (a[0].min(b[0]), a[0].max(b[0]), Item::Seg(i))
            })
            .collect();
        items.extend(p.iter().enumerate().map(|(i, q)| (q[0], q[0], Item::Pt(i))));
        items.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut active: Vec<(f64, usize)> = Vec::new(); // (xmax, segment)
        let mut found: Option<(usize, InputError)> = None;
        let mut record = |key: usize, e: InputError| {
            if found.as_ref().is_none_or(|(k, _)| key < *k) {
                found = Some((key, e));
            }
        };
        for &(xmin, xmax, item) in &items {
            active.retain(|&(end, _)| end >= xmin);
            match item {
                Item::Pt(i) => {
                    for &(_, s) in &active {
                        let sv = self.segments[s];
                        if sv[0] as usize == i || sv[1] as usize == i {
                            continue;
                        }
                        let (a, b) = seg(sv);
                        if point_inside_segment(a, b, p[i]) {
                            record(
                                s,
                                InputError::PointOnSegment {
                                    point: i,
                                    segment: s,
                                },
                            );
                        }
                    }
                }
                Item::Seg(s) => {
                    let (a, b) = seg(self.segments[s]);
                    for &(_, t) in &active {
                        let (c, d) = seg(self.segments[t]);
                        if segments_conflict(self.segments[s], self.segments[t], a, b, c, d) {
                            let (first, second) = (s.min(t), s.max(t));
                            record(first, InputError::CrossingSegments { first, second });
                        }
                    }
                    active.push((xmax, s));
                }
            }
        }
        match found {
            Some((_, e)) => Err(e),
            None => Ok(()),
        }
    }

    /// `check`, turned into the crate's error type.
    pub fn validate_input(&self) -> Result<()> {
        self.check().map_err(Error::input)
    }
}

/// The first pair of equal points (by the smaller second index), found by sorting.
/// Adding 0.0 folds -0.0 into 0.0, so that the two zeros count as one coordinate.
fn first_duplicate(points: &[Point]) -> Option<(usize, usize)> {
    let key = |i: usize| [points[i][0] + 0.0, points[i][1] + 0.0];
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        ka[0]
            .total_cmp(&kb[0])
            .then(ka[1].total_cmp(&kb[1]))
            .then(a.cmp(&b))
    });
    order
        .windows(2)
        .filter(|w| key(w[0]) == key(w[1]))
        .map(|w| (w[0].min(w[1]), w[0].max(w[1])))
        .min_by_key(|&(first, second)| (second, first))
}

/// True when `q` lies on segment ab strictly between its endpoints (exact).
fn point_inside_segment(a: Point, b: Point, q: Point) -> bool {
    orient2d(a, b, q) == 0.0 && strictly_between(a, b, q)
}

fn strictly_between(a: Point, b: Point, q: Point) -> bool {
    let (lo_x, hi_x) = (a[0].min(b[0]), a[0].max(b[0]));
    let (lo_y, hi_y) = (a[1].min(b[1]), a[1].max(b[1]));
    q[0] >= lo_x && q[0] <= hi_x && q[1] >= lo_y && q[1] <= hi_y && q != a && q != b
}

/// True when one of two exact orientation values is positive and the other negative. Their
/// product would underflow to zero for coordinates below about 1e-77, and miss the crossing.
pub(crate) fn opposite_signs(x: f64, y: f64) -> bool {
    (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0)
}

/// True when segments s = ab and t = cd meet anywhere but at a shared endpoint.
fn segments_conflict(s: [u32; 2], t: [u32; 2], a: Point, b: Point, c: Point, d: Point) -> bool {
    let shared = s.iter().filter(|v| t.contains(v)).count();
    if shared == 2 {
        return true; // the same segment twice
    }
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: they conflict when they overlap in more than a shared endpoint.
        return strictly_between(a, b, c)
            || strictly_between(a, b, d)
            || strictly_between(c, d, a)
            || strictly_between(c, d, b);
    }
    if shared == 1 {
        // Meeting at a vertex: a conflict only if one runs along the other, handled above.
        return false;
    }
    let proper = opposite_signs(o1, o2) && opposite_signs(o3, o4);
    let touching = (o1 == 0.0 && strictly_between(a, b, c))
        || (o2 == 0.0 && strictly_between(a, b, d))
        || (o3 == 0.0 && strictly_between(c, d, a))
        || (o4 == 0.0 && strictly_between(c, d, b));
    proper || touching
}

/// A triangle mesh: f64 vertices and counter-clockwise triangles of 0-based vertex indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// The vertex coordinates; vertex i is `vertices[i]`.
    pub vertices: Vec<Point>,
    /// Each triangle's three vertex indices (0-based), counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The three corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [Point; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// Sum of the (signed) triangle areas.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            })
            .sum()
    }

    /// The triangles by the bits of their corners, each rotated to start at its least corner,
    /// sorted: equal for two meshes that differ only in how vertices and triangles are
    /// numbered and ordered.
    pub fn corner_bits_sorted(&self) -> Vec<[[u64; 2]; 3]> {
        let bits = |p: Point| [p[0].to_bits(), p[1].to_bits()];
        let mut triangles: Vec<[[u64; 2]; 3]> = (0..self.triangles.len())
            .map(|t| {
                let c = self.corners(t).map(bits);
                let r = (0..3).min_by_key(|&r| c[r]).unwrap_or(0);
                [c[r], c[(r + 1) % 3], c[(r + 2) % 3]]
            })
            .collect();
        triangles.sort_unstable();
        triangles
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_domain_of_a_labelled_point_set_keeps_labels_that_fit() {
        let mut points = Pslg::from_points(vec![[0.0, 0.0], [1.0, 0.5]]);
        points.labels = Labels {
            point_markers: Some(vec![3, 4]),
            point_attributes: vec![vec![1.0], vec![2.0]],
            segment_markers: Some(Vec::new()),
            ..Labels::default()
        };
        let domain = points.reference_domain();
        assert_eq!((domain.points.len(), domain.segments.len()), (8, 6));
        assert_eq!(domain.labels.check_fit(8, 6), Ok(()));
        assert_eq!(
            domain.labels.point_markers,
            Some(vec![3, 4, 0, 0, 0, 0, 0, 0])
        );
        assert_eq!(domain.labels.point_attributes[7], vec![0.0]);
    }

    fn square() -> Pslg {
        Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            ..Pslg::default()
        }
    }

    #[test]
    fn a_square_outline_is_accepted() {
        assert_eq!(square().check(), Ok(()));
    }

    #[test]
    fn crossing_diagonals_are_refused() {
        let mut p = square();
        p.segments.extend([[0, 2], [1, 3]]);
        assert_eq!(
            p.check(),
            Err(InputError::CrossingSegments {
                first: 4,
                second: 5
            })
        );
    }

    #[test]
    fn crossing_segments_at_a_tiny_scale_are_refused() {
        // Orientation values of 1e-200 are exact, but their product underflows to zero.
        let t = 1e-100;
        let p = Pslg {
            points: vec![[0.0, 0.0], [t, t], [0.0, t], [t, 0.0]],
            segments: vec![[0, 1], [2, 3]],
            ..Pslg::default()
        };
        assert_eq!(
            p.check(),
            Err(InputError::CrossingSegments {
                first: 0,
                second: 1
            })
        );
    }

    #[test]
    fn a_point_inside_a_segment_is_refused() {
        let mut p = square();
        p.points.push([0.5, 0.0]);
        assert_eq!(
            p.check(),
            Err(InputError::PointOnSegment {
                point: 4,
                segment: 0
            })
        );
    }

    #[test]
    fn overlapping_collinear_segments_are_refused() {
        let p = Pslg {
            points: vec![[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [3.0, 1.0]],
            segments: vec![[0, 1], [2, 3], [0, 1]],
            ..Pslg::default()
        };
        assert!(matches!(
            p.check(),
            Err(InputError::CrossingSegments {
                first: 0,
                second: 2
            })
        ));
    }

    #[test]
    fn duplicates_nan_and_missing_vertices_are_named() {
        let d = Pslg::from_points(vec![[0.0, 0.0], [1.0, 2.0], [-0.0, 0.0]]);
        assert!(matches!(
            d.check(),
            Err(InputError::Duplicate {
                first: 0,
                second: 2,
                ..
            })
        ));
        let n = Pslg::from_points(vec![[0.0, 0.0], [f64::NAN, 2.0]]);
        assert!(matches!(
            n.check(),
            Err(InputError::NonFinite { index: 1, .. })
        ));
        let mut m = square();
        m.segments.push([2, 9]);
        assert!(matches!(
            m.check(),
            Err(InputError::MissingVertex {
                segment: 4,
                vertex: 9,
                ..
            })
        ));
        assert_eq!(Pslg::default().check(), Err(InputError::Empty));
    }

    #[test]
    fn a_point_outside_a_given_hexagon_is_refused() {
        let p = Pslg {
            points: vec![[0.0, 0.0], [5.0, 5.0]],
            hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
            ..Pslg::default()
        };
        assert_eq!(
            p.check(),
            Err(InputError::OutsideHexagon {
                index: 1,
                point: [5.0, 5.0],
                fitted: false
            })
        );
        // A corner of the given hexagon is on it, not strictly inside.
        let corner = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0]],
            ..p
        };
        assert!(matches!(
            corner.check(),
            Err(InputError::OutsideHexagon { index: 1, .. })
        ));
    }

    #[test]
    fn points_one_ulp_apart_get_a_fitted_hexagon_and_are_refused_by_name() {
        // The minimum enclosing circle has radius 1.1e-16 at coordinate 1: steps of 1e-9 of
        // it do not move the hexagon's corners off the points, the doubling steps do
        // (`Hexagon::fitted`). A mesh of the pair would need hexagons f64 cannot place: the
        // meshers refuse it, naming both points.
        let p = Pslg::from_points(vec![[1.0, 1.0], [1.0 + f64::EPSILON, 1.0]]);
        assert_eq!(p.check(), Ok(()));
        for mesher in ["hex", "hex-simple", "rhomb"] {
            match crate::registry::mesher(mesher)
                .expect("registered")
                .mesh(&p, &crate::Params::default())
            {
                Err(crate::Error::Input {
                    problem:
                        InputError::Rounding {
                            first: 0,
                            second: 1,
                            ..
                        },
                    ..
                }) => {}
                other => panic!("{mesher}: expected a refusal naming points 0 and 1: {other:?}"),
            }
        }
    }

    #[test]
    fn reference_domain_of_a_point_set_is_the_bounding_hexagon() {
        let p = Pslg::from_points(vec![[0.0, 0.0], [1.0, 0.0]]);
        let d = p.reference_domain();
        assert_eq!(d.points.len(), 8);
        assert_eq!(d.segments.len(), 6);
        assert_eq!(d.check(), Ok(()));
    }
}
