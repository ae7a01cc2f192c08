//! The layout rules of docs/architecture.md, checked on the sources: no import cycle
//! between the modules (files) of any crate, and no source file (Rust or WGSL) over 600
//! lines.
//!
//! A module's imports are the module paths its code names: `use crate::a::b::C`,
//! `super::x::f()`, `self::y::Z`, `child::g()` and grouped `use` trees alike. Each path is resolved to
//! the deepest module file it reaches, so `crate::sky::registry::create` is an edge to
//! `sky/registry.rs`. A `mod` declaration is not an import; a parent that re-exports a
//! child (`pub use child::X`) imports it, and a child that names an item of its parent
//! (`super::X`) imports the parent, so a folder's `mod.rs` that does both is a cycle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_LINES: usize = 600;

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the workspace")
        .to_path_buf()
}

fn files_under(dir: &Path, extension: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = entries.map(|e| e.expect("readable").path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            files_under(&path, extension, out);
        } else if path.extension().is_some_and(|e| e == extension) {
            out.push(path);
        }
    }
}

/// The module path of a source file below `src/`: `a/b.rs` and `a/b/mod.rs` are
/// `["a", "b"]`; `lib.rs` and `main.rs` the crate root `[]`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).expect("file below src");
    let mut parts: Vec<String> = relative
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    let stem = last.trim_end_matches(".rs");
    let at_root = parts.is_empty();
    if !(stem == "mod" || (at_root && (stem == "lib" || stem == "main"))) {
        parts.push(stem.to_string());
    }
    parts
}

/// The code of a Rust file without comments, string and character literals (each
/// replaced by a space, line breaks kept).
fn code_only(source: &str) -> String {
    let chars: Vec<char> = source.chars().collect();
    let mut out = String::with_capacity(source.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if chars[i] == '\n' {
                        out.push('\n');
                    }
                    i += 1;
                }
            }
            out.push(' ');
        } else if c == 'r' && matches!(next, Some('#') | Some('"')) && is_raw_string(&chars, i) {
            let hashes = chars[i + 1..].iter().take_while(|&&h| h == '#').count();
            i += 2 + hashes;
            while i < chars.len() {
                if chars[i] == '"' && chars[i + 1..].iter().take(hashes).all(|&h| h == '#') {
                    i += 1 + hashes;
                    break;
                }
                if chars[i] == '\n' {
                    out.push('\n');
                }
                i += 1;
            }
            out.push(' ');
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                }
                if chars.get(i) == Some(&'\n') {
                    out.push('\n');
                }
                i += 1;
            }
            i += 1;
            out.push(' ');
        } else if c == '\'' && is_char_literal(&chars, i) {
            i += 1;
            while i < chars.len() && chars[i] != '\'' {
                if chars[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push(' ');
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn is_raw_string(chars: &[char], i: usize) -> bool {
    let before_is_ident = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
    let hashes = chars[i + 1..].iter().take_while(|&&h| h == '#').count();
    !before_is_ident && chars.get(i + 1 + hashes) == Some(&'"')
}

/// A `'` opening a character literal rather than a lifetime or label.
fn is_char_literal(chars: &[char], i: usize) -> bool {
    matches!(
        (chars.get(i + 1), chars.get(i + 2)),
        (Some('\\'), _) | (Some(_), Some('\''))
    )
}

/// Every path the code names (`crate::`, `super::`, `self::` or a bare `child::`), as its
/// segments, with `use` trees expanded; each with the inline-module depth it was named at
/// (`super` inside `mod tests { .. }` is the file itself).
fn named_paths(code: &str) -> Vec<(Vec<String>, usize)> {
    let tokens = tokenize(code);
    let mut paths = Vec::new();
    let mut inline_modules: Vec<usize> = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    while i < tokens.len() {
        let t = tokens[i].as_str();
        match t {
            "{" => depth += 1,
            "}" => {
                depth -= 1;
                if inline_modules.last() == Some(&depth) {
                    inline_modules.pop();
                }
            }
            "mod" if tokens.get(i + 2).map(String::as_str) == Some("{") => {
                inline_modules.push(depth);
            }
            "use" => {
                let mut prefix = Vec::new();
                i = use_tree(&tokens, i + 1, &mut prefix, &mut |p| {
                    paths.push((p, inline_modules.len()))
                });
                continue;
            }
            _ if is_ident(t)
                && tokens.get(i + 1).map(String::as_str) == Some("::")
                && (i == 0 || tokens[i - 1] != "::") =>
            {
                let mut path = vec![t.to_string()];
                let mut j = i + 1;
                while tokens.get(j).map(String::as_str) == Some("::")
                    && tokens.get(j + 1).is_some_and(|s| is_ident(s))
                {
                    path.push(tokens[j + 1].clone());
                    j += 2;
                }
                paths.push((path, inline_modules.len()));
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    paths
}

/// Expands the `use` tree starting at token `i`; returns the index after it.
fn use_tree(
    tokens: &[String],
    mut i: usize,
    prefix: &mut Vec<String>,
    emit: &mut dyn FnMut(Vec<String>),
) -> usize {
    let base = prefix.len();
    loop {
        match tokens.get(i).map(String::as_str) {
            Some("{") => {
                i += 1;
                loop {
                    i = use_tree(tokens, i, prefix, emit);
                    match tokens.get(i).map(String::as_str) {
                        Some(",") => i += 1,
                        Some("}") => {
                            i += 1;
                            break;
                        }
                        _ => break,
                    }
                    if tokens.get(i).map(String::as_str) == Some("}") {
                        i += 1;
                        break;
                    }
                }
                prefix.truncate(base);
                return i;
            }
            Some("::") => i += 1,
            Some(s) if is_ident(s) || s == "*" => {
                prefix.push(s.to_string());
                i += 1;
                if tokens.get(i).map(String::as_str) == Some("as") {
                    i += 2;
                }
                if tokens.get(i).map(String::as_str) != Some("::") {
                    emit(prefix.clone());
                    prefix.truncate(base);
                    return i;
                }
            }
            _ => {
                prefix.truncate(base);
                return i;
            }
        }
    }
}

fn is_ident(s: &str) -> bool {
    s.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

fn tokenize(code: &str) -> Vec<String> {
    let mut tokens = Vec::new();
    let chars: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push(chars[start..i].iter().collect());
        } else if c == ':' && chars.get(i + 1) == Some(&':') {
            tokens.push("::".into());
            i += 2;
        } else {
            if !c.is_whitespace() {
                tokens.push(c.to_string());
            }
            i += 1;
        }
    }
    tokens
}

/// The module a path names, resolved from `module` (the naming file's module, `inline`
/// inline modules deep) to the deepest module in `modules`.
fn resolve(
    path: &[String],
    module: &[String],
    inline: usize,
    modules: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let mut base: Vec<String> = module.to_vec();
    let mut rest = path;
    let mut inline = inline;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some("self") => rest = &rest[1..],
        Some("super") => {
            while rest.first().map(String::as_str) == Some("super") {
                if inline > 0 {
                    inline -= 1;
                } else {
                    base.pop()?;
                }
                rest = &rest[1..];
            }
        }
        Some(_) => {
            // A bare path in edition 2018+ starts at a child module of this file (or at
            // an extern crate or a type, which are no module of the crate).
            let mut child = base.clone();
            child.push(rest[0].clone());
            if !modules.contains(&child) {
                return None;
            }
        }
        None => return None,
    }
    let mut target = base;
    for segment in rest {
        let mut longer = target.clone();
        longer.push(segment.clone());
        if modules.contains(&longer) {
            target = longer;
        } else {
            break;
        }
    }
    Some(target)
}

/// The strongly connected components of more than one module (Tarjan's algorithm).
fn cycles(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    struct State<'a> {
        edges: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'a Vec<String>, usize>,
        low: BTreeMap<&'a Vec<String>, usize>,
        stack: Vec<&'a Vec<String>>,
        on_stack: BTreeSet<&'a Vec<String>>,
        components: Vec<Vec<Vec<String>>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a Vec<String>) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        if let Some(targets) = s.edges.get(v) {
            for w in targets {
                let w = s.edges.get_key_value(w).map_or(w, |(k, _)| k);
                if !s.index.contains_key(w) {
                    visit(s, w);
                    let low = s.low[v].min(s.low[w]);
                    s.low.insert(v, low);
                } else if s.on_stack.contains(w) {
                    let low = s.low[v].min(s.index[w]);
                    s.low.insert(v, low);
                }
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.components.push(component);
            }
        }
    }
    let mut state = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        components: Vec::new(),
    };
    for v in edges.keys() {
        if !state.index.contains_key(v) {
            visit(&mut state, v);
        }
    }
    state.components
}

/// The import cycles of the crate whose sources are in `src`, each a list of files.
fn import_cycles(src: &Path) -> Vec<Vec<String>> {
    let mut files = Vec::new();
    files_under(src, "rs", &mut files);
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_of(src, f)).collect();
    let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    let mut file_of = BTreeMap::new();
    for file in &files {
        let module = module_of(src, file);
        file_of.insert(module.clone(), file.clone());
        let source = std::fs::read_to_string(file).expect("readable source");
        let targets = edges.entry(module.clone()).or_default();
        for (path, inline) in named_paths(&code_only(&source)) {
            if let Some(target) = resolve(&path, &module, inline, &modules)
                && target != module
            {
                targets.insert(target);
            }
        }
    }
    cycles(&edges)
        .into_iter()
        .map(|component| {
            component
                .iter()
                .map(|m| file_of[m].strip_prefix(src).unwrap().display().to_string())
                .collect()
        })
        .collect()
}

fn crate_sources() -> Vec<PathBuf> {
    let root = workspace_root();
    let mut sources: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .expect("crates/")
        .map(|e| e.expect("readable").path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    sources.push(root.join("tests/src"));
    sources.sort();
    sources
}

#[test]
fn no_crate_has_an_import_cycle_between_its_modules() {
    let mut found = Vec::new();
    for src in crate_sources() {
        for cycle in import_cycles(&src) {
            found.push(format!("{}: {}", src.display(), cycle.join(" <-> ")));
        }
    }
    assert!(found.is_empty(), "import cycles:\n{}", found.join("\n"));
}

#[test]
fn no_source_file_is_over_600_lines() {
    let root = workspace_root();
    let mut files = Vec::new();
    for dir in ["crates", "tests", "shaders"] {
        files_under(&root.join(dir), "rs", &mut files);
        files_under(&root.join(dir), "wgsl", &mut files);
    }
    let long: Vec<String> = files
        .iter()
        .filter(|f| !f.components().any(|c| c.as_os_str() == "target"))
        .filter_map(|f| {
            let lines = std::fs::read_to_string(f)
                .expect("readable")
                .lines()
                .count();
            (lines > MAX_LINES).then(|| format!("{} ({lines} lines)", f.display()))
        })
        .collect();
    assert!(
        long.is_empty(),
        "over {MAX_LINES} lines: {}",
        long.join(", ")
    );
}

#[test]
fn the_cycle_finder_sees_a_cycle_through_a_use_tree_and_super() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    std::fs::create_dir_all(src.join("sky")).unwrap();
    std::fs::write(src.join("lib.rs"), "pub mod sky;\npub mod frame;\n").unwrap();
    std::fs::write(src.join("sky/mod.rs"), "pub mod pass;\npub struct Step;\n").unwrap();
    std::fs::write(
        src.join("sky/pass.rs"),
        "// use crate::frame::Plan; in a comment is no import\nuse super::Step;\n",
    )
    .unwrap();
    std::fs::write(
        src.join("frame.rs"),
        "use crate::{sky::{pass}, x};\nfn f() { let s = \"crate::sky\"; }\n",
    )
    .unwrap();
    assert!(import_cycles(src).is_empty());
    std::fs::write(
        src.join("sky/mod.rs"),
        "pub mod pass;\npub struct Step;\npub use pass::*;\n",
    )
    .unwrap();
    assert_eq!(import_cycles(src), vec![vec!["sky/mod.rs", "sky/pass.rs"]]);
    std::fs::write(
        src.join("sky/pass.rs"),
        "fn f() -> crate::frame::Plan { todo() }\n#[cfg(test)]\nmod tests { use super::*; }\n",
    )
    .unwrap();
    std::fs::write(src.join("sky/mod.rs"), "pub mod pass;\n").unwrap();
    std::fs::write(src.join("frame.rs"), "use crate::sky::pass::{self as p};\n").unwrap();
    assert_eq!(import_cycles(src), vec![vec!["frame.rs", "sky/pass.rs"]]);
}
