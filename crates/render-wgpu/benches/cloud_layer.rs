//! What the cloud layer pass costs against the hillaire sky pass, in one run on one
//! device at 1280 x 720: the hillaire frame of a flight view under the layer (500 m up,
//! looking 10 degrees above the horizon, sun 30 degrees up) through the `Renderer` (its per-step GPU
//! times), then the cloud layer pass of the same view over the generated cover: the
//! riley, octaves and eddington at the default march (48 view, 8 shadow steps), those
//! and four-stream at the interactive preset
//! (`MarchQuality`, whose sun light is the sun map's, filled before the march and timed
//! with it), the interactive preset with a shadow march instead (`sun_light = march`),
//! and octaves at the offline preset (Riley's march does not converge
//! as its shadow steps shrink: `docs/clouds.md`, "Cost"); rounds interleaved, medians.
//! The cloud pass is timed by the wall clock around its dispatch and read-back
//! (lavapipe's timestamps around a lone compute pass read about 0.1 ms whatever it
//! does).
//!
//! Each row's error is measured against the finest march of the same method on the same
//! view at 160 x 90: the mean absolute radiance error over all pixels and wavelengths
//! relative to the finest image's mean radiance, and the largest transmittance error.
//!
//! Run: `cargo bench -p render-wgpu --bench cloud_layer` (on lavapipe:
//! `WGPU_BACKEND=vulkan VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json`).

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::cover::generated::{CoverParameters, GeneratedCover};
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::layer::shell::Shell;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::layer_inputs::LayerInputs;
use render_wgpu::clouds::layer_pass::CloudLayerPass;
use render_wgpu::clouds::layer_uniform::{LayerCamera, LayerUniform};
use render_wgpu::clouds::sun_map_pass::SunMapPass;
use render_wgpu::clouds::sun_map_texture::{SunMapTexture, SunMapUniform};
use render_wgpu::frame::{Frame, LocalView};

const ROUNDS: usize = 2;
const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;
/// The size of the images compared with the finest march.
const ERROR_WIDTH: u32 = 160;
const ERROR_HEIGHT: u32 = 90;

/// A row of the bench: its name and settings.
struct Row {
    name: &'static str,
    settings: LayerSettings,
}

fn rows() -> Vec<Row> {
    let riley = LayerSettings::default();
    let octaves = LayerSettings {
        method: LayerMethod::Octaves,
        ..riley
    };
    let eddington = LayerSettings {
        method: LayerMethod::Eddington,
        ..riley
    };
    let four_stream = LayerSettings {
        method: LayerMethod::FourStream,
        ..riley
    };
    vec![
        Row {
            name: "riley, default",
            settings: riley,
        },
        Row {
            name: "octaves, default",
            settings: octaves,
        },
        Row {
            name: "eddington, default",
            settings: eddington,
        },
        Row {
            name: "riley, interactive",
            settings: MarchQuality::Interactive.apply(riley),
        },
        Row {
            name: "eddington, interactive",
            settings: MarchQuality::Interactive.apply(eddington),
        },
        Row {
            name: "four-stream, interactive",
            settings: MarchQuality::Interactive.apply(four_stream),
        },
        Row {
            name: "octaves, interactive",
            settings: MarchQuality::Interactive.apply(octaves),
        },
        Row {
            name: "riley, interactive, shadow march",
            settings: LayerSettings {
                sun_light: SunLight::March,
                ..MarchQuality::Interactive.apply(riley)
            },
        },
        Row {
            name: "octaves, interactive, shadow march",
            settings: LayerSettings {
                sun_light: SunLight::March,
                ..MarchQuality::Interactive.apply(octaves)
            },
        },
        Row {
            name: "octaves, offline",
            settings: MarchQuality::Offline.apply(octaves),
        },
    ]
}

/// Mean |L - L_finest| over pixels and wavelengths / mean L_finest, and the largest
/// |T - T_finest|.
fn error_against(image: &[[f32; 4]], finest: &[[f32; 4]]) -> (f64, f64) {
    let (mut error, mut total, mut worst_t) = (0.0, 0.0, 0.0_f64);
    for (p, q) in image.iter().zip(finest) {
        for w in 0..3 {
            error += f64::from((p[w] - q[w]).abs());
            total += f64::from(q[w]);
        }
        worst_t = worst_t.max(f64::from((p[3] - q[3]).abs()));
    }
    (error / total, worst_t)
}

/// The sun map and its fill pass of a layer lit by it.
struct SunMap<'a> {
    pass: SunMapPass,
    texture: SunMapTexture,
    camera: &'a LayerCamera,
    bottom_radius_m: f64,
    cover: &'a wgpu::Texture,
}

impl SunMap<'_> {
    /// Renders `params` of `settings`, filling the sun map first when the layer is lit by
    /// it.
    fn render(
        &mut self,
        pass: &CloudLayerPass,
        gpu: &render_wgpu::GpuContext,
        (params, inputs): (&LayerUniform, &LayerInputs),
        settings: &LayerSettings,
    ) -> Vec<[f32; 4]> {
        if settings.sun_light == SunLight::March {
            return pass.render(gpu, (params, inputs), None).unwrap();
        }
        let (base, top) = settings.radii_m(self.bottom_radius_m);
        let shell = Shell {
            ground_radius_m: self.bottom_radius_m,
            base_radius_m: base,
            top_radius_m: top,
        };
        let resolution = SunMapResolution::LIT;
        let grid = CloudSunMap::grid_for(&shell, self.camera.position_m, &resolution).unwrap();
        let [x, y, z, _] = params.sun_direction;
        let sun = DVec3::new(f64::from(x), f64::from(y), f64::from(z));
        let uniform = SunMapUniform::new(&grid, sun, top, &resolution);
        self.texture.set(gpu, Some(&uniform), (1, 1)).unwrap();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        self.pass
            .encode(gpu, &mut encoder, params, self.cover, &self.texture, None);
        gpu.queue.submit([encoder.finish()]);
        pass.render(gpu, (params, inputs), Some(&self.texture))
            .unwrap()
    }
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    let view = LocalView {
        altitude_m: 500.0,
        view_zenith_deg: 80.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 60.0,
        sun_azimuth_deg: 40.0,
    };
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let frame = Frame {
        camera_position_m: view.position_m(atmosphere.bottom_radius_m),
        orientation: view.orientation(),
        vertical_fov_deg: 60.0,
        sun_direction: view.sun_direction(),
        atmosphere: atmosphere.clone(),
        model: ModelId::Hillaire,
        settings: ModelSettings::default(),
        exposure_ev100: 14.0,
        width: WIDTH,
        height: HEIGHT,
        terrain: None,
    };
    let mut renderer = Renderer::headless().expect("a GPU adapter");
    let cover = GeneratedCover::new(CoverParameters::default()).unwrap();
    let grid = CoverGrid::rasterize(1024, 512, |p| cover.cover(p)).unwrap();
    let series = LegendreSeries::henyey_greenstein(0.85, 300);
    let orders = ScatteringOrders::new(&vec![series; 3]).unwrap();
    let gpu = renderer.gpu();
    let inputs = LayerInputs::new(gpu, &grid, &orders).unwrap();
    let pass = CloudLayerPass::new(gpu).unwrap();
    let (map_pass, map_texture) = (SunMapPass::new(gpu).unwrap(), SunMapTexture::new(gpu));
    let orientation = frame.orientation;
    let camera = LayerCamera {
        position_m: frame.camera_position_m,
        forward: orientation * -DVec3::Z,
        right: orientation * DVec3::X,
        up: orientation * DVec3::Y,
        fov_deg: 60.0,
        width: WIDTH,
        height: HEIGHT,
    };
    let light = CloudLight {
        sun_direction: frame.sun_direction,
        sun_irradiance: vec![1.3, 1.5, 1.4],
        sky_irradiance: vec![0.1, 0.2, 0.35],
        up: DVec3::Z,
    };
    let mut sun_map = SunMap {
        pass: map_pass,
        texture: map_texture,
        camera: &camera,
        bottom_radius_m: atmosphere.bottom_radius_m,
        cover: &inputs.cover,
    };
    let rows = rows();
    let params_at = |settings: &LayerSettings, width: u32, height: u32| {
        let camera = LayerCamera {
            width,
            height,
            ..camera
        };
        LayerUniform::new(
            &camera,
            &light,
            settings,
            atmosphere.bottom_radius_m,
            (grid.width(), grid.height()),
        )
        .unwrap()
    };
    // The finest image of each method, rendered once.
    let mut finest: Vec<(LayerMethod, Vec<[f32; 4]>)> = Vec::new();
    let mut errors = Vec::new();
    for row in &rows {
        let method = row.settings.method;
        if !finest.iter().any(|(m, _)| *m == method) {
            let settings = MarchQuality::Finest.apply(row.settings);
            let params = params_at(&settings, ERROR_WIDTH, ERROR_HEIGHT);
            finest.push((
                method,
                pass.render(renderer.gpu(), (&params, &inputs), None)
                    .unwrap(),
            ));
        }
        let reference = &finest.iter().find(|(m, _)| *m == method).unwrap().1;
        let params = params_at(&row.settings, ERROR_WIDTH, ERROR_HEIGHT);
        let image = sun_map.render(&pass, renderer.gpu(), (&params, &inputs), &row.settings);
        errors.push(error_against(&image, reference));
    }
    let mut sky_ms = Vec::new();
    let mut frame_ms = Vec::new();
    let mut cloud_ms = vec![Vec::new(); rows.len()];
    let mut clouded = 0;
    for _ in 0..ROUNDS {
        let start = Instant::now();
        let plan = renderer.render(&frame).expect("the hillaire frame");
        frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
        let step = plan.steps.iter().find(|s| s.name == "hillaire");
        sky_ms.push(
            step.and_then(|s| s.gpu_ms)
                .expect("the hillaire pass's GPU time"),
        );
        for (k, row) in rows.iter().enumerate() {
            let params = params_at(&row.settings, WIDTH, HEIGHT);
            let start = Instant::now();
            let pixels = sun_map.render(&pass, renderer.gpu(), (&params, &inputs), &row.settings);
            cloud_ms[k].push(start.elapsed().as_secs_f64() * 1e3);
            clouded = pixels.iter().filter(|p| p[3] < 0.5).count();
        }
    }
    let (sky, whole) = (median(sky_ms), median(frame_ms));
    println!(
        "{}: hillaire pass {sky:.1} ms (GPU timer), whole hillaire frame {whole:.1} ms (wall \
         clock, with read-back); {clouded} of {} pixels behind cloud (T < 0.5)",
        renderer.gpu().adapter_summary(),
        WIDTH * HEIGHT
    );
    for ((row, times), (error, worst_t)) in rows.iter().zip(cloud_ms).zip(errors) {
        let cloud = median(times);
        println!(
            "cloud layer, {}: {cloud:.1} ms (wall clock, with read-back), {:.2} x the \
             hillaire pass, {:.2} x the whole frame; against the finest march: radiance \
             {:.1} % (mean absolute / mean), transmittance {worst_t:.3} (largest)",
            row.name,
            cloud / sky,
            cloud / whole,
            100.0 * error
        );
    }
}
