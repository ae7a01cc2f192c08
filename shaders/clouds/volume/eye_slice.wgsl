// The eye buffer's pass over one slice (Riley et al. 2004 Eq. 26): each covered pixel
// gets the slice's opacity and source, composited by the pipeline's blending (front to
// back under, back to front over). Twin of atmosphere-core's clouds/volume/slicing.rs.

#import clouds/volume/medium.wgsl

@vertex
fn vertex(@location(0) position: vec3<f32>) -> SliceVertex {
    var out: SliceVertex;
    out.clip = volume.view_proj * vec4<f32>(position, 1.0);
    out.world = position;
    return out;
}

@fragment
fn fragment(in: SliceVertex) -> @location(0) vec4<f32> {
    let sigma = extinction(in.world);
    if sigma <= 0.0 {
        return vec4<f32>(0.0);
    }
    let v = normalize(in.world);
    let path = volume.light_dir.w / abs(dot(v, volume.half.xyz));
    let alpha = 1.0 - exp(-sigma * path);
    let source = volume.sun.w * volume.irradiance.xyz * eye_source(read_light(in.world), dot(v, volume.sun.xyz));
    return vec4<f32>(alpha * source, alpha);
}
