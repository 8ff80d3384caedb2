//! The textbook figure in a terminal: two overlapping polygons and a third
//! that passes through both, drawn by the scanline z-buffer into ASCII art.
//! Each row is printed the moment the renderer finishes it.
//!
//! ```sh
//! cargo run --example scanline_figure
//! ```

use zline::{Depth16, FnSink, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 64 columns; 24 vertices, 3 polygons, 24 edges (corners), 3 active
    // polygons, 24 pooled active edges.
    let mut renderer: Renderer<TableArrays<char, 24, 3, 24>, ScanArrays<char, Depth16, 64, 3, 24>> =
        Renderer::with_height(24, '.')?;
    let v = |x: f32, y: f32, z: f32| ScreenVertex::from_f32(x, y, z);
    // A square at mid depth.
    renderer.push_polygon_vertices(
        &[
            v(4.0, 2.0, 0.5)?,
            v(34.0, 2.0, 0.5)?,
            v(34.0, 17.0, 0.5)?,
            v(4.0, 17.0, 0.5)?,
        ],
        '#',
    )?;
    // A triangle behind it, to the right.
    renderer.push_polygon_vertices(
        &[v(20.0, 6.0, 0.8)?, v(60.0, 4.0, 0.8)?, v(44.0, 22.0, 0.8)?],
        'o',
    )?;
    // A slanted quad from near (left) to far (right), cutting through both.
    renderer.push_polygon_vertices(
        &[
            v(8.0, 10.0, 0.1)?,
            v(56.0, 10.0, 0.95)?,
            v(56.0, 14.0, 0.95)?,
            v(8.0, 14.0, 0.1)?,
        ],
        '=',
    )?;
    let stats = renderer.render(&mut FnSink(|_y: u16, row: &[char], _depth: &[u16]| {
        println!("{}", row.iter().collect::<String>());
        Ok::<(), core::convert::Infallible>(())
    }))?;
    println!("{stats:?}");
    Ok(())
}
