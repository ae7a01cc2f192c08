// Library: what the march or the upsample finds for one pixel of a frame, and where it
// goes: the cloud image and the cloud's entry, for the composite and the model's second
// run (`store_pixel_cloud`), or the model's pixel with the cloud over it
// (`frame_over_full.wgsl`).

#import clouds/frame_rays.wgsl

// Where the sky model's second run ends its rays: xyz the outward vertical at the
// cloud's entry, w the entry distance, m; 0 where the pixel sees no cloud or the camera
// is inside one.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;

struct PixelCloud {
    // rgb: the cloud's radiance; a: its transmittance.
    cloud: vec4<f32>,
    // As `cloud_front` holds it.
    front: vec4<f32>,
}

const CLEAR_PIXEL: PixelCloud = PixelCloud(vec4<f32>(0.0, 0.0, 0.0, 1.0), vec4<f32>(0.0));

// The pixel whose ray along `d` from the camera enters the layer at `entry_m` and sees
// `cloud` there.
fn pixel_cloud(cloud: vec4<f32>, d: vec3<f32>, entry_m: f32) -> PixelCloud {
    var front = vec4<f32>(0.0);
    if cloud.a < 1.0 {
        front = vec4<f32>(normalize(layer.camera_m.xyz + d * entry_m), entry_m);
    }
    return PixelCloud(cloud, front);
}

fn store_pixel_cloud(px: vec2<u32>, p: PixelCloud) {
    textureStore(cloud_image, px, p.cloud);
    textureStore(cloud_front, px, p.front);
}
