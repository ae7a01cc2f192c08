//! The disk cache of tables: a second build reads the file and gives the table bit for
//! bit; a corrupt, cut or foreign file is built again; a cache that cannot be written
//! still gives the table.

use std::cell::Cell;
use std::fs;

use atmosphere_core::clouds::layer::droplets::{droplet_orders, droplet_orders_cached};
use atmosphere_core::hydrometeors::spectral_phase::{Particles, SpectralPhase};
use atmosphere_core::table_cache::TableCache;

/// Rows with values whose bits a text format would lose.
fn awkward_rows() -> Vec<Vec<f64>> {
    vec![
        vec![0.1, -0.0, 1e-310, f64::MAX, std::f64::consts::PI],
        vec![],
        vec![1.0 / 3.0],
    ]
}

fn bits(rows: &[Vec<f64>]) -> Vec<Vec<u64>> {
    rows.iter()
        .map(|r| r.iter().map(|v| v.to_bits()).collect())
        .collect()
}

/// `cache`'s table under `key`, counting the builds in `builds`.
fn load(cache: &TableCache, key: &str, builds: &Cell<usize>) -> Vec<Vec<f64>> {
    cache
        .load_or_build("test", key, || {
            builds.set(builds.get() + 1);
            Ok::<_, String>(awkward_rows())
        })
        .unwrap()
}

#[test]
fn a_second_load_reads_the_file_bit_for_bit_without_building() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path().join("tables"));
    let builds = Cell::new(0);
    let first = load(&cache, "a=1", &builds);
    let second = load(&cache, "a=1", &builds);
    assert_eq!(builds.get(), 1);
    assert_eq!(bits(&first), bits(&awkward_rows()));
    assert_eq!(bits(&second), bits(&first));
    // Another key is another table.
    load(&cache, "a=2", &builds);
    assert_eq!(builds.get(), 2);
    // No temporary file is left beside the tables.
    for entry in fs::read_dir(dir.path().join("tables")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        assert!(name.ends_with(".table"), "{name}");
    }
}

#[test]
fn writers_of_one_table_at_once_leave_one_whole_file() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path());
    std::thread::scope(|scope| {
        for _ in 0..4 {
            scope.spawn(|| {
                let rows = load(&cache, "k", &Cell::new(0));
                assert_eq!(bits(&rows), bits(&awkward_rows()));
            });
        }
    });
    let builds = Cell::new(0);
    assert_eq!(bits(&load(&cache, "k", &builds)), bits(&awkward_rows()));
    assert_eq!(builds.get(), 0);
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn a_corrupt_cut_or_foreign_file_is_built_again_and_rewritten() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path());
    let builds = Cell::new(0);
    load(&cache, "k", &builds);
    let path = cache.path("test", "k").unwrap();
    let good = fs::read(&path).unwrap();
    let mut flipped = good.clone();
    *flipped.last_mut().unwrap() ^= 1;
    let cut = good[..good.len() - 3].to_vec();
    let mut foreign = good.clone();
    let at = good.windows(3).position(|w| w == b"t k").unwrap();
    foreign[at + 2] = b'j';
    let damaged = [
        flipped,
        cut,
        foreign,
        b"garbage".to_vec(),
        Vec::new(),
        vec![0xff; 40],
    ];
    for (i, bytes) in damaged.iter().enumerate() {
        fs::write(&path, bytes).unwrap();
        let rows = load(&cache, "k", &builds);
        assert_eq!(builds.get(), 2 + i, "damage {i} was not built again");
        assert_eq!(bits(&rows), bits(&awkward_rows()));
        assert_eq!(fs::read(&path).unwrap(), good, "damage {i} not rewritten");
    }
}

#[test]
fn an_unwritable_cache_or_none_still_gives_the_table() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    fs::write(&blocker, b"not a folder").unwrap();
    let builds = Cell::new(0);
    for cache in [TableCache::at(blocker.join("tables")), TableCache::off()] {
        assert_eq!(bits(&load(&cache, "k", &builds)), bits(&awkward_rows()));
        assert_eq!(bits(&load(&cache, "k", &builds)), bits(&awkward_rows()));
    }
    assert_eq!(builds.get(), 4);
    assert_eq!(TableCache::off().path("test", "k"), None);
    // A failed build is the caller's error, and nothing is written.
    let cache = TableCache::at(dir.path().join("t"));
    let failed = cache.load_or_build("test", "k", || Err::<Vec<Vec<f64>>, _>("no"));
    assert_eq!(failed, Err("no"));
    assert!(!cache.path("test", "k").unwrap().exists());
}

#[test]
fn the_rain_table_from_the_cache_is_the_table_built() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path());
    let rain = Particles::Rain {
        rain_rate_mm_h: 5.0,
    };
    let built = SpectralPhase::build(&rain, 3, 0.004675).unwrap();
    let cold = SpectralPhase::build_cached(&rain, 3, 0.004675, &cache).unwrap();
    let written = modified_times(dir.path());
    let warm = SpectralPhase::build_cached(&rain, 3, 0.004675, &cache).unwrap();
    // The warm load read the file: a rebuild would have written it again.
    assert_eq!(modified_times(dir.path()), written);
    // Builds are deterministic, and the cache gives back their bits.
    assert!(bits(&cold.phase) == bits(&built.phase));
    assert!(bits(&warm.phase) == bits(&built.phase));
    assert!(warm == built);
    // Every parameter is in the key: another rate, count or sun is another file.
    let other = Particles::Rain {
        rain_rate_mm_h: 5.5,
    };
    SpectralPhase::build_cached(&other, 3, 0.004675, &cache).unwrap();
    SpectralPhase::build_cached(&rain, 4, 0.004675, &cache).unwrap();
    SpectralPhase::build_cached(&rain, 3, 0.0, &cache).unwrap();
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 4);
    // Settings are checked before the cache is read.
    let e = SpectralPhase::build_cached(&rain, 2, 0.0, &cache).unwrap_err();
    assert!(e.to_string().contains("wavelength count"), "{e}");
}

#[test]
fn the_cloud_droplets_series_from_the_cache_are_those_built() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path());
    let built = droplet_orders(&[550.0]).unwrap();
    let cold = droplet_orders_cached(&[550.0], &cache).unwrap();
    let warm = droplet_orders_cached(&[550.0], &cache).unwrap();
    assert_eq!(cold, built);
    assert_eq!(warm, built);
    let e = droplet_orders_cached(&[1500.0], &cache).unwrap_err();
    assert!(e.to_string().contains("1500 nm"), "{e}");
}

/// Every file under `dir` with its modification time, sorted by path.
fn modified_times(dir: &std::path::Path) -> Vec<(std::path::PathBuf, std::time::SystemTime)> {
    let mut times = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else {
                let time = fs::metadata(&path).unwrap().modified().unwrap();
                times.push((path, time));
            }
        }
    }
    times.sort();
    assert!(!times.is_empty(), "no table file under {}", dir.display());
    times
}
