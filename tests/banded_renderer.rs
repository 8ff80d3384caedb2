//! The banded renderer (`zline::host::BandedRenderer`): a frame cut into
//! bands of rows, each band with tables of its own built from the whole
//! scene on a thread of its own, sends exactly the rows one renderer sends,
//! wherever the cuts lie and after they move to balance the work.

mod common;

use std::time::Duration;

use proptest::prelude::*;
use zline::PolygonTables;
use zline::host::{BandTables, BandedRenderer, host_renderer};
use zline::limits::SUBPIXEL_STEPS;
use zline::{Admission, Capacities, Depth16, Depth24, DepthFormat, Error, FnSink, ScreenVertex};
use zline::{Camera, Cull, VertexCache, draw_mesh, reference_model};
use zline_lab::shapes;

const W: u16 = 48;
const H: u16 = 40;
const S: i32 = SUBPIXEL_STEPS;

const CAPS: Capacities = Capacities {
    width: W as usize,
    vertices: 512,
    polygons: 64,
    corners: 512,
    active_polygons: 64,
    pooled_edges: 128,
    mesh_vertices: 0,
};

/// A frame as (row, colours, depths), in the order the sinks got the rows.
type Rows = Vec<(u16, Vec<u32>, Vec<u64>)>;

/// Offers `scene` (polygon k in colour k + 1) to `tables`, as a scene
/// builder would: vertices, then each polygon by its corners.
fn offer<T: PolygonTables<u32> + ?Sized>(tables: &mut T, scene: &[Vec<ScreenVertex>]) {
    for (k, polygon) in scene.iter().enumerate() {
        let ids: Vec<u16> = polygon
            .iter()
            .map(|&v| tables.add_vertex(v).unwrap())
            .collect();
        tables.offer_polygon(ids, |_| Some(k as u32 + 1)).unwrap();
    }
}

/// One renderer's rows of `build`'s scene.
fn whole<D: DepthFormat>(
    caps: &Capacities,
    (width, height): (u16, u16),
    build: impl Fn(&mut zline::host::HostRenderer<u32, D>),
) -> Rows
where
    D::Value: Into<u64>,
{
    let mut renderer = host_renderer::<u32, D>(caps, width, height, 0).unwrap();
    build(&mut renderer);
    let mut rows = Rows::new();
    renderer
        .render(&mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }))
        .unwrap();
    rows
}

/// The banded renderer's rows of one frame, band after band.
fn banded<D: DepthFormat, X: Send>(
    renderer: &mut BandedRenderer<u32, D>,
    scratch: &mut [X],
    build: impl Fn(&mut BandTables<'_, zline::Tables<zline::host::TableVecs<u32>>>, &mut X) + Sync,
) -> Rows
where
    D::Value: Into<u64> + Send,
{
    let n = renderer.bands().count();
    let mut bands: Vec<Rows> = vec![Rows::new(); n];
    let mut sinks: Vec<_> = bands
        .iter_mut()
        .map(|rows| {
            FnSink(move |y: u16, c: &[u32], z: &[D::Value]| {
                rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
                Ok::<(), ()>(())
            })
        })
        .collect();
    renderer
        .render(scratch, &mut sinks, |tables, x| {
            build(tables, x);
            Ok(())
        })
        .unwrap();
    drop(sinks);
    bands.into_iter().flatten().collect()
}

fn check_scene<D: DepthFormat>(scene: &[Vec<ScreenVertex>], count: usize, cuts: &[u16])
where
    D::Value: Into<u64> + Send,
{
    let one = whole::<D>(&CAPS, (W, H), |r| offer(r, scene));
    let mut renderer = BandedRenderer::<u32, D>::new(&CAPS, W, H, 0, count).unwrap();
    let mut bounds: Vec<u16> = cuts.iter().map(|c| 1 + c % (H - 1)).collect();
    bounds.sort_unstable();
    bounds.dedup();
    if bounds.len() + 1 == count {
        renderer.set_cuts(&bounds).unwrap();
    }
    let mut scratch = vec![(); count];
    // The second frame runs with the cuts the first one balanced.
    for frame in 0..2 {
        let cuts: Vec<_> = renderer.bands().collect();
        let rows = banded(&mut renderer, &mut scratch, |t, _| offer(t, scene));
        assert_eq!(rows, one, "frame {frame}, bands {cuts:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn banded_frames_equal_one_renderers(
        scene in prop::collection::vec(common::random_polygon(W, H, 10, 7), 1..=10),
        count in 1usize..=4,
        cuts in prop::collection::vec(0u16..H, 0..4),
    ) {
        check_scene::<Depth16>(&scene, count, &cuts);
        check_scene::<Depth24>(&scene, count, &cuts);
    }
}

#[test]
fn a_mesh_in_bands_equals_one_renderer_culled_or_not() {
    let mesh = shapes::torus_knot(2, 3, 64, 8, 0.45);
    let (width, height) = (96, 72);
    let caps = Capacities {
        width: usize::from(width),
        vertices: 4096,
        polygons: 2048,
        corners: 8192,
        active_polygons: 2048,
        pooled_edges: 256,
        mesh_vertices: 0,
    };
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let camera = Camera::reference(width, height);
    for cull in [Cull::None, Cull::Back] {
        let one = whole::<Depth16>(&caps, (width, height), |r| {
            let mut cache = Box::new(VertexCache::<4096>::new());
            draw_mesh(r, &mut *cache, &mesh, &model, &camera, cull, |f| f.face + 1).unwrap();
        });
        assert!(one.iter().flat_map(|r| &r.1).filter(|&&c| c != 0).count() > 1000);
        for count in 1..=4 {
            let mut renderer =
                BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, count).unwrap();
            let mut caches: Vec<Box<VertexCache<4096>>> =
                (0..count).map(|_| Box::new(VertexCache::new())).collect();
            for frame in 0..3 {
                let rows = banded(&mut renderer, &mut caches, |t, cache| {
                    draw_mesh(t, &mut **cache, &mesh, &model, &camera, cull, |f| {
                        f.face + 1
                    })
                    .unwrap();
                });
                assert_eq!(rows, one, "{cull:?}, {count} bands, frame {frame}");
            }
        }
    }
}

#[test]
fn band_tables_decline_what_misses_the_band() {
    let mut renderer = host_renderer::<u32, Depth16>(&CAPS, W, H, 0).unwrap();
    let mut band = BandTables::new(&mut renderer.tables, 10..20);
    assert_eq!(band.rows(), 10..20);
    let mut offer_triangle = |a, b, c| {
        let ids = [a, b, c].map(|p| band.add_vertex(p).unwrap());
        band.offer_triangle(ids, |_| Some(7))
    };
    // Rows 0 to 5, and rows 20 to 29: outside.
    assert_eq!(
        offer_triangle(at(0, 0), at(20, 0), at(0, 6)),
        Ok(Admission::Declined)
    );
    assert_eq!(
        offer_triangle(at(0, 20), at(20, 20), at(0, 30)),
        Ok(Admission::Declined)
    );
    // Rows 5 to 10 (its last sample row is the band's first), and one off
    // the frame: queued, and counted off-screen as ever.
    assert_eq!(
        offer_triangle(at(0, 5), at(20, 5), at(0, 11)),
        Ok(Admission::Queued(0))
    );
    assert_eq!(
        offer_triangle(at(-30, 12), at(-20, 12), at(-30, 18)),
        Ok(Admission::OffScreen)
    );
    assert_eq!(renderer.polygon_count(), 1);
}

#[test]
fn cuts_move_to_where_the_polygons_are() {
    // Thin triangles starting on rows 30 to 39 only.
    let scene: Vec<Vec<ScreenVertex>> = (0..40)
        .map(|k| {
            let (x, y) = (k % 40, 30 + k / 4);
            vec![at(x, y), at(x + 2, y), at(x, y + 1)]
        })
        .collect();
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&CAPS, W, H, 0, 2).unwrap();
    assert_eq!(renderer.bands().collect::<Vec<_>>(), [0..20, 20..40]);
    let rows = banded(&mut renderer, &mut [(), ()], |t, _| offer(t, &scene));
    assert_eq!(rows, whole::<Depth16>(&CAPS, (W, H), |r| offer(r, &scene)));
    // The last frame's account: drawn with the first cuts, every polygon
    // in the lower band.
    let last: Vec<_> = renderer
        .last_frame()
        .map(|t| (t.rows.clone(), t.polygons))
        .collect();
    assert_eq!(last, [(0..20, 0), (20..40, 40)]);
    // Each of rows 30 to 39 holds 4 activations and 4 active polygons:
    // 4 + 4·5 + 4 = 28 units, the others 4 (see `Band::work`). Half the
    // total, (40·4 + 10·24)/2 = 200, is reached on row 32.
    assert_eq!(renderer.bands().collect::<Vec<_>>(), [0..33, 33..40]);
}

/// A vertex at pixel corner `(x, y)`, at one depth.
fn at(x: i32, y: i32) -> ScreenVertex {
    ScreenVertex::new(x * S, y * S, 1000).unwrap()
}

/// Ten thin triangles from the top of the frame (row 0) to the bottom
/// (row 40), side by side.
fn tall_triangles() -> Vec<Vec<ScreenVertex>> {
    (0..10)
        .map(|k| vec![at(4 * k, 0), at(4 * k + 3, 0), at(4 * k, 40)])
        .collect()
}

/// Work is counted on every row a polygon is active, not only where it
/// starts: ten triangles from the top of the frame to the bottom put the
/// cut near the middle (counting activations alone put it at row 15).
#[test]
fn cuts_follow_the_rows_polygons_are_active_on() {
    let scene = tall_triangles();
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&CAPS, W, H, 0, 2).unwrap();
    renderer.set_cuts(&[5]).unwrap();
    let rows = banded(&mut renderer, &mut [(), ()], |t, _| offer(t, &scene));
    assert_eq!(rows, whole::<Depth16>(&CAPS, (W, H), |r| offer(r, &scene)));
    // Rows hold 4 units of their own and 1 per active polygon (10 on
    // every row), and 5 per activation: the ten on row 0, and again on
    // row 5, the lower band's first row. Of 40·14 + 2·50 = 660 units, half
    // is reached on row 16 (64 + 4·14 + 64 + 10·14 = 324, plus 14).
    assert_eq!(renderer.bands().collect::<Vec<_>>(), [0..17, 17..40]);
}

/// Three bands share the work in thirds: the ten tall triangles again,
/// from cuts after rows 0 and 1. A frame whose work lies on one row cuts
/// after it and after the next (one cut a row), or, on the last row,
/// leaves the cuts where they were (each band keeps at least one row).
#[test]
fn three_bands_share_the_work_in_thirds() {
    let tall = tall_triangles();
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&CAPS, W, H, 0, 3).unwrap();
    renderer.set_cuts(&[1, 2]).unwrap();
    let rows = banded(&mut renderer, &mut [(), (), ()], |t, _| offer(t, &tall));
    assert_eq!(rows, whole::<Depth16>(&CAPS, (W, H), |r| offer(r, &tall)));
    // Activations on rows 0, 1 and 2 (50 units each), 14 a row: of 660
    // units, a third is reached on row 6 and two thirds on row 23.
    assert_eq!(renderer.bands().collect::<Vec<_>>(), [0..7, 7..24, 24..40]);
    // Forty triangles on one row (6 units each, 240 of 400): a third and
    // two thirds of the work are both reached on that row. On row 20 the
    // cuts go after it and after the next row (one cut a row); on the last
    // row the second cut would leave the last band no row, and the cuts
    // stay where they were.
    let flat = |row: i32| -> Vec<Vec<ScreenVertex>> {
        (0..40)
            .map(|k| vec![at(k, row), at(k + 3, row), at(k, row + 1)])
            .collect()
    };
    for (row, cuts) in [(20, [0..21, 21..22, 22..40]), (39, [0..5, 5..10, 10..40])] {
        renderer.set_cuts(&[5, 10]).unwrap();
        let scene = flat(row);
        let rows = banded(&mut renderer, &mut [(), (), ()], |t, _| offer(t, &scene));
        assert_eq!(rows, whole::<Depth16>(&CAPS, (W, H), |r| offer(r, &scene)));
        assert_eq!(renderer.bands().collect::<Vec<_>>(), cuts, "row {row}");
    }
}

#[test]
fn bad_bands_and_cuts_are_errors() {
    let new = |count| BandedRenderer::<u32, Depth16>::new(&CAPS, W, H, 0, count).map(|_| ());
    assert_eq!(new(0), Err(Error::BadFrameSize));
    assert_eq!(new(usize::from(H) + 1), Err(Error::BadFrameSize));
    assert_eq!(new(usize::from(H)), Ok(()));
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&CAPS, W, H, 0, 3).unwrap();
    for cuts in [
        &[10][..],
        &[10, 20, 30],
        &[20, 10],
        &[10, 10],
        &[0, 10],
        &[10, H],
    ] {
        assert_eq!(
            renderer.set_cuts(cuts),
            Err(Error::BadFrameSize),
            "{cuts:?}"
        );
    }
    assert_eq!(renderer.set_cuts(&[1, H - 1]), Ok(()));
    assert_eq!(
        renderer.bands().collect::<Vec<_>>(),
        [0..1, 1..H - 1, H - 1..H]
    );
    // One scratch entry or sink per band.
    let mut sinks: Vec<_> = (0..2)
        .map(|_| FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .collect();
    let result = renderer.render(&mut [(), (), ()], &mut sinks, |_, _| Ok(()));
    assert_eq!(
        result.err(),
        Some(zline::RenderError::Table(Error::BadFrameSize))
    );
    let mut sinks: Vec<_> = (0..3)
        .map(|_| FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .collect();
    let result = renderer.render(&mut [(), ()], &mut sinks, |_, _| Ok(()));
    assert_eq!(
        result.err(),
        Some(zline::RenderError::Table(Error::BadFrameSize))
    );
    let result = renderer.render(&mut [(), (), ()], &mut sinks, |_, _| Ok(()));
    assert!(result.is_ok());
}

/// The threads each band's sink was called on, in one frame of `mesh`
/// drawn by `renderer` (two bands).
fn sink_threads(
    renderer: &mut BandedRenderer<u32, Depth16>,
    mesh: &zline::host::HostMesh,
    size: (u16, u16),
) -> Vec<std::thread::ThreadId> {
    let model = reference_model(mesh, 30.0, 20.0).unwrap();
    let camera = Camera::reference(size.0, size.1);
    let mut threads = vec![None; 2];
    let mut sinks: Vec<_> = threads
        .iter_mut()
        .map(|id| {
            FnSink(move |_: u16, _: &[u32], _: &[u16]| {
                *id = Some(std::thread::current().id());
                Ok::<(), ()>(())
            })
        })
        .collect();
    renderer
        .render_mesh(mesh, &model, &camera, Cull::None, &mut sinks, |f| f.face)
        .unwrap();
    drop(sinks);
    threads.into_iter().map(|id| id.unwrap()).collect()
}

/// A frame whose bands had less work the frame before than the limit
/// (and the first frame, with the default limit) is drawn on the calling
/// thread alone; a frame of more work gives each band a thread. The
/// limit decides, not the clock: with it at zero every frame has threads,
/// at its largest none.
#[test]
fn small_frames_stay_on_the_calling_thread() {
    let here = std::thread::current().id();
    let caps = Capacities {
        width: 96,
        vertices: 16384,
        polygons: 16384,
        corners: 49152,
        active_polygons: 16384,
        pooled_edges: 256,
        mesh_vertices: 0,
    };
    // Two triangles: microseconds of work.
    let small = zline::host::HostMesh {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.2],
        ],
        corners: vec![0, 1, 2, 0, 3, 1],
        face_starts: vec![0, 3],
        ..Default::default()
    };
    let big = shapes::torus_knot(2, 3, 1024, 8, 0.45);
    let new = || BandedRenderer::<u32, Depth16>::new(&caps, 96, 72, 0, 2).unwrap();
    // The default limit: the first frame (no work before it) stays.
    for mesh in [&small, &big] {
        assert_eq!(sink_threads(&mut new(), mesh, (96, 72)), [here, here]);
    }
    // No limit: threads from the first frame on, however small.
    let mut renderer = new();
    renderer.set_one_thread_below(Duration::ZERO);
    for frame in 0..2 {
        let threads = sink_threads(&mut renderer, &small, (96, 72));
        assert_eq!(threads[0], here, "frame {frame}");
        assert_ne!(threads[1], here, "frame {frame}");
    }
    // The largest limit: never, however large.
    let mut renderer = new();
    renderer.set_one_thread_below(Duration::MAX);
    for frame in 0..2 {
        assert_eq!(
            sink_threads(&mut renderer, &big, (96, 72)),
            [here, here],
            "frame {frame}"
        );
    }
    // A limit between the two frames' work: the small mesh's frame after
    // the large one's has threads, the large one's after the small one's
    // has none.
    // Each frame's work is its least of three (a loaded machine only
    // lengthens them), and the limit their geometric mean: the two differ
    // about a thousandfold, so either would have to take some thirty
    // times its least for a frame to land on the wrong side.
    let mut renderer = new();
    let mut least = |mesh| {
        (0..3)
            .map(|_| {
                sink_threads(&mut renderer, mesh, (96, 72));
                renderer
                    .last_frame()
                    .map(|b| b.build + b.scan)
                    .sum::<Duration>()
            })
            .min()
            .unwrap_or_default()
    };
    let big_work = least(&big);
    let small_work = least(&small);
    assert!(small_work * 30 < big_work, "{small_work:?} {big_work:?}");
    let limit = (small_work.as_secs_f64() * big_work.as_secs_f64()).sqrt();
    renderer.set_one_thread_below(Duration::from_secs_f64(limit));
    sink_threads(&mut renderer, &big, (96, 72));
    assert_ne!(sink_threads(&mut renderer, &small, (96, 72))[1], here);
    assert_eq!(sink_threads(&mut renderer, &big, (96, 72)), [here, here]);
}

/// Issue 28, item 1: a banded renderer sized exactly by one renderer's
/// [`Capacities::from_stats`] draws every cut of a scene of concave
/// polygons (a band starting inside a concave polygon once needed more
/// pooled edges than the whole frame).
fn check_exact_capacities(scene: &[Vec<ScreenVertex>], cuts: &[u16]) {
    let (width, height) = (41u16, 12u16);
    let mut one = host_renderer::<u32, Depth16>(&CAPS, width, height, 0).unwrap();
    offer(&mut one, scene);
    let mut rows = Rows::new();
    let stats = one
        .render(&mut FnSink(|y: u16, c: &[u32], z: &[u16]| {
            rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }))
        .unwrap();
    let exact = Capacities::from_stats(&stats, usize::from(width));
    let mut bounds: Vec<u16> = cuts.iter().map(|c| 1 + c % (height - 1)).collect();
    bounds.sort_unstable();
    bounds.dedup();
    let mut renderer =
        BandedRenderer::<u32, Depth16>::new(&exact, width, height, 0, bounds.len() + 1).unwrap();
    renderer.set_cuts(&bounds).unwrap();
    renderer.set_one_thread_below(Duration::ZERO);
    let mut scratch = vec![(); bounds.len() + 1];
    let banded_rows = banded(&mut renderer, &mut scratch, |t, _| offer(t, scene));
    assert_eq!(banded_rows, rows, "cuts {bounds:?} at {exact:?}");
}

#[test]
fn exact_capacities_fit_a_band_inside_concave_quads() {
    let v = |x: i32, y: i32| ScreenVertex::new(x, y, 0).unwrap();
    let scene = vec![
        vec![v(0, 0), v(0, 385), v(0, 129), v(129, 1665)],
        vec![v(0, 1665), v(0, 0), v(0, 1666), v(129, 385)],
    ];
    check_exact_capacities(&scene, &[0]);
    check_exact_capacities(&scene, &[1]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn exact_capacities_fit_every_band(
        scene in prop::collection::vec(common::random_polygon(41, 12, 3, 6), 1..=4),
        cuts in prop::collection::vec(0u16..12, 1..4),
    ) {
        check_exact_capacities(&scene, &cuts);
    }
}
