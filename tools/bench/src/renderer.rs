//! What the harness asks of every renderer, zline and the peers alike.

/// One renderer, built for one mesh and one view.
pub trait Renderer {
    /// The name in the CSV and the table: one name per row kind
    /// (`zline z24`, `zline z16 drawtarget`, `embedded-3dgfx lit`, `euc`…).
    fn name(&self) -> &str;

    /// What [`Self::render`] does, in one line for the report.
    fn timed_region(&self) -> String;

    /// Whether the harness times [`Self::render`] by the wall clock (a
    /// renderer that works on several threads) rather than by the calling
    /// thread's CPU time (the default).
    fn wall_clock(&self) -> bool {
        false
    }

    /// Draws one whole frame of the view: the timed region. What exactly
    /// that includes is stated on each implementation.
    fn render(&mut self) -> Result<(), String>;

    /// The visible face id per pixel for the last frame, row-major from the
    /// top ([`crate::view::BACKGROUND`] where none), or `None` when the
    /// renderer cannot tell. Called after [`Self::render`], untimed; it may
    /// draw the frame again.
    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String>;

    /// The last frame's colours as raw Rgb565, row-major from the top
    /// (for image dumps).
    fn rgb565(&self) -> Vec<u16>;
}
