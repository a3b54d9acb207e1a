//! A cursor over the bytes of a mesh file that mixes text lines and binary blocks (Gmsh `.msh`
//! binary, VTK legacy BINARY): text is read line by line or token by token and its errors
//! name the line; binary is read as fixed-size numbers and its errors name the byte offset.
//! Nothing here panics on malformed or truncated input, and nothing allocates by a count the
//! file claims.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// The byte order of a binary block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Endian {
    /// Least significant byte first (x86, and most files written today).
    Little,
    /// Most significant byte first (VTK legacy BINARY, always).
    Big,
}

/// The bytes of one file and a position in them.
pub(crate) struct Scan<'a> {
    path: PathBuf,
    data: &'a [u8],
    pos: usize,
}

impl<'a> Scan<'a> {
    pub fn new(path: &Path, data: &'a [u8]) -> Scan<'a> {
        Scan {
            path: path.to_path_buf(),
            data,
            pos: 0,
        }
    }

    pub fn pos(&self) -> usize {
        self.pos
    }

    /// The 1-based line that byte `pos` lies on.
    pub fn line_of(&self, pos: usize) -> usize {
        let end = pos.min(self.data.len());
        1 + self.data[..end].iter().filter(|&&b| b == b'\n').count()
    }

    /// A parse error at the line of byte `pos`.
    pub fn error_at(&self, pos: usize, message: impl Into<String>) -> Error {
        Error::parse(&self.path, self.line_of(pos), message)
    }

    /// A parse error in binary data, naming the byte offset `pos` (not a line).
    pub fn error_at_byte(&self, pos: usize, message: impl AsRef<str>) -> Error {
        Error::parse(
            &self.path,
            0,
            format!("at byte offset {pos}: {}", message.as_ref()),
        )
    }

    /// The next line (without its `\n` or `\r\n`) and the offset it starts at; `None` at the
    /// end of the file. Bytes that are not UTF-8 are an error at their line.
    pub fn next_line(&mut self) -> Result<Option<(usize, &'a str)>> {
        if self.pos >= self.data.len() {
            return Ok(None);
        }
        let start = self.pos;
        let rest = &self.data[start..];
        let (line, next) = match rest.iter().position(|&b| b == b'\n') {
            Some(at) => (&rest[..at], start + at + 1),
            None => (rest, self.data.len()),
        };
        self.pos = next;
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        std::str::from_utf8(line)
            .map(|text| Some((start, text)))
            .map_err(|_| self.error_at(start, "this line is not UTF-8 text"))
    }

    /// The next line with something other than whitespace on it, trimmed.
    pub fn next_nonblank_line(&mut self) -> Result<Option<(usize, &'a str)>> {
        while let Some((start, text)) = self.next_line()? {
            if !text.trim().is_empty() {
                return Ok(Some((start, text.trim())));
            }
        }
        Ok(None)
    }

    /// Like [`Scan::next_nonblank_line`], but the end of the file is an error saying what was
    /// expected.
    pub fn expect_line(&mut self, what: &str) -> Result<(usize, &'a str)> {
        match self.next_nonblank_line()? {
            Some(found) => Ok(found),
            None => Err(self.end_error(what)),
        }
    }

    /// The error for a file that ends where `what` was expected, at its last line.
    pub fn end_error(&self, what: &str) -> Error {
        let last = self.data.len().saturating_sub(1);
        self.error_at(last, format!("the file ends where {what} was expected"))
    }

    /// Moves past whitespace (line ends included), to where the next token starts.
    pub fn skip_whitespace(&mut self) {
        while self.pos < self.data.len() && self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its offset, crossing lines; `None` at the end.
    pub fn next_token(&mut self) -> Result<Option<(usize, &'a str)>> {
        self.skip_whitespace();
        if self.pos >= self.data.len() {
            return Ok(None);
        }
        let start = self.pos;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        std::str::from_utf8(&self.data[start..self.pos])
            .map(|t| Some((start, t)))
            .map_err(|_| self.error_at(start, "this token is not UTF-8 text"))
    }

    /// The next token; the end of the file is an error naming `what`.
    pub fn token(&mut self, what: &str) -> Result<(usize, &'a str)> {
        match self.next_token()? {
            Some(found) => Ok(found),
            None => Err(self.end_error(what)),
        }
    }

    /// The next token as an integer of type `T`.
    pub fn int<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let (at, token) = self.token(what)?;
        token.parse().map_err(|_| {
            self.error_at(
                at,
                format!("{what} must be a non-negative integer in range, found '{token}'"),
            )
        })
    }

    /// The next token as a finite f64 (Rust's correctly rounded parse).
    pub fn float(&mut self, what: &str) -> Result<f64> {
        let (at, token) = self.token(what)?;
        let value: f64 = token
            .parse()
            .map_err(|_| self.error_at(at, format!("{what} must be a number, found '{token}'")))?;
        if !value.is_finite() {
            return Err(self.error_at(
                at,
                format!("{what} is '{token}': NaN and infinite values are refused"),
            ));
        }
        Ok(value)
    }

    /// Skips one line end (`\n` or `\r\n`) if one comes next, as after a binary block.
    pub fn skip_newline(&mut self) {
        let rest = &self.data[self.pos.min(self.data.len())..];
        if rest.starts_with(b"\n") {
            self.pos += 1;
        } else if rest.starts_with(b"\r\n") {
            self.pos += 2;
        }
    }

    /// Skips the rest of the current line.
    pub fn skip_line(&mut self) -> Result<()> {
        self.next_line().map(|_| ())
    }

    /// Moves to just after the line that is exactly `marker` (trimmed), searching from here;
    /// for sections that are skipped unread. `what` names the section for the error.
    pub fn skip_past_line(&mut self, marker: &str, what: &str) -> Result<()> {
        let from = self.pos;
        let needle = marker.as_bytes();
        let mut at = from;
        while let Some(found) = find(&self.data[at..], needle) {
            let start = at + found;
            let end = start + needle.len();
            let line_start = start == 0
                || self.data[..start]
                    .iter()
                    .rev()
                    .take_while(|&&b| b != b'\n')
                    .all(|b| b.is_ascii_whitespace());
            let rest = &self.data[end..];
            let line_end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            if line_start && rest[..line_end].iter().all(|b| b.is_ascii_whitespace()) {
                self.pos = (end + line_end + 1).min(self.data.len());
                return Ok(());
            }
            at = end;
        }
        Err(self.error_at(from, format!("{what} has no closing {marker} line")))
    }

    /// The next `n` bytes, for `what`; the end of the file is an error naming the offset.
    pub fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        let start = self.pos;
        match start.checked_add(n).filter(|&end| end <= self.data.len()) {
            Some(end) => {
                self.pos = end;
                Ok(&self.data[start..end])
            }
            None => Err(self.error_at_byte(
                start,
                format!(
                    "the file ends (at byte {}) inside {what}, which needs {n} bytes",
                    self.data.len()
                ),
            )),
        }
    }

    /// Fails unless at least `count` records of `size` bytes are left: checked before a loop
    /// over a count the file claims, so that a truncated file fails at once.
    pub fn require(&self, count: usize, size: usize, what: &str) -> Result<()> {
        let left = self.data.len() - self.pos.min(self.data.len());
        match count.checked_mul(size) {
            Some(needed) if needed <= left => Ok(()),
            _ => Err(self.error_at_byte(
                self.pos,
                format!(
                    "{what}: {count} records of {size} bytes do not fit in the {left} bytes \
                     left in the file"
                ),
            )),
        }
    }

    pub fn i32(&mut self, endian: Endian, what: &str) -> Result<i32> {
        Ok(i32::from_ne_bytes(ordered(self.bytes(4, what)?, endian)))
    }

    pub fn u64(&mut self, endian: Endian, what: &str) -> Result<u64> {
        Ok(u64::from_ne_bytes(ordered(self.bytes(8, what)?, endian)))
    }

    pub fn i64(&mut self, endian: Endian, what: &str) -> Result<i64> {
        Ok(i64::from_ne_bytes(ordered(self.bytes(8, what)?, endian)))
    }

    pub fn f32(&mut self, endian: Endian, what: &str) -> Result<f32> {
        Ok(f32::from_ne_bytes(ordered(self.bytes(4, what)?, endian)))
    }

    pub fn f64(&mut self, endian: Endian, what: &str) -> Result<f64> {
        Ok(f64::from_ne_bytes(ordered(self.bytes(8, what)?, endian)))
    }
}

/// `bytes` (exactly N of them) reordered from `endian` to the machine's order.
pub(crate) fn ordered<const N: usize>(bytes: &[u8], endian: Endian) -> [u8; N] {
    let mut out = [0u8; N];
    out.copy_from_slice(&bytes[..N]);
    let native = if cfg!(target_endian = "little") {
        Endian::Little
    } else {
        Endian::Big
    };
    if endian != native {
        out.reverse();
    }
    out
}

/// The first offset of `needle` in `haystack`.
pub(crate) fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    if needle.is_empty() || needle.len() > haystack.len() {
        return None;
    }
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// Runs `parse` on every truncation of `bytes` and on copies with one byte changed at every
/// offset (to each of a few values), for the readers' tests: each must return, never panic.
/// Returns how many of the truncations were refused; a truncation may still read (a file cut
/// after its last section).
#[cfg(test)]
pub(crate) fn refuses_without_panic<T>(bytes: &[u8], parse: impl Fn(&[u8]) -> Result<T>) -> usize {
    let mut refused = 0;
    for end in 0..bytes.len() {
        refused += usize::from(parse(&bytes[..end]).is_err());
    }
    let mut copy = bytes.to_vec();
    for at in 0..bytes.len() {
        for value in [
            b'0',
            b'9',
            b'-',
            b' ',
            b'\n',
            b'<',
            0x00,
            0xff,
            bytes[at] ^ 0x80,
        ] {
            copy[at] = value;
            let _ = parse(&copy);
        }
        copy[at] = bytes[at];
    }
    refused
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_cross_lines_and_errors_name_their_line() {
        let text = b"3 4\n\n  x 5\n";
        let mut scan = Scan::new(Path::new("t.msh"), text);
        assert_eq!(scan.int::<u32>("a").expect("3"), 3);
        assert_eq!(scan.int::<u32>("b").expect("4"), 4);
        match scan.int::<u32>("c") {
            Err(Error::Parse { line, message, .. }) => {
                assert_eq!(line, 3);
                assert!(message.contains("found 'x'"), "{message}");
            }
            other => panic!("unexpected {other:?}"),
        }
        assert_eq!(scan.int::<u32>("d").expect("5"), 5);
        let e = scan.int::<u32>("the node count").expect_err("end");
        assert!(
            e.to_string()
                .contains("ends where the node count was expected"),
            "{e}"
        );
    }

    #[test]
    fn binary_reads_honour_byte_order_and_name_the_offset_when_short() {
        let mut data = vec![b'\n'];
        data.extend_from_slice(&1.5f64.to_be_bytes());
        data.extend_from_slice(&7i32.to_le_bytes());
        data.extend_from_slice(&[1, 2]);
        let mut scan = Scan::new(Path::new("t.vtk"), &data);
        scan.skip_line().expect("line");
        assert_eq!(scan.f64(Endian::Big, "x").expect("x"), 1.5);
        assert_eq!(scan.i32(Endian::Little, "n").expect("n"), 7);
        let e = scan.i32(Endian::Little, "a tag").expect_err("short");
        assert_eq!(
            e.to_string(),
            "t.vtk: at byte offset 13: the file ends (at byte 15) inside a tag, which needs 4 bytes"
        );
        assert!(scan.require(usize::MAX, 8, "nodes").is_err());
    }

    #[test]
    fn skip_past_line_needs_the_marker_alone_on_its_line() {
        let text = b"$Foo\nnot $EndFoo here\n $EndFoo \n$Next\n";
        let mut scan = Scan::new(Path::new("t.msh"), text);
        scan.skip_line().expect("head");
        scan.skip_past_line("$EndFoo", "section $Foo")
            .expect("found");
        assert_eq!(scan.next_line().expect("line"), Some((32, "$Next")));
        let mut scan = Scan::new(Path::new("t.msh"), b"$Foo\n1 2\n");
        let e = scan
            .skip_past_line("$EndFoo", "section $Foo")
            .expect_err("missing");
        assert!(e.to_string().contains("no closing $EndFoo line"), "{e}");
    }
}
