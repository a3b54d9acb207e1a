//! The bytes of one VTK XML `DataArray` (Kitware, "VTK File Formats", XML formats): inline
//! `binary` (base64) or `appended` (raw or base64) data, each a header of `header_type`
//! words followed by the data, plain or in zlib-compressed blocks
//! (`compressor="vtkZLibDataCompressor"`).
//!
//! Uncompressed, the header is one word: the number of data bytes. Compressed, it is
//! `[blocks, block size, size of the last block, compressed size of each block...]`, and
//! each block is a zlib stream. Writers encode header and data in base64 either together or
//! each with its own padding; [`Base64`] reads both, since it decodes group by group.

/// The width of the header words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum HeaderType {
    UInt32,
    UInt64,
}

/// Where an array's bytes come from.
pub(crate) enum Source<'a> {
    /// Raw bytes (appended `encoding="raw"`), read from `pos`.
    Raw { data: &'a [u8], pos: usize },
    /// Base64 text (inline `binary`, appended `encoding="base64"`).
    Base64(Base64<'a>),
}

impl Source<'_> {
    /// The next `n` bytes; `Err(message)` when the source ends first.
    fn read(&mut self, n: usize, what: &str) -> std::result::Result<Vec<u8>, String> {
        match self {
            Source::Raw { data, pos } => {
                let end = pos
                    .checked_add(n)
                    .filter(|&e| e <= data.len())
                    .ok_or_else(|| {
                        format!(
                            "the appended data end inside {what}, which needs {n} bytes at \
                             offset {pos} of {}",
                            data.len()
                        )
                    })?;
                let out = data[*pos..end].to_vec();
                *pos = end;
                Ok(out)
            }
            Source::Base64(stream) => stream.read(n, what),
        }
    }

    fn word(&mut self, header: HeaderType, what: &str) -> std::result::Result<u64, String> {
        Ok(match header {
            HeaderType::UInt32 => {
                let b = self.read(4, what)?;
                u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            }
            HeaderType::UInt64 => {
                let b = self.read(8, what)?;
                u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
            }
        })
    }
}

/// Reads one array's data from `source`: its header, then its bytes (inflated when
/// `compressed`). Header words are little-endian unless `big_endian`. `Err(message)` says
/// what is wrong, for the caller to place.
pub(crate) fn array_bytes(
    source: &mut Source,
    header: HeaderType,
    big_endian: bool,
    compressed: bool,
) -> std::result::Result<Vec<u8>, String> {
    let word = |source: &mut Source, what: &str| -> std::result::Result<u64, String> {
        let w = source.word(header, what)?;
        Ok(if big_endian {
            match header {
                HeaderType::UInt32 => u64::from((w as u32).swap_bytes()),
                HeaderType::UInt64 => w.swap_bytes(),
            }
        } else {
            w
        })
    };
    let size = |w: u64| usize::try_from(w).map_err(|_| format!("the size {w} is too large"));
    if !compressed {
        let n = size(word(source, "the header")?)?;
        return source.read(n, "the data the header announces");
    }
    let blocks = size(word(source, "the number of compressed blocks")?)?;
    let block_size = size(word(source, "the block size")?)?;
    let last_size = size(word(source, "the size of the last block")?)?;
    let mut compressed_sizes = Vec::with_capacity(blocks.min(1 << 16));
    for _ in 0..blocks {
        compressed_sizes.push(size(word(source, "a compressed block size")?)?);
    }
    let mut out = Vec::new();
    for (k, &n) in compressed_sizes.iter().enumerate() {
        let block = source.read(n, "a compressed block")?;
        let expected = if k + 1 == blocks && last_size != 0 {
            last_size
        } else {
            block_size
        };
        let inflated = inflate(&block, expected)
            .map_err(|e| format!("compressed block {k} does not inflate: {e}"))?;
        if inflated.len() != expected {
            return Err(format!(
                "compressed block {k} inflates to {} bytes, not the {expected} of the header",
                inflated.len()
            ));
        }
        out.extend_from_slice(&inflated);
    }
    Ok(out)
}

/// Inflates one zlib stream of at most `limit` bytes.
#[cfg(feature = "vtu-zlib")]
fn inflate(block: &[u8], limit: usize) -> std::result::Result<Vec<u8>, String> {
    miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(block, limit)
        .map_err(|e| format!("{:?}", e.status))
}

/// Without the `vtu-zlib` feature, compressed files are refused.
#[cfg(not(feature = "vtu-zlib"))]
fn inflate(_block: &[u8], _limit: usize) -> std::result::Result<Vec<u8>, String> {
    Err("hexmesh-core was built without its `vtu-zlib` feature, which inflates zlib data".into())
}

/// Whether this build inflates zlib-compressed `.vtu` data (the `vtu-zlib` feature).
pub(crate) const ZLIB: bool = cfg!(feature = "vtu-zlib");

/// A base64 decoder that reads group by group, skipping whitespace, so that several padded
/// encodings one after another decode as the concatenation of their bytes.
pub(crate) struct Base64<'a> {
    text: &'a [u8],
    pos: usize,
    pending: Vec<u8>,
}

impl<'a> Base64<'a> {
    pub fn new(text: &'a [u8]) -> Base64<'a> {
        Base64 {
            text,
            pos: 0,
            pending: Vec::new(),
        }
    }

    /// The next `n` decoded bytes.
    pub fn read(&mut self, n: usize, what: &str) -> std::result::Result<Vec<u8>, String> {
        while self.pending.len() < n {
            if !self.group()? {
                return Err(format!(
                    "the base64 data end inside {what}, which needs {n} bytes ({} decoded)",
                    self.pending.len()
                ));
            }
        }
        let rest = self.pending.split_off(n);
        Ok(std::mem::replace(&mut self.pending, rest))
    }

    /// Decodes the next group of four characters into `pending`; false at the end.
    fn group(&mut self) -> std::result::Result<bool, String> {
        let mut values = [0u32; 4];
        let mut count = 0;
        let mut padding = 0;
        while count < 4 {
            let Some(&c) = self.text.get(self.pos) else {
                break;
            };
            if c == b'<' {
                break;
            }
            self.pos += 1;
            if c.is_ascii_whitespace() {
                continue;
            }
            let value = match c {
                b'A'..=b'Z' => u32::from(c - b'A'),
                b'a'..=b'z' => u32::from(c - b'a') + 26,
                b'0'..=b'9' => u32::from(c - b'0') + 52,
                b'+' => 62,
                b'/' => 63,
                b'=' if count >= 2 => {
                    padding += 1;
                    0
                }
                _ => {
                    return Err(format!(
                        "'{}' is not a base64 character",
                        char::from(c).escape_default()
                    ))
                }
            };
            if padding > 0 && c != b'=' {
                return Err("base64 data continue inside a padded group".into());
            }
            values[count] = value;
            count += 1;
        }
        let bytes = match (count, padding) {
            (0, _) => return Ok(false),
            (1, _) => return Err("the base64 data end with a lone character".into()),
            (2, 0) | (4, 2) => 1,
            (3, 0) | (4, 1) => 2,
            (4, 0) => 3,
            _ => return Err("malformed base64 padding".into()),
        };
        let word = values[0] << 18 | values[1] << 12 | values[2] << 6 | values[3];
        let decoded = [(word >> 16) as u8, (word >> 8) as u8, word as u8];
        self.pending.extend_from_slice(&decoded[..bytes]);
        Ok(true)
    }
}

/// Base64 with padding, for tests that build files.
#[cfg(test)]
pub(crate) fn encode(bytes: &[u8]) -> String {
    const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let w = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(w >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_padded_pieces_one_after_another() {
        assert_eq!(encode(b"hexmesh"), "aGV4bWVzaA==");
        let text = format!("{} \n {}", encode(b"ab"), encode(b"cdefg"));
        let mut stream = Base64::new(text.as_bytes());
        assert_eq!(stream.read(3, "x").expect("3"), b"abc");
        assert_eq!(stream.read(4, "y").expect("4"), b"defg");
        let e = stream.read(1, "the data").expect_err("end");
        assert!(e.contains("end inside the data"), "{e}");
        let e = Base64::new(b"ab$d").read(1, "x").expect_err("bad");
        assert!(e.contains("'$' is not a base64 character"), "{e}");
    }

    #[test]
    fn uncompressed_arrays_read_their_header_in_either_width() {
        let mut bytes = 5u32.to_le_bytes().to_vec();
        bytes.extend_from_slice(b"12345tail");
        let mut raw = Source::Raw {
            data: &bytes,
            pos: 0,
        };
        assert_eq!(
            array_bytes(&mut raw, HeaderType::UInt32, false, false).expect("raw"),
            b"12345"
        );
        let mut long = 3u64.to_le_bytes().to_vec();
        long.extend_from_slice(b"xyz");
        let text = encode(&long);
        let mut b64 = Source::Base64(Base64::new(text.as_bytes()));
        assert_eq!(
            array_bytes(&mut b64, HeaderType::UInt64, false, false).expect("base64"),
            b"xyz"
        );
        let mut big = 2u32.to_be_bytes().to_vec();
        big.extend_from_slice(b"ok");
        let mut raw = Source::Raw { data: &big, pos: 0 };
        assert_eq!(
            array_bytes(&mut raw, HeaderType::UInt32, true, false).expect("big"),
            b"ok"
        );
        let short = [9u8, 0, 0, 0, 1, 2];
        let mut raw = Source::Raw {
            data: &short,
            pos: 0,
        };
        let e = array_bytes(&mut raw, HeaderType::UInt32, false, false).expect_err("short");
        assert!(e.contains("needs 9 bytes"), "{e}");
    }

    #[cfg(feature = "vtu-zlib")]
    #[test]
    fn compressed_arrays_inflate_block_by_block() {
        let data: Vec<u8> = (0..100u8).collect();
        let (a, b) = data.split_at(64);
        let za = miniz_oxide::deflate::compress_to_vec_zlib(a, 6);
        let zb = miniz_oxide::deflate::compress_to_vec_zlib(b, 6);
        let mut header = Vec::new();
        for w in [2u32, 64, 36, za.len() as u32, zb.len() as u32] {
            header.extend_from_slice(&w.to_le_bytes());
        }
        let mut body = za.clone();
        body.extend_from_slice(&zb);
        // Header and data each encoded with its own padding, as meshio and VTK write them.
        let text = format!("{}{}", encode(&header), encode(&body));
        let mut source = Source::Base64(Base64::new(text.as_bytes()));
        assert_eq!(
            array_bytes(&mut source, HeaderType::UInt32, false, true).expect("inflated"),
            data
        );
        let mut broken = body.clone();
        broken[3] ^= 0xff;
        let text = format!("{}{}", encode(&header), encode(&broken));
        let mut source = Source::Base64(Base64::new(text.as_bytes()));
        let e = array_bytes(&mut source, HeaderType::UInt32, false, true).expect_err("broken");
        assert!(e.contains("compressed block 0"), "{e}");
    }
}
