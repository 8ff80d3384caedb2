//! Errors. Nothing that does not fit is dropped silently: every capacity,
//! every malformed input and every failure of the row sink comes back as a
//! value naming what went wrong.

use core::fmt;

/// Why a vertex or polygon was refused, or a frame could not be finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Error {
    /// The vertex table (const parameter `V`) is full.
    VertexTableFull,
    /// The polygon table (const parameter `P`) is full.
    PolygonTableFull,
    /// The edge table (const parameter `E`, which also holds every
    /// polygon corner) is full.
    EdgeTableFull,
    /// More polygons overlap one scanline than the active polygon table
    /// (const parameter `AP`) holds. Rows above `row` were already sent.
    ActivePolygonsFull {
        /// The scanline that did not fit.
        row: u16,
    },
    /// More edges cross one scanline than the active edge table (const
    /// parameter `AE`) holds. Rows above `row` were already sent.
    ActiveEdgesFull {
        /// The scanline that did not fit.
        row: u16,
    },
    /// A polygon (or a mesh face) has more corners than
    /// [`MAX_POLYGON_CORNERS`](crate::limits::MAX_POLYGON_CORNERS) (for a
    /// face, [`MAX_FACE_CORNERS`](crate::limits::MAX_FACE_CORNERS)).
    TooManyCorners,
    /// A polygon has fewer than three corners.
    TooFewCorners,
    /// A polygon names a vertex that was never added.
    VertexOutOfRange,
    /// A vertex lies outside the guard band
    /// ([`GUARD_BAND_PX`](crate::limits::GUARD_BAND_PX)), or is NaN/infinite.
    OutsideGuardBand,
    /// A vertex depth is outside `[0, DEPTH_MAX]`, or is NaN/infinite.
    DepthOutOfRange,
    /// A mesh face names a vertex beyond the mesh.
    MeshIndexOutOfRange,
    /// The mesh has more vertices than the
    /// [`VertexCache`](crate::front::scene::VertexCache) given to the scene holds.
    VertexCacheTooSmall,
    /// The faces given to
    /// [`draw_mesh_projected`](crate::front::scene::draw_mesh_projected)
    /// are not in increasing order.
    FacesOutOfOrder,
    /// The mesh's size cannot be normalised in `f32`: the radius of its
    /// bounding sphere is positive but outside `[2^-126, 2^126]`, or a
    /// position is not finite.
    MeshExtent,
    /// The frame width is zero or above the row capacity `W`, or the height
    /// is zero or above [`MAX_FRAME_SIZE`](crate::limits::MAX_FRAME_SIZE).
    BadFrameSize,
    /// The buffers lent to a z-buffer method
    /// ([`BandBuffers`](crate::raster::zbuffer::BandBuffers)) hold fewer
    /// rows than the band, a shorter scratch row than the frame, or no
    /// active polygon.
    BandBuffersTooSmall,
    /// [`Tables::share_plane`](crate::raster::Tables::share_plane) was
    /// called when no polygon had just been queued.
    NoPolygonToShare,
    /// A mesh face that needs clipping reaches too far for its distance
    /// from the eye to be clipped within the sub-pixel grid: its
    /// clip-space size is more than
    /// [`CLIP_RANGE`](crate::front::scene::CLIP_RANGE) times the view
    /// frustum's smallest `w` (for a perspective camera, the near
    /// distance), or the projection is singular and has no frustum (for
    /// example a near and far plane whose product underflows `f32`).
    ClipRange,
    /// A mesh face crosses the near or far plane or the guard band and
    /// needs clipping, but zline was built without its `clipping` feature
    /// (the `f64` clipper).
    NeedsClipping,
    /// A painted renderer's storage
    /// ([`PaintStorage`](crate::paint::PaintStorage)) holds values for
    /// fewer vertices than its vertex table, planes for fewer polygons than
    /// its active polygon table, or a row narrower than the frame.
    PaintStorageTooSmall,
    /// A polygon was given a different number of corner values than
    /// corners.
    ValueCountMismatch,
    /// A [`Texture`](crate::paint::Texture)'s width or height is 0 or
    /// above [`TEXTURE_SIZE_MAX`](crate::paint::TEXTURE_SIZE_MAX), or its
    /// texels are not `width · height`.
    BadTextureSize,
    /// A texture coordinate does not fit a quantized mesh's range
    /// (`-8..8` texture sizes: [`UV_SCALE`](crate::limits::UV_SCALE)), or is
    /// not finite.
    TexCoordRange,
    /// A face of a [`Triangles`](crate::Triangles) mesh has other than
    /// three corners.
    NotATriangle,
    /// A polygon of more than three corners was offered to the tables,
    /// but zline was built without its `polygons` feature.
    NeedsPolygons,
    /// The host's `Vec` storage for the capacities given (`host_renderer`
    /// and the storage types beside it, `std` only) could not be
    /// allocated.
    StorageTooLarge,
    /// A scan ([`scan`](crate::scan), [`scan_painted`](crate::scan_painted))
    /// was given the tables in drawing order
    /// ([`Tables::in_drawing_order`](crate::Tables::in_drawing_order), for
    /// the z-buffer methods), not sorted with their edge table by
    /// [`Tables::prepare`](crate::Tables::prepare).
    NotPrepared,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::VertexTableFull => f.write_str("vertex table full"),
            Error::PolygonTableFull => f.write_str("polygon table full"),
            Error::EdgeTableFull => f.write_str("edge table full"),
            Error::ActivePolygonsFull { row } => {
                write!(f, "active polygon table full at row {row}")
            }
            Error::ActiveEdgesFull { row } => write!(f, "active edge table full at row {row}"),
            Error::TooManyCorners => write!(
                f,
                "polygon has more than {} corners (a mesh face more than {})",
                crate::limits::MAX_POLYGON_CORNERS,
                crate::limits::MAX_FACE_CORNERS
            ),
            Error::TooFewCorners => f.write_str("polygon has fewer than 3 corners"),
            Error::VertexOutOfRange => f.write_str("polygon names a vertex that does not exist"),
            Error::OutsideGuardBand => f.write_str("vertex outside the guard band or not finite"),
            Error::DepthOutOfRange => f.write_str("vertex depth outside [0, 1] or not finite"),
            Error::MeshIndexOutOfRange => f.write_str("mesh face names a vertex beyond the mesh"),
            Error::NotPrepared => {
                f.write_str("tables in drawing order were scanned; scans need Tables::prepare's")
            }
            Error::StorageTooLarge => {
                f.write_str("storage for the capacities given cannot be allocated")
            }
            Error::VertexCacheTooSmall => {
                f.write_str("the vertex cache holds fewer vertices than the mesh has")
            }
            Error::FacesOutOfOrder => f.write_str("the faces to draw are not in increasing order"),
            Error::MeshExtent => f.write_str(
                "mesh size cannot be normalised: its radius must be 0 or between 2^-126 and 2^126",
            ),
            Error::BadFrameSize => f.write_str("frame width or height is zero or too large"),
            Error::BandBuffersTooSmall => {
                f.write_str("the z-buffer's buffers are smaller than the band or the frame's rows")
            }
            Error::NoPolygonToShare => {
                f.write_str("a shared plane was given with no polygon queued just before it")
            }
            Error::ClipRange => f.write_str(
                "face too large for its distance from the eye to be clipped exactly \
                 (clip-space size over 2^28 times the near plane's w), or a singular projection",
            ),
            Error::NeedsClipping => f.write_str(
                "face crosses the near or far plane or the guard band and needs clipping, \
                 but zline was built without its `clipping` feature",
            ),
            Error::PaintStorageTooSmall => f.write_str(
                "the paint storage holds fewer vertex values, active-polygon planes or \
                 pixels than the renderer needs",
            ),
            Error::ValueCountMismatch => {
                f.write_str("a polygon's corner values are not one per corner")
            }
            Error::NeedsPolygons => f.write_str(
                "polygon of more than three corners, but zline was built without its \
                 `polygons` feature",
            ),
            Error::NotATriangle => {
                f.write_str("a face of a mesh of triangles has other than three corners")
            }
            Error::TexCoordRange => {
                f.write_str("a texture coordinate is outside -8..8 or not finite")
            }
            Error::BadTextureSize => write!(
                f,
                "texture size out of 1..={} or not its texel count",
                crate::paint::TEXTURE_SIZE_MAX
            ),
        }
    }
}

impl core::error::Error for Error {}

/// Failure while rendering a frame: either the tables or the row sink.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderError<E> {
    /// A table overflowed while the frame was being scanned.
    Table(Error),
    /// The row sink failed; rows before it were delivered.
    Sink(E),
}

impl<E> From<Error> for RenderError<E> {
    fn from(error: Error) -> Self {
        RenderError::Table(error)
    }
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Table(e) => write!(f, "{e}"),
            RenderError::Sink(e) => write!(f, "row sink failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for RenderError<E> {}
