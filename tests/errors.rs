//! Capacities and bad input: every overflow is the documented error and
//! leaves the tables as they were; degenerate and edge-on polygons neither
//! panic nor draw garbage.

mod common;

use common::{capture, vtx};
use zline::limits::{DEPTH_MAX, GUARD_BAND, MAX_POLYGON_CORNERS, SUBPIXEL_STEPS};
use zline::{Admission, Depth16, Depth24, Error, FnSink, RenderError, Renderer, ScreenVertex};
use zline::{
    EdgeEntry, PolygonEntry, ScanArrays, TableArrays, TableParts, TablePartsRef, TableStorage,
    Tables,
};

const S: i32 = SUBPIXEL_STEPS;

fn tri(x: f32, y: f32) -> [ScreenVertex; 3] {
    [vtx(x, y, 0.5), vtx(x + 4.0, y, 0.5), vtx(x, y + 4.0, 0.5)]
}

#[test]
fn vertex_table_full() {
    let mut r: Renderer<TableArrays<u32, 4, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    for _ in 0..4 {
        r.push_vertex(vtx(1.0, 1.0, 0.5)).unwrap();
    }
    assert_eq!(
        r.push_vertex(vtx(1.0, 1.0, 0.5)),
        Err(Error::VertexTableFull)
    );
    assert_eq!(r.vertex_count(), 4);
    // A polygon needing 3 more vertices fails whole: nothing half-added.
    let mut r: Renderer<TableArrays<u32, 5, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&tri(1.0, 1.0), 1).unwrap();
    assert_eq!(
        r.push_polygon_vertices(&tri(5.0, 5.0), 2),
        Err(Error::VertexTableFull)
    );
    assert_eq!((r.vertex_count(), r.polygon_count()), (3, 1));
}

#[test]
fn polygon_table_full() {
    let mut r: Renderer<TableArrays<u32, 16, 2, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&tri(1.0, 1.0), 1).unwrap();
    r.push_polygon_vertices(&tri(5.0, 5.0), 2).unwrap();
    assert_eq!(
        r.push_polygon_vertices(&tri(9.0, 9.0), 3),
        Err(Error::PolygonTableFull)
    );
    assert_eq!((r.vertex_count(), r.polygon_count()), (6, 2));
}

#[test]
fn edge_table_full() {
    // E = 5: one triangle (3 corners) fits, a second does not.
    let mut r: Renderer<TableArrays<u32, 16, 4, 5>, ScanArrays<u32, Depth16, 16, 4, 5>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&tri(1.0, 1.0), 1).unwrap();
    assert_eq!(
        r.push_polygon_vertices(&tri(5.0, 5.0), 2),
        Err(Error::EdgeTableFull)
    );
    assert_eq!((r.vertex_count(), r.polygon_count()), (3, 1));
}

/// Table storage of one's own whose edge table is shorter than its corner
/// list: 12 corners, room in the edge table for 7.
struct ShortEdgeTable {
    vertices: [ScreenVertex; 16],
    polygons: [PolygonEntry<u32>; 4],
    corners: [u16; 12],
    edges: [EdgeEntry; 7],
}

impl TableStorage for ShortEdgeTable {
    type Color = u32;
    fn parts_mut(&mut self) -> TableParts<'_, u32> {
        TableParts {
            vertices: &mut self.vertices,
            polygons: &mut self.polygons,
            corners: &mut self.corners,
            edges: &mut self.edges,
        }
    }
    fn parts(&self) -> TablePartsRef<'_, u32> {
        TablePartsRef {
            vertices: &self.vertices,
            polygons: &self.polygons,
            corners: &self.corners,
            edges: &self.edges,
        }
    }
}

#[test]
fn a_short_edge_table_bounds_the_corners() {
    // The edge table is the sort's scratch and holds up to one entry per
    // corner: with 7 entries, two triangles fit (6 corners) and a third is
    // refused, by either way in, and preparing the tables does not fail.
    for offer in [false, true] {
        let storage = ShortEdgeTable {
            vertices: [ScreenVertex::default(); 16],
            polygons: [PolygonEntry::filler(0); 4],
            corners: [0; 12],
            edges: [EdgeEntry::ZERO; 7],
        };
        let mut tables = Tables::new(storage, 16, 16).unwrap();
        let mut results = Vec::new();
        for k in 0..3 {
            let x = 1.0 + 4.0 * k as f32;
            let ids = tri(x, 1.0).map(|v| tables.push_vertex(v).unwrap());
            results.push(if offer {
                tables.offer_triangle(ids, |_| Some(k))
            } else {
                tables.push_polygon(&ids, k)
            });
        }
        assert!(
            matches!(results[0], Ok(Admission::Queued(_))),
            "{results:?}"
        );
        assert!(
            matches!(results[1], Ok(Admission::Queued(_))),
            "{results:?}"
        );
        assert_eq!(results[2], Err(Error::EdgeTableFull), "offer {offer}");
        assert_eq!(tables.polygon_count(), 2);
        let prepared = tables.prepare();
        assert_eq!(prepared.width(), 16);
    }
}

#[test]
fn active_tables_full_stop_the_frame_at_the_row() {
    // Three triangles overlapping rows 4..8, but only two active polygons.
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 2, 16>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&tri(0.0, 4.0), 1).unwrap();
    r.push_polygon_vertices(&tri(5.0, 4.0), 2).unwrap();
    r.push_polygon_vertices(&tri(10.0, 4.0), 3).unwrap();
    let mut rows = Vec::new();
    let result = r.render(&mut FnSink(|y: u16, _: &[u32], _: &[u16]| {
        rows.push(y);
        Ok::<(), ()>(())
    }));
    assert_eq!(
        result,
        Err(RenderError::Table(Error::ActivePolygonsFull { row: 4 }))
    );
    assert_eq!(rows, [0, 1, 2, 3], "rows above the overflow were delivered");

    // Triangles keep their two active edges inline: AE = 0 is enough.
    // (Nine pixels wide, so that they are stepped by their edges; small
    // triangles have none.)
    let wide = |x: f32| [vtx(x, 4.0, 0.5), vtx(x + 9.0, 4.0, 0.5), vtx(x, 8.0, 0.5)];
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 0>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&wide(0.0), 1).unwrap();
    r.push_polygon_vertices(&wide(5.0), 2).unwrap();
    let stats = r
        .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .unwrap();
    assert_eq!((stats.peak_active_edges, stats.peak_pooled_edges), (4, 0));
    // Small triangles (three pixels each way) hold none.
    let small = |x: f32| [vtx(x, 4.0, 0.5), vtx(x + 3.0, 4.0, 0.5), vtx(x, 7.0, 0.5)];
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 0>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&small(0.0), 1).unwrap();
    r.push_polygon_vertices(&small(5.0), 2).unwrap();
    let stats = r
        .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .unwrap();
    assert_eq!(
        (stats.peak_active_polygons, stats.peak_active_edges),
        (2, 0)
    );

    // A U shape crosses rows 1..5 four times: two edges go to the pool,
    // which holds one.
    let u = [
        vtx(1.0, 1.0, 0.5),
        vtx(5.0, 1.0, 0.5),
        vtx(5.0, 6.0, 0.5),
        vtx(9.0, 6.0, 0.5),
        vtx(9.0, 1.0, 0.5),
        vtx(13.0, 1.0, 0.5),
        vtx(13.0, 9.0, 0.5),
        vtx(1.0, 9.0, 0.5),
    ];
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 1>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&u, 1).unwrap();
    let result = r.render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())));
    assert_eq!(
        result,
        Err(RenderError::Table(Error::ActiveEdgesFull { row: 1 }))
    );
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 2>> =
        Renderer::with_height(16, 0).unwrap();
    r.push_polygon_vertices(&u, 1).unwrap();
    let stats = r
        .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .unwrap();
    assert_eq!((stats.peak_active_edges, stats.peak_pooled_edges), (4, 2));
}

#[test]
fn sink_errors_come_back() {
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    let result = r.render(&mut FnSink(
        |y: u16, _: &[u32], _: &[u16]| if y == 3 { Err(y) } else { Ok(()) },
    ));
    assert_eq!(result, Err(RenderError::Sink(3)));
}

#[test]
fn corner_counts_and_indices() {
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    let a = r.push_vertex(vtx(1.0, 1.0, 0.5)).unwrap();
    let b = r.push_vertex(vtx(9.0, 1.0, 0.5)).unwrap();
    let c = r.push_vertex(vtx(9.0, 9.0, 0.5)).unwrap();
    assert_eq!(r.push_polygon(&[a, b], 1), Err(Error::TooFewCorners));
    // a, b, c, a, b, c, ...: the triangle, wound round again and again.
    let too_many: Vec<u16> = [a, b, c]
        .into_iter()
        .cycle()
        .take(MAX_POLYGON_CORNERS + 1)
        .collect();
    assert_eq!(r.push_polygon(&too_many, 1), Err(Error::TooManyCorners));
    // Within the limit, a polygon is bounded only by the corner table.
    assert_eq!(
        r.push_polygon(&too_many[..MAX_POLYGON_CORNERS], 1),
        Err(Error::EdgeTableFull)
    );
    // A polygon that is left out needs no room at all.
    assert_eq!(
        r.push_polygon(&[a; MAX_POLYGON_CORNERS], 1),
        Ok(Admission::Degenerate)
    );
    assert_eq!(r.push_polygon(&[a, b, 7], 1), Err(Error::VertexOutOfRange));
    assert_eq!(r.polygon_count(), 0);
    assert_eq!(r.push_polygon(&[a, b, c], 1), Ok(Admission::Queued(0)));
    // A refused polygon left nothing behind: the next one fits exactly.
    let stats = r
        .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .unwrap();
    assert_eq!((stats.vertices, stats.corners, stats.polygons), (3, 3, 1));
}

#[test]
fn bad_vertices_are_refused() {
    assert_eq!(
        ScreenVertex::from_f32(f32::NAN, 0.0, 0.5),
        Err(Error::OutsideGuardBand)
    );
    assert_eq!(
        ScreenVertex::from_f32(0.0, f32::INFINITY, 0.5),
        Err(Error::OutsideGuardBand)
    );
    assert_eq!(
        ScreenVertex::from_f32(1e6, 0.0, 0.5),
        Err(Error::OutsideGuardBand)
    );
    assert_eq!(
        ScreenVertex::from_f32(0.0, 0.0, f32::NAN),
        Err(Error::DepthOutOfRange)
    );
    assert_eq!(
        ScreenVertex::from_f32(0.0, 0.0, 1.5),
        Err(Error::DepthOutOfRange)
    );
    assert_eq!(
        ScreenVertex::new(GUARD_BAND, 0, 0),
        Err(Error::OutsideGuardBand)
    );
    assert_eq!(
        ScreenVertex::new(0, -GUARD_BAND, 0),
        Err(Error::OutsideGuardBand)
    );
    assert_eq!(
        ScreenVertex::new(0, 0, DEPTH_MAX + 1),
        Err(Error::DepthOutOfRange)
    );
    assert!(ScreenVertex::new(GUARD_BAND - 1, 1 - GUARD_BAND, DEPTH_MAX).is_ok());
    let mut r: Renderer<TableArrays<u32, 16, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    let raw = ScreenVertex {
        x: GUARD_BAND,
        y: 0,
        z: 0,
    };
    assert_eq!(r.push_vertex(raw), Err(Error::OutsideGuardBand));
    assert_eq!(r.vertex_count(), 0);
}

#[test]
fn frame_size_is_checked() {
    type R = Renderer<TableArrays<u32, 4, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>>;
    assert_eq!(R::with_height(0, 0).err(), Some(Error::BadFrameSize));
    assert_eq!(R::with_height(5000, 0).err(), Some(Error::BadFrameSize));
    assert!(R::with_height(4096, 0).is_ok());
    assert_eq!(R::new(17, 4, 0).err(), Some(Error::BadFrameSize));
    assert_eq!(R::new(0, 4, 0).err(), Some(Error::BadFrameSize));
    assert!(R::new(9, 4, 0).is_ok());
}

#[test]
fn off_screen_and_zero_area_polygons_are_counted_not_drawn() {
    let mut r: Renderer<TableArrays<u32, 64, 8, 64>, ScanArrays<u32, Depth16, 16, 8, 64>> =
        Renderer::with_height(16, 0).unwrap();
    // Collinear: zero area.
    let line = [vtx(1.0, 1.0, 0.1), vtx(5.0, 5.0, 0.2), vtx(9.0, 9.0, 0.3)];
    assert_eq!(r.push_polygon_vertices(&line, 1), Ok(Admission::Degenerate));
    // All corners equal.
    let point = [vtx(3.0, 3.0, 0.1); 3];
    assert_eq!(
        r.push_polygon_vertices(&point, 1),
        Ok(Admission::Degenerate)
    );
    // Beyond each side.
    for (x, y) in [(-10.0, 4.0), (20.0, 4.0), (4.0, -10.0), (4.0, 20.0)] {
        assert_eq!(
            r.push_polygon_vertices(&tri(x, y), 1),
            Ok(Admission::OffScreen)
        );
    }
    // Inside the frame but between samples: a sliver covering none.
    let between = [vtx(3.6, 3.6, 0.5), vtx(3.9, 3.6, 0.5), vtx(3.6, 3.9, 0.5)];
    assert_eq!(
        r.push_polygon_vertices(&between, 1),
        Ok(Admission::OffScreen)
    );
    assert_eq!((r.vertex_count(), r.polygon_count()), (0, 0));
    let (frame, stats) = capture(&mut r);
    assert!(frame.colors.iter().all(|&c| c == 0));
    assert_eq!(
        (stats.degenerate, stats.off_screen, stats.polygons),
        (2, 5, 0)
    );
}

/// Triangles thinner than a pixel, at every orientation, with depths
/// across the whole range: no panic, and every drawn depth lies within the
/// triangle's corner depths (so nothing is drawn in front of where the
/// triangle is).
#[test]
fn slivers_and_edge_on_triangles_stay_within_their_depth_range() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = |m: i32| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % m as u64) as i32
    };
    let mut drawn_total = 0;
    for _ in 0..2000 {
        let (x0, y0) = (next(40 * S) - 4 * S, next(40 * S) - 4 * S);
        let (dx, dy) = (next(60 * S) - 30 * S, next(60 * S) - 30 * S);
        // Third corner within 40 sub-pixel steps (0.16 px) of the line, often
        // much closer: most of these are steep (edge-on).
        let t = next(S * 64);
        let off = (next(81) - 40) >> next(6);
        let a = ScreenVertex {
            x: x0,
            y: y0,
            z: next(DEPTH_MAX as i32) as u32,
        };
        let b = ScreenVertex {
            x: x0 + dx,
            y: y0 + dy,
            z: next(DEPTH_MAX as i32) as u32,
        };
        let c = ScreenVertex {
            x: x0 + (dx as i64 * t as i64 / (S as i64 * 64)) as i32 + off,
            y: y0 + (dy as i64 * t as i64 / (S as i64 * 64)) as i32 - off,
            z: next(DEPTH_MAX as i32) as u32,
        };
        let mut r: Renderer<TableArrays<u32, 3, 1, 3>, ScanArrays<u32, Depth24, 32, 1, 3>> =
            Renderer::with_height(32, 0).unwrap();
        match r.push_polygon_vertices(&[a, b, c], 1).unwrap() {
            Admission::Queued(_) => {}
            Admission::Degenerate | Admission::OffScreen | Admission::Declined => continue,
        }
        let (frame, _) = capture(&mut r);
        let (lo, hi) = (a.z.min(b.z).min(c.z), a.z.max(b.z).max(c.z));
        for (k, &color) in frame.colors.iter().enumerate() {
            if color == 1 {
                drawn_total += 1;
                let z = frame.depths[k];
                assert!(
                    lo <= z && z <= hi,
                    "depth {z} outside [{lo}, {hi}] for {a:?} {b:?} {c:?}"
                );
                assert!(common::covers(&[a, b, c], (k % 32) as i32, (k / 32) as i32));
            }
        }
    }
    assert!(
        drawn_total > 100,
        "the slivers should cover some samples ({drawn_total})"
    );
}

/// A storage with more polygon slots than the tables can address
/// ([`MAX_POLYGONS`](zline::limits::MAX_POLYGONS), packed in 20
/// bits of an edge-table entry) uses that many: the next polygon is
/// `PolygonTableFull`, and the frame is drawn (a position past the limit
/// once made the sort loop forever).
#[test]
fn polygons_past_the_tables_limit_are_an_error() {
    use zline::limits::MAX_POLYGONS;
    let slots = MAX_POLYGONS + 16;
    let caps = zline::Capacities {
        width: 16,
        vertices: 16,
        polygons: slots,
        corners: 3 * slots,
        active_polygons: 4,
        pooled_edges: 0,
        mesh_vertices: 0,
    };
    let mut r = zline::host::host_renderer::<u32, Depth16>(&caps, 16, 16, 0).unwrap();
    // A triangle covering the sample of pixel (4, 4) alone: drawn when it
    // is activated, never held in the active table.
    let ids = [vtx(4.2, 4.2, 0.5), vtx(5.0, 4.2, 0.5), vtx(4.2, 5.0, 0.5)]
        .map(|v| r.push_vertex(v).unwrap());
    for k in 0..MAX_POLYGONS {
        assert_eq!(
            r.push_polygon(&ids, k as u32 + 1),
            Ok(Admission::Queued(k as u32)),
            "polygon {k}"
        );
    }
    assert_eq!(r.push_polygon(&ids, 7), Err(Error::PolygonTableFull));
    assert_eq!(r.polygon_count(), MAX_POLYGONS);
    let mut drawn = Vec::new();
    let mut sink = FnSink(|y: u16, colors: &[u32], _: &[u16]| {
        for (x, &c) in colors.iter().enumerate() {
            if c != 0 {
                drawn.push((x, y, c));
            }
        }
        Ok::<(), ()>(())
    });
    r.render(&mut sink).unwrap();
    // Equal depths: the polygon added first keeps the pixel.
    assert_eq!(drawn, [(4, 4, 1)]);
}

/// Issue 28, item 6: one admission rule for both ways in. A polygon is
/// judged before it takes room: one that can cover no sample (off-screen,
/// zero area) is counted and left out whatever room is left; only one
/// that will be queued needs room, and one that does not fit is an error
/// with nothing added. (`push_polygon_vertices` stored a polygon's
/// corners before judging it: an off-screen pentagon with room for 4
/// corners was `EdgeTableFull`, where `push_polygon` said `OffScreen`.)
#[test]
fn both_push_functions_judge_before_they_take_room() {
    type R = Renderer<TableArrays<u32, 16, 4, 4>, ScanArrays<u32, Depth16, 16, 4, 16>>;
    let pentagon = |x: f32, y: f32| {
        [(0.0, 0.0), (4.0, 0.0), (5.0, 3.0), (2.0, 5.0), (-1.0, 3.0)]
            .map(|(dx, dy)| vtx(x + dx, y + dy, 0.5))
    };
    let line: [ScreenVertex; 5] = core::array::from_fn(|k| vtx(1.0 + k as f32, 2.0, 0.5));
    for (corners, verdict) in [
        (pentagon(30.0, 4.0), Ok(Admission::OffScreen)),
        (line, Ok(Admission::Degenerate)),
        (pentagon(4.0, 4.0), Err(Error::EdgeTableFull)),
    ] {
        let mut by_vertices = R::with_height(16, 0).unwrap();
        assert_eq!(by_vertices.push_polygon_vertices(&corners, 1), verdict);
        assert_eq!(
            (by_vertices.vertex_count(), by_vertices.polygon_count()),
            (0, 0)
        );
        let mut by_indices = R::with_height(16, 0).unwrap();
        let ids: Vec<u16> = corners
            .iter()
            .map(|&v| by_indices.push_vertex(v).unwrap())
            .collect();
        assert_eq!(by_indices.push_polygon(&ids, 1), verdict);
        assert_eq!(by_indices.polygon_count(), 0);
    }
    // A full vertex table: a triangle that covers no sample is still
    // judged (off-screen), one that would be queued does not fit.
    let mut full: Renderer<TableArrays<u32, 2, 4, 16>, ScanArrays<u32, Depth16, 16, 4, 16>> =
        Renderer::with_height(16, 0).unwrap();
    assert_eq!(
        full.push_polygon_vertices(&tri(30.0, 4.0), 1),
        Ok(Admission::OffScreen)
    );
    assert_eq!(
        full.push_polygon_vertices(&tri(4.0, 4.0), 1),
        Err(Error::VertexTableFull)
    );
    assert_eq!((full.vertex_count(), full.polygon_count()), (0, 0));
    let (_, stats) = capture(&mut full);
    assert_eq!(stats.off_screen, 1);
}
