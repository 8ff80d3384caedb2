//! One prepared painted scene drawn by two scanners, as a second core
//! draws it: the rows above a cut by one renderer's scanner and slots,
//! the rows below by another's, both over the first renderer's prepared
//! tables and vertex values. The tests and the fuzz checks compare its
//! rows with one scan's.

use zline::paint::{PaintMode, PaintStorage, PaintedRenderer, Painter};
use zline::{DepthFormat, RenderError, RowSink, ScanStorage, TableStorage, scan_painted};

/// Paints `painted`'s scene into `sink`: rows `0..cut` with `painted`'s
/// scanner and slots, rows `cut..height` with `other`'s scanner and
/// slots (over `painted`'s tables, vertex values and mode).
pub fn paint_in_two_bands<T, S, K, A, Sink>(
    painted: &mut PaintedRenderer<T, S, K, A>,
    other: &mut PaintedRenderer<T, S, K, A>,
    cut: u16,
    height: u16,
    sink: &mut Sink,
) -> Result<(), RenderError<Sink::Error>>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    A: PaintStorage,
    Sink: RowSink<<A::Mode as PaintMode>::Color, <S::Depth as DepthFormat>::Value>,
{
    let background = painted.background();
    let PaintedRenderer {
        renderer,
        paint,
        mode,
        ..
    } = painted;
    let prepared = renderer.tables.prepare();
    let parts = paint.parts_mut();
    let vertices = &*parts.vertices;
    let mut top = Painter::new(&*mode, vertices, parts.slots, background);
    scan_painted(
        &prepared,
        &mut renderer.scanner,
        &mut top,
        parts.row,
        0..cut,
        sink,
    )?;
    let theirs = other.paint.parts_mut();
    let mut bottom = Painter::new(&*mode, vertices, theirs.slots, background);
    let scanner = &mut other.renderer.scanner;
    scan_painted(
        &prepared,
        scanner,
        &mut bottom,
        theirs.row,
        cut..height,
        sink,
    )?;
    Ok(())
}
