//! Beams scene files: every bad field is named, light maps and glTF meshes load from
//! paths relative to the scene file.

mod common;

use std::path::Path;

use atmosphere_core::beams::scene::BeamScene;
use common::beams::*;
use glam::DVec3;

fn load(rest: &str) -> Result<BeamScene, String> {
    let text = format!(
        "[medium]\n{}\n{CAMERA}\n{rest}",
        medium(0.05, 0.01, ISOTROPIC)
    );
    BeamScene::from_toml(&text, "scene.toml", Path::new("/nonexistent")).map_err(|e| e.to_string())
}

const SPOT: &str = "[[lights]]\nkind = \"spot\"\nposition_m = [0, 5, 0]\ndirection = [0, -1, 0]\n\
                    intensity_w_sr_nm = { kind = \"constant\", value = 1 }\n";

#[test]
fn every_bad_field_is_named() {
    let cases = [
        (format!("{SPOT}cone_deg = 95\n"), "scene.toml: lights[0].cone_deg: 95 must be in (0, 89) degrees"),
        (format!("{SPOT}cone_deg = 20\nfalloff_exponent = -1\n"), "lights[0].falloff_exponent"),
        (format!("{SPOT}cone_deg = 20\nradius_m = 0\n"), "lights[0].radius_m: 0 must be at least 0.0001 m"),
        (format!("{SPOT}cone_deg = 20\nlight_map = \"gobo.png\"\n"), "lights[0].light_map: cannot read image /nonexistent/gobo.png"),
        (
            "[[lights]]\nkind = \"parallel\"\nposition_m = [0, 5, 0]\ndirection = [0, 0, 0]\n\
             irradiance_w_m2_nm = { kind = \"constant\", value = 1 }\n".into(),
            "lights[0].direction: [0.0, 0.0, 0.0] has no length",
        ),
        (
            "[[lights]]\nkind = \"parallel\"\nposition_m = [0, 5, 0]\ndirection = [0, -1, 0]\n\
             irradiance_w_m2_nm = { kind = \"constant\", value = 1 }\nlight_map = \"w.png\"\n".into(),
            "lights[0].size_m: a parallel light with a light_map needs the size the map covers",
        ),
        (
            "[[lights]]\nkind = \"point\"\nposition_m = [0, 5, 0]\n\
             intensity_w_sr_nm = { kind = \"constant\", value = -1 }\n".into(),
            "lights[0].intensity_w_sr_nm: value -1 must be finite and >= 0",
        ),
        ("[[occluders]]\nkind = \"box\"\nmin_m = [0, 0, 0]\nmax_m = [1, -1, 1]\n".into(), "occluders[0].max_m"),
        ("[[occluders]]\nkind = \"sphere\"\ncenter_m = [0, 0, 0]\nradius_m = -2\n".into(), "occluders[0].radius_m"),
        (
            "[[occluders]]\nkind = \"quad\"\ncorner_m = [0, 0, 0]\nedge_u_m = [1, 0, 0]\nedge_v_m = [2, 0, 0]\n".into(),
            "occluders[0].edge_v_m",
        ),
        ("[[occluders]]\nkind = \"gltf\"\nfile = \"teapot.glb\"\n".into(), "occluders[0].file: cannot read glTF /nonexistent/teapot.glb"),
        ("[[occluders]]\nkind = \"cone\"\n".into(), "unknown variant `cone`"),
        (
            "[[lights]]\nkind = \"point\"\nposition_m = [0, 5, 1e9]\n\
             intensity_w_sr_nm = { kind = \"constant\", value = 1 }\n".into(),
            "lights[0].position_m: [0.0, 5.0, 1000000000.0] must be finite, each coordinate at most 1e7 m",
        ),
        (
            "[[lights]]\nkind = \"point\"\nposition_m = [0, 5, 0]\n\
             intensity_w_sr_nm = { kind = \"constant\", value = 1e20 }\n".into(),
            "lights[0].intensity_w_sr_nm: 1e20 exceeds the largest allowed, 1e12",
        ),
        ("[[lights]]\nkind = \"point\"\nposition = [0, 5, 0]\n".into(), "unknown field `position`"),
    ];
    for (text, expected) in cases {
        let e = load(&text).unwrap_err();
        assert!(e.contains(expected), "{text}\n{e}");
    }
    let text = format!("[medium]\n{}\n{CAMERA}", medium(-0.05, 0.0, ISOTROPIC));
    let e = BeamScene::from_toml(&text, "s.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("medium.scattering_per_m: value -0.05"), "{e}");
    let text = format!(
        "[medium]\n{}\n{CAMERA}",
        medium(0.05, 0.0, "{ kind = \"henyey_greenstein\", g = 1.5 }")
    );
    let e = BeamScene::from_toml(&text, "s.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("medium.phase: asymmetry g = 1.5"), "{e}");
}

#[test]
fn camera_errors_are_named() {
    let text = format!(
        "[medium]\n{}\n{}",
        medium(0.05, 0.0, ISOTROPIC),
        CAMERA.replace("look_at_m = [0, 2, 0]", "look_at_m = [0, 2, 20]")
    );
    let e = BeamScene::from_toml(&text, "s.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("camera.look_at_m: must differ from position_m"),
        "{e}"
    );
}

/// A unit cube's 12 triangles as a glTF file with its buffer beside it.
fn write_cube(folder: &Path) {
    let corners: Vec<[f32; 3]> = (0..8)
        .map(|i| {
            [
                (i & 1) as f32 - 0.5,
                ((i >> 1) & 1) as f32 - 0.5,
                ((i >> 2) & 1) as f32 - 0.5,
            ]
        })
        .collect();
    let faces: [[u16; 4]; 6] = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    let indices: Vec<u16> = faces
        .iter()
        .flat_map(|f| [f[0], f[1], f[2], f[0], f[2], f[3]])
        .collect();
    let mut bytes: Vec<u8> = corners
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(folder.join("cube.bin"), &bytes).unwrap();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"mesh":0,"translation":[0,1,0]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"uri":"cube.bin","byteLength":{len}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":96}},{{"buffer":0,"byteOffset":96,"byteLength":72}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-0.5,-0.5,-0.5],"max":[0.5,0.5,0.5]}},
                     {{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}}]}}"#,
        len = bytes.len()
    );
    std::fs::write(folder.join("cube.gltf"), json).unwrap();
}

#[test]
fn gltf_triangles_occlude_where_the_node_scale_and_translation_put_them() {
    let folder = tempfile::tempdir().unwrap();
    write_cube(folder.path());
    let text = format!(
        "[medium]\n{}\n{CAMERA}\n[[occluders]]\nkind = \"gltf\"\nfile = \"cube.gltf\"\n\
         scale = 2\ntranslation_m = [10, 0, 0]\n",
        medium(0.05, 0.0, ISOTROPIC)
    );
    let s = BeamScene::from_toml(&text, "s.toml", folder.path()).unwrap();
    assert_eq!(s.occluders.triangles.len(), 12);
    // The node lifts the cube to y in [0.5, 1.5]; scaled by 2 it spans y in [1, 3] and
    // x in [9, 11] once moved.
    let hit = s
        .occluders
        .nearest(DVec3::new(0.0, 2.0, 0.0), DVec3::X, f64::INFINITY);
    assert!((hit.unwrap() - 9.0).abs() < 1e-6, "{hit:?}");
    assert!(
        s.occluders
            .nearest(DVec3::new(0.0, 0.5, 0.0), DVec3::X, f64::INFINITY)
            .is_none()
    );
    assert!(
        s.occluders
            .blocks(DVec3::new(10.0, -5.0, 0.0), DVec3::Y, 10.0)
    );
    assert!(
        !s.occluders
            .blocks(DVec3::new(10.0, -5.0, 0.0), DVec3::Y, 5.0)
    );
}
