//! The image files of `atmos render` and `atmos record`, written atomically: PNG (the tone-mapped 8-bit
//! sRGB image) and OpenEXR (linear HDR: linear sRGB in cd/m^2, f32, with the scene, the
//! model, the atmosphere and the camera in header attributes).

use std::io::Cursor;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::color::SpectrumToColor;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{
    Encoding, Image, Layer, LayerAttributes, LineOrder, SpecificChannels, Vec2, WritableImage,
};
use render_wgpu::Frame;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

use crate::files::write_atomically;

/// Writes the 8-bit sRGB pixels (row-major, RGBA) as an RGB PNG.
pub fn write_png(path: &Path, frame: &Frame, pixels: &[[u8; 4]]) -> anyhow::Result<()> {
    write_atomically(path, &png_bytes(frame, pixels, &[], &[])?)
}

/// The 8-bit sRGB pixels (row-major, RGBA) as an RGB PNG with `text` in tEXt chunks
/// (keyword, Latin-1 text) and `utf8_text` in compressed iTXt chunks, before the image.
pub fn png_bytes(
    frame: &Frame,
    pixels: &[[u8; 4]],
    text: &[(&str, String)],
    utf8_text: &[(&str, String)],
) -> anyhow::Result<Vec<u8>> {
    png_of_size((frame.width, frame.height), pixels, text, utf8_text)
}

/// As [`png_bytes`], for an image of (width, height) pixels of any scene.
pub fn png_of_size(
    (width, height): (u32, u32),
    pixels: &[[u8; 4]],
    text: &[(&str, String)],
    utf8_text: &[(&str, String)],
) -> anyhow::Result<Vec<u8>> {
    if pixels.len() != width as usize * height as usize {
        bail!("pixel count does not match the image size");
    }
    let rgb: Vec<u8> = pixels.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    for (keyword, value) in text {
        encoder
            .add_text_chunk(keyword.to_string(), value.clone())
            .with_context(|| format!("PNG text {keyword}"))?;
    }
    for (keyword, value) in utf8_text {
        encoder
            .add_itxt_chunk(keyword.to_string(), value.clone())
            .with_context(|| format!("PNG text {keyword}"))?;
    }
    let mut writer = encoder.write_header().context("cannot encode the PNG")?;
    writer
        .write_image_data(&rgb)
        .and_then(|()| writer.finish())
        .context("cannot encode the PNG")?;
    Ok(bytes)
}

/// The header attributes (name, text) of an EXR of `frame` rendered from `scene_toml`.
pub fn header_attributes(frame: &Frame, scene_toml: &str) -> Vec<(&'static str, String)> {
    let [right, up, forward] = frame.axes();
    let model_settings: Vec<String> = frame
        .settings
        .options
        .items()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    vec![
        (
            "atmos:units",
            "linear sRGB (IEC 61966-2-1, D65) in cd/m^2, from spectral radiance at 680, 550, 440 nm (CIE 1931)".into(),
        ),
        ("atmos:model", frame.model.to_string()),
        ("atmos:model_settings", model_settings.join(", ")),
        ("atmos:atmosphere_name", frame.atmosphere.name.clone()),
        ("atmos:atmosphere", frame.atmosphere.to_toml()),
        (
            "atmos:camera",
            format!(
                "position_m = {:?}\nright = {:?}\nup = {:?}\nforward = {:?}\nvertical_fov_deg = {}\n",
                frame.camera_position_m.to_array(),
                right.to_array(),
                up.to_array(),
                forward.to_array(),
                frame.vertical_fov_deg
            ),
        ),
        ("atmos:sun_direction", format!("{:?}", frame.sun_direction.to_array())),
        ("atmos:exposure_ev100", frame.exposure_ev100.to_string()),
        ("atmos:scene", scene_toml.to_string()),
    ]
}

/// Writes the HDR pixels (spectral radiance at 680, 550, 440 nm, row-major) as linear
/// sRGB in cd/m^2, with [`header_attributes`].
pub fn write_exr(
    path: &Path,
    frame: &Frame,
    scene_toml: &str,
    radiance: &[[f32; 4]],
) -> anyhow::Result<()> {
    let attributes = header_attributes(frame, scene_toml);
    write_atomically(path, &exr_bytes(frame, &attributes, radiance)?)
}

/// The HDR pixels as an EXR file's bytes: linear sRGB in cd/m^2 with `attributes`
/// (name, text) in the header.
pub fn exr_bytes(
    frame: &Frame,
    attributes: &[(&str, String)],
    radiance: &[[f32; 4]],
) -> anyhow::Result<Vec<u8>> {
    // OpenEXR's standard place of the image: the camera's planetocentric latitude and
    // longitude, degrees, and its altitude above the ground sphere, m.
    let camera = frame.camera_position_m;
    let radius_m = camera.length();
    let place = [
        (camera.z / radius_m).asin().to_degrees(),
        camera.y.atan2(camera.x).to_degrees(),
        radius_m - frame.atmosphere.bottom_radius_m,
    ];
    exr_of_size(
        (frame.width, frame.height),
        Some(place),
        attributes,
        radiance,
    )
}

/// As [`exr_bytes`], for an image of (width, height) pixels of any scene, with the
/// camera's latitude, longitude (degrees) and altitude (m) where it is on a planet.
pub fn exr_of_size(
    (width, height): (u32, u32),
    place: Option<[f64; 3]>,
    attributes: &[(&str, String)],
    radiance: &[[f32; 4]],
) -> anyhow::Result<Vec<u8>> {
    let to_srgb = SpectrumToColor::new(&RGB_WAVELENGTHS_NM)?;
    let width = width as usize;
    if radiance.len() != width * height as usize {
        bail!("pixel count does not match the image size");
    }
    let srgb: Vec<[f32; 3]> = radiance
        .iter()
        .map(|p| {
            to_srgb
                .linear_srgb_cd_m2(&[p[0], p[1], p[2]].map(f64::from))
                .map(|v| v as f32)
        })
        .collect();
    let mut layer_attributes = LayerAttributes::named("atmos");
    layer_attributes.software_name = Some(Text::from("atmos"));
    if let Some([latitude, longitude, altitude]) = place {
        layer_attributes.latitude = Some(latitude as f32);
        layer_attributes.longitude = Some(longitude as f32);
        layer_attributes.altitude = Some(altitude as f32);
    }
    for (name, value) in attributes {
        let text = Text::new_or_none(value)
            .with_context(|| format!("header attribute {name} has characters EXR cannot hold"))?;
        layer_attributes
            .other
            .insert(Text::from(*name), AttributeValue::Text(text));
    }
    let layer = Layer::new(
        (width, height as usize),
        layer_attributes,
        // Tiles in increasing order: the same image always gives the same bytes.
        Encoding {
            line_order: LineOrder::Increasing,
            ..Encoding::FAST_LOSSLESS
        },
        SpecificChannels::rgb(|p: Vec2<usize>| {
            let [r, g, b] = srgb[p.y() * width + p.x()];
            (r, g, b)
        }),
    );
    let mut bytes = Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .context("cannot encode the EXR")?;
    Ok(bytes.into_inner())
}
