//! The luminance pass (`shaders/post/luminance.wgsl`, automatic exposure) against its CPU twin
//! (`render_wgpu::post::luminance::log_average_luminance`): on a known image with dark,
//! bright and very bright (sun-disk) pixels, of a size that is no multiple of the
//! dispatch, and on a rendered frame read back from the renderer.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::models::id::ModelId;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::post::luminance::{
    FLOOR_CD_M2, LuminancePass, log_average_luminance, luminance_weights,
};

/// Largest relative difference GPU against CPU: the f32 sums of about 1e4 logarithms
/// per workgroup lose about 1e-6 of each, and exp turns an absolute error in the mean
/// log into the same relative one; 1e-4 leaves a wide margin.
const MAX_RELATIVE_ERROR: f64 = 1e-4;

/// A `width` x `height` image of radiance: a gradient over six decades, black pixels
/// (left out) and a few at the f16 ceiling, as the sun's disk.
fn known_image(width: u32, height: u32) -> Vec<[f32; 4]> {
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            if (x + y) % 7 == 0 {
                [0.0, 0.0, 0.0, 1.0]
            } else if x == 3 && y % 5 == 0 {
                [65504.0; 4]
            } else {
                let t = f64::from(x * height + y) / f64::from(width * height);
                let v = 10f64.powf(-5.0 + 6.0 * t) as f32;
                [v, 0.7 * v, 0.4 * v, 1.0]
            }
        })
        .collect()
}

fn relative(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

#[test]
fn a_known_image_matches_the_cpu() {
    let Some(renderer) = support::renderer_or_skip("luminance") else {
        return;
    };
    let gpu = renderer.gpu();
    let pass = LuminancePass::new(gpu, RGB_WAVELENGTHS_NM).unwrap();
    let weights = luminance_weights(RGB_WAVELENGTHS_NM).unwrap();
    for (width, height) in [(301, 173), (5, 3), (1, 1)] {
        let pixels = known_image(width, height);
        let texture = render_wgpu::gpu::pipeline::texture_2d(
            &gpu.device,
            "known image",
            (width, height),
            wgpu::TextureFormat::Rgba32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        gpu.queue.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(&pixels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 16),
                rows_per_image: Some(height),
            },
            texture.size(),
        );
        let gpu_mean = pass.measure(gpu, &texture).unwrap();
        let cpu_mean = log_average_luminance(weights, &pixels);
        println!("{width}x{height}: GPU {gpu_mean} CPU {cpu_mean} cd/m^2");
        assert!(
            relative(gpu_mean, cpu_mean) < MAX_RELATIVE_ERROR,
            "{width}x{height}: GPU {gpu_mean}, CPU {cpu_mean}"
        );
    }
    // All black: the floor.
    assert_eq!(log_average_luminance(weights, &[[0.0; 4]; 4]), FLOOR_CD_M2);
}

#[test]
fn a_rendered_frame_matches_the_cpu() {
    let Some(mut renderer) = support::renderer_or_skip("luminance") else {
        return;
    };
    let frame = support::frame(
        ModelId::Nishita,
        support::view(2_000.0, 80.0, 85.0),
        60.0,
        97,
        61,
    );
    renderer.render(&frame).unwrap();
    let gpu_mean = renderer.average_luminance().unwrap();
    let hdr = renderer.read_hdr().unwrap();
    let cpu_mean = log_average_luminance(luminance_weights(RGB_WAVELENGTHS_NM).unwrap(), &hdr);
    println!("frame: GPU {gpu_mean} CPU {cpu_mean} cd/m^2");
    assert!(cpu_mean > 1.0, "a lit sky: {cpu_mean}");
    assert!(
        relative(gpu_mean, cpu_mean) < MAX_RELATIVE_ERROR,
        "GPU {gpu_mean}, CPU {cpu_mean}"
    );
}
