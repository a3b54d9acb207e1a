//! The user's Triangle switches (`--triangle-switches`, `Params::switches`), read the way
//! Triangle 1.6's `parsecommandline` reads a switch string, and refused where they would break
//! what the harness relies on.
//!
//! Triangle reads every character on its own and silently ignores the ones it does not know;
//! a number may follow `q` and `a` (digits and dots only, copied into a 2048-byte buffer
//! without a bound check, then `strtod`), and an integer may follow `S` (accumulated in an
//! `int` without an overflow check). So this reader refuses unknown characters, numbers that
//! would not parse as Triangle parses them or would overrun its buffer, and an `a` number that
//! is not positive (Triangle would `exit(1)`).

use crate::error::{Error, Result};

/// Triangle's buffer for a switch's number (`FILENAMESIZE`), terminating zero included.
pub const NUMBER_BUFFER: usize = 2048;

/// Switches the harness needs fixed, and why each one the user may not pass is refused.
const REFUSED: &[(char, &str)] = &[
    ('j', "jettisons vertices no triangle uses and renumbers the rest: the harness needs the input points first, in input order"),
    ('r', "refines a previous mesh, which the harness never passes"),
    ('v', "writes the Voronoi diagram, which the harness neither asks for nor frees"),
    ('n', "writes triangle neighbours, which the harness does not read"),
    ('e', "writes the edges, which the harness does not read"),
    ('g', "writes an .off file, which a library call does not do"),
    ('B', "drops the boundary markers of the output"),
    ('P', "drops the output segments"),
    ('N', "drops the output points, which the harness reads"),
    ('E', "drops the output triangles, which the harness reads"),
    ('I', "suppresses iteration numbers of output files, which a library call does not write"),
    ('O', "ignores the holes, which the harness carves"),
    ('X', "turns off exact arithmetic, on which the harness's robustness claims rest"),
    ('k', "is not a Triangle 1.6 switch the harness passes"),
    ('o', "(o2) makes quadratic elements: the harness reads 3-node triangles"),
    ('w', "makes a weighted Delaunay triangulation from point attributes, which the harness does not pass"),
    ('W', "makes a weighted Delaunay triangulation from point attributes, which the harness does not pass"),
    ('L', "is an undocumented alias of D: write D"),
    ('h', "prints Triangle's help, which a library call does not do"),
];

/// What a switch string asks of Triangle, as far as the harness cares.
#[derive(Debug, Clone, PartialEq)]
pub struct Switches {
    /// The string as it is sent (a leading dash removed).
    pub text: String,
    /// The angle of a `q` switch (20° for a bare one); the last `q` wins, as in Triangle.
    pub min_angle: Option<f64>,
    /// The number of an `a` switch (a fixed area bound); the last one wins.
    pub max_area: Option<f64>,
    /// A bare `a`: the regions' area bounds.
    pub regional_area: bool,
    /// The number of an `S` switch (0 for a bare one): at most that many Steiner points.
    pub steiner_limit: Option<u32>,
    /// How many `Y` switches: 1 keeps the boundary segments whole, 2 every segment.
    pub whole_segments: u32,
    /// `c`: the convex hull is meshed, not only the segments' region.
    pub convex_hull: bool,
}

impl Switches {
    /// True when the switches let Triangle stop short of the minimum angle: `S` caps the
    /// Steiner points and `Y` forbids them on segments (Triangle's documentation of both says
    /// the mesh may then not meet the quality asked for).
    pub fn may_miss_the_angle(&self) -> bool {
        self.steiner_limit.is_some() || self.whole_segments > 0
    }
}

fn usage(text: &str, what: String) -> Error {
    Error::Usage(format!("--triangle-switches \"{text}\": {what}"))
}

/// Reads the user's switch string. Refuses, as a usage error naming the switch, every switch
/// in `REFUSED`, every character that is not a switch Triangle 1.6 knows, and numbers Triangle
/// would misread or exit on.
pub fn parse(given: &str) -> Result<Switches> {
    let text = given.strip_prefix('-').unwrap_or(given);
    let mut s = Switches {
        text: text.to_string(),
        min_angle: None,
        max_area: None,
        regional_area: false,
        steiner_limit: None,
        whole_segments: 0,
        convex_hull: false,
    };
    let bytes = text.as_bytes();
    let mut i = 0;
    // The run of bytes after position `i` for which `accept` holds.
    let run = |i: usize, accept: fn(u8) -> bool| {
        let end = bytes[i + 1..]
            .iter()
            .position(|&b| !accept(b))
            .map_or(bytes.len(), |k| i + 1 + k);
        (&text[i + 1..end], end)
    };
    let decimal = |b: u8| b.is_ascii_digit() || b == b'.';
    while i < bytes.len() {
        let c = bytes[i];
        if !c.is_ascii() {
            let ch = text[i..].chars().next().unwrap_or('?');
            return Err(usage(text, format!("'{ch}' is not a Triangle switch")));
        }
        let c = c as char;
        if let Some((_, why)) = REFUSED.iter().find(|(r, _)| *r == c) {
            return Err(usage(text, format!("switch {c} is refused: it {why}")));
        }
        let mut next = i + 1;
        match c {
            'p' | 'z' | 'Q' | 'A' | 'u' | 'D' | 'i' | 'F' | 'l' | 's' | 'C' | 'V' => {}
            'c' => s.convex_hull = true,
            'Y' => s.whole_segments += 1,
            'q' | 'a' => {
                let (digits, end) = run(i, decimal);
                next = end;
                if digits.len() >= NUMBER_BUFFER {
                    return Err(usage(
                        text,
                        format!("the number after {c} is longer than Triangle's buffer of {NUMBER_BUFFER} bytes"),
                    ));
                }
                let value = if digits.is_empty() {
                    None
                } else {
                    Some(digits.parse::<f64>().map_err(|_| {
                        usage(text, format!("{c}{digits}: \"{digits}\" is not a number"))
                    })?)
                };
                if c == 'q' {
                    let angle = value.unwrap_or(super::DEFAULT_MIN_ANGLE);
                    if !(0.0..60.0).contains(&angle) {
                        return Err(usage(
                            text,
                            format!("q{digits}: the minimum angle must be in [0°, 60°)"),
                        ));
                    }
                    s.min_angle = Some(angle);
                } else if let Some(area) = value {
                    if !(area.is_finite() && area > 0.0) {
                        return Err(usage(
                            text,
                            format!("a{digits}: the maximum area must be a positive number (Triangle exits on it)"),
                        ));
                    }
                    s.max_area = Some(area);
                } else {
                    s.regional_area = true;
                }
            }
            'S' => {
                let (digits, end) = run(i, |b| b.is_ascii_digit());
                next = end;
                // Triangle accumulates the digits in an int.
                if digits.len() > 9 {
                    return Err(usage(
                        text,
                        format!("S{digits}: at most 999999999 Steiner points (Triangle counts in an int)"),
                    ));
                }
                s.steiner_limit = Some(digits.parse().unwrap_or(0));
            }
            other => {
                return Err(usage(
                    text,
                    format!("'{other}' is not a Triangle switch the harness passes"),
                ))
            }
        }
        i = next;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_read_as_triangle_reads_them() {
        let s = parse("-q25.5a0.125S40YYcDV").unwrap();
        assert_eq!(s.text, "q25.5a0.125S40YYcDV");
        assert_eq!(s.min_angle, Some(25.5));
        assert_eq!(s.max_area, Some(0.125));
        assert_eq!(s.steiner_limit, Some(40));
        assert_eq!(s.whole_segments, 2);
        assert!(s.convex_hull && !s.regional_area && s.may_miss_the_angle());
        let bare = parse("qaS").unwrap();
        assert_eq!(bare.min_angle, Some(20.0));
        assert_eq!(bare.max_area, None);
        assert!(bare.regional_area);
        assert_eq!(bare.steiner_limit, Some(0));
        let last = parse("q10q30").unwrap();
        assert_eq!(last.min_angle, Some(30.0));
        assert!(!parse("q30uDiFlsCAQpz").unwrap().may_miss_the_angle());
    }

    #[test]
    fn every_refused_switch_is_named_in_its_error() {
        for (c, _) in REFUSED {
            let e = parse(&format!("q25{c}")).unwrap_err();
            assert!(matches!(e, Error::Usage(_)), "{c}: {e:?}");
            assert!(
                e.to_string().contains(&format!("switch {c} is refused")),
                "{c}: {e}"
            );
        }
        assert!(parse("o2").unwrap_err().to_string().contains("quadratic"));
    }

    #[test]
    fn unknown_characters_and_bad_numbers_are_refused() {
        for bad in [
            "q 25",
            "q25;",
            "x",
            "qé",
            "a0",
            "a.",
            "a0.0",
            "q1.2.3",
            "q60",
            "q75",
            "S1234567890",
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        let long = format!("a1{}", "0".repeat(NUMBER_BUFFER));
        assert!(parse(&long).unwrap_err().to_string().contains("buffer"));
        assert!(parse("").is_ok());
    }
}
