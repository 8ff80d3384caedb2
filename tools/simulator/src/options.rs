//! The command line of the simulator window.

use std::path::PathBuf;

use zline::host::HostMesh;
use zline_lab::cli::parse_size;

/// The usage line, printed with `--help` and after a bad argument.
pub const USAGE: &str = "usage: simulator [MODEL.obj | shape:NAME] [--size WxH] [--scale N] [--yaw DEG] [--pitch DEG] [--texture FILE.png] [--no-overlay]";

/// The keys, printed with `--help`.
pub const KEYS: &str = "keys: arrows rotate (5 degrees), +/- zoom, space auto-spin, \
s shading, c culling, d depth format, m method, q/Esc quit";

/// The mesh when no MODEL is given.
pub const DEFAULT_MODEL: &str = "shape:torus-knot";

/// Parsed command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// An OBJ path, or `shape:NAME`.
    pub model: PathBuf,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
    /// Window pixels per frame pixel.
    pub scale: u32,
    /// Initial yaw in degrees.
    pub yaw: f32,
    /// Initial pitch in degrees.
    pub pitch: f32,
    /// The texture of the `texture` shading (a checker when `None`).
    pub texture: Option<PathBuf>,
    /// Whether to draw the text overlay.
    pub overlay: bool,
    /// `--help` was given.
    pub help: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            model: PathBuf::from(DEFAULT_MODEL),
            width: 320,
            height: 240,
            scale: 2,
            yaw: 30.0,
            pitch: 20.0,
            texture: None,
            overlay: true,
            help: false,
        }
    }
}

/// Parses the arguments after the program name.
pub fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options::default();
    let mut model = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--size" => (o.width, o.height) = parse_size(value()?)?,
            "--scale" => {
                o.scale = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=16).contains(n))
                    .ok_or("--scale: expected a whole number 1 to 16")?
            }
            "--yaw" => o.yaw = zline_lab::cli::parse_angle(arg, value()?)?,
            "--pitch" => o.pitch = zline_lab::cli::parse_angle(arg, value()?)?,
            "--texture" => o.texture = Some(PathBuf::from(value()?)),
            "--no-overlay" => o.overlay = false,
            "-h" | "--help" => o.help = true,
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s if model.is_none() => model = Some(PathBuf::from(s)),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    if let Some(model) = model {
        o.model = model;
    }
    Ok(o)
}

/// Loads an OBJ file, or a built-in mesh for `shape:NAME`, and checks that
/// the window's renderer can take it.
pub fn load_model(path: &std::path::Path) -> Result<HostMesh, String> {
    let mesh = zline_lab::cli::load_model(&path.to_string_lossy())?;
    if mesh.positions.len() > crate::frame::MAX_MESH_VERTICES {
        return Err(format!(
            "{}: {} vertices, the window takes at most {}",
            path.display(),
            mesh.positions.len(),
            crate::frame::MAX_MESH_VERTICES
        ));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn defaults() {
        let o = parse_args(&[]).unwrap();
        assert_eq!(o, Options::default());
        assert_eq!(o.model, PathBuf::from("shape:torus-knot"));
    }

    #[test]
    fn options() {
        let o = parse_args(&args(
            "m.obj --size 160x120 --scale 1 --yaw -45 --pitch 10 --no-overlay",
        ))
        .unwrap();
        assert_eq!(o.model, PathBuf::from("m.obj"));
        assert_eq!((o.width, o.height, o.scale), (160, 120, 1));
        assert_eq!((o.yaw, o.pitch, o.overlay), (-45.0, 10.0, false));
    }

    #[test]
    fn refusals() {
        for bad in [
            "--size 0x10",
            "--size 10",
            "--scale 0",
            "--yaw x",
            "--frobnicate",
            "a.obj b.obj",
            "--scale",
        ] {
            assert!(parse_args(&args(bad)).is_err(), "{bad}");
        }
        assert!(load_model(std::path::Path::new("shape:nope")).is_err());
        assert!(load_model(std::path::Path::new("/nonexistent/x.obj")).is_err());
    }
}
