//! Where a painted renderer's own arrays live: the values of the vertex
//! table's vertices, the planes of the active polygons (one entry per APT
//! slot) and the painted row for sinks that lend none.

use crate::paint::PaintMode;

/// An APT slot's polygon, as its painter knows it (opaque).
#[derive(Debug, Clone, Copy)]
pub struct SlotPlanes<P> {
    /// The polygon's position in the prepared polygon table.
    pub(crate) position: u32,
    /// Its planes, once `ready`.
    pub(crate) planes: P,
    /// Whether `planes` are the polygon's: they are set up when its first
    /// run is painted, so that a polygon no pixel shows costs none.
    pub(crate) ready: bool,
}

impl<P: Copy> SlotPlanes<P> {
    /// A filler for unused slots.
    pub const fn filler(planes: P) -> Self {
        Self {
            position: 0,
            planes,
            ready: false,
        }
    }
}

/// The arrays of a [`PaintStorage`], mutably.
pub struct PaintParts<'a, M: PaintMode> {
    /// A value per vertex-table entry (at least as long as the vertex
    /// table).
    pub vertices: &'a mut [M::Vertex],
    /// The planes per APT slot (at least as long as the APT).
    pub slots: &'a mut [SlotPlanes<M::Planes>],
    /// The painted row (at least as wide as the frame).
    pub row: &'a mut [M::Color],
}

/// Where a painted renderer's arrays live. [`PaintArrays`] holds them in
/// fixed arrays (for statics on a microcontroller); the host's
/// `zline::host::PaintVecs` in `Vec`s.
pub trait PaintStorage {
    /// The paint mode whose values and planes it holds.
    type Mode: PaintMode;
    /// The arrays, mutably.
    fn parts_mut(&mut self) -> PaintParts<'_, Self::Mode>;
}

/// Fixed-capacity storage for painting: values for `V` vertices (the
/// vertex table's capacity), planes for `AP` active polygons (the APT's)
/// and a row of `W` pixels (the scanner's).
pub struct PaintArrays<M: PaintMode, const V: usize, const AP: usize, const W: usize> {
    vertices: [M::Vertex; V],
    slots: [SlotPlanes<M::Planes>; AP],
    row: [M::Color; W],
}

impl<M: PaintMode, const V: usize, const AP: usize, const W: usize> PaintArrays<M, V, AP, W> {
    /// Empty storage; `color` fills the row (any colour: each pixel is
    /// written before it is read).
    pub const fn new(color: M::Color) -> Self {
        Self {
            vertices: [M::VERTEX_FILLER; V],
            slots: [SlotPlanes::filler(M::PLANES_FILLER); AP],
            row: [color; W],
        }
    }
}

impl<M: PaintMode, const V: usize, const AP: usize, const W: usize> PaintStorage
    for PaintArrays<M, V, AP, W>
{
    type Mode = M;

    fn parts_mut(&mut self) -> PaintParts<'_, M> {
        PaintParts {
            vertices: &mut self.vertices,
            slots: &mut self.slots,
            row: &mut self.row,
        }
    }
}
