//! Reading a text input file (an atmosphere or scene TOML, a probe CSV) with bounds: at
//! most `max_bytes` in all and `max_line_bytes` per line, each line decoded as UTF-8 on
//! its own so that an invalid byte is reported with its line and column. A file without
//! end (`/dev/zero`, an endless FIFO) stops at the first bound it passes.

use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

use thiserror::Error;

/// The bounds of one kind of input file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextLimits {
    /// Largest file, bytes.
    pub max_bytes: u64,
    /// Longest line, bytes, without its line break.
    pub max_line_bytes: usize,
}

/// TOML files (atmospheres, scenes): 1 MiB, lines of 64 KiB (a spectral table on one line
/// is a few kilobytes).
pub const TOML_LIMITS: TextLimits = TextLimits {
    max_bytes: 1 << 20,
    max_line_bytes: 64 << 10,
};

/// What is wrong with a text file. Lines and columns count from 1; columns in characters.
#[derive(Debug, Error)]
pub enum TextFileError {
    #[error("cannot read {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path} is larger than {max_bytes} bytes, the most this file may hold")]
    TooLarge { path: String, max_bytes: u64 },
    #[error("{path} line {line} is longer than {max_line_bytes} bytes, the longest line allowed")]
    LineTooLong {
        path: String,
        line: u64,
        max_line_bytes: usize,
    },
    #[error("{path} line {line}, column {column}: not UTF-8 text (byte 0x{byte:02x})")]
    NotUtf8 {
        path: String,
        line: u64,
        column: usize,
        byte: u8,
    },
}

/// The text of the file at `path` within `limits`.
pub fn read_text(path: &Path, limits: TextLimits) -> Result<String, TextFileError> {
    let name = path.display().to_string();
    let file = File::open(path).map_err(|source| TextFileError::Io {
        path: name.clone(),
        source,
    })?;
    read_text_from(BufReader::new(file), &name, limits)
}

/// The text read from `reader` (named `name` in errors) within `limits`.
pub fn read_text_from(
    mut reader: impl BufRead,
    name: &str,
    limits: TextLimits,
) -> Result<String, TextFileError> {
    let mut text = String::new();
    let mut bytes = Vec::new();
    for line in 1u64.. {
        bytes.clear();
        // A line break and one byte more than allowed tell a too-long line apart.
        let cap = limits.max_line_bytes as u64 + 2;
        let read = (&mut reader)
            .take(cap)
            .read_until(b'\n', &mut bytes)
            .map_err(|source| TextFileError::Io {
                path: name.to_string(),
                source,
            })?;
        if read == 0 {
            break;
        }
        let content = bytes.strip_suffix(b"\n").unwrap_or(&bytes);
        let content = content.strip_suffix(b"\r").unwrap_or(content);
        if content.len() > limits.max_line_bytes {
            return Err(TextFileError::LineTooLong {
                path: name.to_string(),
                line,
                max_line_bytes: limits.max_line_bytes,
            });
        }
        if (text.len() + bytes.len()) as u64 > limits.max_bytes {
            return Err(TextFileError::TooLarge {
                path: name.to_string(),
                max_bytes: limits.max_bytes,
            });
        }
        match std::str::from_utf8(&bytes) {
            Ok(decoded) => text.push_str(decoded),
            Err(e) => {
                let valid = &bytes[..e.valid_up_to()];
                let column = String::from_utf8_lossy(valid).chars().count() + 1;
                return Err(TextFileError::NotUtf8 {
                    path: name.to_string(),
                    line,
                    column,
                    byte: bytes[e.valid_up_to()],
                });
            }
        }
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: TextLimits = TextLimits {
        max_bytes: 64,
        max_line_bytes: 16,
    };

    fn read(bytes: &[u8]) -> Result<String, TextFileError> {
        read_text_from(bytes, "f.txt", SMALL)
    }

    #[test]
    fn text_within_the_limits_reads_whole() {
        let text = "a = 1\r\n# é\nlast line";
        assert_eq!(read(text.as_bytes()).unwrap(), text);
        assert_eq!(read(b"").unwrap(), "");
    }

    #[test]
    fn an_invalid_byte_is_named_by_line_and_column() {
        let err = read(b"a = 1\n# \xc3\xa9 \xff\nb = 2\n").unwrap_err();
        assert_eq!(
            err.to_string(),
            "f.txt line 2, column 5: not UTF-8 text (byte 0xff)"
        );
    }

    #[test]
    fn long_lines_and_large_files_are_refused() {
        let line = [b'x'; 16];
        assert!(read(&line).is_ok());
        let err = read(&[b'x'; 17]).unwrap_err();
        assert!(
            matches!(err, TextFileError::LineTooLong { line: 1, .. }),
            "{err}"
        );
        let many = "0123456789\n".repeat(6);
        let err = read(many.as_bytes()).unwrap_err();
        assert!(
            matches!(err, TextFileError::TooLarge { max_bytes: 64, .. }),
            "{err}"
        );
    }

    #[test]
    fn an_endless_stream_stops_at_the_line_bound() {
        let err = read_text_from(std::io::BufReader::new(std::io::repeat(0)), "zeros", SMALL)
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "zeros line 1 is longer than 16 bytes, the longest line allowed"
        );
    }
}
