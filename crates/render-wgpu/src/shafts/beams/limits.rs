//! What a beams scene asks of the device, checked before any buffer is made, so that a
//! scene too large for it is an error naming what does not fit rather than a validation
//! panic or a silently wrong image.

use atmosphere_core::models::gpu_loops::check_loop_trips;

use crate::gpu::error::RenderError;
use crate::shafts::beams::gpu_scene::GpuScene;

/// The loop trips one invocation of the march may run at most: the ray's end (every
/// node and triangle of the hierarchy, every primitive), then per light its steps, and
/// per step the light's shadow views, the planes tested beyond them and the phase
/// table's rows.
pub fn march_loop_trips(scene: &GpuScene) -> usize {
    let [_, _, steps, lights] = scene.uniform.size_steps_lights.map(|v| v as usize);
    let primitives = scene.primitives.len();
    let views = scene
        .lights
        .iter()
        .map(|l| l.view_count as usize)
        .max()
        .unwrap_or(0);
    let per_step = 1 + views + primitives + scene.phase_table.len();
    scene.nodes.len() + scene.triangles.len() / 3 + primitives + lights * (1 + steps * per_step)
}

/// Nothing, or an error naming the image side, buffer or loop count of `scene` that
/// exceeds the device's `limits`.
pub fn check(scene: &GpuScene, limits: &wgpu::Limits) -> Result<(), RenderError> {
    let [width, height, ..] = scene.uniform.size_steps_lights;
    let side = limits.max_texture_dimension_2d;
    if width > side || height > side {
        return Err(RenderError::BeamsTooLarge(format!(
            "the image {width}x{height} px exceeds the device's largest texture side, {side} px"
        )));
    }
    let buffers: [(&str, usize); 8] = [
        ("lights", size_of_val(scene.lights.as_slice())),
        ("light maps", size_of_val(scene.light_texels.as_slice())),
        ("shadow views", size_of_val(scene.views.as_slice())),
        ("shadow maps", size_of_val(scene.depths.as_slice())),
        ("primitives", size_of_val(scene.primitives.as_slice())),
        ("BVH nodes", size_of_val(scene.nodes.as_slice())),
        ("triangles", size_of_val(scene.triangles.as_slice())),
        ("phase table", size_of_val(scene.phase_table.as_slice())),
    ];
    let most = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    if let Some((what, bytes)) = buffers.iter().find(|(_, b)| *b as u64 > most) {
        return Err(RenderError::BeamsTooLarge(format!(
            "its {what} take {bytes} bytes, over the device's {most} bytes per buffer \
             (lower shadow_map_px or use smaller light maps)"
        )));
    }
    check_trips(scene)
}

/// Nothing, or an error naming the steps and lights of `scene` whose loops exceed what
/// one GPU invocation may run (no device needed).
pub fn check_trips(scene: &GpuScene) -> Result<(), RenderError> {
    let [_, _, steps, lights] = scene.uniform.size_steps_lights;
    let what =
        format!("steps={steps} x {lights} lights (with shadow views, planes and the ray's end)");
    check_loop_trips("march", &what, march_loop_trips(scene))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shafts::beams::gpu_scene::LightUniform;

    fn scene(width: u32, steps: u32, depths: usize) -> GpuScene {
        let mut scene = GpuScene {
            lights: vec![LightUniform {
                view_count: 1,
                ..Default::default()
            }],
            depths: vec![0.0; depths],
            ..Default::default()
        };
        scene.uniform.size_steps_lights = [width, 10, steps, 1];
        scene
    }

    #[test]
    fn what_does_not_fit_the_device_is_named() {
        let limits = wgpu::Limits {
            max_texture_dimension_2d: 8192,
            max_storage_buffer_binding_size: 4096,
            ..wgpu::Limits::default()
        };
        assert!(check(&scene(8192, 128, 1024), &limits).is_ok());
        let err = check(&scene(8193, 128, 1024), &limits).unwrap_err();
        assert!(err.to_string().contains("8193x10 px exceeds"), "{err}");
        let err = check(&scene(64, 128, 1025), &limits).unwrap_err();
        assert!(
            err.to_string().contains("shadow maps take 4100 bytes"),
            "{err}"
        );
        // One light with one view: 1 + steps x 2 trips.
        assert_eq!(march_loop_trips(&scene(64, 100, 0)), 201);
        assert!(check(&scene(64, 16383, 0), &limits).is_ok());
        let err = check(&scene(64, 16384, 0), &limits).unwrap_err();
        assert!(err.to_string().contains("32769 loop trips"), "{err}");
    }
}
