//! A sink that lends the scanner its own row buffers (`RowSink::lend_row`)
//! gets exactly the rows a copying sink gets: whether its buffers arrive
//! black (`filled`) or hold an old row, whatever the scene, whole or in
//! bands; a buffer too short for the row is an error, not a cut row.

mod common;

use proptest::prelude::*;
use zline::host::ScanVecs;
use zline::limits::SUBPIXEL_STEPS;
use zline::{
    Depth16, Depth24, DepthFormat, Error, FnSink, FrameBufferSink, LentRow, RenderError, RowSink,
    Scanner, ScreenVertex, scan,
};

const W: u16 = 40;
const H: u16 = 32;
const S: i32 = SUBPIXEL_STEPS;
const BACKGROUND: u32 = 0xB1AC;

/// Rows as a sink received them: `(y, colours, depths)`.
type Rows = Vec<(u16, Vec<u32>, Vec<u64>)>;

/// Lends one buffer of `len` entries. When `filled` it refills it with the
/// background after each row, as a DMA-clearing sink would; otherwise the
/// buffer keeps the last row plus a stripe of junk.
struct Lender {
    buffer: Vec<u32>,
    filled: bool,
    lent: Option<u16>,
    rows: Rows,
}

impl Lender {
    fn new(len: usize, filled: bool) -> Self {
        let fill = if filled { BACKGROUND } else { 0xDEAD };
        Self {
            buffer: vec![fill; len],
            filled,
            lent: None,
            rows: Vec::new(),
        }
    }
}

impl<Z: Copy + Into<u64>> RowSink<u32, Z> for Lender {
    type Error = &'static str;

    fn write_row(&mut self, _: u16, _: &[u32], _: &[Z]) -> Result<(), Self::Error> {
        Err("write_row called on a lending sink")
    }

    fn lend_row(
        &mut self,
        y: u16,
        width: usize,
        background: u32,
    ) -> Result<Option<LentRow<'_, u32>>, Self::Error> {
        if self.lent.replace(y).is_some() {
            return Err("lent twice");
        }
        assert_eq!(background, BACKGROUND);
        assert_eq!(width, usize::from(W));
        Ok(Some(LentRow {
            colors: &mut self.buffer,
            filled: self.filled,
        }))
    }

    fn send_lent_row(&mut self, y: u16, depths: &[Z]) -> Result<(), Self::Error> {
        if self.lent.take() != Some(y) {
            return Err("sent a row that was not lent");
        }
        let width = depths.len();
        let depths = depths.iter().map(|&z| z.into()).collect();
        self.rows.push((y, self.buffer[..width].to_vec(), depths));
        if self.filled {
            self.buffer.fill(BACKGROUND);
        } else if let Some(junk) = self.buffer.get_mut(y as usize % width) {
            *junk = 0xBAD;
        }
        Ok(())
    }
}

/// The rows of `band` through a copying sink, and through a lending one.
fn both<D: DepthFormat>(
    scene: &[Vec<ScreenVertex>],
    band: core::ops::Range<u16>,
    filled: bool,
) -> (Rows, Rows)
where
    D::Value: Into<u64>,
{
    let mut tables = common::scene_tables(scene, &common::small_caps(W), W, H);
    let prepared = tables.prepare();
    let mut copied = Vec::new();
    let mut scanner = Scanner::new(
        ScanVecs::<u32, D>::new(&common::small_caps(W), 0).unwrap(),
        BACKGROUND,
    );
    scan(
        &prepared,
        &mut scanner,
        band.clone(),
        &mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            copied.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }),
    )
    .unwrap();
    // A buffer longer than the row: only the row's part is used.
    let mut lender = Lender::new(usize::from(W) + 3, filled);
    let mut scanner = Scanner::new(
        ScanVecs::<u32, D>::new(&common::small_caps(W), 0).unwrap(),
        BACKGROUND,
    );
    scan(&prepared, &mut scanner, band, &mut lender).unwrap();
    assert_eq!(lender.lent, None, "a lent row was never sent");
    (copied, lender.rows)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn lent_rows_equal_copied_rows(
        scene in prop::collection::vec(common::random_polygon(W, H, 8, 6), 1..=10),
        start in 0u16..H,
        filled: bool,
    ) {
        for (copied, lent) in [
            both::<Depth16>(&scene, 0..H, filled),
            both::<Depth24>(&scene, 0..H, filled),
            both::<Depth16>(&scene, start..H, filled),
        ] {
            prop_assert_eq!(copied.len(), lent.len());
            for (c, l) in copied.iter().zip(&lent) {
                prop_assert_eq!(c, l);
            }
        }
    }
}

#[test]
fn an_unfilled_buffer_is_cleared_and_tiny_triangles_land_in_it() {
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x, y, z).unwrap();
    // A large triangle and a one-row sliver, drawn at activation.
    let scene = vec![
        vec![
            v(2 * S, S, 1000),
            v(30 * S, 5 * S, 2000),
            v(8 * S, 25 * S, 3000),
        ],
        vec![
            v(20 * S, 10 * S + 100, 500),
            v(24 * S, 10 * S + 120, 500),
            v(22 * S, 10 * S + 140, 500),
        ],
    ];
    let (copied, lent) = both::<Depth16>(&scene, 0..H, false);
    assert_eq!(copied, lent);
    // The rows are not all background: the test sees drawn pixels.
    assert!(lent.iter().any(|(_, c, _)| c.contains(&2)));
    assert!(lent.iter().any(|(_, c, _)| c.contains(&1)));
    assert!(
        lent.iter()
            .all(|(_, c, _)| c.iter().all(|&p| p <= 2 || p == BACKGROUND))
    );
}

/// One triangle across most of the frame.
fn one_triangle() -> Vec<Vec<ScreenVertex>> {
    vec![vec![
        ScreenVertex::new(S, S, 100).unwrap(),
        ScreenVertex::new(30 * S, 2 * S, 100).unwrap(),
        ScreenVertex::new(9 * S, 20 * S, 100).unwrap(),
    ]]
}

/// A z16 scanner for the frame, on `Vec`s.
fn z16_scanner() -> Scanner<ScanVecs<u32, Depth16>> {
    Scanner::new(
        ScanVecs::<u32, Depth16>::new(&common::small_caps(W), 0).unwrap(),
        BACKGROUND,
    )
}

#[test]
fn a_buffer_shorter_than_the_row_is_an_error() {
    let mut tables = common::scene_tables(&one_triangle(), &common::small_caps(W), W, H);
    let prepared = tables.prepare();
    let mut scanner = z16_scanner();
    let mut lender = Lender::new(usize::from(W) - 1, true);
    let result = scan(&prepared, &mut scanner, 0..H, &mut lender);
    assert!(matches!(
        result,
        Err(RenderError::Table(Error::BadFrameSize))
    ));
    assert!(lender.rows.is_empty());
}

/// The frame a copying sink assembles from `rows` (`width` pixels each).
fn frame_of(rows: &Rows, width: usize, height: usize) -> Vec<u32> {
    let mut frame = vec![0; width * height];
    for (y, colors, _) in rows {
        frame[usize::from(*y) * width..][..width].copy_from_slice(colors);
    }
    frame
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// `FrameBufferSink` draws in place the frame a copying sink gets, the
    /// whole frame at once or in two bands into their parts of it, over
    /// a frame that held something else.
    #[test]
    fn a_frame_buffer_sink_gets_the_copied_frame(
        scene in prop::collection::vec(common::random_polygon(W, H, 8, 6), 1..=10),
        cut in 0u16..=H,
    ) {
        let (copied, _) = both::<Depth16>(&scene, 0..H, false);
        let (w, h) = (usize::from(W), usize::from(H));
        let want = frame_of(&copied, w, h);
        let mut tables = common::scene_tables(&scene, &common::small_caps(W), W, H);
        let prepared = tables.prepare();
        let mut scanner = z16_scanner();
        let mut frame = vec![0xDEAD; w * h];
        scan(&prepared, &mut scanner, 0..H, &mut FrameBufferSink::new(&mut frame, w)).unwrap();
        prop_assert_eq!(&frame, &want);
        let mut banded = vec![0xDEAD; w * h];
        let (top, bottom) = banded.split_at_mut(usize::from(cut) * w);
        scan(&prepared, &mut scanner, 0..cut, &mut FrameBufferSink::new(top, w)).unwrap();
        let mut lower = FrameBufferSink::from_row(bottom, w, cut);
        scan(&prepared, &mut scanner, cut..H, &mut lower).unwrap();
        prop_assert_eq!(&banded, &want);
    }
}

#[test]
fn a_frame_buffer_too_small_or_too_narrow_is_an_error() {
    let mut tables = common::scene_tables(&one_triangle(), &common::small_caps(W), W, H);
    let prepared = tables.prepare();
    let mut scanner = z16_scanner();
    let (w, h) = (usize::from(W), usize::from(H));
    // One pixel short of the last row; rows narrower than the frame's;
    // a band's sink asked for a row above its band.
    let mut short = vec![0; w * h - 1];
    let mut narrow = vec![0; w * h];
    let mut band = vec![0; w * h];
    let results = [
        scan(
            &prepared,
            &mut scanner,
            0..H,
            &mut FrameBufferSink::new(&mut short, w),
        ),
        scan(
            &prepared,
            &mut scanner,
            0..H,
            &mut FrameBufferSink::new(&mut narrow, w - 1),
        ),
        scan(
            &prepared,
            &mut scanner,
            0..H,
            &mut FrameBufferSink::from_row(&mut band, w, 1),
        ),
    ];
    for result in results {
        assert!(
            matches!(result, Err(RenderError::Sink(Error::BadFrameSize))),
            "{result:?}"
        );
    }
    // Every row but the last one was drawn before the short buffer ran out.
    assert_ne!(short[w..2 * w], vec![0; w][..]);
}
