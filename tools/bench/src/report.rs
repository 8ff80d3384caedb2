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
    let (model, cpus) = zline_lab::machine::cpu();
    format!("{model}, {cpus} cores")
}
