//! The one error type of the crate: every failure names what went wrong, and for files where.

use std::fmt;
use std::path::PathBuf;

/// A problem with an input point set or PSLG, found before any mesher runs.
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// The input has no points.
    Empty,
    /// Point `index` (0-based) has a NaN or infinite coordinate.
    NonFinite {
        /// The point's 0-based index.
        index: usize,
        /// Its coordinates as given.
        point: [f64; 2],
    },
    /// Points `first` and `second` (0-based) have the same coordinates.
    Duplicate {
        /// The smaller of the two 0-based indices.
        first: usize,
        /// The larger of the two 0-based indices.
        second: usize,
        /// The coordinates both share.
        point: [f64; 2],
    },
    /// Segment `segment` names a vertex that does not exist.
    MissingVertex {
        /// The segment's 0-based index.
        segment: usize,
        /// The vertex it names, 0-based.
        vertex: i64,
        /// How many points there are: valid vertices are `0..count`.
        count: usize,
    },
    /// Segment `segment` joins a vertex to itself.
    DegenerateSegment {
        /// The segment's 0-based index.
        segment: usize,
    },
    /// Two segments cross or overlap somewhere other than a shared endpoint.
    CrossingSegments {
        /// One segment's 0-based index.
        first: usize,
        /// The other's.
        second: usize,
    },
    /// A point lies in the interior of a segment it is not an endpoint of.
    PointOnSegment {
        /// The point's 0-based index.
        point: usize,
        /// The segment's 0-based index.
        segment: usize,
    },
    /// A hole seed has a NaN or infinite coordinate.
    NonFiniteHole {
        /// The hole's 0-based index.
        index: usize,
    },
    /// Point `index` of a point set does not lie strictly inside its bounding hexagon: the
    /// one the input gives, or (`fitted`) the one fitted to the points, which f64 cannot
    /// make contain points that are too close together for their coordinates.
    OutsideHexagon {
        /// The point's 0-based index.
        index: usize,
        /// Its coordinates.
        point: [f64; 2],
        /// Whether the hexagon was fitted to the points rather than given.
        fitted: bool,
    },
    /// The points are too close together or too far apart for f64 to mesh them.
    Range {
        /// The whole message, naming the points and the distances.
        detail: String,
    },
    /// Points `first` and `second` (0-based), `distance` apart, are too close together for
    /// their coordinates: a mesh of them would use a rounding allowance of `needed` degrees
    /// (infinite: more levels than the mesher's lattice has), more than the `allowed`
    /// (`--max-rounding`; README "Checks").
    Rounding {
        /// One point's 0-based index.
        first: usize,
        /// The other's.
        second: usize,
        /// Their Euclidean distance, in input units.
        distance: f64,
        /// The allowance a mesh of them would use, in degrees; 180 or more: rounding alone
        /// could turn a triangle over; infinite: beyond the lattice's depth.
        needed: f64,
        /// The largest allowance permitted, in degrees.
        allowed: f64,
    },
    /// Segment `segment` ends at `vertex`, which no other segment continues: the boundary of
    /// a polygonal domain (paper 001 Sec. 3: closed polygons) has no free end.
    DanglingSegment {
        /// The segment's 0-based index.
        segment: usize,
        /// Its free end, a 0-based point index.
        vertex: usize,
    },
    /// `count` segments meet at `vertex` (0-based), `segment` being the third of them by
    /// index: the polygons of a polygonal domain neither branch nor touch one another.
    BranchingSegment {
        /// The 0-based index of the third segment at the vertex.
        segment: usize,
        /// The vertex, a 0-based point index.
        vertex: usize,
        /// How many segments meet there.
        count: usize,
    },
    /// Segment `segment` has the domain on both sides (a slit, or a polygon with no hole seed
    /// inside it drawn within the domain); a mesher of polygonal domains refuses it.
    SegmentInsideDomain {
        /// The 0-based index of the polygon's first segment.
        segment: usize,
    },
    /// The segments enclose no region to mesh: the domain of a PSLG is what its segments
    /// enclose, minus the regions the hole seeds lie in (Triangle's .poly semantics), and
    /// nothing is left (`cause` says why).
    NoEnclosedRegion {
        /// How many segments the input has.
        segments: usize,
        /// Why nothing is enclosed.
        cause: Unenclosed,
    },
    /// Segment `segment` has no domain on either side: it lies outside the region the segments
    /// enclose or in a hole (a segment beyond the outer boundary, a polygon inside a hole, or
    /// a polygon emptied by a hole seed with nothing meshed around it), so no mesh of the
    /// domain has it as edges.
    SegmentOutsideDomain {
        /// The 0-based index of the polygon's first segment.
        segment: usize,
    },
    /// Point `point` (0-based) lies outside the domain or in a hole.
    PointOutsideDomain {
        /// The point's 0-based index.
        point: usize,
    },
    /// Point `index` (0-based) lies only `distance` inside the bounding hexagon's edge, too
    /// close for the mesher's lattice to put triangles between them in f64.
    NearBoundary {
        /// The point's 0-based index.
        index: usize,
        /// How far it lies inside the hexagon's nearest edge, in input units.
        distance: f64,
    },
}

/// Why the segments of a PSLG enclose no region ([`InputError::NoEnclosedRegion`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unenclosed {
    /// No closed chain of segments goes around an area (an open polyline, a tree of segments).
    Open,
    /// The hole seeds empty every region the segments enclose.
    Holes,
    /// Every point lies on one line: not even the points' convex hull encloses an area.
    Collinear,
}

impl InputError {
    /// The problem in words, with point, segment and hole numbers counted from `first`: 0 for
    /// the 0-based indices of a `Pslg`, or the first number of the file the input came from
    /// (Triangle's files number from 0 or 1), so that the numbers match what the file says.
    pub fn describe(&self, first: u32) -> String {
        let n = |i: &usize| *i as u64 + u64::from(first);
        match self {
            InputError::Empty => "the input has no points".to_string(),
            InputError::NonFinite { index, point } => format!(
                "point {} has a non-finite coordinate ({}, {})",
                n(index),
                point[0],
                point[1]
            ),
            InputError::Duplicate {
                first: a,
                second: b,
                point,
            } => format!(
                "points {} and {} are duplicates, both at ({:?}, {:?})",
                n(a),
                n(b),
                point[0],
                point[1]
            ),
            InputError::MissingVertex {
                segment,
                vertex,
                count,
            } => format!(
                "segment {} names vertex {}, but there are only {count} points",
                n(segment),
                vertex + i64::from(first)
            ),
            InputError::DegenerateSegment { segment } => {
                format!("segment {} joins a vertex to itself", n(segment))
            }
            InputError::CrossingSegments {
                first: a,
                second: b,
            } => format!("segments {} and {} cross or overlap", n(a), n(b)),
            InputError::PointOnSegment { point, segment } => format!(
                "point {} lies inside segment {} without being one of its endpoints",
                n(point),
                n(segment)
            ),
            InputError::NonFiniteHole { index } => {
                format!("hole {} has a non-finite coordinate", n(index))
            }
            InputError::OutsideHexagon {
                index,
                point,
                fitted: false,
            } => format!(
                "point {} ({:?}, {:?}) does not lie strictly inside the given bounding hexagon",
                n(index),
                point[0],
                point[1]
            ),
            InputError::OutsideHexagon {
                index,
                point,
                fitted: true,
            } => format!(
                "point {} ({:?}, {:?}) is not strictly inside the bounding hexagon fitted to the \
                 points: they are too close together for f64 at their coordinates",
                n(index),
                point[0],
                point[1]
            ),
            InputError::DanglingSegment { segment, vertex } => format!(
                "segment {} ends at point {}, which no other segment continues: the boundary \
                 of a polygonal domain has no free end",
                n(segment),
                n(vertex)
            ),
            InputError::BranchingSegment {
                segment,
                vertex,
                count,
            } => format!(
                "segment {} is the third of {count} segments at point {}: the polygons of a \
                 polygonal domain neither branch nor touch",
                n(segment),
                n(vertex)
            ),
            InputError::SegmentInsideDomain { segment } => format!(
                "segment {} has the domain on both sides: a mesher of polygonal domains \
                 (polygons with holes) takes no segment inside the domain",
                n(segment)
            ),
            InputError::NoEnclosedRegion { segments, cause } => {
                let why = match cause {
                    Unenclosed::Open => format!(
                        "no closed chain of its {segments} segments ({} to {}) goes around an \
                         area, and the domain of a .poly input is what its segments enclose; \
                         mesh it inside its convex hull with --convex-hull",
                        u64::from(first),
                        (*segments as u64 + u64::from(first)).saturating_sub(1)
                    ),
                    Unenclosed::Holes => "the hole seeds empty every region they enclose (a \
                                          seed removes the whole region it lies in); remove \
                                          the seed, or mesh around the holes inside the convex \
                                          hull with --convex-hull"
                        .to_string(),
                    Unenclosed::Collinear => "every point lies on one line, so not even their \
                                              convex hull encloses an area"
                        .to_string(),
                };
                format!("the segments enclose no region: {why}")
            }
            InputError::SegmentOutsideDomain { segment } => format!(
                "segment {} has no domain on either side: it lies outside the region the \
                 segments enclose, or in a hole (a polygon inside a hole, or emptied by a hole \
                 seed), so no mesh of the domain can keep it; remove it, or enclose it \
                 (--convex-hull adds the convex hull's edges)",
                n(segment)
            ),
            InputError::PointOutsideDomain { point } => format!(
                "point {} lies outside the domain (outside every polygon the segments bound, \
                 or in a hole), so it cannot be a vertex of the mesh",
                n(point)
            ),
            InputError::Range { detail } => detail.clone(),
            InputError::NearBoundary { index, distance } => format!(
                "point {} lies {distance:e} inside the bounding hexagon's edge, too close for \
                 f64 at its coordinates: meshing between them needs more levels than the \
                 mesher's lattice has",
                n(index)
            ),
            InputError::Rounding {
                first: a,
                second: b,
                distance,
                needed,
                allowed,
            } => {
                let need = if *needed >= 180.0 && needed.is_finite() {
                    "rounding to f64 alone could turn their triangles over".to_string()
                } else if needed.is_finite() {
                    format!(
                        "rounding to f64 would move an angle of their mesh by up to \
                         {needed:.3e}°, more than the {allowed}° allowed (--max-rounding)"
                    )
                } else {
                    "meshing them needs more levels than the mesher's lattice has".to_string()
                };
                format!(
                    "points {} and {} are {distance:e} apart, too close together for their \
                     coordinates: {need}",
                    n(a),
                    n(b)
                )
            }
        }
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(0))
    }
}

impl std::error::Error for InputError {}

/// Everything that can go wrong in hexmesh.
#[derive(Debug)]
pub enum Error {
    /// Reading or writing a file failed at the operating-system level.
    Io {
        /// The file read or written.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A file is malformed: `line` is 1-based, 0 when the problem is the file as a whole.
    Parse {
        /// The file.
        path: PathBuf,
        /// The 1-based line, or 0 for the whole file.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// The input is unusable; `path` is the file it came from, when it came from one, and
    /// `first_index` the number that file gives its first point, segment and hole (0 or 1;
    /// 0 without a file): the message counts from it, `problem` keeps 0-based indices.
    Input {
        /// The file the input came from, if any.
        path: Option<PathBuf>,
        /// The 1-based line of that file the problem is on, when one line shows it.
        line: Option<usize>,
        /// The problem, with 0-based indices.
        problem: InputError,
        /// The number the file gives its first item (0 or 1; 0 without a file).
        first_index: u32,
    },
    /// No mesher of that name is registered.
    UnknownMesher {
        /// The name asked for.
        name: String,
        /// The names that are registered.
        known: Vec<String>,
    },
    /// A mesher failed; `message` says why (a C++ exception, an unsupported input, ...).
    Mesher {
        /// The mesher's registered name.
        mesher: String,
        /// Why it failed.
        message: String,
    },
    /// A bad command-line argument or option value.
    Usage(String),
}

impl Error {
    /// An input error with no file attached.
    pub fn input(problem: InputError) -> Error {
        Error::Input {
            path: None,
            line: None,
            problem,
            first_index: 0,
        }
    }

    /// A mesher failure.
    pub fn mesher(mesher: &str, message: impl Into<String>) -> Error {
        Error::Mesher {
            mesher: mesher.to_string(),
            message: message.into(),
        }
    }

    /// A parse error at `line` (1-based) of `path`.
    pub fn parse(path: impl Into<PathBuf>, line: usize, message: impl Into<String>) -> Error {
        Error::Parse {
            path: path.into(),
            line,
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Error::Parse {
                path,
                line: 0,
                message,
            } => write!(f, "{}: {message}", path.display()),
            Error::Parse {
                path,
                line,
                message,
            } => write!(f, "{}:{line}: {message}", path.display()),
            Error::Input {
                path,
                line,
                problem,
                first_index,
            } => {
                let problem = problem.describe(*first_index);
                match (path, line) {
                    (Some(p), Some(l)) => write!(f, "{}:{l}: {problem}", p.display()),
                    (Some(p), None) => write!(f, "{}: {problem}", p.display()),
                    _ => write!(f, "bad input: {problem}"),
                }
            }
            Error::UnknownMesher { name, known } => write!(
                f,
                "unknown mesher '{name}'; registered meshers: {}",
                known.join(", ")
            ),
            Error::Mesher { mesher, message } => write!(f, "mesher {mesher}: {message}"),
            Error::Usage(message) => write!(f, "{message}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
