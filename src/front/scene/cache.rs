//! The vertex cache: where each mesh vertex went in the vertex table
//! during one draw ([`VertexCache`], or any [`CacheStorage`]), with the
//! markers for a vertex not yet transformed, needing clipping, or not
//! finite.

/// Where each mesh vertex went in the vertex table during one
/// [`draw_mesh`]: 2 bytes per mesh vertex, for meshes of up to `VM`
/// vertices. It is scratch space: `draw_mesh` resets the entries it uses
/// before it starts, so one cache serves any number of meshes (and any
/// number of draws of one mesh with different model matrices) in a frame.
///
/// [`draw_mesh`]: crate::draw_mesh
#[derive(Debug, Clone)]
pub struct VertexCache<const VM: usize> {
    slots: [u16; VM],
}

/// Not yet transformed in this draw.
pub(super) const EMPTY: u16 = u16::MAX;
/// Transformed, and it needs clipping: never projected as it is.
pub(super) const NEEDS_CLIP: u16 = u16::MAX - 1;
/// Its position is not finite even in `f64`.
pub(super) const NON_FINITE: u16 = u16::MAX - 2;

impl<const VM: usize> VertexCache<VM> {
    /// An empty cache.
    pub const fn new() -> Self {
        Self { slots: [EMPTY; VM] }
    }

    /// Forgets every vertex. [`draw_mesh`] does this itself for the
    /// vertices it uses; there is no need to call it between draws.
    ///
    /// [`draw_mesh`]: crate::draw_mesh
    pub fn clear(&mut self) {
        self.slots.fill(EMPTY);
    }
}

impl<const VM: usize> Default for VertexCache<VM> {
    fn default() -> Self {
        Self::new()
    }
}

/// Where [`draw_mesh`] remembers, for one draw, which vertex-table entry
/// each mesh vertex went to: a [`VertexCache`], a `Vec<u16>` on a desktop
/// (feature `std`, one entry per mesh vertex), or none ([`NoVertexCache`],
/// for a [`Renderer`](crate::Renderer) that does not draw meshes). Its
/// contents between draws do not matter: each draw resets the entries it
/// uses.
///
/// [`draw_mesh`]: crate::draw_mesh
pub trait CacheStorage: cache_seal::Sealed {
    /// An empty cache of this kind (for a `Vec`, of no entries).
    #[doc(hidden)]
    const EMPTY: Self;
    /// The entries, one per mesh vertex.
    #[doc(hidden)]
    fn slots_mut(&mut self) -> &mut [u16];
}

/// No vertex cache: a [`Renderer`](crate::Renderer) with it draws screen
/// polygons only ([`draw_mesh`] needs a cache).
///
/// [`draw_mesh`]: crate::draw_mesh
#[derive(Debug, Clone, Copy, Default)]
pub struct NoVertexCache;

impl CacheStorage for NoVertexCache {
    const EMPTY: Self = Self;

    fn slots_mut(&mut self) -> &mut [u16] {
        &mut []
    }
}

impl<const VM: usize> CacheStorage for VertexCache<VM> {
    const EMPTY: Self = Self::new();

    fn slots_mut(&mut self) -> &mut [u16] {
        &mut self.slots
    }
}

#[cfg(feature = "std")]
impl CacheStorage for std::vec::Vec<u16> {
    const EMPTY: Self = std::vec::Vec::new();

    fn slots_mut(&mut self) -> &mut [u16] {
        self
    }
}

/// Keeps [`CacheStorage`] to this crate's caches.
mod cache_seal {
    pub trait Sealed {}
    impl Sealed for super::NoVertexCache {}
    impl<const VM: usize> Sealed for super::VertexCache<VM> {}
    #[cfg(feature = "std")]
    impl Sealed for std::vec::Vec<u16> {}
}
