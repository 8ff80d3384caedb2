//! Checks that two PNG files hold the same picture.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin same_png -- a.png b.png
//! ```
//!
//! Both files are decoded to RGB 8-bit. Exits 0 when they have the same
//! size and every pixel is equal; otherwise prints the sizes or how many
//! pixels differ (and the first few) and exits 1. Exits 2 when a file
//! cannot be read or decoded, or on a bad command line.

use std::process::ExitCode;

use zline_lab::cli::help_requested;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::SimulatorDisplay;

/// How many differing pixels to list.
const SHOWN: usize = 10;

fn load(path: &str) -> Result<SimulatorDisplay<Rgb888>, String> {
    SimulatorDisplay::<Rgb888>::load_png(path).map_err(|e| format!("{path}: {e}"))
}

const USAGE: &str = "usage: same_png A.png B.png
Whether two PNG frames are equal pixel for pixel; lists the first pixels that differ.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    let [a_path, b_path] = args.as_slice() else {
        eprintln!("usage: same_png A.png B.png");
        return ExitCode::from(2);
    };
    let (a, b) = match (load(a_path), load(b_path)) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("same_png: {e}");
            return ExitCode::from(2);
        }
    };
    let (sa, sb) = (a.size(), b.size());
    if sa != sb {
        println!(
            "different sizes: {a_path} is {}x{}, {b_path} is {}x{}",
            sa.width, sa.height, sb.width, sb.height
        );
        return ExitCode::FAILURE;
    }
    let differing: Vec<(Point, Rgb888, Rgb888)> = a
        .bounding_box()
        .points()
        .filter_map(|p| {
            let (ca, cb) = (a.get_pixel(p), b.get_pixel(p));
            (ca != cb).then_some((p, ca, cb))
        })
        .collect();
    if differing.is_empty() {
        println!("same: {}x{}, every pixel equal", sa.width, sa.height);
        return ExitCode::SUCCESS;
    }
    println!(
        "{} of {} pixels differ; the first {}:",
        differing.len(),
        sa.width * sa.height,
        differing.len().min(SHOWN)
    );
    let rgb = |c: Rgb888| format!("({}, {}, {})", c.r(), c.g(), c.b());
    for (p, ca, cb) in differing.iter().take(SHOWN) {
        println!("  ({}, {}): {} vs {}", p.x, p.y, rgb(*ca), rgb(*cb));
    }
    ExitCode::FAILURE
}
