//! The results: CSV file, Markdown table, and the machine header.

use std::fmt::Write as _;
use std::path::Path;

use crate::Kind;

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
    /// `median_ms` over the median of the row it is measured against in
    /// the same configuration ([`crate::ratio_base`]: `zline z24`, or
    /// zline in place with the same depth for a `drawtarget` row).
    pub ratio: f64,
    /// Pixels whose face id differs from the float64 reference's, over
    /// the pixels the reference's object covers ([`Self::object_pixels`]);
    /// `None` when the renderer gives no face ids.
    pub wrong: Option<f64>,
    /// Pixels the float64 reference's object covers (its face ids that
    /// are not the background).
    pub object_pixels: usize,
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

/// Writes `rows` as CSV to `path`, creating its directory: medians and
/// minima to 0.0001 ms and ratios to 0.001, so that a frame of 0.007 ms
/// is told from one of 0.0074 (with three decimals, two such medians
/// read as a tie).
pub fn write_csv(path: &Path, rows: &[Row]) -> Result<(), String> {
    prepare_output(path)?;
    let mut text = String::from(CSV_HEADER);
    text.push('\n');
    for r in rows {
        let _ = writeln!(
            text,
            "{},{},{},{},{:.4},{:.4},{:.3}",
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

/// The wrong-face CSV's header, exactly. `wrong_fraction` is the share of
/// the object's pixels (those the float64 reference covers, counted in
/// `object_pixels`), not of the frame: wrong pixels are those whose face
/// differs from the reference's anywhere in the frame.
pub const WRONG_CSV_HEADER: &str = "mesh,size,cull,renderer,wrong_fraction,object_pixels";

/// Where the wrong-face rates go: next to the timing CSV `path`, named
/// `STEM_wrong_faces.csv` (`target/bench/peers_wrong_faces.csv` by default).
pub fn wrong_faces_path(path: &Path) -> std::path::PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "peers".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}_wrong_faces.csv"))
}

/// Writes the wrong-face rate of every row that has one (renderers that
/// give face ids) as CSV to `path`, as a share of the object's pixels.
pub fn write_wrong_csv(path: &Path, rows: &[Row]) -> Result<(), String> {
    prepare_output(path)?;
    let mut text = String::from(WRONG_CSV_HEADER);
    text.push('\n');
    for r in rows {
        if let Some(wrong) = r.wrong {
            let _ = writeln!(
                text,
                "{},{},{},{},{:.6},{}",
                csv_field(&r.mesh),
                r.size,
                r.cull,
                csv_field(&r.renderer),
                wrong,
                r.object_pixels
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

/// Each renderer's timed region, one line each.
pub fn timed_regions(regions: &[(String, String)]) -> String {
    let mut t = String::from("## Timed regions (one frame each)\n\n");
    for (name, region) in regions {
        let _ = writeln!(t, "- `{name}`: {region}");
    }
    t
}

/// The rows as a Markdown table, with the wrong-face column.
pub fn markdown(rows: &[Row]) -> String {
    let mut t = String::from(
        "| mesh | size | cull | renderer | median ms | min ms | ratio | wrong faces (% of object) |\n\
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

/// The run against the bar: for zline z24 and z16, how many flat
/// peer rows are at or below 1.00 (peer median over zline's) and the
/// lowest, and the largest cost of drawing through a plain `DrawTarget`
/// over drawing in place; then the same count for the Gouraud peer rows
/// against `zline gouraud z24` and the textured ones against `zline
/// textured z24`, when they ran.
pub fn checks(rows: &[Row]) -> String {
    let config = |r: &Row| (r.mesh.clone(), r.size.clone(), r.cull.clone());
    let median = |r: &Row, name: &str| {
        rows.iter()
            .find(|o| o.renderer == name && config(o) == config(r))
            .map(|o| o.median_ms)
    };
    let mut t = String::from("## Against the bar (this run)\n\n");
    for depth in ["z24", "z16"] {
        let zline = format!("zline {depth}");
        let ratios: Vec<(f64, &Row)> = rows
            .iter()
            .filter(|r| !r.renderer.starts_with("zline") && crate::kind(&r.renderer) == Kind::Flat)
            .filter_map(|r| median(r, &zline).map(|z| (r.median_ms / z, r)))
            .collect();
        let below = ratios.iter().filter(|(q, _)| *q <= 1.0).count();
        if let Some((q, r)) = ratios.iter().min_by(|a, b| a.0.total_cmp(&b.0)) {
            let _ = writeln!(
                t,
                "- peers against `{zline}`: {below} of {} peer rows at or below 1.00 (peer as \
                 fast as zline or faster); lowest: `{}` on {} {} {} at {q:.2}",
                ratios.len(),
                r.renderer,
                r.mesh,
                r.size,
                r.cull
            );
        }
        let gap = rows
            .iter()
            .filter(|r| r.renderer == format!("{zline} drawtarget"))
            .filter_map(|r| median(r, &zline).map(|z| (r.median_ms / z, r)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((q, r)) = gap {
            let _ = writeln!(
                t,
                "- `{zline} drawtarget` over `{zline}` in place: at most {q:.2} ({} {} {})",
                r.mesh, r.size, r.cull
            );
        }
    }
    for (kind, zline) in [
        (Kind::Gouraud, "zline gouraud z24"),
        (Kind::Textured, "zline textured z24"),
    ] {
        let ratios: Vec<(f64, &Row)> = rows
            .iter()
            .filter(|r| !r.renderer.starts_with("zline") && crate::kind(&r.renderer) == kind)
            .filter_map(|r| median(r, zline).map(|z| (r.median_ms / z, r)))
            .collect();
        let below = ratios.iter().filter(|(q, _)| *q <= 1.0).count();
        if let Some((q, r)) = ratios.iter().min_by(|a, b| a.0.total_cmp(&b.0)) {
            let _ = writeln!(
                t,
                "- peers against `{zline}`: {below} of {} peer rows at or below 1.00 (peer as \
                 fast as zline or faster); lowest: `{}` on {} {} {} at {q:.2}",
                ratios.len(),
                r.renderer,
                r.mesh,
                r.size,
                r.cull
            );
        }
    }
    t
}

/// The profile the binary was built with (from its build script), and
/// what it sets.
pub fn build() -> String {
    let profile = env!("ZLINE_BENCH_PROFILE");
    let opt = env!("ZLINE_BENCH_OPT_LEVEL");
    if profile == "peers" {
        format!(
            "profile `peers` of the root Cargo.toml (release with fat LTO and one codegen unit \
             for every crate), opt-level {opt}"
        )
    } else {
        format!(
            "profile `{profile}`, opt-level {opt}: not the peers profile (fat LTO, one codegen \
             unit); `cargo bench-peers` builds with it"
        )
    }
}

/// `model name` from `/proc/cpuinfo` and the number of logical CPUs.
pub fn machine() -> String {
    let (model, cpus) = zline_lab::machine::cpu();
    format!("{model}, {cpus} cores")
}
