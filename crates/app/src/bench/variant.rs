//! A model with its settings as `atmos bench` and the report's GPU column measure it:
//! `model key=value ...`, where `orders=N` is the highest scattering order and every
//! other key is the model's own setting (docs/models/).

use anyhow::{Context, bail};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::check_settings;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::Renderer;

/// A model with its settings, as benchmarked.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// `model` or `model key=value ...`.
    pub label: String,
    pub model: ModelId,
    /// Highest scattering order; `None` for the model's own choice.
    pub max_orders: Option<u32>,
    pub options: ModelOptions,
}

impl Variant {
    /// `model` with `orders=N` if `max_orders` is given, then `options` in order.
    pub fn new(model: ModelId, max_orders: Option<u32>, options: &[&str]) -> Variant {
        let mut label = model.to_string();
        if let Some(n) = max_orders {
            label.push_str(&format!(" orders={n}"));
        }
        for o in options {
            label.push(' ');
            label.push_str(o);
        }
        Variant {
            label,
            model,
            max_orders,
            options: ModelOptions::parse(options).expect("variants are made of key=value"),
        }
    }

    /// Parses `model key=value ...` (as `--variant` takes it); an unknown model, a model
    /// not on the GPU, or a key or value the model does not accept is an error naming it.
    pub fn parse(text: &str) -> anyhow::Result<Variant> {
        let mut words = text.split_whitespace();
        let Some(name) = words.next() else {
            bail!("--variant '{text}': expected a model and key=value settings");
        };
        let model: ModelId = name
            .parse()
            .map_err(|_| anyhow::anyhow!("--variant '{text}': no model '{name}'"))?;
        Renderer::check_model(model).with_context(|| format!("--variant '{text}'"))?;
        let mut max_orders = None;
        let mut options = Vec::new();
        for word in words {
            match word.strip_prefix("orders=") {
                Some(n) => {
                    let n = n
                        .parse()
                        .with_context(|| format!("--variant '{text}': orders={n}"))?;
                    max_orders = Some(n);
                }
                None => options.push(word),
            }
        }
        let variant = Variant::new(model, max_orders, &options);
        check_settings(model, &variant.settings())
            .with_context(|| format!("--variant '{text}'"))?;
        Ok(variant)
    }

    /// The model settings of the variant, the others at their defaults.
    pub fn settings(&self) -> ModelSettings {
        ModelSettings {
            max_orders: self.max_orders,
            options: self.options.clone(),
            ..ModelSettings::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_models_orders_and_settings_and_names_what_is_wrong() {
        let v = Variant::parse("bruneton orders=2 view_samples=30").unwrap();
        assert_eq!(v.model, ModelId::Bruneton);
        assert_eq!(v.max_orders, Some(2));
        assert_eq!(
            v.options,
            ModelOptions::parse(&["view_samples=30"]).unwrap()
        );
        assert_eq!(v.label, "bruneton orders=2 view_samples=30");
        assert_eq!(Variant::parse("  riley ").unwrap().label, "riley");

        for (text, says) in [
            ("", "expected a model"),
            ("sky", "no model 'sky'"),
            ("reference", "reference"),
            ("nishita orders=x", "orders=x"),
            ("nishita orders=0", "orders 0"),
            ("nishita samples=0", "samples=0"),
            ("nishita foo=1", "no setting foo"),
        ] {
            let e = format!("{:#}", Variant::parse(text).unwrap_err());
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
