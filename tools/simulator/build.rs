//! Stops the build at once, with the command that installs it, when the
//! linker cannot find SDL2's development library. Without this check the
//! build compiles every dependency first and then fails at the link, minutes
//! later, with a long linker error.
//!
//! The check runs on Linux, where the C compiler can say where it would
//! find `libSDL2.so`; elsewhere, or with `ZLINE_SKIP_SDL2_CHECK` set, the
//! link itself is the check.

use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=ZLINE_SKIP_SDL2_CHECK");
    println!("cargo:rerun-if-env-changed=CC");
    if std::env::var_os("ZLINE_SKIP_SDL2_CHECK").is_some()
        || std::env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("linux")
    {
        return ExitCode::SUCCESS;
    }
    let cc = std::env::var("CC").unwrap_or_else(|_| String::from("cc"));
    // With no C compiler to ask, leave it to the link.
    let Ok(output) = Command::new(&cc)
        .arg("-print-file-name=libSDL2.so")
        .output()
    else {
        return ExitCode::SUCCESS;
    };
    // The compiler prints a path when it finds the file, the bare name
    // when it does not.
    if !output.status.success() || String::from_utf8_lossy(&output.stdout).contains('/') {
        return ExitCode::SUCCESS;
    }
    eprintln!(
        "zline-simulator needs SDL2's development library (libSDL2.so), which the linker cannot find.\n\
         Install it, then run the same command again:\n\
         \n    sudo apt-get install libsdl2-dev      # Debian, Ubuntu\n\
         \n(Fedora: sudo dnf install SDL2-devel; Arch: sudo pacman -S sdl2.) \
         Set ZLINE_SKIP_SDL2_CHECK=1 to skip this check."
    );
    ExitCode::FAILURE
}
