//! Prints `core::mem::size_of` of the renderer for typical configurations,
//! split into the scene-sized tables and the row-sized scanner, and the
//! size of each item, as the Markdown tables in `docs/results/memory.md`:
//!
//! ```sh
//! cargo run --example renderer_memory
//! ```

use core::mem::size_of;
use embedded_graphics::pixelcolor::Rgb565;
use zline::TableArrays;
use zline::{ActiveEdge, ActivePolygon, EdgeEntry, PolygonEntry, ScanArrays, SmallActive};
use zline::{Depth16, Depth24, Renderer, ScreenVertex};

/// 240x240, a 1,000-triangle mesh (about 500 vertices), generous active
/// tables (triangles keep their edge pairs inline: the edge pool only
/// serves concave polygons).
type SmallTables = TableArrays<Rgb565, 600, 1000, 3000>;
type SmallScan<D> = ScanArrays<Rgb565, D, 240, 256, 32>;
type Small<D> = Renderer<SmallTables, SmallScan<D>>;
/// 320x240, a 5,000-triangle mesh.
type LargeTables = TableArrays<Rgb565, 2600, 5000, 15000>;
type LargeScan<D> = ScanArrays<Rgb565, D, 320, 512, 32>;
type Large<D> = Renderer<LargeTables, LargeScan<D>>;

fn row(name: &str, w: usize, h: usize, z16: usize, z24: usize) {
    let full = w * h * 2 * 2;
    println!(
        "| {name} | {z16} B ({:.1} KiB) | {z24} B ({:.1} KiB) | {full} B ({:.1} KiB) |",
        z16 as f64 / 1024.0,
        z24 as f64 / 1024.0,
        full as f64 / 1024.0
    );
}

fn main() {
    println!(
        "| configuration (Rgb565) | `Renderer` with z16 | `Renderer` with z24 | full-frame z16 + Rgb565 framebuffer |"
    );
    println!("|---|---|---|---|");
    row(
        "240x240, V=600 P=1000 E=3000 AP=256 AE=32",
        240,
        240,
        size_of::<Small<Depth16>>(),
        size_of::<Small<Depth24>>(),
    );
    row(
        "320x240, V=2600 P=5000 E=15000 AP=512 AE=32",
        320,
        240,
        size_of::<Large<Depth16>>(),
        size_of::<Large<Depth24>>(),
    );
    println!();
    println!("| configuration (Rgb565) | tables | scanner with z16 | scanner with z24 |");
    println!("|---|---|---|---|");
    println!(
        "| 240x240, V=600 P=1000 E=3000 AP=256 AE=32 | {} B | {} B | {} B |",
        size_of::<SmallTables>(),
        size_of::<SmallScan<Depth16>>(),
        size_of::<SmallScan<Depth24>>()
    );
    println!(
        "| 320x240, V=2600 P=5000 E=15000 AP=512 AE=32 | {} B | {} B | {} B |",
        size_of::<LargeTables>(),
        size_of::<LargeScan<Depth16>>(),
        size_of::<LargeScan<Depth24>>()
    );
    println!();
    println!("| item (Rgb565) | bytes |");
    println!("|---|---|");
    println!(
        "| vertex (`ScreenVertex`) | {} |",
        size_of::<ScreenVertex>()
    );
    println!(
        "| polygon (`PolygonEntry`) | {} |",
        size_of::<PolygonEntry<Rgb565>>()
    );
    println!(
        "| corner (its vertex index and its edge-table entry) | {} |",
        size_of::<u16>() + size_of::<EdgeEntry>()
    );
    println!(
        "| active polygon (`ActivePolygon`, its edge pair inline) | {} |",
        size_of::<ActivePolygon<Rgb565>>()
    );
    println!(
        "| small triangle waiting for its next rows (`SmallActive`; `AP` of them, on every target but 32-bit Arm) | {} |",
        size_of::<SmallActive<Rgb565>>()
    );
    println!(
        "| pooled active edge (`ActiveEdge`) | {} |",
        size_of::<ActiveEdge>()
    );
    println!(
        "| one pixel of the rows: colour + z16 + tie-break key | {} |",
        size_of::<Rgb565>() + size_of::<u16>() + size_of::<u32>()
    );
}
