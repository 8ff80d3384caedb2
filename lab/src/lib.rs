//! # zline-lab
//!
//! What zline is measured and checked against, and what its tools share.
//! Not published: a program that draws with zline never links it.
//!
//! | module | what it holds |
//! |---|---|
//! | [`methods`] | the hidden-surface methods zline is compared with, behind one input and output ([`methods::Method`], [`methods::MethodRenderer`]): the interval scanline, the painter's algorithm, the float64 ray-cast reference, the exact rational oracle for the core, the double-double clip reference, the accuracy comparison and the catalogue of adversarial scenes |
//! | [`fuzz_checks`] | the properties the fuzzers check, replayed by `cargo test` |
//! | [`shapes`] | procedural meshes (torus knot, icosphere, boxes, terrain) |
//! | [`rust_source`] | a mesh as Rust statics for flash |
//! | [`needs`] | the capacities a firmware needs for a mesh over the views it shows |
//! | [`textures`] | Rgb565 textures: read from PNG files (scaled for flash) or made procedurally, written as Rust statics |
//! | [`two_bands`] | one prepared painted scene drawn by two scanners in two bands, as a second core draws it |
//! | [`cli`] | the command-line helpers the tools share |
//! | [`machine`] | the machine a measurement ran on |

pub mod cli;
pub mod fuzz_checks;
pub mod machine;
pub mod methods;
pub mod needs;
pub mod rust_source;
pub mod shapes;
pub mod textures;
pub mod two_bands;

/// The book's code (`docs/`), compiled as doctests: every `rust` block of
/// these pages builds and runs with `cargo test -p zline-lab --doc`.
#[cfg(doctest)]
mod book {
    #[doc = include_str!("../../docs/guide/drawing.md")]
    struct Drawing;
    #[doc = include_str!("../../docs/guide/capacities.md")]
    struct Capacities;
    #[doc = include_str!("../../docs/guide/shading.md")]
    struct Shading;
}
