//! Smooth shading and textures: modes that paint each visible pixel from
//! planes of values given at a polygon's corners, after visibility is
//! decided (a painted scan, [`scan_painted`](crate::scan_painted)): each
//! pixel is shaded once,
//! however many polygons covered it.
//!
//! * [`PaintMode`]: what a vertex carries, the planes a polygon gets from
//!   its corners, and how a run of pixels is painted from them;
//!   [`Gouraud`] (a colour per vertex, interpolated) and [`Textured`]
//!   (texture coordinates per vertex, perspective-correct, sampling a
//!   [`Texture`]); [`LitTextured`] (a texture scaled by a light per
//!   vertex, interpolated as Gouraud's colours);
//! * [`PaintColor`]: the colours a painted row can hold, quantised from
//!   8.8 fixed-point channels, with an ordered dither ([`bayer_threshold`]);
//! * [`PaintStorage`] and [`PaintArrays`]: the values of the vertex table,
//!   the planes of the active polygons and the painted row;
//!   [`PaintedRenderer`] joins them to a [`Renderer`](crate::Renderer).

mod color;
mod gouraud;
mod lit;
mod renderer;
mod storage;
mod texture;
mod textured;

pub use color::{CHANNEL_MAX, PaintColor, bayer_threshold};
pub use gouraud::{Gouraud, GouraudPlanes, Rgb8p8};
pub use lit::{LitTexCoord, LitTextured, LitTexturedPlanes};
pub use renderer::PaintedRenderer;
pub use storage::{PaintArrays, PaintParts, PaintStorage, SlotPlanes};
pub use texture::{Filter, TEXEL_FRAC_BITS, TEXTURE_SIZE_MAX, Texture, Wrap};
pub use textured::{CHORD_TOLERANCE, SPAN, Textured, TexturedPlanes};

pub use crate::front::clip_w::ClipW;
pub use crate::front::tex_coord::{TexCoord, UV_ONE};

use crate::front::clip::ClipValue;
use core::ops::Range;

use crate::raster::paint::{NO_SLOT, RowPainter};
use crate::raster::tables::Prepared;
use crate::raster::tables::entry::entry_corner_ids;
use crate::raster::vertex::ScreenVertex;

/// A way of painting polygons from values at their corners.
pub trait PaintMode {
    /// What a mesh's vertex shading gives each vertex
    /// ([`PaintedRenderer::draw_mesh`]), interpolated where clipping cuts
    /// an edge.
    type Source: ClipValue;
    /// What each vertex of the vertex table carries.
    type Vertex: Copy;
    /// What an active polygon holds to paint its pixels: its planes.
    type Planes: Copy;
    /// The colour painted.
    type Color: Copy;
    /// What the runs of one row share, made once a row ([`Self::row`]):
    /// its dither offsets, say.
    type Row;
    /// A value of [`Self::Vertex`] to fill storage with.
    const VERTEX_FILLER: Self::Vertex;
    /// A value of [`Self::Planes`] to fill storage with.
    const PLANES_FILLER: Self::Planes;

    /// A vertex's value from its source.
    fn vertex(&self, source: Self::Source) -> Self::Vertex;

    /// The planes of a polygon, from its corners (position and value, in
    /// order), in a frame `width` x `height`. A polygon of zero area (never
    /// queued) may get any planes.
    fn planes(
        &self,
        corners: impl Iterator<Item = (ScreenVertex, Self::Vertex)> + Clone,
        width: u16,
        height: u16,
    ) -> Self::Planes;

    /// What the runs of row `y` share.
    fn row(&self, y: u16) -> Self::Row;

    /// Paints `out`, the pixels from column `x0` on of row `y` (whose
    /// shared values are `row`), all won by the polygon with these
    /// `planes` and the corners `corners()` gives (from which a steep
    /// plane's exact values are taken; most runs never ask).
    fn paint_run<I: Iterator<Item = (ScreenVertex, Self::Vertex)> + Clone>(
        &self,
        row: &Self::Row,
        planes: &Self::Planes,
        corners: impl Fn() -> I,
        x0: u16,
        y: u16,
        out: &mut [Self::Color],
    );
}

/// A [`RowPainter`] from a [`PaintMode`] over [`PaintParts`]: what
/// [`PaintedRenderer::render`] paints with. Built from the parts of two
/// renderers, it lets a second scanner paint another renderer's prepared
/// scene: the scene's vertex values with this scanner's own slots (for
/// [`scan_painted`](crate::scan_painted) of a band of rows, as a second
/// core does).
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
/// use zline::paint::{Gouraud, PaintStorage, PaintedRenderer, Painter, Rgb8p8};
/// use zline::{Capacities, Depth16, FnSink, ScreenVertex, limits::SUBPIXEL_STEPS as S};
///
/// const CAPS: Capacities = Capacities {
///     width: 16, vertices: 3, polygons: 1, corners: 3,
///     active_polygons: 1, pooled_edges: 3, mesh_vertices: 0,
/// };
/// type Painted = zline::painted_renderer_type!(Gouraud<Rgb888>, Depth16, CAPS);
/// let mut scene = Painted::new(16, 8, Gouraud::new(), Rgb888::BLACK)?;
/// // Only its scanner and slots are used (on a second core, say).
/// let mut second = Painted::new(16, 8, Gouraud::new(), Rgb888::BLACK)?;
/// let corners = [(0, 0), (16, 0), (0, 8)].map(|(x, y)| ScreenVertex { x: x * S, y: y * S, z: 1 });
/// let red = Rgb8p8::from_rgb888(Rgb888::RED);
/// scene.push_polygon_vertices(&corners, &[red; 3])?;
///
/// let background = scene.background();
/// let PaintedRenderer { renderer, paint, mode, .. } = &mut scene;
/// let prepared = renderer.tables.prepare();
/// let ours = paint.parts_mut();
/// let vertices = &*ours.vertices;
/// let mut painted = 0;
/// let mut sink = FnSink(|_: u16, row: &[Rgb888], _: &[u16]| {
///     painted += row.iter().filter(|&&c| c != Rgb888::BLACK).count();
///     Ok::<(), ()>(())
/// });
/// // Rows 0..4 with the scene's own scanner and slots...
/// let mut top = Painter::new(&*mode, vertices, ours.slots, background);
/// zline::scan_painted(&prepared, &mut renderer.scanner, &mut top, ours.row, 0..4, &mut sink)?;
/// // ...rows 4..8 with the second renderer's.
/// let theirs = second.paint.parts_mut();
/// let mut bottom = Painter::new(&*mode, vertices, theirs.slots, background);
/// let scanner = &mut second.renderer.scanner;
/// zline::scan_painted(&prepared, scanner, &mut bottom, theirs.row, 4..8, &mut sink)?;
/// assert!(painted > 40);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Painter<'a, M: PaintMode> {
    pub(crate) mode: &'a M,
    /// The values of the vertex table's vertices.
    pub(crate) vertices: &'a [M::Vertex],
    /// The planes of the polygons in each APT slot.
    pub(crate) slots: &'a mut [SlotPlanes<M::Planes>],
    pub(crate) background: M::Color,
}

impl<'a, M: PaintMode> Painter<'a, M> {
    /// A painter with `mode` of the scene whose vertex values are
    /// `vertices` (its tables' vertex table, in order), keeping the planes
    /// of the polygons in its scanner's APT slots in `slots` (at least as
    /// many as the scanner's APT holds, and `vertices` at least as many as
    /// the tables' vertices: [`scan_painted`](crate::scan_painted) refuses
    /// fewer) and painting `background` where no polygon is.
    pub fn new(
        mode: &'a M,
        vertices: &'a [M::Vertex],
        slots: &'a mut [SlotPlanes<M::Planes>],
        background: M::Color,
    ) -> Self {
        Self {
            mode,
            vertices,
            slots,
            background,
        }
    }
}

impl<M: PaintMode> Painter<'_, M> {
    /// The corners of the polygon at `position`, with their values.
    #[inline]
    fn corners<'t>(
        vertices: &'t [M::Vertex],
        tables: &'t Prepared<'t, u16>,
        position: usize,
    ) -> impl Iterator<Item = (ScreenVertex, M::Vertex)> + Clone + 't {
        let ids: &[u16] = match tables.polygons.get(position) {
            Some(polygon) => entry_corner_ids(polygon, tables.corners),
            None => &[],
        };
        ids.iter().filter_map(move |&id| {
            let id = usize::from(id);
            Some((*tables.vertices.get(id)?, *vertices.get(id)?))
        })
    }
}

impl<M: PaintMode> RowPainter for Painter<'_, M> {
    type Color = M::Color;

    fn enter(&mut self, slot: usize, position: usize, _row: u16, _tables: &Prepared<'_, u16>) {
        if let Some(entry) = self.slots.get_mut(slot) {
            // Its planes are set up when its first run is painted.
            (entry.position, entry.ready) = (position as u32, false);
        }
    }

    fn paint(
        &mut self,
        row: u16,
        slots: &[u16],
        tables: &Prepared<'_, u16>,
        out: &mut [M::Color],
        filled: bool,
    ) {
        let width = slots.len().min(out.len());
        self.paint_columns(row, slots, tables, out, filled, 0..width);
    }

    fn paint_columns(
        &mut self,
        row: u16,
        slots: &[u16],
        tables: &Prepared<'_, u16>,
        out: &mut [M::Color],
        filled: bool,
        columns: Range<usize>,
    ) {
        let width = slots.len().min(out.len());
        let (slots, out) = (&slots[..width], &mut out[..width]);
        // The background first (unless the row holds it), in unrolled
        // stores, so that uncovered runs need only be skipped.
        if !filled {
            fill(out, self.background);
        }
        // Only the columns the scan can have written hold slots.
        let end = columns.end.min(width);
        let Some(slots) = slots.get(..end) else {
            return;
        };
        let shared = self.mode.row(row);
        let mut x = columns.start;
        while let Some(&slot) = slots.get(x) {
            let end = run_end(slots, x, slot);
            if slot == NO_SLOT {
                x = end;
                continue;
            }
            if let (Some(entry), Some(run)) =
                (self.slots.get_mut(usize::from(slot)), out.get_mut(x..end))
            {
                let position = entry.position as usize;
                let corners = || Self::corners(self.vertices, tables, position);
                if !entry.ready {
                    entry.planes = self.mode.planes(corners(), tables.width, tables.height);
                    entry.ready = true;
                }
                self.mode
                    .paint_run(&shared, &entry.planes, corners, x as u16, row, run);
            }
            x = end;
        }
    }

    fn background(&self) -> M::Color {
        self.background
    }

    fn capacity(&self) -> (usize, usize) {
        (self.slots.len(), self.vertices.len())
    }
}

/// Sets every pixel of `out` to `color`, eight stores a loop step.
#[inline(always)]
fn fill<C: Copy>(out: &mut [C], color: C) {
    let mut chunks = out.chunks_exact_mut(8);
    for chunk in &mut chunks {
        for pixel in chunk {
            *pixel = color;
        }
    }
    for pixel in chunks.into_remainder() {
        *pixel = color;
    }
}

/// One past the last pixel from `start` on whose slot is `slot`
/// (`slots[start]` is), looking at four slots a loop step: on a 64-bit
/// core as one word, the first slot that differs found from the trailing
/// zeros of its difference from `slot` four times over; elsewhere (a
/// 32-bit core, where a 64-bit word is two and a Cortex-M0+ has no
/// instruction to count zeros) one by one.
#[inline(always)]
fn run_end(slots: &[u16], start: usize, slot: u16) -> usize {
    let mut end = start + 1;
    let four = |end: usize| {
        slots
            .get(end..end + 4)
            .and_then(|s| <&[u16; 4]>::try_from(s).ok())
    };
    if cfg!(target_pointer_width = "64") {
        let pattern = u64::from(slot) * 0x0001_0001_0001_0001;
        while let Some(&[a, b, c, d]) = four(end) {
            let word = u64::from(a) | u64::from(b) << 16 | u64::from(c) << 32 | u64::from(d) << 48;
            let differ = word ^ pattern;
            if differ != 0 {
                return end + (differ.trailing_zeros() / 16) as usize;
            }
            end += 4;
        }
    } else {
        while let Some(&[a, b, c, d]) = four(end) {
            if a != slot {
                return end;
            }
            if b != slot {
                return end + 1;
            }
            if c != slot {
                return end + 2;
            }
            if d != slot {
                return end + 3;
            }
            end += 4;
        }
    }
    while slots.get(end) == Some(&slot) {
        end += 1;
    }
    end
}

/// Whether pixel `(x, y)`'s sample is strictly inside the triangle with
/// these corners (tests of the paint modes).
#[cfg(test)]
pub(crate) fn sample_inside(corners: [ScreenVertex; 3], x: u16, y: u16) -> bool {
    use crate::limits::{HALF_PIXEL, SUBPIXEL_STEPS};
    let (px, py) = (
        i64::from(i32::from(x) * SUBPIXEL_STEPS + HALF_PIXEL),
        i64::from(i32::from(y) * SUBPIXEL_STEPS + HALF_PIXEL),
    );
    let edge = |a: ScreenVertex, b: ScreenVertex| {
        (i64::from(b.x) - i64::from(a.x)) * (py - i64::from(a.y))
            - (i64::from(b.y) - i64::from(a.y)) * (px - i64::from(a.x))
    };
    let [a, b, c] = corners;
    let e = [edge(a, b), edge(b, c), edge(c, a)];
    e.iter().all(|&e| e > 0) || e.iter().all(|&e| e < 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_end_finds_every_run() {
        // Rows of every length to 39 with runs cut at every place, the
        // slot values near 0 and NO_SLOT (so the word's high bits count).
        for len in 1..40usize {
            for cut in 0..1u32 << len.min(10) {
                let mut slots = std::vec::Vec::with_capacity(len);
                let mut value = NO_SLOT;
                for k in 0..len {
                    if cut >> (k % 10) & 1 != 0 {
                        value = if value == NO_SLOT {
                            (k % 3) as u16
                        } else {
                            NO_SLOT
                        };
                    }
                    slots.push(value);
                }
                for start in 0..len {
                    let slot = slots[start];
                    let naive = (start..len).find(|&k| slots[k] != slot).unwrap_or(len);
                    assert_eq!(
                        run_end(&slots, start, slot),
                        naive,
                        "{slots:?} from {start}"
                    );
                }
            }
        }
    }
}
