//! Per-thread CPU time, and the statistics the report shows.

/// CPU time this thread has used, in milliseconds
/// (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`): time spent by other
/// processes on a shared machine does not count.
pub fn thread_cpu_ms() -> Result<f64, String> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return Err(format!(
            "clock_gettime(CLOCK_THREAD_CPUTIME_ID): {}",
            std::io::Error::last_os_error()
        ));
    }
    Ok(ts.tv_sec as f64 * 1e3 + ts.tv_nsec as f64 * 1e-6)
}

/// Runs `f` once and returns its thread CPU time in milliseconds.
pub fn time_ms(f: impl FnOnce() -> Result<(), String>) -> Result<f64, String> {
    let start = thread_cpu_ms()?;
    f()?;
    Ok(thread_cpu_ms()? - start)
}

/// Runs `f` once and returns the wall-clock time it took in milliseconds
/// (for work spread over several threads).
pub fn wall_ms(f: impl FnOnce() -> Result<(), String>) -> Result<f64, String> {
    let start = std::time::Instant::now();
    f()?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

/// Median (mean of the middle two for an even count) and minimum; NaN
/// for no samples.
pub fn median_min(samples: &[f64]) -> (f64, f64) {
    let mut v = samples.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let median = match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => v[n / 2],
        _ => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    };
    (median, v.first().copied().unwrap_or(f64::NAN))
}
