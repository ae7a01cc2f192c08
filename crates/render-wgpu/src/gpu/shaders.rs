//! WGSL sources from the workspace's `shaders/` folder, embedded by `build.rs` so the
//! binary needs no files at run time, and composed by a small textual resolver.
//!
//! A shader is named by its path below `shaders/` (`sky/nishita/pixel.wgsl`). The import
//! rules:
//! - a line `#import path.wgsl` (the path below `shaders/`, never relative to the
//!   importing file) is replaced by that file's text, its own imports resolved first;
//! - each file is included once per composed shader, however many files import it, so
//!   an import cycle ends instead of repeating;
//! - an unknown path is an error naming the shader that imports it.
//!
//! Libraries (`common/`, and the files of a model's folder that declare its bindings,
//! types and functions) have no entry point; entry-point files hold the `@compute`,
//! `@vertex` or `@fragment` functions of one pass or table build.

use crate::gpu::error::GpuError;

include!(concat!(env!("OUT_DIR"), "/shaders.rs"));

/// The names of all embedded shader files.
pub fn shader_names() -> impl Iterator<Item = &'static str> {
    SHADERS.iter().map(|(name, _)| *name)
}

/// Every embedded shader file with its imports resolved, by file name.
pub fn all_composed() -> Result<Vec<(&'static str, String)>, GpuError> {
    shader_names()
        .map(|name| Ok((name, composed(name)?)))
        .collect()
}

/// The source of shader `name` (a path below `shaders/` such as
/// `sky/transmittance_table.wgsl`) with its
/// `#import` lines resolved.
pub fn composed(name: &str) -> Result<String, GpuError> {
    let mut out = String::new();
    let mut included = Vec::new();
    append(name, name, &mut included, &mut out)?;
    Ok(out)
}

fn raw(name: &str) -> Option<&'static str> {
    SHADERS.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// Appends `name`'s text to `out`, replacing each import by the module's text unless
/// already included (which also ends import cycles).
fn append<'a>(
    root: &str,
    name: &'a str,
    included: &mut Vec<&'a str>,
    out: &mut String,
) -> Result<(), GpuError> {
    let text = raw(name).ok_or_else(|| {
        if name == root {
            GpuError::UnknownShader(name.to_string())
        } else {
            GpuError::UnknownImport {
                shader: root.to_string(),
                import: name.to_string(),
            }
        }
    })?;
    included.push(name);
    for line in text.lines() {
        if let Some(import) = line.trim().strip_prefix("#import") {
            let import = import.trim();
            if !included.contains(&import) {
                append(root, import, included, out)?;
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn imports_are_resolved_once_and_unknown_names_are_errors() {
        let table = composed("sky/transmittance_table.wgsl").unwrap();
        assert!(!table.contains("#import"));
        assert_eq!(table.matches("struct AtmosphereParams").count(), 1);
        assert!(matches!(
            composed("missing.wgsl"),
            Err(GpuError::UnknownShader(_))
        ));
    }
}
