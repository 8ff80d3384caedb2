//! The adversarial catalogue (`zline_lab::methods::catalogue`): every case by
//! every method against the float64 reference, as a Markdown table (the one in
//! `docs/results/catalogue.md`), and the gallery: each case's frame by the scanline core (and
//! by the painter where it breaks) as PNG.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin catalogue [-- --gallery docs/catalogue]
//! ```
//!
//! A cell is `correct` (no hard mismatch; pixels excused at edges or as
//! depth ties counted in brackets), **wrong: N px** (hard mismatches), or
//! the error the method reported. It exits non-zero when any method does
//! other than the case expects.

use std::path::PathBuf;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use zline_lab::cli::{help_requested, run_tool};
use zline_lab::methods::catalogue::{self, Expect, METHODS, label};
use zline_lab::methods::{Method, MethodFrame};

fn save(frame: &MethodFrame, path: &PathBuf) -> Result<(), String> {
    let (w, h) = catalogue::SIZE;
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(u32::from(w), u32::from(h)));
    let pixels = frame.colors.iter().enumerate().map(|(k, &c)| {
        Pixel(
            Point::new((k % usize::from(w)) as i32, (k / usize::from(w)) as i32),
            c,
        )
    });
    display.draw_iter(pixels).map_err(|e| format!("{e:?}"))?;
    display
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn run(args: &[String]) -> Result<bool, String> {
    let gallery = match args {
        [] => None,
        [flag, dir] if flag == "--gallery" => Some(PathBuf::from(dir)),
        _ => return Err("usage: catalogue [--gallery DIR]".into()),
    };
    if let Some(dir) = &gallery {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let (w, h) = catalogue::SIZE;
    println!("{w}x{h}, no culling, Lambert; against the float64 reference with the same camera\n");
    print!("| case | what |");
    for (m, z24) in METHODS {
        print!(" {} |", label(m, z24));
    }
    println!();
    println!("|---|---|{}", "---|".repeat(METHODS.len()));
    let mut as_expected = true;
    for case in catalogue::cases() {
        print!("| `{}` | {} |", case.name, case.what);
        for (method, z24) in METHODS {
            let (outcome, frame) = catalogue::run(&case, method, z24);
            let expected = case.expect(method);
            let ok = outcome.kind() == expected;
            as_expected &= ok;
            print!(
                " {}{} |",
                outcome.cell(),
                if ok { "" } else { " (UNEXPECTED)" }
            );
            let keep = (method == Method::Scanline && !z24)
                || (expected == Expect::Wrong && method == Method::Painter);
            if let (Some(dir), Some(frame), true) = (&gallery, &frame, keep) {
                save(
                    frame,
                    &dir.join(format!("{}-{}.png", case.name, method.name())),
                )?;
            }
        }
        println!();
    }
    println!(
        "\n| coplanar over 21 frames of a turning camera | planes | frames where a later face wins a pixel of face 0 | most pixels lost in a frame | share of face 0 |\n|---|---|---|---|---|"
    );
    let own_planes = [
        (Method::Scanline, false),
        (Method::Scanline, true),
        (Method::Interval, true),
    ];
    let runs = METHODS
        .into_iter()
        .filter(|&(method, _)| method != Method::Reference)
        .map(|run| (run, true))
        .chain(own_planes.into_iter().map(|run| (run, false)));
    for ((method, z24), shared) in runs {
        let losses = catalogue::coplanar_losses(method, z24, shared)?;
        let frames = losses.iter().filter(|&&(lost, _)| lost > 0).count();
        let (lost, own) = losses
            .iter()
            .copied()
            .max_by(|a, b| (a.0 * b.1).cmp(&(b.0 * a.1)))
            .unwrap_or((0, 1));
        println!(
            "| {} | {} | {frames} of {} | {lost} | {:.2} % |",
            label(method, z24),
            if shared { "shared" } else { "each face's own" },
            losses.len(),
            100.0 * lost as f64 / own as f64
        );
    }
    println!("\n| capacity exceeded | what the method says |\n|---|---|");
    for (what, said) in catalogue::capacity_errors() {
        as_expected &= said.starts_with("error: ");
        println!("| {what} | {said} |");
    }
    Ok(as_expected)
}

const USAGE: &str = "usage: catalogue [--gallery DIR]
Every method on every case of the adversarial catalogue against the float64 reference, as a
Markdown table; exits non-zero when a method does other than the case expects. --gallery writes
each case's frames as PNG into DIR.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("catalogue", USAGE, move || match run(&args)? {
        true => Ok(()),
        false => Err("a method did other than the catalogue expects".into()),
    })
}
