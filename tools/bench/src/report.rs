//! The results: CSV file, Markdown table, and the machine header.

use std::fmt::Write as _;
use std::path::Path;

/// The CSV header, exactly.
pub const CSV_HEADER: &str = "mesh,size,cull,renderer,median_ms,min_ms,ratio";

/// One renderer's result for one mesh, size and cull.
#[derive(Debug, Clone)]
pub struct Row {
    /// Mesh name.
    pub mesh: String,
    /// `WxH`.
    pub size: String,
    /// `none` or `back`.
    pub cull: String,
    /// Renderer name.
    pub renderer: String,
    /// Median frame time, ms of thread CPU time.
    pub median_ms: f64,
    /// Fastest frame, ms of thread CPU time.
    pub min_ms: f64,
    /// `median_ms` over zline's median in the same configuration.
    pub ratio: f64,
    /// Fraction of pixels whose face id differs from the float64
    /// reference's; `None` when the renderer gives no face ids.
    pub wrong: Option<f64>,
}

/// Creates the directory of the CSV file `path`, so that a path that
/// cannot be written fails before the benchmark runs.
pub fn prepare_output(path: &Path) -> Result<(), String> {
    if path.is_dir() {
        return Err(format!("{}: is a directory", path.display()));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    Ok(())
}

/// Writes `rows` as CSV to `path`, creating its directory.
pub fn write_csv(path: &Path, rows: &[Row]) -> Result<(), String> {
    prepare_output(path)?;
    let mut text = String::from(CSV_HEADER);
    text.push('\n');
    for r in rows {
        let _ = writeln!(
            text,
            "{},{},{},{},{:.3},{:.3},{:.2}",
            csv_field(&r.mesh),
            r.size,
            r.cull,
            csv_field(&r.renderer),
            r.median_ms,
            r.min_ms,
            r.ratio
        );
    }
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The wrong-face CSV's header, exactly.
pub const WRONG_CSV_HEADER: &str = "mesh,size,cull,renderer,wrong_fraction";

/// Where the wrong-face rates go: next to the timing CSV `path`, named
/// `STEM_wrong_faces.csv` (`target/bench/peers_wrong_faces.csv` by default).
pub fn wrong_faces_path(path: &Path) -> std::path::PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "peers".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}_wrong_faces.csv"))
}

/// Writes the wrong-face rate of every row that has one (renderers that
/// colour by face id) as CSV to `path`: the sweep's accuracy chart reads it.
pub fn write_wrong_csv(path: &Path, rows: &[Row]) -> Result<(), String> {
    prepare_output(path)?;
    let mut text = String::from(WRONG_CSV_HEADER);
    text.push('\n');
    for r in rows {
        if let Some(wrong) = r.wrong {
            let _ = writeln!(
                text,
                "{},{},{},{},{:.6}",
                csv_field(&r.mesh),
                r.size,
                r.cull,
                csv_field(&r.renderer),
                wrong
            );
        }
    }
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The rows as a Markdown table, with the wrong-face column.
pub fn markdown(rows: &[Row]) -> String {
    let mut t = String::from(
        "| mesh | size | cull | renderer | median ms | min ms | ratio | wrong faces |\n\
         |---|---|---|---|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let wrong = r
            .wrong
            .map_or_else(|| "n/a".to_string(), |w| format!("{:.3} %", w * 100.0));
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.2} | {} |",
            r.mesh, r.size, r.cull, r.renderer, r.median_ms, r.min_ms, r.ratio, wrong
        );
    }
    t
}

/// `model name` from `/proc/cpuinfo` and the number of logical CPUs.
pub fn machine() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info
        .lines()
        .find_map(|l| {
            let (k, v) = l.split_once(':')?;
            (k.trim() == "model name").then(|| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cpus = info
        .lines()
        .filter(|l| l.split(':').next().is_some_and(|k| k.trim() == "processor"))
        .count();
    let cpus = if cpus > 0 {
        cpus
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    };
    format!("{model}, {cpus} cores")
}

/// The current UTC date and time, `YYYY-MM-DD HH:MM UTC`.
pub fn now_utc() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}
