//! A model's own settings from text: `key=value` pairs (`atmos probe --set samples=16`,
//! the report's variants). Each model reads the keys it knows with its paper's values as
//! defaults; a key no model reads, a value that does not parse, or one outside the key's
//! range is an error naming it.

use std::collections::BTreeMap;
use std::fmt::Display;
use std::ops::RangeInclusive;

use crate::models::error::ModelError;

/// `key=value` settings for one model, in the order they were given (a later value of
/// the same key wins).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ModelOptions {
    values: BTreeMap<String, String>,
}

impl ModelOptions {
    /// Parses `key=value` items.
    pub fn parse<S: AsRef<str>>(items: &[S]) -> Result<ModelOptions, ModelError> {
        let mut options = ModelOptions::default();
        for item in items {
            let item = item.as_ref();
            let Some((key, value)) = item.split_once('=') else {
                return Err(ModelError::Settings(format!(
                    "model setting '{item}' is not of the form key=value"
                )));
            };
            let key = key.trim();
            if key.is_empty() {
                return Err(ModelError::Settings(format!(
                    "model setting '{item}' has no key"
                )));
            }
            options.set(key, value.trim());
        }
        Ok(options)
    }

    /// Sets one key.
    pub fn set(&mut self, key: &str, value: impl ToString) {
        self.values.insert(key.to_string(), value.to_string());
    }

    /// Removes one key (nothing where it is not set).
    pub fn remove(&mut self, key: &str) {
        self.values.remove(key);
    }

    /// True when no key is set.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// `key=value` items, sorted by key.
    pub fn items(&self) -> impl Iterator<Item = (&str, &str)> {
        self.values.iter().map(|(k, v)| (k.as_str(), v.as_str()))
    }

    /// `model`'s settings in one go: `read` takes each key it knows from the reader, the
    /// default settings giving the value of an absent key; a key left unread is an error,
    /// and `validate` checks the settings read.
    pub fn read_settings<S: Default>(
        &self,
        model: &'static str,
        validate: impl FnOnce(&S) -> Result<(), ModelError>,
        read: impl FnOnce(&mut OptionReader<'_>, S) -> Result<S, ModelError>,
    ) -> Result<S, ModelError> {
        let mut reader = self.reader(model);
        let settings = read(&mut reader, S::default())?;
        reader.finish()?;
        validate(&settings)?;
        Ok(settings)
    }

    /// A reader for `model`'s settings, which records the keys read.
    pub fn reader(&self, model: &'static str) -> OptionReader<'_> {
        OptionReader {
            options: self,
            model,
            known: Vec::new(),
        }
    }
}

impl std::fmt::Display for ModelOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let items: Vec<String> = self.items().map(|(k, v)| format!("{k}={v}")).collect();
        write!(f, "{}", items.join(" "))
    }
}

/// Reads a model's keys one by one; [`OptionReader::finish`] rejects the keys left over.
#[derive(Debug)]
pub struct OptionReader<'a> {
    options: &'a ModelOptions,
    model: &'static str,
    known: Vec<&'static str>,
}

/// One setting of a model: its key and the values it may take. Every setting is read and
/// checked through one, so none is without a range.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting<T> {
    pub model: &'static str,
    pub key: &'static str,
    pub range: RangeInclusive<T>,
}

impl<T: PartialOrd + Display> Setting<T> {
    /// `value`, or an error naming the setting, the value and the range.
    pub fn check(&self, value: T) -> Result<T, ModelError> {
        if self.range.contains(&value) {
            Ok(value)
        } else {
            Err(ModelError::Settings(format!(
                "{} setting {}={value} is outside {}..={}",
                self.model,
                self.key,
                self.range.start(),
                self.range.end()
            )))
        }
    }
}

impl OptionReader<'_> {
    fn parse<T: std::str::FromStr + PartialOrd + Display + Copy>(
        &mut self,
        setting: &Setting<T>,
        default: T,
        kind: &str,
    ) -> Result<T, ModelError> {
        let key = setting.key;
        self.known.push(key);
        let value = match self.options.values.get(key) {
            None => default,
            Some(text) => text.parse().map_err(|_| {
                ModelError::Settings(format!(
                    "{} setting {key}={text}: expected {kind}",
                    self.model
                ))
            })?,
        };
        setting.check(value)
    }

    /// A count (non-negative integer) within the setting's range.
    pub fn count(&mut self, setting: &Setting<usize>, default: usize) -> Result<usize, ModelError> {
        self.parse(setting, default, "a whole number")
    }

    /// A real number within the setting's range (which excludes NaN and infinities).
    pub fn number(&mut self, setting: &Setting<f64>, default: f64) -> Result<f64, ModelError> {
        self.parse(setting, default, "a number")
    }

    /// `true` or `false`.
    pub fn flag(&mut self, key: &'static str, default: bool) -> Result<bool, ModelError> {
        self.known.push(key);
        match self.options.values.get(key) {
            None => Ok(default),
            Some(text) => text.parse().map_err(|_| {
                ModelError::Settings(format!(
                    "{} setting {key}={text}: expected true or false",
                    self.model
                ))
            }),
        }
    }

    /// Errors on any key that was not read, listing the keys the model knows.
    pub fn finish(self) -> Result<(), ModelError> {
        let unknown: Vec<&str> = self
            .options
            .values
            .keys()
            .map(String::as_str)
            .filter(|k| !self.known.contains(k))
            .collect();
        if unknown.is_empty() {
            return Ok(());
        }
        let known = if self.known.is_empty() {
            "none".to_string()
        } else {
            self.known.join(", ")
        };
        Err(ModelError::Settings(format!(
            "{} has no setting {} (its settings: {known})",
            self.model,
            unknown.join(", ")
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLES: Setting<usize> = Setting {
        model: "nishita",
        key: "samples",
        range: 1..=4096,
    };
    const THRESHOLD: Setting<f64> = Setting {
        model: "nishita",
        key: "threshold",
        range: 0.0..=1.0,
    };

    #[test]
    fn reads_known_keys_and_names_unknown_and_malformed_ones() {
        let o = ModelOptions::parse(&["samples=16", "orders = 2"]).unwrap();
        let mut r = o.reader("nishita");
        assert_eq!(r.count(&SAMPLES, 100).unwrap(), 16);
        assert_eq!(r.number(&THRESHOLD, 0.5).unwrap(), 0.5);
        let e = r.finish().unwrap_err().to_string();
        assert!(e.contains("no setting orders"), "{e}");
        assert!(e.contains("samples, threshold"), "{e}");

        let bad = ModelOptions::parse(&["samples=many"]).unwrap();
        let e = bad.reader("nishita").count(&SAMPLES, 1).unwrap_err();
        assert!(e.to_string().contains("samples=many"), "{e}");
        assert!(ModelOptions::parse(&["samples"]).is_err());
        assert!(ModelOptions::parse(&["=3"]).is_err());
    }

    #[test]
    fn values_outside_the_range_name_the_key_and_the_range() {
        for (text, setting) in [("samples=1000000000", &SAMPLES), ("samples=0", &SAMPLES)] {
            let o = ModelOptions::parse(&[text]).unwrap();
            let e = o
                .reader("nishita")
                .count(setting, 1)
                .unwrap_err()
                .to_string();
            assert!(
                e.contains(&format!("nishita setting {text} is outside 1..=4096")),
                "{e}"
            );
        }
        for text in [
            "threshold=NaN",
            "threshold=inf",
            "threshold=-0.1",
            "threshold=2",
        ] {
            let o = ModelOptions::parse(&[text]).unwrap();
            let e = o
                .reader("nishita")
                .number(&THRESHOLD, 0.5)
                .unwrap_err()
                .to_string();
            assert!(e.contains("is outside 0..=1"), "{text}: {e}");
        }
        let edge = ModelOptions::parse(&["samples=4096"]).unwrap();
        assert_eq!(edge.reader("nishita").count(&SAMPLES, 1).unwrap(), 4096);
    }
}
