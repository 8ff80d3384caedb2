//! The command line.

use std::path::PathBuf;

use crate::view::{Cull, DEFAULT_PITCH_DEG, DEFAULT_YAW_DEG};

/// Usage text.
pub const USAGE: &str = "\
usage: zline-bench [--sizes WxH,...] [--cull none,back] [--rounds N] [--quick]
                   [--out FILE.csv] [--yaw DEG] [--pitch DEG] [--dump DIR]
                   [--threads N] [--shading flat|gouraud|textured|all]
                   MESH.obj|MESH_DIR...

Times zline (z24 and z16, rows in place and through a plain DrawTarget),
embedded-3dgfx 0.7 (its frame driver lit and unlit, and its rasteriser fed
once-transformed shared vertices) and euc 0.5 drawing the same reference view
of each mesh (a directory means every .obj in it, sorted) with flat Lambert
shading computed inside every timed frame, in interleaved rounds, by
per-thread CPU time, and compares each frame's face ids with zline's float64
reference (wrong pixels as a share of the object's pixels). Ratio: a row's
median over zline z24's (a drawtarget row: over zline in place, same depth).
Build it with `cargo bench-peers` (profile peers: fat LTO, one codegen unit).

  --sizes LIST   frame sizes [240x240,320x240,800x600]
  --cull LIST    none, back or both [none,back]
  --rounds N     timed rounds, after a second of untimed warm-up frames [15]
  --quick        240x240 only, 3 rounds, at most the 3 smallest mesh files
                 (overrides --sizes and --rounds)
  --out FILE     CSV output [target/bench/peers.csv]
  --yaw DEG      rotation about +Y [30]
  --pitch DEG    rotation about +X after yaw [20]
  --dump DIR     also write every renderer's last frame, and the reference's,
                 as PNG images
  --threads N    also time zline drawing in N bands on N threads, by the wall
                 clock (`zline z24 N threads`; its frame must equal
                 zline z24's); 1 leaves it out [2]
  --shading LIST which rows: flat (the rows above), gouraud (per-vertex
                 Lambert interpolated: zline gouraud z24, embedded-3dgfx
                 gouraud, euc gouraud; ratio over zline gouraud z24),
                 textured (meshes with NAME_texture.png beside NAME.obj:
                 zline textured z24, embedded-3dgfx textured, euc textured;
                 ratio over zline textured z24), or all; the smooth rows
                 read the mesh with HostMesh::from_obj_smooth [flat]";

/// Most rounds `--rounds` accepts.
pub const MAX_ROUNDS: usize = 100_000;

/// Most threads `--threads` accepts.
pub const MAX_THREADS: usize = 64;

/// Parsed options.
#[derive(Debug, Clone)]
pub struct Options {
    /// Frame sizes.
    pub sizes: Vec<(u16, u16)>,
    /// Cull settings.
    pub culls: Vec<Cull>,
    /// Timed rounds.
    pub rounds: usize,
    /// CI mode: one small size, few rounds, few meshes.
    pub quick: bool,
    /// CSV path.
    pub out: PathBuf,
    /// Yaw, degrees.
    pub yaw: f32,
    /// Pitch, degrees.
    pub pitch: f32,
    /// Where to write PNG images of the frames, if anywhere.
    pub dump: Option<PathBuf>,
    /// Threads (bands) for the banded zline renderer; 1 leaves it out.
    pub threads: usize,
    /// Which rows: flat, Gouraud, textured.
    pub shading: ShadingRows,
    /// Mesh files and directories as given.
    pub inputs: Vec<PathBuf>,
    /// `-h` or `--help` was given.
    pub help: bool,
}

/// Which kinds of rows `--shading` asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShadingRows {
    /// The flat Lambert rows (today's).
    pub flat: bool,
    /// The Gouraud rows.
    pub gouraud: bool,
    /// The textured rows (meshes with a texture only).
    pub textured: bool,
}

impl ShadingRows {
    /// Whether any row needs the smooth mesh.
    pub fn smooth(&self) -> bool {
        self.gouraud || self.textured
    }
}

fn parse_shading(s: &str) -> Result<ShadingRows, String> {
    let mut rows = ShadingRows {
        flat: false,
        gouraud: false,
        textured: false,
    };
    for part in s.split(',').filter(|p| !p.is_empty()) {
        match part {
            "flat" => rows.flat = true,
            "gouraud" => rows.gouraud = true,
            "textured" => rows.textured = true,
            "all" => {
                rows = ShadingRows {
                    flat: true,
                    gouraud: true,
                    textured: true,
                }
            }
            _ => {
                return Err(format!(
                    "--shading: unknown '{part}' (flat, gouraud, textured, all)"
                ));
            }
        }
    }
    if !(rows.flat || rows.smooth()) {
        return Err(format!("--shading: empty list '{s}'"));
    }
    Ok(rows)
}

/// Parses the arguments after the program name.
pub fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        sizes: vec![(240, 240), (320, 240), (800, 600)],
        culls: vec![Cull::None, Cull::Back],
        rounds: 15,
        quick: false,
        out: PathBuf::from("target/bench/peers.csv"),
        yaw: DEFAULT_YAW_DEG,
        pitch: DEFAULT_PITCH_DEG,
        dump: None,
        threads: 2,
        shading: ShadingRows {
            flat: true,
            gouraud: false,
            textured: false,
        },
        inputs: Vec::new(),
        help: false,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--sizes" => o.sizes = list(value()?, parse_size)?,
            "--cull" => o.culls = list(value()?, Cull::parse)?,
            "--rounds" => {
                o.rounds = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=MAX_ROUNDS).contains(n))
                    .ok_or_else(|| format!("--rounds: expected 1 to {MAX_ROUNDS}"))?
            }
            "--quick" => o.quick = true,
            "--out" => o.out = PathBuf::from(value()?),
            "--yaw" => o.yaw = parse_angle("--yaw", value()?)?,
            "--pitch" => o.pitch = parse_angle("--pitch", value()?)?,
            "--dump" => o.dump = Some(PathBuf::from(value()?)),
            "--threads" => {
                o.threads = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=MAX_THREADS).contains(n))
                    .ok_or_else(|| format!("--threads: expected 1 to {MAX_THREADS}"))?
            }
            "--shading" => o.shading = parse_shading(value()?)?,
            "-h" | "--help" => o.help = true,
            s if s.starts_with('-') && s.len() > 1 => return Err(format!("unknown option {s}")),
            s => o.inputs.push(PathBuf::from(s)),
        }
    }
    if o.quick {
        o.sizes = vec![(240, 240)];
        o.rounds = 3;
    }
    if o.inputs.is_empty() && !o.help {
        return Err("no mesh given".into());
    }
    Ok(o)
}

fn list<T>(s: &str, item: impl Fn(&str) -> Result<T, String>) -> Result<Vec<T>, String> {
    let items: Vec<T> = s
        .split(',')
        .filter(|p| !p.is_empty())
        .map(item)
        .collect::<Result<_, _>>()?;
    if items.is_empty() {
        return Err(format!("empty list '{s}'"));
    }
    Ok(items)
}

/// `WxH`, each side 1 to 4096.
fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let bad = || format!("--sizes: expected WxH with each side 1 to 4096, got '{s}'");
    let (w, h) = s.split_once('x').ok_or_else(bad)?;
    let side = |v: &str| v.parse::<u16>().ok().filter(|n| (1..=4096).contains(n));
    Ok((side(w).ok_or_else(bad)?, side(h).ok_or_else(bad)?))
}

fn parse_angle(name: &str, s: &str) -> Result<f32, String> {
    s.parse::<f32>()
        .ok()
        .filter(|a| a.is_finite())
        .ok_or_else(|| format!("{name}: expected degrees, got '{s}'"))
}
