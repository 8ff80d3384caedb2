//! A closed mesh's hull ([`ClosedHull`]): what lets a draw with
//! [`Cull::None`](crate::Cull::None) leave out back faces that cannot show.
//!
//! (The argument is on [`ClosedHull`].)

use crate::front::geometry::Mat4;

/// Relative margin of the frame's tests: far beyond the front end's own
/// rounding (`f32`, about `6e-8` a step), so a vertex the tests call
/// inside the near and far planes is never clipped by them.
const MARGIN: f64 = 1e-4;

/// A closed mesh's hull: every edge of its faces is met by exactly one
/// other face running the other way, its faces wind counter-clockwise seen
/// from outside (the volume they enclose is positive; OBJ's convention),
/// and every position lies in the sphere of `centre` and `radius` (model
/// space).
///
/// A mesh that has one ([`Mesh::closed_hull`](crate::Mesh::closed_hull))
/// is drawn with [`Cull::None`](crate::Cull::None) as with
/// [`Cull::Back`](crate::Cull::Back) whenever the sphere lies wholly
/// between the camera's near and far planes and the matrices keep the
/// winding: the same samples are covered, and a colour changes only where
/// a back face tied in depth with a front face that is nearer. (A mesh
/// with face planes, [`Mesh::face_planes`](crate::Mesh::face_planes), is
/// then culled as with `Cull::Back` in this too: a face seen edge-on that
/// the exact projection turns away is left out even where its rounded
/// corners would cover a sample, which can leave such a sample to what
/// lies behind: 1 pixel of the bunny in 96 views, none on the other shared
/// meshes.)
///
/// # Why back faces of a closed mesh never show
/// Let every edge of the mesh's faces be met by exactly one other face
/// running the other way (the surface is closed and consistently wound)
/// and the faces wind counter-clockwise seen from outside. Project the
/// faces (triangles, or the polygons the pipeline draws) onto the screen
/// with no part clipped away: the faces turned to the viewer (front) and
/// those turned away (back) then cover every sample the same number of
/// times, since the signed coverage of a closed surface cancels edge by
/// edge (the rasteriser's fill rule decides a shared edge's samples by the
/// edge alone, so this holds sample for sample, not only almost
/// everywhere). So a back face never covers a sample that no front face
/// covers. And along the ray from an eye outside the surface, the first
/// face met is one where the ray enters the solid: a front face. So a
/// back face can win a sample only by a depth tie, or a difference
/// smaller than the depth buffer's step, with a front face that is in
/// fact nearer. Culling it changes no covered sample, and where it
/// changes a colour it gives the nearer face's.
///
/// Both conditions hold when the mesh's bounding sphere lies wholly
/// between the near and the far plane: the eye is then outside the sphere,
/// and so outside the surface, and the front end clips nothing away but
/// parts beyond the frame's sides (outside the frame).
///
/// # A mesh with holes, closed by caps
/// A mesh whose open edges run round holes may have a hull with caps
/// ([`Mesh::hull_caps`](crate::Mesh::hull_caps)): triangles over each
/// hole, wound against its rim, so that mesh and caps together are closed
/// and wound as above. Then the argument holds for mesh and caps together.
/// Every frame, each cap triangle is placed on the screen where the front
/// end places vertices, and tested as a face is. Where every cap faces
/// away (or covers nothing), the caps' share of the signed coverage is at
/// most zero at every sample, so the mesh's front faces cover every
/// sample its back faces cover; and a ray from the eye can reach the
/// inside only through a cap it crosses going in, which would face the
/// viewer. A cap that faces the viewer but has no pixel sample within a
/// sub-pixel step of its snapped corners' triangle covers no sample (the
/// cap lies within half a step of that triangle) and counts as facing
/// away. Where some caps face the viewer, the frame keeps each one's
/// rectangle on the screen, grown by a pixel (the cap between its
/// snapped corners lies within half a sub-pixel step of it), as a grid
/// of cells over the rectangle that holds them all: a back face whose
/// rectangle meets a cell some cap's rectangle meets is drawn, and any
/// other is culled, since at its samples no cap faces the viewer and
/// both reasons hold there (the teapot in the reference view at
/// 240x240 culls 2,203 back faces so, 1,821 when one rectangle held all
/// the caps).
/// The rectangles are kept only with the `std` feature (the host, whose
/// meshes get caps): a build without it draws a mesh whose caps do not
/// all face away with every face, and a microcontroller's draw keeps the
/// code it had.
///
/// # What is checked, and where
/// The host checks the mesh (`zline::host::HostMesh` finds its hull,
/// with caps over any holes, when it reads a file; `obj2rust` writes the
/// hull of a closed mesh into flash meshes, which carry no caps). Every frame, [`ClosedHull::hides_back_faces`] checks the
/// sphere against the near and far planes and that the model, view and
/// projection keep the faces' winding, in `f64` with a margin for the
/// front end's own rounding.
///
/// A mesh that passes through itself may fold a pocket inside out, where
/// a ray from outside meets a back face first. The host's check cannot
/// see that (it refuses a mesh whose enclosed volume is not positive, or
/// a face that crosses itself, not a pocket between faces): there the
/// draw shows the front face behind,
/// as [`Cull::Back`](crate::Cull::Back) would. The shared meshes' cow has
/// such folds: at 320x240 they change 2 of 76,800 pixels in one of the
/// accuracy run's three views (both within 1/16 px of a face's edge).
/// Clear `HostMesh::closed_hull` to draw every face of such a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedHull {
    /// Centre of a sphere holding every position.
    pub centre: [f32; 3],
    /// Its radius.
    pub radius: f32,
}

impl ClosedHull {
    /// Whether, drawn through `mvp` (projection · view · model), no back
    /// face can show: the sphere lies wholly, with a margin, between the
    /// near plane (`z >= -w` in clip space) and the far plane (`z <= w`),
    /// and `mvp` keeps the winding of a counter-clockwise face seen from
    /// outside as the front end's back-face test reads it (its
    /// determinant is negative, as a right-handed view's perspective or
    /// orthographic projection makes it: the map to normalised device
    /// coordinates, whose Jacobian is `det / w^4` where `w > 0`, mirrors
    /// depth). `false` for anything not finite.
    pub fn hides_back_faces(&self, mvp: &Mat4) -> bool {
        let m = mvp.m.map(|row| row.map(f64::from));
        let c = self.centre.map(f64::from);
        let r = f64::from(self.radius);
        // The plane function `p · (x, 1)` is above the margin all over the
        // sphere: its value at the centre less `r` times its slope.
        let inside = |p: [f64; 4]| {
            let slope = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            let at_centre = p[0] * c[0] + p[1] * c[1] + p[2] * c[2] + p[3];
            let scale = slope * (c[0].abs() + c[1].abs() + c[2].abs() + r) + p[3].abs();
            at_centre - r * slope > MARGIN * scale
        };
        let (z, w) = (m[2], m[3]);
        let near = [0, 1, 2, 3].map(|k| w[k] + z[k]);
        let far = [0, 1, 2, 3].map(|k| w[k] - z[k]);
        r >= 0.0 && determinant(&m) < 0.0 && inside(near) && inside(far)
    }
}

/// The determinant of a 4x4 matrix (expansion by 2x2 minors of its top
/// and bottom row pairs).
fn determinant(m: &[[f64; 4]; 4]) -> f64 {
    let minor = |rows: [usize; 2], a: usize, b: usize| {
        m[rows[0]][a] * m[rows[1]][b] - m[rows[0]][b] * m[rows[1]][a]
    };
    let (top, bottom) = ([0, 1], [2, 3]);
    minor(top, 0, 1) * minor(bottom, 2, 3) - minor(top, 0, 2) * minor(bottom, 1, 3)
        + minor(top, 0, 3) * minor(bottom, 1, 2)
        + minor(top, 1, 2) * minor(bottom, 0, 3)
        - minor(top, 1, 3) * minor(bottom, 0, 2)
        + minor(top, 2, 3) * minor(bottom, 0, 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::geometry::{Vec3, radians};
    use crate::front::scene::Camera;

    const UNIT: ClosedHull = ClosedHull {
        centre: [0.0; 3],
        radius: 1.0,
    };

    fn mvp(camera: &Camera, model: &Mat4) -> Mat4 {
        camera.projection.mul(&camera.view.mul(model))
    }

    #[test]
    fn determinant_of_known_matrices() {
        let scale = Mat4::scale(Vec3::new(2.0, 3.0, 5.0));
        let m = |a: &Mat4| a.m.map(|row| row.map(f64::from));
        assert_eq!(determinant(&m(&scale)), 30.0);
        let turned = Mat4::rotation_y(0.7).mul(&Mat4::translation(Vec3::new(1.0, 2.0, 3.0)));
        assert!((determinant(&m(&turned)) - 1.0).abs() < 1e-6);
        let mirror = Mat4::scale(Vec3::new(-1.0, 1.0, 1.0));
        assert_eq!(determinant(&m(&mirror)), -1.0);
        // Swapping two rows of the identity.
        let mut swap = m(&Mat4::IDENTITY);
        swap.swap(1, 3);
        assert_eq!(determinant(&swap), -1.0);
    }

    #[test]
    fn the_reference_view_hides_back_faces() {
        let camera = Camera::reference(240, 240);
        assert!(UNIT.hides_back_faces(&mvp(&camera, &Mat4::IDENTITY)));
        let turned = Mat4::rotation_x(radians(20.0)).mul(&Mat4::rotation_y(radians(30.0)));
        assert!(UNIT.hides_back_faces(&mvp(&camera, &turned)));
    }

    #[test]
    fn a_sphere_at_or_across_a_clip_plane_does_not() {
        // The eye at z = 3, near 0.1, far 10: the sphere reaches
        // 3 - 0.1 = 2.9 towards the eye before it crosses the near plane.
        let camera = Camera::reference(240, 240);
        let at = |z: f32, radius: f32| {
            let hull = ClosedHull {
                centre: [0.0, 0.0, z],
                radius,
            };
            hull.hides_back_faces(&mvp(&camera, &Mat4::IDENTITY))
        };
        assert!(at(0.0, 2.89));
        assert!(!at(0.0, 2.9), "touches the near plane");
        assert!(!at(0.0, 3.5), "holds the eye");
        assert!(!at(2.5, 1.0), "across the near plane");
        assert!(!at(-6.5, 1.0), "across the far plane (z = -7)");
        assert!(at(-5.5, 1.0));
        assert!(!at(0.0, f32::NAN));
        assert!(!at(f32::INFINITY, 1.0));
    }

    #[test]
    fn a_mirroring_model_does_not() {
        let camera = Camera::reference(240, 240);
        let mirror = Mat4::scale(Vec3::new(-1.0, 1.0, 1.0));
        assert!(!UNIT.hides_back_faces(&mvp(&camera, &mirror)));
        // Two mirrors keep the winding.
        let both = Mat4::scale(Vec3::new(-1.0, -1.0, 1.0));
        assert!(UNIT.hides_back_faces(&mvp(&camera, &both)));
    }
}
