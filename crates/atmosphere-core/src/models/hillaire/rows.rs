//! The rows of a per-view table built in parallel on plain scoped threads, not rayon's
//! pool: a view's table is built inside a once-cell (`view_cache`), and a rayon task there
//! could, while waiting for its own tasks, steal another ray of the same view from the
//! caller's pool and re-enter the cell.

/// `f(row)` for rows 0..rows on plain scoped threads, one contiguous band of rows per
/// available core, concatenated in row order (the result does not depend on the thread
/// count).
pub fn rows_in_parallel<F>(rows: usize, f: F) -> Vec<f32>
where
    F: Fn(usize) -> Vec<f32> + Sync,
{
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, rows.max(1));
    let band = rows.div_ceil(threads);
    let f = &f;
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                scope.spawn(move || {
                    (t * band..((t + 1) * band).min(rows))
                        .flat_map(f)
                        .collect::<Vec<f32>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}
