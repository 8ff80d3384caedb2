//! `zline-simulator`: a desktop window (embedded-graphics-simulator with
//! SDL2) showing a mesh drawn by zline, row by row through
//! `zline::DrawTargetSink`.
//!
//! Start it from the repository root (a workspace member of its own, so
//! the root crate never needs SDL2 and the window builds only what it
//! needs):
//!
//! ```sh
//! cargo run --release -p zline-simulator [-- MODEL] [options]
//! ```
//!
//! `MODEL` is an OBJ file or `shape:NAME` for a built-in mesh (`torus-knot`,
//! the default, `icosphere`, `boxes`, `terrain`).
//!
//! Options (defaults in brackets):
//! * `--size WxH` [320x240]: the frame in display pixels
//! * `--scale N` [2]: window pixels per display pixel
//! * `--yaw DEG` [30] and `--pitch DEG` [20]
//! * `--no-overlay`: no text on top of the frame
//!
//! Keys: arrows rotate (left/right yaw, up/down pitch, 5° steps), `+`/`-`
//! zoom (×1.1 per step), space toggles auto-spin (on at start), `s` cycles
//! shading (lambert, flat, depth, id, gouraud, texture: the last two the scanline core only; `--texture FILE.png` gives the texture, else a checker), `c` toggles back-face culling, `d`
//! cycles the depth format (z16, z24), `m` cycles the method (scanline,
//! zbuffer, bands:8, interval, painter, the float64 reference), `q` or Esc
//! quits.
//!
//! The overlay shows the method and depth format, the frame time (around
//! `draw_mesh` and `render`), the polygons drawn, the RAM a renderer sized
//! for this scene needs (as `render --stats` reports `ram_bytes`), the
//! shading, the culling and the view.
//!
//! `EG_SIMULATOR_DUMP=frame.png` saves the first frame (scaled by
//! `--scale`, overlay included) and exits without opening a window;
//! `EG_SIMULATOR_DUMP_RAW` saves it unscaled. With `--scale 1 --no-overlay`
//! and the default view, the dump equals `render -- MODEL --out x.png`
//! pixel for pixel.

mod frame;
mod options;
mod overlay;

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use zline::Cull;

use frame::{Method, Renderers, SHADINGS, View};
use options::{KEYS, Options, USAGE};

/// Degrees per arrow key press.
const STEP_DEG: f32 = 5.0;
/// Degrees of yaw per frame while spinning.
const SPIN_DEG: f32 = 1.0;
/// Zoom steps allowed either way.
const MAX_ZOOM: i32 = 30;

/// Why the program stops early.
enum Failure {
    /// Bad command line: the message and the usage.
    Usage(String),
    /// Anything else: the message.
    Other(String),
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            eprintln!("simulator: {message}");
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
        Err(Failure::Other(message)) => {
            eprintln!("simulator: {message}");
            ExitCode::from(2)
        }
    }
}

fn run(args: &[String]) -> Result<(), Failure> {
    let o = options::parse_args(args).map_err(Failure::Usage)?;
    if o.help {
        println!("{USAGE}\n{KEYS}");
        return Ok(());
    }
    let mesh = options::load_model(&o.model).map_err(Failure::Other)?;
    let (w, h) = (o.width, o.height);
    // The renderers' storage is in `Vec`s, sized once for any mesh.
    let mut renderers = Renderers::new(w, h).map_err(Failure::Other)?;
    // The painted shadings draw the mesh read with its normals and
    // texture coordinates.
    let smooth = zline_lab::cli::load_model_smooth(&o.model.to_string_lossy());
    renderers.set_smooth(&mesh, smooth.map_err(Failure::Other)?);
    if let Some(path) = &o.texture {
        // The texture lives as long as the window.
        let png = zline_lab::textures::Rgb565Texture::read(path, 1).map_err(Failure::Other)?;
        let png: &'static _ = Box::leak(Box::new(png));
        renderers.set_texture(png.texture().map_err(Failure::Other)?);
    }
    show(&o, &mesh, renderers).map_err(Failure::Other)
}

/// The window loop: draw a whole frame (and the overlay), show it, handle
/// the keys.
fn show(o: &Options, mesh: &zline::host::HostMesh, mut renderers: Renderers) -> Result<(), String> {
    let mut display =
        SimulatorDisplay::<Rgb888>::new(Size::new(u32::from(o.width), u32::from(o.height)));
    let settings = OutputSettingsBuilder::new().scale(o.scale).build();
    let mut window = Window::new("zline", &settings);
    let mut view = View {
        yaw: o.yaw,
        pitch: o.pitch,
        ..View::default()
    };
    // The mesh spins from the start; space stops it.
    let mut spin = true;
    // Smoothed scanline frame time, restarted when the renderer changes.
    let mut smoothed_ms: Option<f64> = None;
    loop {
        // The whole frame, overlay included, is drawn before `update`:
        // with EG_SIMULATOR_DUMP set, the first `update` saves it and exits.
        let mut report = renderers.draw(mesh, &view, &mut display)?;
        if view.method == Method::Scanline {
            let ms = smoothed_ms.map_or(report.ms, |s| 0.9 * s + 0.1 * report.ms);
            smoothed_ms = Some(ms);
            report.ms = ms;
        }
        if o.overlay {
            overlay::draw(&mut display, &view, &report);
        }
        window.update(&display);

        for event in window.events() {
            let keycode = match event {
                SimulatorEvent::Quit => return Ok(()),
                SimulatorEvent::KeyDown { keycode, .. } => keycode,
                _ => continue,
            };
            let before = (view.method, view.depth);
            if handle_key(keycode, &mut view, &mut spin) == Flow::Quit {
                return Ok(());
            }
            if (view.method, view.depth) != before {
                smoothed_ms = None;
            }
        }
        if spin {
            view.yaw = (view.yaw + SPIN_DEG).rem_euclid(360.0);
        }
    }
}

/// Whether the window stays open after a key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flow {
    Continue,
    Quit,
}

/// Applies one key press to the view and the spin flag.
fn handle_key(keycode: Keycode, view: &mut View, spin: &mut bool) -> Flow {
    match keycode {
        Keycode::ESCAPE | Keycode::Q => return Flow::Quit,
        Keycode::LEFT => view.yaw = (view.yaw - STEP_DEG).rem_euclid(360.0),
        Keycode::RIGHT => view.yaw = (view.yaw + STEP_DEG).rem_euclid(360.0),
        Keycode::UP => view.pitch = (view.pitch + STEP_DEG).rem_euclid(360.0),
        Keycode::DOWN => view.pitch = (view.pitch - STEP_DEG).rem_euclid(360.0),
        Keycode::PLUS | Keycode::EQUALS | Keycode::KP_PLUS => {
            view.zoom = (view.zoom + 1).min(MAX_ZOOM)
        }
        Keycode::MINUS | Keycode::KP_MINUS => view.zoom = (view.zoom - 1).max(-MAX_ZOOM),
        Keycode::SPACE => *spin = !*spin,
        Keycode::S => view.shading = (view.shading + 1) % SHADINGS.len(),
        Keycode::C => {
            view.cull = match view.cull {
                Cull::None => Cull::Back,
                Cull::Back => Cull::None,
            }
        }
        Keycode::D => view.depth = view.depth.next(),
        Keycode::M => view.method = view.method.next(),
        _ => {}
    }
    Flow::Continue
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::DepthChoice;

    #[test]
    fn keys() {
        let mut view = View::default();
        let mut spin = false;
        let mut press = |k| handle_key(k, &mut view, &mut spin);
        for k in [
            Keycode::LEFT,
            Keycode::LEFT,
            Keycode::RIGHT,
            Keycode::UP,
            Keycode::EQUALS,
            Keycode::PLUS,
            Keycode::MINUS,
            Keycode::SPACE,
            Keycode::S,
            Keycode::S,
            Keycode::C,
            Keycode::D,
            Keycode::M,
            Keycode::A,
        ] {
            assert_eq!(press(k), Flow::Continue);
        }
        assert_eq!(press(Keycode::Q), Flow::Quit);
        assert_eq!(press(Keycode::ESCAPE), Flow::Quit);
        assert_eq!((view.yaw, view.pitch, view.zoom), (25.0, 25.0, 1));
        assert_eq!(view.shading, 2);
        assert_eq!(view.cull, Cull::Back);
        assert_eq!(view.depth, DepthChoice::Z16);
        assert_eq!(view.method, Method::ZBuffer);
        assert!(spin);
        for _ in 0..8 {
            handle_key(Keycode::LEFT, &mut view, &mut spin);
        }
        assert_eq!(view.yaw, 345.0);
        for _ in 0..100 {
            handle_key(Keycode::KP_PLUS, &mut view, &mut spin);
        }
        assert_eq!(view.zoom, MAX_ZOOM);
    }
}
