//! What the beams parity tests share: a shipped scene at a test's size, the CPU twin's
//! radiance on the camera's pixel rays, the GPU image's radiance, and the comparison of
//! the two relative to each pixel with a floor at 1e-3 of the brightest value.

use std::path::Path;

use atmosphere_core::beams::methods::method::BeamMethod;
use atmosphere_core::beams::scene::BeamScene;

/// A scene of `assets/scenes/beams/` with its camera at `width` x `height` pixels.
pub fn shipped_scene(name: &str, width: u32, height: u32) -> BeamScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/scenes/beams")
        .join(name);
    let mut scene = BeamScene::load(&path).unwrap();
    scene.camera.width_px = width;
    scene.camera.height_px = height;
    scene
}

/// The method's radiance at the three wavelengths through each pixel's centre, row by row.
pub fn cpu_pixels(method: &dyn BeamMethod, scene: &BeamScene) -> Vec<[f64; 3]> {
    let camera = &scene.camera;
    (0..camera.height_px)
        .flat_map(|y| (0..camera.width_px).map(move |x| (x, y)))
        .map(|(x, y)| {
            let l = method
                .radiance(&camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5))
                .unwrap();
            [l[0], l[1], l[2]]
        })
        .collect()
}

/// A GPU radiance image's texels (rgb = the three wavelengths) as f64, row by row.
pub fn gpu_pixels(texels: Vec<[f32; 4]>) -> Vec<[f64; 3]> {
    texels
        .into_iter()
        .map(|p| [p[0], p[1], p[2]].map(f64::from))
        .collect()
}

/// Asserts |L_gpu - L_cpu| / max(L_cpu, floor) <= `tolerance` on every pixel and
/// wavelength, the floor 1e-3 of the image's brightest value at that wavelength; returns
/// the largest relative error.
pub fn check_relative(name: &str, cpu: &[[f64; 3]], gpu: &[[f64; 3]], tolerance: f64) -> f64 {
    let floor: [f64; 3] =
        std::array::from_fn(|k| 1e-3 * cpu.iter().map(|p| p[k]).fold(0.0, f64::max));
    assert!(floor.iter().all(|&f| f > 0.0), "{name}: a black image");
    let mut worst = 0.0f64;
    for (i, (c, g)) in cpu.iter().zip(gpu).enumerate() {
        let e = (0..3)
            .map(|k| (g[k] - c[k]).abs() / c[k].max(floor[k]))
            .fold(0.0, f64::max);
        assert!(e <= tolerance, "{name}: pixel {i}: GPU {g:?}, CPU {c:?}");
        worst = worst.max(e);
    }
    println!("{name}: largest relative error {worst:.2e}");
    worst
}
