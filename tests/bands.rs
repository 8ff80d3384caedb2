//! The split between the scene-sized tables and the row-sized scanner:
//! several scanners over one set of prepared tables, each over its own band
//! of rows (on threads or not), send exactly the rows one scanner sends;
//! array-backed and `Vec`-backed storage give the same frames.

mod common;

use proptest::prelude::*;
use zline::host::ScanVecs;
use zline::limits::SUBPIXEL_STEPS;
use zline::{
    Capacities, Depth16, Depth24, DepthFormat, FnSink, Renderer, ScanStorage, Scanner,
    ScreenVertex, scan,
};
use zline::{ScanArrays, TableArrays};

const W: u16 = 48;
const H: u16 = 40;
const S: i32 = SUBPIXEL_STEPS;

const CAPS: Capacities = Capacities {
    width: W as usize,
    vertices: 256,
    polygons: 32,
    corners: 256,
    active_polygons: 32,
    pooled_edges: 64,
    mesh_vertices: 0,
};

/// The frame as rows of (colour, depth), row by row as the sink got them.
type Rows = Vec<(u16, Vec<u32>, Vec<u64>)>;

fn scan_band<S: ScanStorage<Color = u32>>(
    prepared: &zline::Prepared<'_, u32>,
    scanner: &mut Scanner<S>,
    band: core::ops::Range<u16>,
) -> Rows
where
    <S::Depth as DepthFormat>::Value: Into<u64>,
{
    let mut rows = Vec::new();
    scan(
        prepared,
        scanner,
        band,
        &mut FnSink(
            |y: u16, c: &[u32], z: &[<S::Depth as DepthFormat>::Value]| {
                rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
                Ok::<(), ()>(())
            },
        ),
    )
    .unwrap();
    rows
}

fn check_bands<D: DepthFormat>(scene: &[Vec<ScreenVertex>], cuts: &[u16])
where
    D::Value: Into<u64>,
{
    let mut tables = common::scene_tables(scene, &CAPS, W, H);
    let prepared = tables.prepare();
    let mut whole = Scanner::new(ScanVecs::<u32, D>::new(&CAPS, 0).unwrap(), 0);
    let one = scan_band(&prepared, &mut whole, 0..H);
    // Bands on threads: each thread its own scanner, all sharing the
    // prepared tables.
    let mut bounds: Vec<u16> = cuts.iter().map(|c| c % (H + 1)).collect();
    bounds.extend([0, H]);
    bounds.sort_unstable();
    let bands: Vec<Rows> = std::thread::scope(|s| {
        let handles: Vec<_> = bounds
            .windows(2)
            .map(|w| {
                let (band, prepared) = (w[0]..w[1], &prepared);
                s.spawn(move || {
                    let mut scanner = Scanner::new(ScanVecs::<u32, D>::new(&CAPS, 0).unwrap(), 0);
                    scan_band(prepared, &mut scanner, band)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let joined: Rows = bands.into_iter().flatten().collect();
    assert_eq!(joined.len(), one.len(), "bands {bounds:?}");
    for (band_row, whole_row) in joined.iter().zip(&one) {
        assert_eq!(band_row, whole_row, "bands {bounds:?}, row {}", whole_row.0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn bands_on_threads_equal_one_scan(
        scene in prop::collection::vec(common::random_polygon(W, H, 10, 7), 1..=10),
        cuts in prop::collection::vec(0u16..=H, 0..4),
    ) {
        check_bands::<Depth16>(&scene, &cuts);
        check_bands::<Depth24>(&scene, &cuts);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The tables in drawing order (for the z-buffer methods: not sorted,
    /// no edge table) are refused by a scan of any band, never scanned as
    /// if sorted (which started edges below the rows they begin on).
    #[test]
    fn a_scan_of_tables_in_drawing_order_is_an_error(
        scene in prop::collection::vec(common::random_polygon(W, H, 10, 7), 1..=10),
        start in 0..H,
    ) {
        let mut tables = common::scene_tables(&scene, &CAPS, W, H);
        let in_order = tables.in_drawing_order();
        let mut scanner = Scanner::new(ScanVecs::<u32, Depth16>::new(&CAPS, 0).unwrap(), 0);
        let result = scan(
            &in_order,
            &mut scanner,
            start..H,
            &mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())),
        );
        prop_assert!(
            matches!(result, Err(zline::RenderError::Table(zline::Error::NotPrepared))),
            "{:?}",
            result
        );
    }
}

/// A small triangle two or three rows tall (at most 4 columns wide), with
/// depths far apart, anywhere in the frame.
fn small_triangle() -> impl Strategy<Value = Vec<ScreenVertex>> {
    (
        0..(i32::from(W) - 5) * S,
        0..(i32::from(H) - 4) * S,
        prop::array::uniform3((0..4 * S, 0..3 * S, 0u32..16_000_000)),
    )
        .prop_map(|(x0, y0, corners)| {
            corners
                .iter()
                .map(|&(dx, dy, z)| ScreenVertex::new(x0 + dx, y0 + dy, z).unwrap())
                .collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A band that starts on a small triangle's last row draws that row
    /// as one scan does: stepped from the triangle's first row, not as a
    /// triangle of one row (whose exact depths may differ by a step of
    /// the format). The pipeline fuzzer found it (a warped cube in bands
    /// of the banded renderer: one pixel one z16 step apart).
    #[test]
    fn bands_starting_on_a_small_triangles_last_row_equal_one_scan(
        scene in prop::collection::vec(small_triangle(), 1..=12),
    ) {
        let cuts: Vec<u16> = (1..H).collect();
        check_bands::<Depth16>(&scene, &cuts);
        check_bands::<Depth24>(&scene, &cuts);
    }
}

/// The smallest scene the property above found against the code before
/// the fix (20,000 cases): one triangle over rows 20–22, whose exact depth
/// at its last row's pixel is one z16 step from the stepped one.
#[test]
fn a_band_on_a_triangles_last_row_steps_it_from_its_first() {
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x, y, z).unwrap();
    let scene = vec![vec![
        v(8953, 5346, 6_088_302),
        v(9120, 6071, 6_631_425),
        v(9231, 5562, 3_333_644),
    ]];
    check_bands::<Depth16>(&scene, &[22]);
    let cuts: Vec<u16> = (1..H).collect();
    check_bands::<Depth16>(&scene, &cuts);
    check_bands::<Depth24>(&scene, &cuts);
}

#[test]
fn every_single_row_band_equals_one_scan() {
    // A tall triangle, a concave U and a quad: each band starts inside
    // some of them.
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x * S, y * S, z).unwrap();
    let scene = vec![
        vec![v(2, -5, 100), v(45, 10, 9_000_000), v(10, 50, 16_000_000)],
        vec![
            v(5, 5, 5_000_000),
            v(15, 5, 5_000_000),
            v(15, 30, 5_000_000),
            v(25, 30, 5_000_000),
            v(25, 5, 5_000_000),
            v(35, 5, 5_000_000),
            v(35, 38, 5_000_000),
            v(5, 38, 5_000_000),
        ],
        vec![
            v(0, 0, 8_000_000),
            v(47, 3, 8_000_000),
            v(40, 39, 1_000),
            v(3, 35, 8_000_000),
        ],
    ];
    let cuts: Vec<u16> = (1..H).collect();
    check_bands::<Depth24>(&scene, &cuts);
}

#[test]
fn array_and_vec_storage_give_the_same_frame() {
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x * S, y * S, z).unwrap();
    let scene = [
        vec![v(2, 1, 100), v(40, 12, 9_000_000), v(10, 38, 16_000_000)],
        vec![
            v(30, 2, 50),
            v(46, 30, 50),
            v(5, 20, 12_000_000),
            v(20, 6, 3_000),
        ],
    ];
    let mut fixed: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 48, 4, 4>> =
        Renderer::new(W, H, 0).unwrap();
    let mut vecs = zline::host::host_renderer::<u32, Depth16>(&CAPS, W, H, 0).unwrap();
    for (k, poly) in scene.iter().enumerate() {
        fixed.push_polygon_vertices(poly, k as u32 + 1).unwrap();
        vecs.push_polygon_vertices(poly, k as u32 + 1).unwrap();
    }
    let (mut a, mut b) = (Vec::new(), Vec::new());
    fixed
        .render(&mut FnSink(|y: u16, c: &[u32], _: &[u16]| {
            a.push((y, c.to_vec()));
            Ok::<(), ()>(())
        }))
        .unwrap();
    vecs.render(&mut FnSink(|y: u16, c: &[u32], _: &[u16]| {
        b.push((y, c.to_vec()));
        Ok::<(), ()>(())
    }))
    .unwrap();
    assert_eq!(a, b);
    assert!(a.iter().flat_map(|(_, c)| c).any(|&c| c == 1));
    assert!(a.iter().flat_map(|(_, c)| c).any(|&c| c == 2));
}

/// Scans `scene` once over the whole frame, sizes a scanner exactly by
/// that scan's [`Capacities::from_stats`], and scans every band of `cuts`
/// with it: each band must fit (no `ActiveEdgesFull`, no
/// `ActivePolygonsFull`) and the bands' rows must be the whole scan's.
fn bands_fit_the_whole_frames_capacities(
    scene: &[Vec<ScreenVertex>],
    cuts: &[u16],
    width: u16,
    height: u16,
) {
    let caps = common::small_caps(width);
    let mut tables = common::scene_tables(scene, &caps, width, height);
    let prepared = tables.prepare();
    let mut whole = Scanner::new(ScanVecs::<u32, Depth16>::new(&caps, 0).unwrap(), 0);
    let mut one = Rows::new();
    let stats = scan(
        &prepared,
        &mut whole,
        0..height,
        &mut FnSink(|y: u16, c: &[u32], z: &[u16]| {
            one.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }),
    )
    .unwrap();
    let exact = Capacities::from_stats(&stats, usize::from(width));
    let mut bounds: Vec<u16> = cuts.iter().map(|c| c % (height + 1)).collect();
    bounds.extend([0, height]);
    bounds.sort_unstable();
    let mut joined = Rows::new();
    for band in bounds.windows(2) {
        let mut scanner = Scanner::new(ScanVecs::<u32, Depth16>::new(&exact, 0).unwrap(), 0);
        let band_stats = scan(
            &prepared,
            &mut scanner,
            band[0]..band[1],
            &mut FnSink(|y: u16, c: &[u32], z: &[u16]| {
                joined.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
                Ok::<(), ()>(())
            }),
        )
        .unwrap_or_else(|e| panic!("band {band:?} at {exact:?}: {e:?}"));
        assert!(band_stats.peak_pooled_edges <= stats.peak_pooled_edges);
        assert!(band_stats.peak_active_polygons <= stats.peak_active_polygons);
    }
    assert_eq!(joined, one, "bands {bounds:?}");
}

/// Issue 28, item 1: a band that starts inside two concave quads
/// activates each with the edges crossing its first row. Their pooled
/// edges must then never outnumber one scan's: before the fix, the band
/// below row 1 kept both quads' first pair of edges inline and, when
/// those ended on row 3, held the other four in the pool, where one scan
/// over the whole frame held three.
#[test]
fn a_band_inside_concave_polygons_fits_the_frames_pooled_edges() {
    let v = |x: i32, y: i32| ScreenVertex::new(x, y, 0).unwrap();
    let scene = vec![
        vec![v(0, 0), v(0, 385), v(0, 129), v(129, 1665)],
        vec![v(0, 1665), v(0, 0), v(0, 1666), v(129, 385)],
    ];
    bands_fit_the_whole_frames_capacities(&scene, &[1], 41, 12);
    let cuts: Vec<u16> = (1..12).collect();
    bands_fit_the_whole_frames_capacities(&scene, &cuts, 41, 12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any cut of any scene of concave polygons: scanners sized exactly
    /// by the whole frame's statistics draw every band.
    #[test]
    fn bands_fit_capacities_from_the_whole_frames_stats(
        scene in prop::collection::vec(common::random_polygon(41, 12, 3, 6), 1..=4),
        cuts in prop::collection::vec(0u16..=12, 1..4),
    ) {
        bands_fit_the_whole_frames_capacities(&scene, &cuts, 41, 12);
    }
}
