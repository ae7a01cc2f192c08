// The density table of the Bruneton model: relative densities (Rayleigh, Mie, ozone) at
// 8192 altitudes evenly spaced over the atmosphere's thickness, read with linear
// interpolation while building the scattering tables. The GPU twin of `DensityTable::new`
// (atmosphere-core `bruneton/tables.rs`).

#import sky/bruneton/tables.wgsl

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= DENSITY_SAMPLES {
        return;
    }
    store_write(bruneton.density_offset + id.x, vec4<f32>(densities(f32(id.x) * bruneton.density_step_m), 0.0));
}
