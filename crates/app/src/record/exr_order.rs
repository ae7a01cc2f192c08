//! The same EXR bytes for the same frame: the exr crate writes a header's attributes in
//! hash-map order, which changes from run to run, so shards and resumed runs could not
//! match a single run byte for byte. The attributes are sorted by name in place; the
//! header keeps its length, so the chunk offsets after it stay right.

use anyhow::{Context, bail};

/// The magic number that opens every OpenEXR file.
const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// The version field's multi-part flag (OpenEXR file layout, "version field").
const MULTI_PART: u32 = 0x1000;

/// Sorts the attributes of a single-part EXR's header by name.
pub fn sort_header_attributes(bytes: &mut [u8]) -> anyhow::Result<()> {
    if bytes.len() < 8 || bytes[..4] != MAGIC {
        bail!("not an OpenEXR file");
    }
    let version = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
    if version & MULTI_PART != 0 {
        bail!("a multi-part EXR, whose headers are not sorted here");
    }
    let truncated = || "the EXR header ends early";
    let zero_after = |from: usize| {
        bytes
            .get(from..)
            .and_then(|rest| rest.iter().position(|&b| b == 0))
            .map(|i| from + i)
            .with_context(truncated)
    };
    let mut records = Vec::new();
    let mut at = 8;
    while *bytes.get(at).with_context(truncated)? != 0 {
        let name_end = zero_after(at)?;
        let type_end = zero_after(name_end + 1)?;
        let size_at = type_end + 1;
        let size = bytes.get(size_at..size_at + 4).with_context(truncated)?;
        let size = u32::from_le_bytes([size[0], size[1], size[2], size[3]]) as usize;
        let end = size_at + 4 + size;
        if end > bytes.len() {
            bail!(truncated());
        }
        records.push((at, name_end, end));
        at = end;
    }
    records.sort_by(|a, b| bytes[a.0..a.1].cmp(&bytes[b.0..b.1]));
    let sorted: Vec<u8> = records
        .iter()
        .flat_map(|&(start, _, end)| bytes[start..end].to_vec())
        .collect();
    bytes[8..at].copy_from_slice(&sorted);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A header of two attributes in the wrong order, then the end byte and a chunk.
    fn file(first: (&str, &[u8]), second: (&str, &[u8])) -> Vec<u8> {
        let mut bytes = MAGIC.to_vec();
        bytes.extend(2u32.to_le_bytes());
        for (name, value) in [first, second] {
            bytes.extend(name.as_bytes());
            bytes.extend(b"\0string\0");
            bytes.extend((value.len() as u32).to_le_bytes());
            bytes.extend(value);
        }
        bytes.push(0);
        bytes.extend(b"chunk");
        bytes
    }

    #[test]
    fn attributes_are_sorted_by_name_and_the_rest_kept() {
        let mut bytes = file(("zeta", b"zz\0z"), ("alpha", b""));
        sort_header_attributes(&mut bytes).unwrap();
        assert_eq!(bytes, file(("alpha", b""), ("zeta", b"zz\0z")));
        let mut short = bytes[..20].to_vec();
        let e = sort_header_attributes(&mut short).unwrap_err().to_string();
        assert_eq!(e, "the EXR header ends early");
        assert!(sort_header_attributes(&mut [0u8; 12]).is_err());
    }
}
