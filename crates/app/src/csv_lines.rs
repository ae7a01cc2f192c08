//! CSV input read one record per line, so that every error can name its line: blank
//! lines and lines starting with `#` are skipped.

/// The lines holding records, with their numbers from 1.
pub fn record_lines(text: &str) -> impl Iterator<Item = (u64, &str)> {
    (1..).zip(text.lines()).filter(|(_, l)| {
        let l = l.trim_start();
        !l.is_empty() && !l.starts_with('#')
    })
}

/// The trimmed fields of one line's record (none for an empty record).
pub fn record_fields(line: &str) -> Result<Vec<String>, csv::Error> {
    let record = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(line.as_bytes())
        .records()
        .next()
        .transpose()?;
    Ok(record.map_or_else(Vec::new, |r| r.iter().map(str::to_string).collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_blank_lines_are_skipped_and_fields_trimmed() {
        let lines: Vec<_> = record_lines("# c\na, b\n\n  # d\n\"x,y\",2\n").collect();
        assert_eq!(lines, vec![(2, "a, b"), (5, "\"x,y\",2")]);
        assert_eq!(record_fields(lines[0].1).unwrap(), ["a", "b"]);
        assert_eq!(record_fields(lines[1].1).unwrap(), ["x,y", "2"]);
    }
}
