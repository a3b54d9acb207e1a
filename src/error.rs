//! The one error type of the crate: every failure names what went wrong, and for files where.

use std::fmt;
use std::path::PathBuf;

/// A problem with an input point set or PSLG, found before any mesher runs.
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// The input has no points.
    Empty,
    /// Point `index` (0-based) has a NaN or infinite coordinate.
    NonFinite { index: usize, point: [f64; 2] },
    /// Points `first` and `second` (0-based) have the same coordinates.
    Duplicate {
        first: usize,
        second: usize,
        point: [f64; 2],
    },
    /// Segment `index` names a vertex that does not exist.
    MissingVertex {
        segment: usize,
        vertex: i64,
        count: usize,
    },
    /// Segment `index` joins a vertex to itself.
    DegenerateSegment { segment: usize },
    /// Two segments cross or overlap somewhere other than a shared endpoint.
    CrossingSegments { first: usize, second: usize },
    /// A point lies in the interior of a segment it is not an endpoint of.
    PointOnSegment { point: usize, segment: usize },
    /// A hole seed has a NaN or infinite coordinate.
    NonFiniteHole { index: usize },
    /// The points are too close together or too far apart for f64 to mesh them.
    Range { detail: String },
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::Empty => write!(f, "the input has no points"),
            InputError::NonFinite { index, point } => write!(
                f,
                "point {index} has a non-finite coordinate ({}, {})",
                point[0], point[1]
            ),
            InputError::Duplicate {
                first,
                second,
                point,
            } => write!(
                f,
                "points {first} and {second} are duplicates, both at ({}, {})",
                point[0], point[1]
            ),
            InputError::MissingVertex {
                segment,
                vertex,
                count,
            } => write!(
                f,
                "segment {segment} names vertex {vertex}, but there are only {count} points"
            ),
            InputError::DegenerateSegment { segment } => {
                write!(f, "segment {segment} joins a vertex to itself")
            }
            InputError::CrossingSegments { first, second } => {
                write!(f, "segments {first} and {second} cross or overlap")
            }
            InputError::PointOnSegment { point, segment } => write!(
                f,
                "point {point} lies inside segment {segment} without being one of its endpoints"
            ),
            InputError::NonFiniteHole { index } => {
                write!(f, "hole {index} has a non-finite coordinate")
            }
            InputError::Range { detail } => write!(f, "{detail}"),
        }
    }
}

/// Everything that can go wrong in hexmesh.
#[derive(Debug)]
pub enum Error {
    /// Reading or writing a file failed at the operating-system level.
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A file is malformed: `line` is 1-based, 0 when the problem is the file as a whole.
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// The input is unusable; `path` is the file it came from, when it came from one.
    Input {
        path: Option<PathBuf>,
        line: Option<usize>,
        problem: InputError,
    },
    /// No mesher of that name is registered.
    UnknownMesher { name: String, known: Vec<String> },
    /// A mesher failed; `message` says why (a C++ exception, an unsupported input, ...).
    Mesher { mesher: String, message: String },
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
            } => match (path, line) {
                (Some(p), Some(l)) => write!(f, "{}:{l}: {problem}", p.display()),
                (Some(p), None) => write!(f, "{}: {problem}", p.display()),
                _ => write!(f, "bad input: {problem}"),
            },
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
