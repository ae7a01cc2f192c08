//! The triangles of a glTF 2.0 file: every triangle primitive of every mesh of the
//! default scene (or the first), placed by its node's world transform.

use std::path::Path;

use glam::{DMat4, DVec3, Mat4};

use crate::beams::triangle::Triangle;

/// The largest glTF file read, bytes (its buffers are read by the `gltf` crate).
pub const MAX_GLTF_BYTES: u64 = 256 << 20;

/// The triangles of the file at `path`, in its frame (metres, y up); the error says
/// what is wrong in words.
pub fn load_triangles(path: &Path) -> Result<Vec<Triangle>, String> {
    let size = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    if size > MAX_GLTF_BYTES {
        return Err(format!("{size} bytes; at most {MAX_GLTF_BYTES}"));
    }
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| e.to_string())?;
    let document = &gltf.document;
    let buffers = gltf::import_buffers(document, path.parent(), gltf.blob.clone())
        .map_err(|e| e.to_string())?;
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or("the file has no scene")?;
    let mut triangles = Vec::new();
    // Nodes with their parents' transform, without recursion.
    let mut pending: Vec<(gltf::Node, DMat4)> =
        scene.nodes().map(|n| (n, DMat4::IDENTITY)).collect();
    while let Some((node, parent)) = pending.pop() {
        let local = Mat4::from_cols_array_2d(&node.transform().matrix()).as_dmat4();
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                if primitive.mode() != gltf::mesh::Mode::Triangles {
                    return Err(format!(
                        "mesh {} has a primitive of mode {:?}; only triangles occlude",
                        mesh.index(),
                        primitive.mode()
                    ));
                }
                let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                let positions: Vec<DVec3> = reader
                    .read_positions()
                    .ok_or_else(|| format!("mesh {} has no positions", mesh.index()))?
                    .map(|p| world.transform_point3(DVec3::from(p.map(f64::from))))
                    .collect();
                let indices: Vec<usize> = match reader.read_indices() {
                    Some(i) => i.into_u32().map(|i| i as usize).collect(),
                    None => (0..positions.len()).collect(),
                };
                for corners in indices.chunks_exact(3) {
                    let corner = |i: usize| {
                        positions.get(corners[i]).copied().ok_or_else(|| {
                            format!("mesh {} has an index past its vertices", mesh.index())
                        })
                    };
                    triangles.push(Triangle([corner(0)?, corner(1)?, corner(2)?]));
                }
            }
        }
        pending.extend(node.children().map(|c| (c, world)));
    }
    if triangles.is_empty() {
        return Err("the scene has no triangles".into());
    }
    Ok(triangles)
}
