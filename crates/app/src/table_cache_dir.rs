//! Where `atmos` keeps the tables that take seconds to minutes to build (the rain's and
//! ice's phase functions, the cloud droplets' series; atmosphere-core's `table_cache.rs`):
//! `ATMOS_CACHE_DIR` when set (`off` keeps nothing), else `$XDG_CACHE_HOME/atmos`, else
//! `$HOME/.cache/atmos` (the XDG base directory specification's default), each with a
//! `tables` folder inside; with none of them set, nothing is kept.

use std::ffi::OsString;
use std::path::PathBuf;

use atmosphere_core::table_cache::TableCache;

/// The environment variable naming the cache folder, or `off`.
pub const CACHE_DIR_ENV: &str = "ATMOS_CACHE_DIR";

/// The cache the process's environment names.
pub fn table_cache() -> TableCache {
    table_cache_from(|name| std::env::var_os(name))
}

/// The cache named by the variables `env` looks up (empty values count as unset).
pub fn table_cache_from(env: impl Fn(&str) -> Option<OsString>) -> TableCache {
    let set = |name: &str| env(name).filter(|v| !v.is_empty());
    if let Some(dir) = set(CACHE_DIR_ENV) {
        if dir == "off" {
            return TableCache::off();
        }
        return TableCache::at(PathBuf::from(dir).join("tables"));
    }
    // The XDG specification ignores a relative XDG_CACHE_HOME.
    if let Some(dir) = set("XDG_CACHE_HOME").map(PathBuf::from)
        && dir.is_absolute()
    {
        return TableCache::at(dir.join("atmos").join("tables"));
    }
    match set("HOME") {
        Some(home) => TableCache::at(PathBuf::from(home).join(".cache/atmos/tables")),
        None => TableCache::off(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cache_of(vars: &[(&str, &str)]) -> TableCache {
        table_cache_from(|name| {
            vars.iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| OsString::from(v))
        })
    }

    #[test]
    fn the_variable_then_xdg_then_home_name_the_folder() {
        let all = [
            (CACHE_DIR_ENV, "/c"),
            ("XDG_CACHE_HOME", "/x"),
            ("HOME", "/h"),
        ];
        assert_eq!(cache_of(&all), TableCache::at("/c/tables"));
        assert_eq!(cache_of(&all[1..]), TableCache::at("/x/atmos/tables"));
        assert_eq!(
            cache_of(&all[2..]),
            TableCache::at("/h/.cache/atmos/tables")
        );
        let relative = [("XDG_CACHE_HOME", "rel"), ("HOME", "/h")];
        assert_eq!(
            cache_of(&relative),
            TableCache::at("/h/.cache/atmos/tables")
        );
        assert_eq!(
            cache_of(&[(CACHE_DIR_ENV, "off"), ("HOME", "/h")]),
            TableCache::off()
        );
        assert_eq!(
            cache_of(&[(CACHE_DIR_ENV, ""), ("HOME", "")]),
            TableCache::off()
        );
    }
}
