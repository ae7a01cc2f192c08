// The light buffer's pass over one slice (Riley et al. 2004 Eq. 25): each texel whose
// column meets the slice inside the box multiplies its intensity by Eq. 25's factor over
// the slice's optical depth and adds it to tau, reading the previous buffer at its own
// texel. Twin of atmosphere-core's clouds/volume/light_buffer.rs (`advance`).

#import clouds/volume/medium.wgsl

@vertex
fn vertex(@location(0) position: vec3<f32>) -> SliceVertex {
    let uv = (vec2<f32>(dot(position, volume.light_u.xyz), dot(position, volume.light_v.xyz))
        - vec2<f32>(volume.light_u.w, volume.light_v.w)) / volume.light_size.xy;
    var out: SliceVertex;
    out.clip = vec4<f32>(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y, 0.5, 1.0);
    out.world = position;
    return out;
}

@fragment
fn fragment(in: SliceVertex) -> @location(0) vec4<f32> {
    let previous = textureLoad(light_in, vec2<u32>(in.clip.xy), 0);
    let d = extinction(in.world) * volume.light_size.w;
    if d <= 0.0 {
        return previous;
    }
    return vec4<f32>(previous.xyz * riley_step(previous.w, d), previous.w + d);
}
