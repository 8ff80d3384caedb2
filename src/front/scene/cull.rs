//! Which faces a draw culls before they reach the tables ([`Cull`]): the
//! caller's choice, carried by the draw's constants to the face offering.

/// Which faces to cull before they reach the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cull {
    /// Draw both sides (for meshes with inconsistent winding, or open
    /// ones). A closed mesh ([`Mesh::closed_hull`](crate::Mesh::closed_hull))
    /// whose bounding sphere lies between the near and far planes is drawn
    /// as with [`Cull::Back`]: seen from outside it shows no back face
    /// ([`ClosedHull`](crate::ClosedHull)).
    #[default]
    None,
    /// Cull faces whose corners run clockwise on screen: their back is
    /// turned to the viewer when the mesh winds its faces counter-clockwise
    /// seen from outside (the OBJ convention).
    Back,
}
