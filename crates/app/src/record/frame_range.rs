//! `--frames`: which frames of a path to record, by index from 0, as Rust writes ranges:
//! `A..B` (A to B-1), `A..=B` (A to B), `A..` (A to the last), `..B`, or one index `A`.

use std::ops::Range;

use anyhow::{Context, bail};

/// A range of frame indices as given, its end checked against the path's frame count
/// by [`FrameRange::resolve`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameRange {
    text: String,
    start: u64,
    /// One past the last frame; `None`: to the path's end.
    end: Option<u64>,
}

impl FrameRange {
    /// The range of `--frames TEXT`.
    pub fn parse(text: &str) -> anyhow::Result<FrameRange> {
        let number = |s: &str| {
            s.trim().parse::<u64>().with_context(|| {
                format!("--frames {text}: '{s}' is not a frame index (a whole number >= 0)")
            })
        };
        let (start, end) = match text.split_once("..") {
            None => {
                let at = number(text)?;
                (at, Some(at + 1))
            }
            Some((a, b)) => {
                let start = if a.trim().is_empty() { 0 } else { number(a)? };
                let end = match b.strip_prefix('=') {
                    Some(last) => Some(
                        number(last)?
                            .checked_add(1)
                            .context("--frames: too large")?,
                    ),
                    None if b.trim().is_empty() => None,
                    None => Some(number(b)?),
                };
                (start, end)
            }
        };
        if let Some(end) = end
            && end <= start
        {
            bail!(
                "--frames {text} selects no frame: the end must come after the start (A..B renders A to B-1, A..=B A to B)"
            );
        }
        Ok(FrameRange {
            text: text.to_string(),
            start,
            end,
        })
    }

    /// The indices selected from a path of `count` frames; an error names the count when
    /// the range runs past it.
    pub fn resolve(&self, count: u64) -> anyhow::Result<Range<u64>> {
        let end = self.end.unwrap_or(count);
        if self.start >= count || end > count {
            bail!(
                "--frames {} runs past the path's {count} frames (indices 0 to {})",
                self.text,
                count.saturating_sub(1)
            );
        }
        Ok(self.start..end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(text: &str, count: u64) -> anyhow::Result<Range<u64>> {
        FrameRange::parse(text)?.resolve(count)
    }

    fn err(result: anyhow::Result<Range<u64>>) -> String {
        format!("{:#}", result.unwrap_err())
    }

    #[test]
    fn every_form_selects_its_frames() {
        assert_eq!(frames("2..5", 10).unwrap(), 2..5);
        assert_eq!(frames("2..=5", 10).unwrap(), 2..6);
        assert_eq!(frames("7..", 10).unwrap(), 7..10);
        assert_eq!(frames("..3", 10).unwrap(), 0..3);
        assert_eq!(frames("4", 10).unwrap(), 4..5);
        assert_eq!(frames("0..10", 10).unwrap(), 0..10);
    }

    #[test]
    fn bad_ranges_are_named() {
        assert!(err(frames("5..2", 10)).contains("--frames 5..2 selects no frame"));
        assert!(err(frames("3..3", 10)).contains("selects no frame"));
        assert!(err(frames("a..2", 10)).contains("'a' is not a frame index"));
        assert!(err(frames("-1..2", 10)).contains("'-1' is not a frame index"));
        assert_eq!(
            err(frames("0..11", 10)),
            "--frames 0..11 runs past the path's 10 frames (indices 0 to 9)"
        );
        assert!(err(frames("10..", 10)).contains("runs past"));
    }
}
