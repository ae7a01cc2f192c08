//! The file of `reference_cache.rs`: a title line, the column header, then per view a
//! line `# view <id> fingerprint <16 hex digits>`, followed by ` batches <n>` where it
//! pools more than one batch, and then its rays in order.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::models::sky_model::RayRadiance;

use crate::files::write_atomically;
use crate::report::views::ReportView;

/// The first line of the file.
const TITLE: &str = "# atmos report reference radiance, one fingerprint per view";
/// What starts the line naming a view and its fingerprint.
const VIEW_MARK: &str = "# view ";
/// What follows the fingerprint of a view that pools more than one batch.
const BATCHES_MARK: &str = " batches ";

/// One view's cached rows and the fingerprint they were computed under.
#[derive(Clone, Debug, PartialEq)]
pub struct CachedView {
    pub fingerprint: String,
    pub batches: usize,
    pub answers: Vec<RayRadiance>,
}

fn header(wavelengths: usize) -> String {
    let mut columns = vec!["view".to_string(), "ray".to_string()];
    for prefix in ["L", "T", "stderr"] {
        columns.extend((0..wavelengths).map(|w| format!("{prefix}_{w}")));
    }
    columns.join(",")
}

/// Writes the views that have answers (a view not computed yet is left out), each with
/// the number of batches it pools.
pub fn write(
    path: &Path,
    reference: &[Vec<RayRadiance>],
    views: &[ReportView],
    keys: &[String],
    batches: &[usize],
) -> anyhow::Result<()> {
    let wavelengths = reference
        .iter()
        .flatten()
        .next()
        .map_or(0, |r| r.radiance.len());
    let mut text = format!("{TITLE}\n{}\n", header(wavelengths));
    for (((view, answers), key), n) in views.iter().zip(reference).zip(keys).zip(batches) {
        if answers.is_empty() {
            continue;
        }
        text.push_str(&format!("{VIEW_MARK}{} fingerprint {key}", view.id));
        if *n > 1 {
            text.push_str(&format!("{BATCHES_MARK}{n}"));
        }
        text.push('\n');
        for (i, a) in answers.iter().enumerate() {
            let numbers = a
                .radiance
                .iter()
                .chain(&a.transmittance)
                .chain(&a.radiance_std_error)
                .map(|x| format!("{x:e}"));
            let fields: Vec<String> = [view.id.to_string(), i.to_string()]
                .into_iter()
                .chain(numbers)
                .collect();
            text.push_str(&fields.join(","));
            text.push('\n');
        }
    }
    write_atomically(path, text.as_bytes())
}

/// Every view in the file, by id; an error for a file that is not a cache of this layout
/// or has a malformed line, naming the line.
pub fn read(path: &Path, wavelengths: usize) -> anyhow::Result<BTreeMap<String, CachedView>> {
    let text = fs::read_to_string(path)?;
    let mut lines = text.lines();
    if lines.next() != Some(TITLE) {
        bail!("its first line is not \"{TITLE}\"");
    }
    if lines.next() != Some(header(wavelengths).as_str()) {
        bail!("its second line is not the header for {wavelengths} wavelengths");
    }
    let mut views: BTreeMap<String, CachedView> = BTreeMap::new();
    let mut current: Option<String> = None;
    for (n, line) in lines.enumerate() {
        let bad = || format!("{} line {}", path.display(), n + 3);
        if let Some(rest) = line.strip_prefix(VIEW_MARK) {
            let Some((id, key)) = rest.split_once(" fingerprint ") else {
                bail!("{}: expected \"# view <id> fingerprint <hex>\"", bad());
            };
            let (key, batches) = match key.split_once(BATCHES_MARK) {
                None => (key, 1),
                Some((key, n)) => match n.parse::<usize>() {
                    Ok(n) if n >= 1 => (key, n),
                    _ => bail!("{}: batches {n:?} is not a count from 1", bad()),
                },
            };
            if views.contains_key(id) {
                bail!("{}: view {id} appears twice", bad());
            }
            views.insert(
                id.to_string(),
                CachedView {
                    fingerprint: key.to_string(),
                    batches,
                    answers: Vec::new(),
                },
            );
            current = Some(id.to_string());
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != 2 + 3 * wavelengths {
            bail!(
                "{}: {} fields, expected {}",
                bad(),
                fields.len(),
                2 + 3 * wavelengths
            );
        }
        let view = match &current {
            Some(id) if id == fields[0] => views.get_mut(id).expect("inserted above"),
            _ => bail!("{}: a row of view {} outside its section", bad(), fields[0]),
        };
        if fields[1] != view.answers.len().to_string() {
            bail!(
                "{}: ray {}, expected {}",
                bad(),
                fields[1],
                view.answers.len()
            );
        }
        let numbers = fields[2..]
            .iter()
            .map(|f| f.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(bad)?;
        view.answers.push(RayRadiance {
            radiance: numbers[..wavelengths].to_vec(),
            transmittance: numbers[wavelengths..2 * wavelengths].to_vec(),
            radiance_std_error: numbers[2 * wavelengths..].to_vec(),
        });
    }
    Ok(views)
}

#[cfg(test)]
pub mod tests {
    use super::*;
    use crate::report::views::report_views;

    /// Made-up answers of view number `v`, `rays` rays.
    pub fn answers(v: usize, rays: usize) -> Vec<RayRadiance> {
        (0..rays)
            .map(|i| RayRadiance {
                radiance: vec![0.1 * v as f64 + 1e-9 * i as f64; 3],
                transmittance: vec![0.5; 3],
                radiance_std_error: vec![1e-4; 3],
            })
            .collect()
    }

    #[test]
    fn round_trips_every_view_with_its_fingerprint_and_batches() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let views = report_views(2, 1);
        let reference: Vec<Vec<RayRadiance>> = (0..views.len()).map(|v| answers(v, 2)).collect();
        let keys: Vec<String> = (0..views.len()).map(|v| format!("{v:016x}")).collect();
        let batches: Vec<usize> = (0..views.len()).map(|v| 1 + v % 3).collect();
        write(&path, &reference, &views, &keys, &batches).unwrap();
        let read_back = read(&path, 3).unwrap();
        assert_eq!(read_back.len(), views.len());
        for (v, view) in views.iter().enumerate() {
            assert_eq!(read_back[view.id].answers, reference[v]);
            assert_eq!(read_back[view.id].fingerprint, keys[v]);
            assert_eq!(read_back[view.id].batches, batches[v]);
        }
        // A single batch is written as the file always was.
        let text = fs::read_to_string(&path).unwrap();
        assert!(text.contains(&format!(
            "{VIEW_MARK}{} fingerprint {}\n",
            views[0].id, keys[0]
        )));
    }

    #[test]
    fn a_malformed_file_is_named_with_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let views = report_views(1, 1);
        let keys = vec!["0123456789abcdef".to_string()];
        write(&path, &[answers(0, 1)], &views[..1], &keys, &[1]).unwrap();
        let good = fs::read_to_string(&path).unwrap();

        fs::write(&path, good.replace(TITLE, "# something else")).unwrap();
        let e = format!("{:#}", read(&path, 3).unwrap_err());
        assert!(e.contains("first line"), "{e}");

        fs::write(&path, good.replace("1e-4", "x")).unwrap();
        let e = format!("{:#}", read(&path, 3).unwrap_err());
        assert!(e.contains("line 4"), "{e}");

        let without_section: String = good
            .lines()
            .filter(|l| !l.starts_with(VIEW_MARK))
            .map(|l| format!("{l}\n"))
            .collect();
        fs::write(&path, without_section).unwrap();
        let e = format!("{:#}", read(&path, 3).unwrap_err());
        assert!(e.contains("outside its section"), "{e}");

        let key = &keys[0];
        fs::write(&path, good.replace(key, &format!("{key} batches 0"))).unwrap();
        let e = format!("{:#}", read(&path, 3).unwrap_err());
        assert!(e.contains("line 3") && e.contains("batches \"0\""), "{e}");
    }
}
