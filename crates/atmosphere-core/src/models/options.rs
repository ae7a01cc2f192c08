//! A model's own settings from text: `key=value` pairs (`atmos probe --set samples=16`,
//! the report's variants). Each model reads the keys it knows with its paper's values as
//! defaults; a key no model reads, or a value that does not parse, is an error naming it.

use std::collections::BTreeMap;

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

impl OptionReader<'_> {
    fn parse<T: std::str::FromStr>(
        &mut self,
        key: &'static str,
        default: T,
        kind: &str,
    ) -> Result<T, ModelError> {
        self.known.push(key);
        match self.options.values.get(key) {
            None => Ok(default),
            Some(text) => text.parse().map_err(|_| {
                ModelError::Settings(format!(
                    "{} setting {key}={text}: expected {kind}",
                    self.model
                ))
            }),
        }
    }

    /// A count (non-negative integer).
    pub fn count(&mut self, key: &'static str, default: usize) -> Result<usize, ModelError> {
        self.parse(key, default, "a whole number")
    }

    /// A real number.
    pub fn number(&mut self, key: &'static str, default: f64) -> Result<f64, ModelError> {
        let v = self.parse(key, default, "a number")?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(ModelError::Settings(format!(
                "{} setting {key} must be finite",
                self.model
            )))
        }
    }

    /// `true` or `false`.
    pub fn flag(&mut self, key: &'static str, default: bool) -> Result<bool, ModelError> {
        self.parse(key, default, "true or false")
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

    #[test]
    fn reads_known_keys_and_names_unknown_and_malformed_ones() {
        let o = ModelOptions::parse(&["samples=16", "orders = 2"]).unwrap();
        let mut r = o.reader("nishita");
        assert_eq!(r.count("samples", 100).unwrap(), 16);
        assert_eq!(r.number("threshold", 0.5).unwrap(), 0.5);
        let e = r.finish().unwrap_err().to_string();
        assert!(e.contains("no setting orders"), "{e}");
        assert!(e.contains("samples, threshold"), "{e}");

        let bad = ModelOptions::parse(&["samples=many"]).unwrap();
        let e = bad.reader("nishita").count("samples", 1).unwrap_err();
        assert!(e.to_string().contains("samples=many"), "{e}");
        assert!(ModelOptions::parse(&["samples"]).is_err());
        assert!(ModelOptions::parse(&["=3"]).is_err());
        let nan = ModelOptions::parse(&["g=NaN"]).unwrap();
        assert!(nan.reader("x").number("g", 0.0).is_err());
    }
}
