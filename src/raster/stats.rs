//! The counts a scan reports: [`FrameStats`].

/// Counts for one rendered frame (or band of rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameStats {
    /// Vertices in the vertex table.
    pub vertices: u32,
    /// Polygon corners stored.
    pub corners: u32,
    /// Polygons in the polygon table.
    pub polygons: u32,
    /// Edges that entered the active edge table.
    pub edges: u32,
    /// Largest number of polygons active on one row.
    pub peak_active_polygons: u32,
    /// Largest number of edges active on one row.
    pub peak_active_edges: u32,
    /// Largest number of those held in the edge pool, beyond each
    /// polygon's inline pair (zero for triangles and other convex
    /// polygons). A polygon pools only the edges beyond two that cover
    /// the row, so a scan of any band of the frame's rows needs no more
    /// than one scan of the whole frame.
    pub peak_pooled_edges: u32,
    /// Spans filled.
    pub spans: u32,
    /// Polygons offered but left out as off-screen.
    pub off_screen: u32,
    /// Polygons offered but left out as zero-area.
    pub degenerate: u32,
}

impl FrameStats {
    /// The larger of each peak and count of `self` and `other` (to size
    /// capacities over several frames, or add up bands).
    pub fn max(self, other: Self) -> Self {
        Self {
            vertices: self.vertices.max(other.vertices),
            corners: self.corners.max(other.corners),
            polygons: self.polygons.max(other.polygons),
            edges: self.edges.max(other.edges),
            peak_active_polygons: self.peak_active_polygons.max(other.peak_active_polygons),
            peak_active_edges: self.peak_active_edges.max(other.peak_active_edges),
            peak_pooled_edges: self.peak_pooled_edges.max(other.peak_pooled_edges),
            spans: self.spans.max(other.spans),
            off_screen: self.off_screen.max(other.off_screen),
            degenerate: self.degenerate.max(other.degenerate),
        }
    }
}
