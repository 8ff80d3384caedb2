//! The tables themselves: [`Tables`] over a [`TableStorage`], the lengths
//! of its four lists and its counts; made, resized and cleared here, with
//! the capacity-erased view ([`TablesMut`]) that admission and preparation
//! are written on.

use crate::error::Error;
use crate::limits::MAX_FRAME_SIZE;
use crate::raster::slots::Slots;
use crate::raster::tables::entry::PolygonEntry;
use crate::raster::tables::storage::{TableEdge, TableStorage, corner_room, usable_polygons};
use crate::raster::vertex::ScreenVertex;

/// Counts kept by the tables, beside the lists' lengths.
#[derive(Debug, Clone, Copy)]
pub(super) struct Counts {
    pub(super) width: u16,
    pub(super) height: u16,
    /// Corners of queued polygons (`corners` beyond them are the open
    /// polygon's).
    pub(super) committed_corners: usize,
    /// `Some(vertex count when it began)` while a polygon is open.
    pub(super) open_polygon: Option<usize>,
    /// The PT is sorted and the ET built for the polygons now queued.
    pub(super) prepared: bool,
    pub(super) next_id: u32,
    /// The polygon queued last was the last thing offered: it may still
    /// be given a shared plane.
    pub(super) shareable: bool,
    pub(super) off_screen: u32,
    pub(super) degenerate: u32,
}

/// Lengths of the four lists and the counts.
#[derive(Debug, Clone, Copy)]
pub(super) struct TableState {
    pub(super) vertices: usize,
    pub(super) polygons: usize,
    pub(super) corners: usize,
    pub(super) edges: usize,
    pub(super) counts: Counts,
}

/// The scene-sized tables over some [`TableStorage`]: build a frame's
/// scene into them, [`Self::prepare`] them, and scan the rows with one or
/// more [`Scanner`](crate::raster::Scanner)s.
#[derive(Debug, Clone)]
pub struct Tables<S: TableStorage> {
    pub(super) storage: S,
    pub(super) state: TableState,
}

/// The tables, capacity-erased: every operation is written once here.
pub(super) struct TablesMut<'a, C> {
    pub(super) vertices: Slots<'a, ScreenVertex>,
    pub(super) polygons: Slots<'a, PolygonEntry<C>>,
    pub(super) corners: Slots<'a, u16>,
    pub(super) edges: Slots<'a, TableEdge>,
    pub(super) counts: &'a mut Counts,
}

impl<S: TableStorage> Tables<S> {
    /// Empty tables for frames `width` x `height` (each 1 to 4,096).
    pub fn new(storage: S, width: u16, height: u16) -> Result<Self, Error> {
        check_size(width, height)?;
        Ok(Self::new_unchecked(storage, width, height))
    }

    /// As [`Self::new`], `const`, for statics; an invalid size stops the
    /// build.
    pub const fn new_in_static(storage: S, width: u16, height: u16) -> Self {
        if check_size(width, height).is_err() {
            panic!("zline: frame width and height must be 1..=4096");
        }
        Self::new_unchecked(storage, width, height)
    }

    const fn new_unchecked(storage: S, width: u16, height: u16) -> Self {
        Self {
            storage,
            state: TableState {
                vertices: 0,
                polygons: 0,
                corners: 0,
                edges: 0,
                counts: Counts {
                    width,
                    height,
                    committed_corners: 0,
                    open_polygon: None,
                    prepared: false,
                    next_id: 0,
                    shareable: false,
                    off_screen: 0,
                    degenerate: 0,
                },
            },
        }
    }

    pub(super) fn view(&mut self) -> TablesMut<'_, S::Color> {
        let parts = self.storage.parts_mut();
        let st = &mut self.state;
        let room = corner_room(parts.corners.len(), parts.edges.len());
        TablesMut {
            vertices: Slots::new(parts.vertices, &mut st.vertices),
            polygons: Slots::new(usable_polygons(parts.polygons), &mut st.polygons),
            corners: Slots::new(&mut parts.corners[..room], &mut st.corners),
            edges: Slots::new(parts.edges, &mut st.edges),
            counts: &mut st.counts,
        }
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.state.counts.width
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.state.counts.height
    }

    /// Changes the frame size (each 1 to 4,096) and empties the tables.
    pub fn set_size(&mut self, width: u16, height: u16) -> Result<(), Error> {
        check_size(width, height)?;
        self.clear();
        (self.state.counts.width, self.state.counts.height) = (width, height);
        Ok(())
    }

    /// Empties every table for the next frame.
    pub fn clear(&mut self) {
        let counts = &mut self.state.counts;
        (self.state.vertices, self.state.polygons) = (0, 0);
        (self.state.corners, self.state.edges) = (0, 0);
        counts.committed_corners = 0;
        counts.open_polygon = None;
        counts.prepared = false;
        counts.shareable = false;
        (counts.next_id, counts.off_screen, counts.degenerate) = (0, 0, 0);
    }

    /// Number of vertices in the vertex table.
    pub fn vertex_count(&self) -> usize {
        self.state.vertices
    }

    /// Number of polygons in the polygon table.
    pub fn polygon_count(&self) -> usize {
        self.state.polygons
    }

    /// Number of corners stored for the queued polygons.
    pub fn corner_count(&self) -> usize {
        self.state.counts.committed_corners
    }

    /// Vertex `index` of the vertex table.
    pub fn vertex(&self, index: u16) -> Option<ScreenVertex> {
        let parts = self.storage.parts();
        parts.vertices[..self.state.vertices]
            .get(usize::from(index))
            .copied()
    }
}

const fn check_size(width: u16, height: u16) -> Result<(), Error> {
    if width == 0
        || width as usize > MAX_FRAME_SIZE
        || height == 0
        || height as usize > MAX_FRAME_SIZE
    {
        Err(Error::BadFrameSize)
    } else {
        Ok(())
    }
}
