//! A sink that lends the scanner its own row buffers (`RowSink::lend_row`)
//! gets exactly the rows a copying sink gets: whether its buffers arrive
//! black (`filled`) or hold an old row, whatever the scene, whole or in
//! bands; a buffer too short for the row is an error, not a cut row.

mod common;

use proptest::prelude::*;
use zline::host::ScanVecs;
use zline::raster::fixed::SUBPIXEL_STEPS;
use zline::{
    Depth16, Depth24, DepthFormat, Error, FnSink, LentRow, RenderError, RowSink, Scanner,
    ScreenVertex, scan,
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
        ScanVecs::<u32, D>::new(&common::small_caps(W), 0),
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
        ScanVecs::<u32, D>::new(&common::small_caps(W), 0),
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

#[test]
fn a_buffer_shorter_than_the_row_is_an_error() {
    let scene = vec![vec![
        ScreenVertex::new(S, S, 100).unwrap(),
        ScreenVertex::new(30 * S, 2 * S, 100).unwrap(),
        ScreenVertex::new(9 * S, 20 * S, 100).unwrap(),
    ]];
    let mut tables = common::scene_tables(&scene, &common::small_caps(W), W, H);
    let prepared = tables.prepare();
    let mut scanner = Scanner::new(
        ScanVecs::<u32, Depth16>::new(&common::small_caps(W), 0),
        BACKGROUND,
    );
    let mut lender = Lender::new(usize::from(W) - 1, true);
    let result = scan(&prepared, &mut scanner, 0..H, &mut lender);
    assert!(matches!(
        result,
        Err(RenderError::Table(Error::BadFrameSize))
    ));
    assert!(lender.rows.is_empty());
}
