//! `atmos probe --clouds`: the probe's rays under the planet's cloud cover, placed at
//! `--latitude-deg`, `--longitude-deg` with the sun at `--sun-azimuth-deg` as
//! `--terrain` places them (`probe_terrain.rs`), through the layer of the `--cloud-*`
//! flags of `atmos render` (`render/cloud_flags.rs`): a sky model answers with the
//! layer's march (`cloud_rays.rs`; a layer lit by the sun map gets the map of a frame
//! whose camera stands at the ray's origin), `--model reference` with the cloud path
//! tracer, hillaire's air around the cloud, to `--target-error` (its standard error in
//! `L_stderr_<nm>`). `--cloud-form` chooses as in frames: the layer, the cloud
//! spheres (the same field as Dobashi et al. 2002's spheres, `cloud_rays.rs`, made once
//! per sun direction), or by each ray's altitude (`auto`, blended across the hand-over
//! band); the path tracer traces the field itself and takes no form but `auto` or
//! `layer`. Extra columns: `T_cloud`, and `paths` for the path tracer.

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::droplets::droplet_orders_cached;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::handover::{CloudForm, sphere_weight};
use atmosphere_core::models::error::ModelError;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, ViewRay};
use glam::DVec3;

use crate::cloud_rays::{CloudAnswer, CloudRays, RayMaps};
use crate::probe_args::ProbeArgs;
use crate::probe_table::ExtraColumns;
use crate::probe_terrain::TerrainPlace;
use crate::progress::map_with_progress;
use crate::table_cache_dir::table_cache;

/// The sky model the path tracer's air comes from.
pub const AIR_MODEL: ModelId = ModelId::Hillaire;

/// The solar irradiance, each ray's answer and the extra columns.
pub type CloudResults = (Vec<f64>, Vec<Result<RayRadiance, ModelError>>, ExtraColumns);

/// The path tracer's stopping rule for `--target-error` and `--seed`; the error is
/// named by its flag.
pub fn path_settings(settings: &ModelSettings) -> anyhow::Result<PathSettings> {
    let paths = PathSettings {
        target_relative_error: settings.target_relative_error,
        seed: settings.seed,
        ..PathSettings::default()
    };
    if paths.check().is_err() {
        bail!(
            "--target-error {} must lie in [1e-4, 0.5] for the cloud path tracer",
            settings.target_relative_error
        );
    }
    Ok(paths)
}

/// The air model the path tracer runs with: `AIR_MODEL` at the probe's wavelengths.
pub fn air_settings(settings: &ModelSettings) -> ModelSettings {
    ModelSettings {
        options: ModelOptions::default(),
        max_orders: None,
        ..settings.clone()
    }
}

/// `rays` (in the probe's local frame) placed at `place` and answered with the cloud
/// layer of `args.clouds` by `model`.
pub fn evaluate(
    model: ModelId,
    atmosphere: &Atmosphere,
    settings: &ModelSettings,
    rays: &[ViewRay],
    place: &TerrainPlace,
    args: &ProbeArgs,
) -> anyhow::Result<CloudResults> {
    let Some(layer) = args.clouds.settings()? else {
        bail!("--clouds is off");
    };
    let form = args.clouds.form()?;
    if model == ModelId::Reference && form == CloudForm::Spheres {
        bail!(
            "--cloud-form spheres: the path tracer (--model reference) traces the cloud field \
             itself; the form chooses how a sky model shows it (auto or layer here)"
        );
    }
    let cover = args.clouds.cover_grid()?;
    let orders = droplet_orders_cached(&settings.wavelengths_nm, &table_cache())
        .context("--clouds: the droplets' phase functions at --wavelengths")?;
    let (sky, paths) = match model {
        ModelId::Reference => (
            prepare(AIR_MODEL, atmosphere, &air_settings(settings))?,
            Some(path_settings(settings)?),
        ),
        other => (prepare(other, atmosphere, settings)?, None),
    };
    let clouds = CloudRays::new(layer, cover, orders, atmosphere, sky.as_ref())?.shading_air(
        args.clouds.shafts.unwrap_or(true),
        atmosphere,
        sky.as_ref(),
    );
    let placed: Vec<ViewRay> = rays.iter().map(|ray| place.placed(ray)).collect();
    let (spheres, maps) = match paths {
        Some(_) => (Vec::new(), Vec::new()),
        None => (
            spheres_by_sun(&clouds, &placed, form)?,
            maps_by_camera(&clouds, &placed)?,
        ),
    };
    let answers: Vec<Result<CloudAnswer, ModelError>> =
        map_with_progress("probe", "rays", &placed, |ray| match &paths {
            Some(paths) => clouds.reference(sky.as_ref(), ray, paths),
            None => {
                let sun = ray.sun_direction.normalize();
                let made = spheres.iter().find(|(s, _)| *s == sun).map(|(_, m)| m);
                let camera = (ray.origin_m, sun);
                let Some((_, maps)) = maps.iter().find(|(c, _)| *c == camera) else {
                    return Err(ModelError::Settings(
                        "no sun maps were made for this ray's camera".into(),
                    ));
                };
                clouds.in_form(sky.as_ref(), ray, form, maps, made)
            }
        });
    let mut names = vec!["T_cloud".to_string()];
    if paths.is_some() {
        names.push("paths".into());
    }
    let mut extra = ExtraColumns {
        names,
        rows: Vec::new(),
    };
    let mut results = Vec::new();
    for answer in answers {
        match answer {
            Ok(a) => {
                let mut row = vec![a.cloud_transmittance];
                row.extend(a.paths.map(|p| p as f64));
                extra.rows.push(row);
                results.push(Ok(a.radiance));
            }
            Err(e) => {
                extra.rows.push(Vec::new());
                results.push(Err(e));
            }
        }
    }
    Ok((sky.solar_irradiance_w_m2_nm().to_vec(), results, extra))
}

/// The sun maps ([`CloudRays::maps`]) for each camera and sun of the `rays`, made once
/// for the rays that share them.
fn maps_by_camera(
    clouds: &CloudRays,
    rays: &[ViewRay],
) -> anyhow::Result<Vec<((DVec3, DVec3), RayMaps)>> {
    let mut made: Vec<((DVec3, DVec3), RayMaps)> = Vec::new();
    for ray in rays {
        let camera = (ray.origin_m, ray.sun_direction.normalize());
        if !made.iter().any(|(c, _)| *c == camera) {
            made.push((camera, clouds.maps(camera.0, camera.1)?));
        }
    }
    Ok(made)
}

/// The cloud spheres for each sun direction of the `rays` whose camera sees them in
/// `form` (none for the layer alone).
fn spheres_by_sun(
    clouds: &CloudRays,
    rays: &[ViewRay],
    form: CloudForm,
) -> anyhow::Result<Vec<(DVec3, CloudSpheres)>> {
    let ground = clouds.ground_radius_m();
    let mut made: Vec<(DVec3, CloudSpheres)> = Vec::new();
    for ray in rays {
        let sun = ray.sun_direction.normalize();
        let seen = sphere_weight(form, ray.origin_m.length() - ground) > 0.0;
        if seen && !made.iter().any(|(s, _)| *s == sun) {
            made.push((sun, clouds.spheres(sun)?));
        }
    }
    Ok(made)
}
