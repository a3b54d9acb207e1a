//! Line-numbered tokenizer for Triangle's text formats (Shewchuk, "Triangle" file format pages):
//! `#` starts a comment anywhere on a line, blank lines are skipped, fields are separated by
//! whitespace. Every row keeps its 1-based line number so that errors can name it.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// The one comment that carries data: `# hexmesh: hexagon CX CY CIRCUMRADIUS [COS SIN]`
/// records a bounding hexagon (and its turn) that Triangle's formats cannot express; Triangle
/// itself ignores it.
pub(crate) const DIRECTIVE: &str = "hexmesh:";

/// One non-empty row: its line and its whitespace-separated fields.
#[derive(Debug)]
pub(crate) struct Row<'a> {
    pub line: usize,
    pub tokens: Vec<&'a str>,
}

/// A `# hexmesh: ...` comment and its line.
pub(crate) struct Directive<'a> {
    pub line: usize,
    pub tokens: Vec<&'a str>,
}

/// The rows of one file, read front to back.
pub(crate) struct Lines<'a> {
    path: PathBuf,
    rows: std::iter::Enumerate<std::str::Lines<'a>>,
    /// Number of lines seen so far, so that "the file ends" errors can point at the end.
    last_line: usize,
    pub directives: Vec<Directive<'a>>,
}

impl<'a> Lines<'a> {
    pub fn new(path: &Path, text: &'a str) -> Lines<'a> {
        Lines {
            path: path.to_path_buf(),
            rows: text.lines().enumerate(),
            last_line: 0,
            directives: Vec::new(),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The next row with at least one field, or `None` at the end of the file.
    pub fn next_row(&mut self) -> Option<Row<'a>> {
        for (index, text) in self.rows.by_ref() {
            let line = index + 1;
            self.last_line = line;
            let (data, comment) = match text.find('#') {
                Some(at) => (&text[..at], Some(&text[at + 1..])),
                None => (text, None),
            };
            if let Some(comment) = comment {
                let comment = comment.trim_start();
                if let Some(rest) = comment.strip_prefix(DIRECTIVE) {
                    self.directives.push(Directive {
                        line,
                        tokens: rest.split_whitespace().collect(),
                    });
                }
            }
            let tokens: Vec<&str> = data.split_whitespace().collect();
            if !tokens.is_empty() {
                return Some(Row { line, tokens });
            }
        }
        None
    }

    /// The next row; the end of the file is an error saying what was still expected.
    pub fn expect_row(&mut self, what: &str) -> Result<Row<'a>> {
        match self.next_row() {
            Some(row) => Ok(row),
            None => Err(self.error(
                self.end_line(),
                format!("the file ends where {what} was expected"),
            )),
        }
    }

    /// Fails when any data row is left: a header that promises fewer rows than the file has is
    /// as wrong as one that promises more.
    pub fn expect_end(&mut self, after: &str) -> Result<()> {
        match self.next_row() {
            None => Ok(()),
            Some(row) => Err(self.error(
                row.line,
                format!("unexpected data after {after}: '{}'", row.tokens.join(" ")),
            )),
        }
    }

    /// The line to blame once `next_row` has returned `None`: the file's last line, at least 1.
    pub fn end_line(&self) -> usize {
        self.last_line.max(1)
    }

    pub fn error(&self, line: usize, message: impl Into<String>) -> Error {
        Error::parse(&self.path, line, message)
    }

    /// Field `i` of `row` as a finite float. Rust parses "nan" and "inf"; Triangle's formats
    /// carry coordinates, so those are refused by name.
    pub fn float(&self, row: &Row, i: usize, what: &str) -> Result<f64> {
        let token = row.tokens[i];
        let value: f64 = token.parse().map_err(|_| {
            self.error(
                row.line,
                format!("{what} must be a number, found '{token}'"),
            )
        })?;
        if !value.is_finite() {
            return Err(self.error(
                row.line,
                format!("{what} is '{token}': NaN and infinite values are refused"),
            ));
        }
        Ok(value)
    }

    /// Field `i` of `row` as an integer.
    pub fn int(&self, row: &Row, i: usize, what: &str) -> Result<i64> {
        let token = row.tokens[i];
        token.parse().map_err(|_| {
            self.error(
                row.line,
                format!("{what} must be an integer, found '{token}'"),
            )
        })
    }

    /// Field `i` of `row` as a count (a non-negative integer).
    pub fn count(&self, row: &Row, i: usize, what: &str) -> Result<usize> {
        let n = self.int(row, i, what)?;
        usize::try_from(n)
            .map_err(|_| self.error(row.line, format!("{what} must not be negative, found {n}")))
    }

    /// Field `i` of `row` as a 0/1 flag, as Triangle's "number of boundary markers".
    pub fn flag(&self, row: &Row, i: usize, what: &str) -> Result<bool> {
        match self.int(row, i, what)? {
            0 => Ok(false),
            1 => Ok(true),
            n => Err(self.error(row.line, format!("{what} must be 0 or 1, found {n}"))),
        }
    }

    /// Field `i` of `row` as a vertex number as written (not yet shifted to 0-based).
    pub fn vertex(&self, row: &Row, i: usize, what: &str) -> Result<u32> {
        let n = self.int(row, i, what)?;
        u32::try_from(n).map_err(|_| {
            self.error(
                row.line,
                format!("{what} is {n}, which is not a valid vertex number"),
            )
        })
    }

    /// Fails unless `row` has between `min` and `max` fields; `layout` names them.
    pub fn fields(&self, row: &Row, min: usize, max: usize, layout: &str) -> Result<()> {
        let n = row.tokens.len();
        if n < min || n > max {
            let expected = if min == max {
                format!("{min}")
            } else {
                format!("{min} to {max}")
            };
            return Err(self.error(
                row.line,
                format!("expected {expected} fields ({layout}), found {n}"),
            ));
        }
        Ok(())
    }
}

/// Reads a whole file as text; bytes that are not UTF-8 are a parse error at their line.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count();
        Error::parse(path, line, "the file is not UTF-8 text")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_blank_lines_are_skipped_and_lines_counted() {
        let text = "# header comment\n\n3 2 # trailing\n  \n# hexmesh: hexagon 0 0 1\n4 5\n";
        let mut lines = Lines::new(Path::new("t.node"), text);
        let a = lines.next_row().expect("first row");
        assert_eq!((a.line, a.tokens), (3, vec!["3", "2"]));
        let b = lines.next_row().expect("second row");
        assert_eq!((b.line, b.tokens), (6, vec!["4", "5"]));
        assert!(lines.next_row().is_none());
        assert_eq!(lines.directives.len(), 1);
        assert_eq!(lines.directives[0].line, 5);
        assert_eq!(lines.directives[0].tokens, vec!["hexagon", "0", "0", "1"]);
    }

    #[test]
    fn nan_and_infinity_are_refused_by_name() {
        let mut lines = Lines::new(Path::new("t.node"), "nan inf 1e400 -0.0");
        let row = lines.next_row().expect("row");
        for i in 0..3 {
            let e = lines.float(&row, i, "x").expect_err("non-finite accepted");
            assert!(e.to_string().contains("NaN and infinite"), "{e}");
        }
        assert_eq!(
            lines.float(&row, 3, "x").expect("-0.0").to_bits(),
            (-0.0f64).to_bits()
        );
    }

    #[test]
    fn end_of_file_errors_point_at_the_last_line() {
        let mut lines = Lines::new(Path::new("t.node"), "1 2\n# c\n\n");
        lines.next_row();
        match lines.expect_row("a point") {
            Err(Error::Parse { line, .. }) => assert_eq!(line, 3),
            other => panic!("unexpected {other:?}"),
        }
    }
}
