//! The file layout of the report's path-traced caches (`clouds_reference.rs`,
//! `optics_reference.rs`): a title line, the column header (`view, ray`, the row's
//! numbers, `paths`), then per view a line `# view <id> fingerprint <16 hex digits>`
//! followed by its rays in order. A view whose fingerprint no longer matches what its
//! answers depend on is computed again.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use anyhow::{Context, bail};

use crate::files::write_atomically;

const VIEW_MARK: &str = "# view ";

/// One ray's answer as a row of numbers and its path count.
pub trait RayRow: Sized {
    /// The numbers between `ray` and `paths`, in the header's order.
    fn numbers(&self) -> Vec<f64>;
    fn paths(&self) -> u64;
    /// The answer from `numbers` (as many as the header names) and `paths`.
    fn from_numbers(numbers: &[f64], paths: u64) -> Self;
}

/// What a cached view holds: its fingerprint and its rays' answers.
pub type Sections<T> = BTreeMap<String, (String, Vec<T>)>;

/// A stable 64-bit hash (FNV-1a) of `text`, as 16 hex digits: a view's fingerprint.
pub fn fingerprint_of(text: &str) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{hash:016x}")
}

/// A view the section asks of its cache.
#[derive(Clone, Copy, Debug)]
pub struct Wanted<'a> {
    pub id: &'a str,
    /// What its answers depend on now.
    pub fingerprint: &'a str,
    /// Its rays.
    pub rays: usize,
    /// Computed again whatever the cache holds.
    pub recompute: bool,
}

/// Each of `wanted`'s answers from the cache at `path` where its fingerprint and ray
/// count match and it is not to be recomputed, else none; and the indices of the views
/// without answers, each said on stderr with the reason (a cache of another layout is
/// said once and taken as empty).
pub fn cached<T: RayRow>(
    path: &Path,
    title: &str,
    header: &str,
    wanted: &[Wanted],
) -> (Vec<Vec<T>>, Vec<usize>) {
    let mut sections = Sections::new();
    if path.exists() {
        match read(path, title, header) {
            Ok(found) => sections = found,
            Err(why) => eprintln!(
                "report: recomputing every view of {} ({why:#})",
                path.display()
            ),
        }
    }
    let mut answers = Vec::with_capacity(wanted.len());
    let mut missing = Vec::new();
    for (i, w) in wanted.iter().enumerate() {
        match sections.remove(w.id) {
            Some((key, rays)) if key == w.fingerprint && rays.len() == w.rays && !w.recompute => {
                answers.push(rays);
            }
            found => {
                let why = if w.recompute {
                    "asked to recompute it"
                } else if found.is_some() {
                    "what it depends on changed"
                } else {
                    "not in the cache"
                };
                eprintln!(
                    "report: computing view {} of {} ({why})",
                    w.id,
                    path.display()
                );
                answers.push(Vec::new());
                missing.push(i);
            }
        }
    }
    (answers, missing)
}

/// Writes `views` (id, fingerprint, answers; views without answers left out) to `path`
/// atomically under `title` and `header`.
pub fn write<'a, T: RayRow + 'a>(
    path: &Path,
    title: &str,
    header: &str,
    views: impl IntoIterator<Item = (&'a str, &'a str, &'a [T])>,
) -> anyhow::Result<()> {
    let mut text = format!("{title}\n{header}\n");
    for (id, key, answers) in views {
        if answers.is_empty() {
            continue;
        }
        text.push_str(&format!("{VIEW_MARK}{id} fingerprint {key}\n"));
        for (i, a) in answers.iter().enumerate() {
            let mut fields = vec![id.to_string(), i.to_string()];
            fields.extend(a.numbers().iter().map(|x| format!("{x:e}")));
            fields.push(a.paths().to_string());
            text.push_str(&fields.join(","));
            text.push('\n');
        }
    }
    write_atomically(path, text.as_bytes())
}

/// Every view in the file at `path` by id; an error naming the line for a file of
/// another layout (another title or header, a row of the wrong length or outside its
/// view, rays out of order).
pub fn read<T: RayRow>(path: &Path, title: &str, header: &str) -> anyhow::Result<Sections<T>> {
    let text = fs::read_to_string(path)?;
    let mut lines = text.lines();
    if lines.next() != Some(title) {
        bail!("its first line is not \"{title}\"");
    }
    if lines.next() != Some(header) {
        bail!("its second line is not the header {header}");
    }
    let fields_per_row = header.split(',').count();
    let mut views: Sections<T> = BTreeMap::new();
    let mut current: Option<String> = None;
    for (n, line) in lines.enumerate() {
        let bad = || format!("{} line {}", path.display(), n + 3);
        if let Some(rest) = line.strip_prefix(VIEW_MARK) {
            let Some((id, key)) = rest.split_once(" fingerprint ") else {
                bail!("{}: expected \"# view <id> fingerprint <hex>\"", bad());
            };
            if views
                .insert(id.to_string(), (key.to_string(), Vec::new()))
                .is_some()
            {
                bail!("{}: view {id} appears twice", bad());
            }
            current = Some(id.to_string());
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != fields_per_row {
            bail!(
                "{}: {} fields, expected {fields_per_row}",
                bad(),
                fields.len()
            );
        }
        let answers = match &current {
            Some(id) if id == fields[0] => &mut views.get_mut(id).expect("inserted above").1,
            _ => bail!("{}: a row of view {} outside its section", bad(), fields[0]),
        };
        if fields[1] != answers.len().to_string() {
            bail!("{}: ray {}, expected {}", bad(), fields[1], answers.len());
        }
        let numbers = fields[2..fields_per_row - 1]
            .iter()
            .map(|f| f.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(bad)?;
        let paths: u64 = fields[fields_per_row - 1].parse().with_context(bad)?;
        answers.push(T::from_numbers(&numbers, paths));
    }
    Ok(views)
}

/// The file at `path` as reading it and writing it again makes it (views in the
/// file's order): the committed caches' tests compare it with the file.
#[cfg(test)]
pub fn rewritten<T: RayRow>(path: &Path, title: &str, header: &str) -> anyhow::Result<String> {
    let text = fs::read_to_string(path)?;
    let views: Sections<T> = read(path, title, header)?;
    let order: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix(VIEW_MARK)?.split_once(' ').map(|(id, _)| id))
        .collect();
    let dir = tempfile::tempdir()?;
    let copy = dir.path().join("copy.csv");
    let sections = order
        .iter()
        .map(|id| (*id, views[*id].0.as_str(), views[*id].1.as_slice()));
    write(&copy, title, header, sections)?;
    Ok(fs::read_to_string(&copy)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Clone, Debug, PartialEq)]
    struct Pair(f64, f64, u64);

    impl RayRow for Pair {
        fn numbers(&self) -> Vec<f64> {
            vec![self.0, self.1]
        }
        fn paths(&self) -> u64 {
            self.2
        }
        fn from_numbers(numbers: &[f64], paths: u64) -> Self {
            Pair(numbers[0], numbers[1], paths)
        }
    }

    #[test]
    fn views_come_back_as_written_and_bad_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cache.csv");
        let (title, header) = ("# test cache", "view,ray,a,b,paths");
        let a = [Pair(1.5, -2e-7, 10), Pair(0.0, 3.0, 0)];
        let b = [Pair(4.0, 5.0, 7)];
        let none: [Pair; 0] = [];
        let views = [
            ("a", "00ff", &a[..]),
            ("b", "0001", &b[..]),
            ("c", "0002", &none[..]),
        ];
        write(&path, title, header, views).unwrap();
        let back: Sections<Pair> = read(&path, title, header).unwrap();
        assert_eq!(back.len(), 2, "a view without answers is left out");
        assert_eq!(back["a"], ("00ff".to_string(), a.to_vec()));
        assert_eq!(back["b"].1, vec![Pair(4.0, 5.0, 7)]);
        let other = read::<Pair>(&path, title, "view,ray,a,paths").unwrap_err();
        assert!(other.to_string().contains("header"), "{other}");
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, text.replace("a,1,0e0,3e0,0", "a,2,0e0,3e0,0")).unwrap();
        let order = read::<Pair>(&path, title, header).unwrap_err();
        assert!(
            format!("{order:#}").contains("ray 2, expected 1"),
            "{order:#}"
        );
        assert_eq!(fingerprint_of("atmos"), fingerprint_of("atmos"));
        assert_ne!(fingerprint_of("atmos"), fingerprint_of("atmoz"));
    }
}
