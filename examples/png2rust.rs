//! Converts a PNG into Rust source for a texture in flash, the Rgb565
//! texels a [`Texture`](zline::paint::Texture) samples:
//!
//! ```sh
//! cargo run --example png2rust -- [--shrink N] TEXTURE.png NAME > name.rs
//! ```
//!
//! `name.rs` defines `pub static NAME: [u16; W·H]` (raw Rgb565, row by row
//! from the top, converted as embedded-graphics converts `Rgb888`) and
//! `NAME_WIDTH`, `NAME_HEIGHT`; in firmware,
//! `Texture::new(&NAME, NAME_WIDTH, NAME_HEIGHT)` is `const`. With
//! `--shrink N` each texel is the mean of an N x N square of pixels (the
//! size must divide by N): Spot's 1024x1024 texture is 2 MB of Rgb565,
//! `--shrink 4` makes it 128 KB. Sizes up to 4096 a side. Errors
//! (unreadable or undecodable file, a size that does not divide or is out
//! of range) go to stderr with a non-zero exit code.

use std::io::Write as _;
use std::process::ExitCode;

use zline_lab::cli::{help_requested, run_tool};
use zline_lab::textures::Rgb565Texture;

fn run(args: &[String]) -> Result<(), String> {
    let (shrink, rest) = match args {
        [flag, n, rest @ ..] if flag == "--shrink" => {
            let n = n
                .parse::<u32>()
                .ok()
                .filter(|&n| (1..=4096).contains(&n))
                .ok_or_else(|| {
                    format!("--shrink: expected a whole number from 1 to 4096, got '{n}'")
                })?;
            (n, rest)
        }
        _ => (1, args),
    };
    let [path, name] = rest else {
        return Err(USAGE.lines().next().unwrap_or_default().into());
    };
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!(
            "NAME must be a Rust identifier of A-Z, 0-9 and _, not '{name}'"
        ));
    }
    let texture = Rgb565Texture::read(std::path::Path::new(path), shrink)?;
    let origin = std::path::Path::new(path)
        .file_name()
        .map_or(path.clone(), |f| f.to_string_lossy().into_owned());
    let text = texture.rust_source(name, &format!("`{origin}`"));
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| format!("cannot write the output: {e}"))
}

const USAGE: &str = "usage: png2rust [--shrink N] TEXTURE.png NAME > name.rs
Writes Rust source for TEXTURE.png as Rgb565 texels in a static named NAME (with NAME_WIDTH and
NAME_HEIGHT), each texel the mean of an N x N square of pixels with --shrink N.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    // No usage after an error: the message says what was wrong (a wrong
    // number of arguments gets the usage line as its message).
    run_tool("png2rust", "", move || run(&args))
}
