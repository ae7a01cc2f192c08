//! `atmos contact-sheet`: every GPU model (rows) in six views (columns): noon, sunset and
//! civil twilight from the ground, 10 km, 100 km and orbit, rendered headless and laid
//! out with labels in one PNG, to compare the models at a glance (docs/images/).

use std::io::Cursor;
use std::path::Path;

use anyhow::{Context, anyhow, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use plotters::prelude::*;
use render_wgpu::Renderer;
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::sky::registry::GPU_MODELS;

use crate::cli::ContactSheetArgs;
use crate::files::{check_writable, write_atomically};
use crate::progress::Progress;
use crate::report::plot::register_sans_serif;

/// One column of the sheet: camera, sun, field of view and exposure (EV100).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SheetView {
    pub name: &'static str,
    pub view: LocalView,
    pub fov_deg: f64,
    pub exposure_ev100: f64,
}

const fn view(
    altitude_m: f64,
    view_zenith_deg: f64,
    sun_zenith_deg: f64,
    sun_azimuth_deg: f64,
) -> LocalView {
    LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg,
    }
}

/// The six views. Sunset and twilight look towards the sun; twilight (sun 6
/// degrees below the horizon) needs about 8 stops more exposure than noon; orbit looks at
/// the limb from 1,000 km, where the horizon dips 30 degrees.
pub const SHEET_VIEWS: [SheetView; 6] = [
    SheetView {
        name: "noon, 2 m",
        view: view(2.0, 70.0, 20.0, 150.0),
        fov_deg: 70.0,
        exposure_ev100: 14.5,
    },
    SheetView {
        name: "sunset, 2 m",
        view: view(2.0, 80.0, 89.0, 0.0),
        fov_deg: 70.0,
        exposure_ev100: 12.0,
    },
    SheetView {
        name: "twilight, 2 m",
        view: view(2.0, 80.0, 96.0, 0.0),
        fov_deg: 70.0,
        exposure_ev100: 5.0,
    },
    SheetView {
        name: "10 km",
        view: view(10_000.0, 88.0, 60.0, 90.0),
        fov_deg: 70.0,
        exposure_ev100: 14.5,
    },
    SheetView {
        name: "100 km",
        view: view(100_000.0, 95.0, 70.0, 30.0),
        fov_deg: 70.0,
        exposure_ev100: 14.5,
    },
    SheetView {
        name: "orbit, 1000 km",
        view: view(1_000_000.0, 115.0, 50.0, 40.0),
        fov_deg: 70.0,
        exposure_ev100: 14.5,
    },
];

/// Left margin for the model names and top margin for the view names, px.
const LEFT_PX: u32 = 110;
const TOP_PX: u32 = 26;

/// The image format of the sheet's file, from its extension: PNG or JPEG.
fn sheet_format(out: &Path) -> anyhow::Result<image::ImageFormat> {
    match image::ImageFormat::from_path(out) {
        Ok(format @ (image::ImageFormat::Png | image::ImageFormat::Jpeg)) => Ok(format),
        _ => bail!(
            "--out {}: the contact sheet is written as .png or .jpg",
            out.display()
        ),
    }
}

/// Renders the sheet of `args` and writes it atomically.
pub fn run(args: &ContactSheetArgs) -> anyhow::Result<()> {
    let format = sheet_format(&args.out)?;
    check_writable(&args.out)?;
    let (tile_w, tile_h) = args.tile;
    for m in &args.model {
        Renderer::check_model(*m)?;
    }
    let models: Vec<ModelId> = if args.model.is_empty() {
        GPU_MODELS.to_vec()
    } else {
        args.model.clone()
    };
    let atmosphere = Atmosphere::from_preset_or_file(&args.atmosphere)
        .with_context(|| format!("--atmosphere {}", args.atmosphere))?;
    let mut renderer = Renderer::headless()?;
    let progress = Progress::new(
        "contact sheet",
        "frames",
        (models.len() * SHEET_VIEWS.len()) as u64,
    );
    let (width, height) = (
        LEFT_PX + tile_w * SHEET_VIEWS.len() as u32,
        TOP_PX + tile_h * models.len() as u32,
    );
    let mut sheet = image::RgbImage::new(width, height);
    for (row, model) in models.iter().enumerate() {
        for (column, v) in SHEET_VIEWS.iter().enumerate() {
            let frame = Frame {
                camera_position_m: v.view.position_m(atmosphere.bottom_radius_m),
                orientation: v.view.orientation(),
                vertical_fov_deg: v.fov_deg,
                sun_direction: v.view.sun_direction(),
                atmosphere: atmosphere.clone(),
                model: *model,
                settings: ModelSettings::default(),
                exposure_ev100: v.exposure_ev100,
                width: tile_w,
                height: tile_h,
                terrain: None,
            };
            renderer
                .render(&frame)
                .with_context(|| format!("rendering {model}, {}", v.name))?;
            let pixels = renderer.read_ldr()?;
            let (x0, y0) = (
                LEFT_PX + column as u32 * tile_w,
                TOP_PX + row as u32 * tile_h,
            );
            for (i, p) in pixels.iter().enumerate() {
                let (x, y) = (i as u32 % tile_w, i as u32 / tile_w);
                sheet.put_pixel(x0 + x, y0 + y, image::Rgb([p[0], p[1], p[2]]));
            }
            progress.inc();
        }
    }
    progress.finish();
    label(&mut sheet, &models, tile_w, tile_h)?;
    let mut bytes = Cursor::new(Vec::new());
    sheet
        .write_to(&mut bytes, format)
        .with_context(|| format!("cannot encode {}", args.out.display()))?;
    write_atomically(&args.out, bytes.get_ref())?;
    eprintln!(
        "contact sheet of {} models x {} views on {}: wrote {}",
        models.len(),
        SHEET_VIEWS.len(),
        renderer.gpu().adapter_summary(),
        args.out.display()
    );
    Ok(())
}

/// Writes the view names above the columns and the model names left of the rows.
fn label(
    sheet: &mut image::RgbImage,
    models: &[ModelId],
    tile_w: u32,
    tile_h: u32,
) -> anyhow::Result<()> {
    register_sans_serif()?;
    let size = sheet.dimensions();
    let root = BitMapBackend::with_buffer(sheet.as_mut(), size).into_drawing_area();
    let font = ("sans-serif", 16).into_font().color(&WHITE);
    let err = |e: DrawingAreaErrorKind<_>| anyhow!("cannot label the contact sheet: {e}");
    for (column, v) in SHEET_VIEWS.iter().enumerate() {
        let x = (LEFT_PX + column as u32 * tile_w + 6) as i32;
        root.draw(&Text::new(v.name, (x, 4), font.clone()))
            .map_err(err)?;
    }
    for (row, model) in models.iter().enumerate() {
        let y = (TOP_PX + row as u32 * tile_h + tile_h / 2 - 8) as i32;
        root.draw(&Text::new(model.as_str(), (8, y), font.clone()))
            .map_err(err)?;
    }
    root.present().map_err(err)
}
