//! WGSL sources from the workspace's `shaders/` folder, embedded with `include_str!` so
//! the binary needs no files at run time, and composed by a tiny textual resolver: a line
//! `#import name.wgsl` is replaced by that module's text, each module included once per
//! composed shader, so shared code lives in one file.

use crate::error::GpuError;

/// Every file of `shaders/`, by file name. The validation test checks that this list and
/// the folder agree.
const SHADERS: &[(&str, &str)] = &[
    (
        "bruneton.wgsl",
        include_str!("../../../shaders/bruneton.wgsl"),
    ),
    (
        "bruneton_density.wgsl",
        include_str!("../../../shaders/bruneton_density.wgsl"),
    ),
    (
        "bruneton_irradiance.wgsl",
        include_str!("../../../shaders/bruneton_irradiance.wgsl"),
    ),
    (
        "bruneton_lookup.wgsl",
        include_str!("../../../shaders/bruneton_lookup.wgsl"),
    ),
    (
        "bruneton_orders.wgsl",
        include_str!("../../../shaders/bruneton_orders.wgsl"),
    ),
    (
        "bruneton_parameterization.wgsl",
        include_str!("../../../shaders/bruneton_parameterization.wgsl"),
    ),
    (
        "bruneton_previous_order.wgsl",
        include_str!("../../../shaders/bruneton_previous_order.wgsl"),
    ),
    (
        "bruneton_ray_nodes.wgsl",
        include_str!("../../../shaders/bruneton_ray_nodes.wgsl"),
    ),
    (
        "bruneton_scattering.wgsl",
        include_str!("../../../shaders/bruneton_scattering.wgsl"),
    ),
    (
        "bruneton_scattering_density.wgsl",
        include_str!("../../../shaders/bruneton_scattering_density.wgsl"),
    ),
    (
        "bruneton_scattering_texture.wgsl",
        include_str!("../../../shaders/bruneton_scattering_texture.wgsl"),
    ),
    (
        "bruneton_single_scattering.wgsl",
        include_str!("../../../shaders/bruneton_single_scattering.wgsl"),
    ),
    (
        "bruneton_tables.wgsl",
        include_str!("../../../shaders/bruneton_tables.wgsl"),
    ),
    (
        "atmosphere_params.wgsl",
        include_str!("../../../shaders/atmosphere_params.wgsl"),
    ),
    (
        "bruneton_view_slice.wgsl",
        include_str!("../../../shaders/bruneton_view_slice.wgsl"),
    ),
    (
        "dobashi.wgsl",
        include_str!("../../../shaders/dobashi.wgsl"),
    ),
    (
        "dobashi_ambient.wgsl",
        include_str!("../../../shaders/dobashi_ambient.wgsl"),
    ),
    (
        "dobashi_tables.wgsl",
        include_str!("../../../shaders/dobashi_tables.wgsl"),
    ),
    (
        "dobashi_trace.wgsl",
        include_str!("../../../shaders/dobashi_trace.wgsl"),
    ),
    (
        "frame_params.wgsl",
        include_str!("../../../shaders/frame_params.wgsl"),
    ),
    (
        "hillaire.wgsl",
        include_str!("../../../shaders/hillaire.wgsl"),
    ),
    (
        "hillaire_aerial_perspective.wgsl",
        include_str!("../../../shaders/hillaire_aerial_perspective.wgsl"),
    ),
    (
        "hillaire_directions.wgsl",
        include_str!("../../../shaders/hillaire_directions.wgsl"),
    ),
    (
        "hillaire_ground.wgsl",
        include_str!("../../../shaders/hillaire_ground.wgsl"),
    ),
    (
        "hillaire_march.wgsl",
        include_str!("../../../shaders/hillaire_march.wgsl"),
    ),
    (
        "hillaire_medium.wgsl",
        include_str!("../../../shaders/hillaire_medium.wgsl"),
    ),
    (
        "hillaire_multiple_scattering.wgsl",
        include_str!("../../../shaders/hillaire_multiple_scattering.wgsl"),
    ),
    (
        "hillaire_sky_view.wgsl",
        include_str!("../../../shaders/hillaire_sky_view.wgsl"),
    ),
    (
        "luminance.wgsl",
        include_str!("../../../shaders/luminance.wgsl"),
    ),
    (
        "nishita.wgsl",
        include_str!("../../../shaders/nishita.wgsl"),
    ),
    ("phase.wgsl", include_str!("../../../shaders/phase.wgsl")),
    ("oneil.wgsl", include_str!("../../../shaders/oneil.wgsl")),
    (
        "oneil_table.wgsl",
        include_str!("../../../shaders/oneil_table.wgsl"),
    ),
    ("riley.wgsl", include_str!("../../../shaders/riley.wgsl")),
    (
        "sun_disk.wgsl",
        include_str!("../../../shaders/sun_disk.wgsl"),
    ),
    (
        "surface.wgsl",
        include_str!("../../../shaders/surface.wgsl"),
    ),
    (
        "table_sampling.wgsl",
        include_str!("../../../shaders/table_sampling.wgsl"),
    ),
    (
        "terrain.wgsl",
        include_str!("../../../shaders/terrain.wgsl"),
    ),
    (
        "tone_map.wgsl",
        include_str!("../../../shaders/tone_map.wgsl"),
    ),
    (
        "transmittance_lookup.wgsl",
        include_str!("../../../shaders/transmittance_lookup.wgsl"),
    ),
    (
        "transmittance_table.wgsl",
        include_str!("../../../shaders/transmittance_table.wgsl"),
    ),
];

/// The names of all embedded shader files.
pub fn shader_names() -> impl Iterator<Item = &'static str> {
    SHADERS.iter().map(|(name, _)| *name)
}

/// Every embedded shader file with its imports resolved, by file name.
pub fn all_composed() -> Result<Vec<(&'static str, String)>, GpuError> {
    shader_names()
        .map(|name| Ok((name, composed(name)?)))
        .collect()
}

/// The source of shader `name` (a file name such as `transmittance_table.wgsl`) with its
/// `#import` lines resolved.
pub fn composed(name: &str) -> Result<String, GpuError> {
    let mut out = String::new();
    let mut included = Vec::new();
    append(name, name, &mut included, &mut out)?;
    Ok(out)
}

fn raw(name: &str) -> Option<&'static str> {
    SHADERS.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// Appends `name`'s text to `out`, replacing each import by the module's text unless
/// already included (which also ends import cycles).
fn append<'a>(
    root: &str,
    name: &'a str,
    included: &mut Vec<&'a str>,
    out: &mut String,
) -> Result<(), GpuError> {
    let text = raw(name).ok_or_else(|| {
        if name == root {
            GpuError::UnknownShader(name.to_string())
        } else {
            GpuError::UnknownImport {
                shader: root.to_string(),
                import: name.to_string(),
            }
        }
    })?;
    included.push(name);
    for line in text.lines() {
        if let Some(import) = line.trim().strip_prefix("#import") {
            let import = import.trim();
            if !included.contains(&import) {
                append(root, import, included, out)?;
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn imports_are_resolved_once_and_unknown_names_are_errors() {
        let table = composed("transmittance_table.wgsl").unwrap();
        assert!(!table.contains("#import"));
        assert_eq!(table.matches("struct AtmosphereParams").count(), 1);
        assert!(matches!(
            composed("missing.wgsl"),
            Err(GpuError::UnknownShader(_))
        ));
    }
}
