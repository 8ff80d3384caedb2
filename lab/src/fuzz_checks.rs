//! The properties the fuzzers check, as plain functions over raw bytes, so
//! that the `cargo fuzz` targets in `fuzz/` and the regression tests
//! (`tests/fuzz_regressions.rs`, which replays every saved finding) run
//! the very same code. Each function decodes its input deterministically,
//! runs zline on it and panics when a property does not hold.
//!
//! * [`obj_reader`]: the OBJ reader on any bytes: its three ways in agree,
//!   errors carry a real line, what it accepts is a valid mesh, and a
//!   model of each line (continuations, what follows a vertex's z, an
//!   index as written) agrees with it.
//! * [`core_scene`]: the scanline core on arbitrary screen-space polygons
//!   (coordinates anywhere in the guard band, depths anywhere in range)
//!   against the exact oracle ([`crate::methods::exact::check_frame`]): coverage
//!   exact, depth within 1 LSB, or a documented `Err`; the same tables in
//!   bands, each scanner sized exactly by the frame's counts; one
//!   admission rule for both ways of pushing a polygon.
//! * [`pipeline`]: OBJ bytes and a camera (near and far anywhere in the
//!   `f32` range) through [`draw_mesh`] to rows, in storage the mesh's
//!   own capacities size: every face accounted for exactly once, no
//!   capacity error, no face refused but beyond the clipper's range,
//!   triangle faces as the double-double clip reference draws them, every
//!   row delivered once, in order; then every other method on the same
//!   scene ([`crate::methods::MethodRenderer`]): the z-buffer and the bands
//!   draw the scanline's frame exactly, the interval and the painter's
//!   methods and the reference finish with valid face ids (a wrong
//!   picture from the painter is no finding; a panic or an overflow in any
//!   method is); and the same scene from vertices projected beforehand
//!   ([`draw_mesh_projected`]) and in two bands on two threads
//!   ([`zline::host::BandedRenderer::render_mesh`]) gives the same rows;
//!   with back faces culled, the mesh's face planes change only pixels of
//!   faces seen edge-on.
//! * [`painted`]: Gouraud shading on [`core_scene`]'s polygons with a
//!   colour at each corner: uniform corners paint the flat frame, a
//!   triangle's pixels stay within its corners' colours.

use std::boxed::Box;
use std::format;
use std::string::ToString;
use std::vec;
use std::vec::Vec;

use crate::methods::exact::{Offered, check_frame_shared};
use zline::FnSink;
use zline::Outline;
use zline::ScreenVertex;
use zline::host::{BandedRenderer, ScanVecs, host_renderer};
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::limits::{DEPTH_MAX, GUARD_BAND, MAX_POLYGONS, SUBPIXEL_STEPS};
use zline::obj::{ObjMesh, ObjReader, Statement, count};
use zline::{Admission, Capacities, PolygonTables, Scanner, scan};
use zline::{
    Camera, Cull, DrawError, ProjectedVertex, VertexCache, draw_mesh, draw_mesh_projected,
    project_vertices, reference_model,
};
use zline::{Depth16, Depth24, DepthFormat};
use zline::{Error, RenderError};
use zline::{Mat4, Vec3};
use zline::{Mesh, StaticMesh};
use zline::{Shading, VertexInfo};

/// Reads fixed-size values from the front of the input; zeros once it
/// runs out, so every input decodes to something.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }

    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The OBJ reader on any bytes.
pub fn obj_reader(data: &[u8]) {
    type Small = ObjMesh<64, 256, 64, 8>;
    let lines = data.split(|&b| b == b'\n' || b == b'\r').count() as u32;
    let counted = count(data);
    let parsed = Small::parse(data);
    let host = HostMesh::from_obj(data);
    if let Err(e) = &counted {
        assert!(
            e.line >= 1 && e.line <= lines,
            "error line {} of {lines}",
            e.line
        );
        assert!(!e.to_string().is_empty());
    }
    match (&counted, &host) {
        (Ok(c), Ok(h)) => {
            assert_eq!(
                (c.vertices, c.faces, c.corners),
                (h.positions.len(), h.face_starts.len(), h.corners.len())
            );
            let mesh = StaticMesh::new(&h.positions, &h.corners, &h.face_starts);
            assert!(mesh.is_ok(), "accepted mesh is invalid: {mesh:?}");
            assert!(h.positions.iter().flatten().all(|x| x.is_finite()));
        }
        (c, h) => assert_eq!(
            c.as_ref().err(),
            h.as_ref().err(),
            "count and the host mesh disagree"
        ),
    }
    match (&parsed, &counted) {
        (Ok(mesh), Ok(c)) => {
            assert_eq!(
                (mesh.vertex_count(), mesh.face_count(), mesh.corners().len()),
                (c.vertices, c.faces, c.corners)
            );
            assert_eq!(
                (mesh.texcoord_count(), mesh.normal_count()),
                (c.texcoords, c.normals)
            );
        }
        (Ok(_), Err(e)) => panic!("count failed ({e}) where parse succeeded"),
        (Err(e), Ok(c)) => {
            let fits = c.vertices <= 64 && c.corners <= 256 && c.faces <= 64 && c.max_corners <= 8;
            assert!(!fits, "parse failed ({e}) on a mesh that fits: {c:?}");
        }
        (Err(p), Err(c)) => assert!(p.line <= c.line),
    }
    // The host mesh numbers vertices in first-use order: each face keeps
    // its corners' positions (those of the file's numbering, as the
    // fixed-capacity mesh keeps it), and each corner names a vertex used
    // before or the next one.
    if let (Ok(mesh), Ok(h)) = (&parsed, &host) {
        let mut next = 0usize;
        for f in 0..mesh.face_count() {
            let (file, host) = (mesh.face(f), h.face(f));
            assert_eq!(file.len(), host.len(), "face {f}");
            for (&a, &b) in file.iter().zip(host) {
                let (a, b) = (usize::from(a), usize::from(b));
                assert_eq!(
                    mesh.position(a).map(f32::to_bits),
                    h.positions[b].map(f32::to_bits),
                    "face {f}"
                );
                assert!(b <= next, "corner {b} after {next} vertices");
                next = next.max(b + 1);
            }
        }
    }
    // The streaming reader stops at the first error, and every face it
    // yields names vertices that exist.
    let mut vertices = 0usize;
    for statement in ObjReader::<8>::new(data) {
        match statement {
            Ok(Statement::Vertex(_)) => vertices += 1,
            Ok(Statement::Face(corners)) => assert!(corners.len() >= 3),
            Ok(Statement::TexCoord(_) | Statement::Normal(_) | Statement::Other(_)) => {}
            Err(_) => break,
        }
    }
    if let Ok(c) = counted {
        assert_eq!(vertices.min(c.vertices), vertices);
    }
    line_model_check(data, counted.err());
}

/// What the reader's documentation says of each line, written apart from
/// the reader: a line that ends with `\\` (before any comment) is refused
/// whatever its statement, and after a vertex's `x y z` come at most four
/// more tokens, each a finite number. Every line before the reader's first
/// error (all of them when it accepts the file) keeps both rules, and the
/// line it stops at is refused with the kind the rules give, when they
/// give one.
fn line_model_check(data: &[u8], error: Option<zline::obj::ObjError>) {
    use zline::obj::ObjErrorKind;
    let data = data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data);
    // Lines end with LF, CRLF or a lone CR.
    let mut lines = Vec::new();
    let mut rest = data;
    while !rest.is_empty() {
        match rest.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(end) => {
                lines.push(&rest[..end]);
                let skip = if rest[end..].starts_with(b"\r\n") {
                    2
                } else {
                    1
                };
                rest = &rest[end + skip..];
            }
            None => {
                lines.push(rest);
                rest = &[];
            }
        }
    }
    let number = |token: &[u8]| {
        core::str::from_utf8(token)
            .ok()
            .and_then(|t| t.parse::<f32>().ok())
            .is_some_and(f32::is_finite)
    };
    let stop = error.map_or(u32::MAX, |e| e.line);
    for (k, line) in lines.iter().enumerate() {
        let line_number = k as u32 + 1;
        if line_number > stop {
            break;
        }
        let text = line.split(|&b| b == b'#').next().unwrap_or(&[]);
        let continues = text.iter().rev().find(|b| !b.is_ascii_whitespace()) == Some(&b'\\');
        let tokens: Vec<&[u8]> = text
            .split(u8::is_ascii_whitespace)
            .filter(|t| !t.is_empty())
            .collect();
        let vertex = tokens.first() == Some(&&b"v"[..])
            && tokens.len() >= 4
            && tokens[1..4].iter().all(|t| number(t));
        let extra = tokens.get(4..).unwrap_or(&[]);
        let too_many = vertex && extra.len() > 4;
        let bad_extra = vertex && extra.iter().take(4).any(|t| !number(t));
        // `vt`: one to three numbers; `vn`: three. A line of either that
        // keeps the rule is accepted; one that breaks it is refused, with
        // the kind the first fault gives.
        let attribute_rule = match tokens.first().copied() {
            Some(b"vt") => Some((1, 3)),
            Some(b"vn") => Some((3, 3)),
            _ => None,
        };
        let attribute_fault = attribute_rule.and_then(|(least, most)| {
            let args = &tokens[1..];
            match args.iter().take(most).position(|t| !number(t)) {
                Some(_) => Some(ObjErrorKind::BadNumber),
                None if args.len() > most => Some(ObjErrorKind::TooManyNumbers),
                None if args.len() < least => Some(ObjErrorKind::MissingCoordinate),
                None => None,
            }
        });
        if line_number < stop {
            assert!(
                !continues,
                "line {line_number} ends with a backslash and was accepted"
            );
            assert!(
                !too_many && !bad_extra,
                "line {line_number}: a vertex with {extra:?} after z was accepted"
            );
            assert_eq!(
                attribute_fault, None,
                "line {line_number}: a malformed vt or vn line was accepted"
            );
        } else if let Some(e) = error {
            if let ObjErrorKind::IndexOutOfRange { index, .. } = e.kind {
                // The index as written (in i128, saturated to i64): one of
                // the line's.
                let written = tokens.iter().skip(1).flat_map(|t| t.split(|&b| b == b'/'));
                let as_written = written.filter_map(|t| {
                    let (negative, digits) = match t {
                        [b'-', rest @ ..] => (true, rest),
                        [b'+', rest @ ..] => (false, rest),
                        _ => (false, t),
                    };
                    let magnitude = core::str::from_utf8(digits).ok()?.parse::<u128>().ok();
                    let magnitude =
                        magnitude.map_or(i128::MAX, |m| m.min(i128::MAX as u128) as i128);
                    let value = if negative { -magnitude } else { magnitude };
                    Some(value.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64)
                });
                assert!(
                    as_written.clone().any(|v| v == index),
                    "line {line_number}: index {index} is none of {:?}",
                    as_written.collect::<Vec<_>>()
                );
            }
            if continues {
                assert_eq!(e.kind, ObjErrorKind::LineContinuation, "line {line_number}");
            } else if bad_extra {
                assert_eq!(e.kind, ObjErrorKind::BadNumber, "line {line_number}");
            } else if too_many {
                assert_eq!(e.kind, ObjErrorKind::TooManyNumbers, "line {line_number}");
            } else if let Some(kind) = attribute_fault {
                assert_eq!(e.kind, kind, "line {line_number}");
            }
        }
    }
}

/// A sub-pixel coordinate for a frame `size` pixels wide: near the frame,
/// anywhere in the guard band, at its very edge, or on pixel boundaries
/// and sample points.
fn coordinate(bytes: &mut Bytes<'_>, size: u16) -> i32 {
    let s = SUBPIXEL_STEPS;
    match bytes.u8() % 4 {
        0 => i32::from(bytes.u16()) % ((i32::from(size) + 16) * s) - 8 * s,
        1 => (bytes.u32() as i32) % GUARD_BAND,
        2 => {
            let inset = i32::from(bytes.u8());
            if bytes.u8().is_multiple_of(2) {
                GUARD_BAND - 1 - inset
            } else {
                1 - GUARD_BAND + inset
            }
        }
        _ => {
            let pixel = i32::from(bytes.u8()) % (i32::from(size) + 2) - 1;
            pixel * s + [0, s / 2, 1, s - 1][usize::from(bytes.u8() % 4)]
        }
    }
}

/// A depth: anywhere, or near either end of the range.
fn depth(bytes: &mut Bytes<'_>) -> u32 {
    match bytes.u8() % 4 {
        0 => bytes.u32() % (DEPTH_MAX + 1),
        1 => u32::from(bytes.u8()),
        2 => DEPTH_MAX - u32::from(bytes.u8()),
        _ => u32::from(bytes.u16()) << 8,
    }
}

/// Widest frame [`core_scene`] draws.
const CORE_WIDTH: usize = 48;
/// Most polygons [`core_scene`] draws.
const CORE_POLYGONS: usize = 10;

/// The scanline core on arbitrary screen-space polygons, against the exact
/// oracle.
pub fn core_scene(data: &[u8]) {
    let mut bytes = Bytes(data);
    let width = 1 + u16::from(bytes.u8()) % CORE_WIDTH as u16;
    let height = 1 + u16::from(bytes.u8()) % 40;
    // Bit 0: the depth format; bit k (1 to 7): polygon k takes the plane
    // of polygon k - 1's first three corners (a shared plane).
    let flags = bytes.u8();
    let z24 = flags % 2 == 0;
    let mut polygons = Vec::new();
    while !bytes.is_empty() && polygons.len() < CORE_POLYGONS {
        let corners = 3 + usize::from(bytes.u8() % 6);
        let poly: Vec<ScreenVertex> = (0..corners)
            .map(|_| {
                let x = coordinate(&mut bytes, width);
                let y = coordinate(&mut bytes, height);
                ScreenVertex::new(x, y, depth(&mut bytes)).expect("inside the guard band")
            })
            .collect();
        polygons.push(poly);
    }
    let shares = |k: usize| (1..8).contains(&k) && flags & (1 << k) != 0;
    // The bands' cuts: from a hash of the whole input, so that inputs
    // saved before the bands were checked decode to the same scene.
    let cuts = band_cuts(data, height);
    if z24 {
        core_check::<Depth24>(&polygons, shares, width, height, &cuts);
    } else {
        core_check::<Depth16>(&polygons, shares, width, height, &cuts);
    }
}

/// One admission rule for both ways in: each polygon, offered to tables
/// with one corner, one vertex or no polygon slot too few for it, gets
/// the same verdict from `push_polygon_vertices` as from `push_polygon`
/// over the same vertices, and a refused one leaves nothing behind.
fn admission_check<D: DepthFormat>(polygons: &[Vec<ScreenVertex>], width: u16, height: u16) {
    for poly in polygons {
        let n = poly.len();
        let room = Capacities {
            width: CORE_WIDTH,
            vertices: 2 * n,
            polygons: 1,
            corners: n,
            active_polygons: 1,
            pooled_edges: 0,
            mesh_vertices: 0,
        };
        for tight in [
            Capacities {
                corners: n - 1,
                ..room
            },
            Capacities {
                polygons: 0,
                ..room
            },
            Capacities {
                vertices: n - 1,
                ..room
            },
            room,
        ] {
            let mut by_vertices =
                host_renderer::<u32, D>(&tight, width, height, 0).expect("frame size");
            let verdict = by_vertices.push_polygon_vertices(poly, 1);
            if verdict.is_err() {
                assert_eq!(
                    (by_vertices.vertex_count(), by_vertices.polygon_count()),
                    (0, 0)
                );
            }
            // The same polygon by indices, its vertices given room first.
            let indexed = Capacities {
                vertices: 2 * n,
                ..tight
            };
            let mut by_indices =
                host_renderer::<u32, D>(&indexed, width, height, 0).expect("frame size");
            let ids: Vec<u16> = poly
                .iter()
                .map(|&v| by_indices.push_vertex(v).expect("room"))
                .collect();
            let by_index = by_indices.push_polygon(&ids, 1);
            let expected = if tight.vertices < n
                && by_index.is_ok_and(|a| matches!(a, Admission::Queued(_)))
            {
                Err(Error::VertexTableFull)
            } else {
                by_index
            };
            assert_eq!(verdict, expected, "{poly:?} at {tight:?}");
        }
    }
}

/// Up to three cuts of `height` rows, from an FNV-1a hash of `data`.
fn band_cuts(data: &[u8], height: u16) -> Vec<u16> {
    let hash = data.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    let count = (hash % 4) as usize;
    (0..count)
        .map(|k| ((hash >> (16 * k + 2)) % u64::from(height + 1)) as u16)
        .collect()
}

fn core_check<D: DepthFormat>(
    polygons: &[Vec<ScreenVertex>],
    shares: impl Fn(usize) -> bool,
    width: u16,
    height: u16,
    cuts: &[u16],
) where
    D::Value: Into<u64>,
{
    // Room for every polygon and shared plane: no capacity error is
    // possible.
    let caps = Capacities {
        width: CORE_WIDTH,
        vertices: 128,
        polygons: 12,
        corners: 128,
        active_polygons: 12,
        pooled_edges: 96,
        mesh_vertices: 0,
    };
    admission_check::<D>(polygons, width, height);
    let mut renderer = host_renderer::<u32, D>(&caps, width, height, 0).expect("frame size");
    let offered: Vec<Offered> = polygons
        .iter()
        .enumerate()
        .map(|(k, poly)| {
            let admission = renderer
                .push_polygon_vertices(poly, k as u32 + 1)
                .expect("the tables have room");
            let queued = matches!(admission, Admission::Queued(_));
            let mut plane = None;
            if queued && shares(k) {
                let corners = [0, 1, 2].map(|c| polygons[k - 1][c]);
                let ids = corners.map(|v| renderer.push_vertex(v).expect("room"));
                if renderer.share_plane(ids).expect("just queued") {
                    plane = Some(corners);
                }
            }
            Offered {
                corners: poly.clone(),
                plane,
                queued,
            }
        })
        .collect();
    let (w, h) = (usize::from(width), usize::from(height));
    let (mut colors, mut depths) = (vec![0u32; w * h], vec![0u64; w * h]);
    let mut next_row = 0u16;
    let stats = renderer
        .render(&mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            assert_eq!(y, next_row, "rows in order, once each");
            next_row += 1;
            let at = usize::from(y) * w;
            colors[at..at + w].copy_from_slice(c);
            for (out, &d) in depths[at..at + w].iter_mut().zip(z) {
                *out = d.into();
            }
            Ok::<(), ()>(())
        }))
        .expect("render");
    assert_eq!(next_row, height);
    if let Err(e) = check_frame_shared::<D>(&offered, w, h, &colors, &depths) {
        panic!("{}: {e}\npolygons: {offered:?}", D::NAME);
    }
    // The same tables in bands at `cuts`, each scanner sized exactly by
    // the whole frame's counts: every band fits, and sends the whole
    // scan's rows.
    let exact = Capacities::from_stats(&stats, w);
    let prepared = renderer.tables.prepare();
    let mut bounds: Vec<u16> = cuts.iter().map(|&c| c.min(height)).collect();
    bounds.extend([0, height]);
    bounds.sort_unstable();
    for band in bounds.windows(2) {
        let mut scanner = Scanner::new(
            ScanVecs::<u32, D>::new(&exact, 0).expect("a frame's own counts fit"),
            0,
        );
        let mut next = band[0];
        scan(
            &prepared,
            &mut scanner,
            band[0]..band[1],
            &mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
                assert_eq!(y, next, "band {band:?}: rows in order");
                next += 1;
                let at = usize::from(y) * w;
                assert!(
                    c == &colors[at..at + w],
                    "band {band:?}: row {y}'s colours differ"
                );
                let same = z
                    .iter()
                    .zip(&depths[at..at + w])
                    .all(|(&a, &b)| a.into() == b);
                assert!(same, "band {band:?}: row {y}'s depths differ");
                Ok::<(), ()>(())
            }),
        )
        .unwrap_or_else(|e| panic!("band {band:?} at the frame's capacities {exact:?}: {e:?}"));
        assert_eq!(next, band[1]);
    }
}

/// Frame size limit of [`pipeline`].
const PIPELINE_WIDTH: usize = 64;

/// A finite `f32` from the input, or `fallback`.
fn finite(bytes: &mut Bytes<'_>, fallback: f32) -> f32 {
    let v = f32::from_bits(bytes.u32());
    if v.is_finite() { v } else { fallback }
}

/// OBJ bytes and a camera through the whole pipeline to rows.
///
/// The first 32 bytes choose the view; the rest is the OBJ file.
pub fn pipeline(data: &[u8]) {
    let (head, obj) = data.split_at(data.len().min(32));
    let mut bytes = Bytes(head);
    let width = 1 + u16::from(bytes.u8()) % PIPELINE_WIDTH as u16;
    let height = 1 + u16::from(bytes.u8()) % 48;
    let flags = bytes.u8();
    let (z24, cull, reference_view) = (flags & 1 != 0, flags & 2 != 0, flags & 4 == 0);
    let cull = if cull { Cull::Back } else { Cull::None };
    let yaw = f32::from(bytes.u16()) / 64.0;
    let pitch = f32::from(bytes.u16()) / 64.0;
    let fov = 5.0 + f32::from(bytes.u8()) * (170.0 / 255.0);
    let near = 10f32.powf(f32::from(bytes.u8() % 8) - 4.0);
    let far = near * 10f32.powf(1.0 + f32::from(bytes.u8() % 6));
    let eye = Vec3::new(
        finite(&mut bytes, 0.0),
        finite(&mut bytes, 0.0),
        finite(&mut bytes, 3.0),
    );
    // Byte 22 (zero in the inputs saved before it was read): bit 0, near
    // and far anywhere in the f32 range (bytes 23-30); bit 1, the banded
    // renderer cut at a row of byte 31's choosing; bit 2, a closed mesh
    // keeps its hull (`Cull::None` then culls back faces where none can
    // show, checked against the mesh drawn two-sided).
    let wide = bytes.u8();
    let (near, far) = if wide & 1 != 0 {
        let a = finite(&mut bytes, near).abs();
        let b = finite(&mut bytes, far).abs();
        let (near, far) = (a.min(b), a.max(b));
        if near > 0.0 && far > near {
            (near, far)
        } else {
            (near.max(f32::MIN_POSITIVE), (near * 2.0).max(1.0))
        }
    } else {
        let _ = (bytes.u32(), bytes.u32());
        (near, far)
    };
    let band_cut = (wide & 2 != 0).then(|| 1 + u16::from(bytes.u8()) % height.max(1));
    let Ok(mut mesh) = HostMesh::from_obj(obj) else {
        return; // The reader's own target checks its errors.
    };
    if wide & 4 == 0 {
        mesh.closed_hull = None;
    }
    let (model, camera) = if reference_view {
        let Ok(model) = reference_model(&mesh, yaw, pitch) else {
            return; // Error::MeshExtent: documented and tested.
        };
        (
            model,
            Camera::perspective(
                Mat4::translation(Vec3::new(0.0, 0.0, -3.0)),
                fov,
                width,
                height,
                near,
                far,
            ),
        )
    } else {
        let view = Mat4::look_at(eye, Vec3::default(), Vec3::new(0.0, 1.0, 0.0));
        (
            Mat4::IDENTITY,
            Camera::perspective(view, fov, width, height, near, far),
        )
    };
    // Flags 16..: the band height of the bands method.
    let band_rows = 1 + u16::from(flags >> 4);
    let reference_camera = reference_view.then_some(crate::methods::ReferenceCamera {
        eye_distance: 3.0,
        fov_y_deg: f64::from(fov),
        near: f64::from(near),
        far: f64::from(far),
    });
    let view = crate::methods::ReferenceView {
        width: usize::from(width),
        height: usize::from(height),
        yaw_deg: f64::from(yaw),
        pitch_deg: f64::from(pitch),
        cull_back: cull == Cull::Back,
    };
    let methods = OtherMethods {
        band_rows,
        reference: reference_camera.map(|c| (c, view)),
        band_cut: band_cut.filter(|&c| c < height),
    };
    if mesh.closed_hull.is_some() && cull == Cull::None {
        closed_hull_check(&mesh, &model, &camera);
    }
    if cull == Cull::Back && flags & 8 == 0 {
        face_planes_check(&mesh, &model, &camera);
    }
    // Flag 8: the same mesh quantized, through the integer front end.
    // The mesh's own capacities, worst case over every view: no capacity
    // error may occur below the core's own limits.
    let caps = mesh.capacities(width);
    if flags & 8 != 0 {
        let Ok(quantized) = QuantizedHostMesh::new(&mesh) else {
            return; // Error::MeshExtent, as for the f32 mesh.
        };
        let quantized = quantized.mesh().expect("a quantized host mesh is valid");
        if z24 {
            pipeline_check::<Depth24, _>(&quantized, &model, &camera, cull, &methods, &caps);
        } else {
            pipeline_check::<Depth16, _>(&quantized, &model, &camera, cull, &methods, &caps);
        }
    } else if z24 {
        pipeline_check::<Depth24, _>(&mesh, &model, &camera, cull, &methods, &caps);
    } else {
        pipeline_check::<Depth16, _>(&mesh, &model, &camera, cull, &methods, &caps);
    }
}

/// No face: the background of [`face_frame`].
const NONE: u32 = u32::MAX;

/// `mesh` drawn z24 with `cull`, each face coloured by `color` on a
/// background of [`NONE`]: the frame's pixels, row-major from the top.
/// `None` when the draw or the render fails (capacities, clipping
/// range: the pipeline check's to judge).
fn face_frame(
    mesh: &HostMesh,
    (model, camera): (&Mat4, &Camera),
    cull: Cull,
    color: impl FnMut(&zline::FaceInfo) -> u32,
) -> Option<Vec<u32>> {
    let (w, h) = (camera.width, camera.height);
    let caps = mesh.capacities(w);
    let mut renderer = host_renderer::<u32, Depth24>(&caps, w, h, NONE).ok()?;
    renderer.draw_mesh(mesh, model, camera, cull, color).ok()?;
    let mut pixels = Vec::new();
    renderer
        .render(&mut FnSink(|_: u16, row: &[u32], _: &[u32]| {
            pixels.extend_from_slice(row);
            Ok::<(), ()>(())
        }))
        .ok()?;
    Some(pixels)
}

/// A closed mesh drawn with `Cull::None` covers the samples it covers
/// drawn two-sided (its hull cleared), and a pixel differs only where the
/// two-sided frame shows a back face and the other a front face (see
/// [`zline::ClosedHull`]). Draws that fail (capacities, clipping range)
/// are the pipeline check's to judge.
fn closed_hull_check(mesh: &HostMesh, model: &Mat4, camera: &Camera) {
    let frame = |mesh: &HostMesh| {
        face_frame(mesh, (model, camera), Cull::None, |f| {
            f.face << 1 | u32::from(f.front)
        })
    };
    let open = HostMesh {
        closed_hull: None,
        ..mesh.clone()
    };
    let (Some(culled), Some(two_sided)) = (frame(mesh), frame(&open)) else {
        return;
    };
    for (k, (&a, &b)) in culled.iter().zip(&two_sided).enumerate() {
        // A back face tied with a nearer front face; or, as with
        // `Cull::Back`, a face seen edge-on that the face planes' test
        // left out (its exact projection turned away).
        assert!(
            a == b
                || (a != NONE && a & 1 == 1 && b != NONE && b & 1 == 0)
                || (b != NONE && b & 1 == 1 && !turned_towards(mesh, b >> 1, model, camera)),
            "pixel {k}: culled {a:#x}, two-sided {b:#x}"
        );
    }
}

/// Whether triangle `face` of `mesh` is turned towards the eye by more
/// than a rounding's worth: its corners' clip `x, y, w` determinant in
/// `f64` above `1e-6` of its size. (A face that is not a triangle counts
/// as turned towards it.)
fn turned_towards(mesh: &HostMesh, face: u32, model: &Mat4, camera: &Camera) -> bool {
    let corners = mesh.face(face as usize);
    if corners.len() != 3 {
        return true;
    }
    let mvp = camera.projection.mul(&camera.view.mul(model));
    let clip: Vec<[f64; 3]> = corners
        .iter()
        .map(|&i| {
            let p = mesh.positions[usize::from(i)].map(f64::from);
            let row =
                |r: [f32; 4]| (0..3).map(|c| f64::from(r[c]) * p[c]).sum::<f64>() + f64::from(r[3]);
            [row(mvp.m[0]), row(mvp.m[1]), row(mvp.m[3])]
        })
        .collect();
    let [p, q, r] = [clip[0], clip[1], clip[2]];
    let d = p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0])
        + p[2] * (q[0] * r[1] - q[1] * r[0]);
    let size: f64 = clip
        .iter()
        .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
        .product();
    d > 1e-6 * size
}

/// A mesh drawn with `Cull::Back` and its face planes
/// ([`zline::Mesh::face_planes`]) gives the frame it gives without them,
/// but where a face that the planes' test left out showed: each such
/// pixel shows, without the planes, a face the draw with them did not
/// shade, and one not turned towards the eye by more than a rounding's
/// worth (its corners' clip `x, y, w` determinant in `f64`). Draws that
/// fail are the pipeline check's to judge.
fn face_planes_check(mesh: &HostMesh, model: &Mat4, camera: &Camera) {
    let frame = |mesh: &HostMesh, shaded: &mut Vec<bool>| {
        face_frame(mesh, (model, camera), Cull::Back, |f| {
            if let Some(s) = shaded.get_mut(f.face as usize) {
                *s = true;
            }
            f.face
        })
    };
    if mesh.face_planes.is_empty() {
        return;
    }
    let bare = HostMesh {
        face_planes: Vec::new(),
        ..mesh.clone()
    };
    let mut shaded = vec![false; mesh.face_count()];
    let mut unused = Vec::new();
    let (Some(with), Some(without)) = (frame(mesh, &mut shaded), frame(&bare, &mut unused)) else {
        return;
    };
    for (k, (&a, &b)) in with.iter().zip(&without).enumerate() {
        if a == b {
            continue;
        }
        assert!(b != NONE, "pixel {k}: {a} drawn only with the planes");
        assert!(
            !shaded[b as usize],
            "pixel {k}: face {b} shaded, yet hidden with the planes"
        );
        assert_eq!(
            mesh.face(b as usize).len(),
            3,
            "pixel {k}: face {b} is no triangle"
        );
        assert!(
            !turned_towards(mesh, b, model, camera),
            "pixel {k}: face {b} left out, turned towards the eye"
        );
    }
}

/// What [`pipeline`] asks of the methods beyond the scanline core.
struct OtherMethods {
    /// Rows of the bands method.
    band_rows: u16,
    /// Where the banded renderer's two bands meet (else its own cut).
    band_cut: Option<u16>,
    /// The reference's camera and view, when the view is the reference
    /// view's (the reference knows no other).
    reference: Option<(
        crate::methods::ReferenceCamera,
        crate::methods::ReferenceView,
    )>,
}

/// Every method on the scene: the z-buffer and the bands give the
/// scanline's frame exactly; the interval and painter's methods and the
/// reference give valid face ids.
fn other_methods_check<D: DepthFormat, M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    other: &OtherMethods,
) where
    D::Value: Into<u32>,
{
    use crate::methods::{BACKGROUND, Method, MethodRenderer};
    let mut renderer = MethodRenderer::<D>::new(camera.width, camera.height).expect("frame size");
    if let Some((c, _)) = other.reference {
        renderer.set_reference_camera(c);
    }
    let shading = Shading::lambert();
    let (view, reference) = match other.reference {
        Some((c, v)) => (v, Some(c)),
        None => (
            crate::methods::ReferenceView {
                width: usize::from(camera.width),
                height: usize::from(camera.height),
                yaw_deg: 0.0,
                pitch_deg: 0.0,
                cull_back: false,
            },
            None,
        ),
    };
    let mut frame = |method: Method| {
        renderer
            .render(method, mesh, model, camera, cull, &shading, &view)
            .unwrap_or_else(|e| panic!("{}: {e}", method.name()))
            .faces
    };
    let scanline = frame(Method::Scanline);
    for method in [Method::ZBuffer, Method::Bands(other.band_rows)] {
        assert!(
            frame(method) == scanline,
            "{} differs from the scanline",
            method.name()
        );
    }
    let faces = mesh.face_count() as u32;
    for method in [Method::Interval, Method::Painter] {
        let ids = frame(method);
        assert!(
            ids.iter().all(|&id| id == BACKGROUND || id < faces),
            "{} names no face",
            method.name()
        );
    }
    if reference.is_some() {
        let ids = frame(Method::Reference);
        assert!(ids.iter().all(|&id| id == BACKGROUND || id < faces));
    }
}

/// A row as (row, colours, depths).
type Rows = Vec<(u16, Vec<u32>, Vec<u32>)>;

fn row_of<V: Copy + Into<u32>>(y: u16, colors: &[u32], depths: &[V]) -> (u16, Vec<u32>, Vec<u32>) {
    (
        y,
        colors.to_vec(),
        depths.iter().map(|&z| z.into()).collect(),
    )
}

/// The scene `rows` came from, drawn from vertices projected beforehand
/// (in two runs) and by the banded renderer in two bands on two threads:
/// the same rows, and no error where `draw_mesh` had none.
#[allow(clippy::too_many_arguments)]
fn projected_check<D: DepthFormat, M: Mesh + Sync>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    rows: &Rows,
    caps: &Capacities,
    exact: &Capacities,
    band_cut: Option<u16>,
) where
    D::Value: Into<u32> + Send,
{
    let count = mesh.vertex_count();
    let mut projected = vec![ProjectedVertex::NonFinite; count];
    let (low, high) = projected.split_at_mut(count / 2);
    project_vertices(mesh, model, camera, 0, low).expect("vertices of the mesh");
    project_vertices(mesh, model, camera, count / 2, high).expect("vertices of the mesh");
    let mut renderer =
        host_renderer::<u32, D>(caps, camera.width, camera.height, 0).expect("frame size");
    let mut cache: Box<VertexCache<4096>> = Box::default();
    draw_mesh_projected(
        &mut renderer,
        &mut *cache,
        &projected,
        None,
        mesh,
        model,
        camera,
        cull,
        |f| f.face + 1,
    )
    .expect("draw_mesh drew it");
    let mut again = Rows::new();
    renderer
        .render(&mut FnSink(
            |y: u16, colors: &[u32], depths: &[D::Value]| {
                again.push(row_of(y, colors, depths));
                Ok::<(), ()>(())
            },
        ))
        .expect("draw_mesh's frame was rendered");
    assert!(again == *rows, "draw_mesh_projected's rows differ");
    if camera.height < 2 {
        return;
    }
    // Each band sized exactly by one renderer's counts: a band needs no
    // more than the whole frame.
    let mut banded =
        BandedRenderer::<u32, D>::new(exact, camera.width, camera.height, 0, 2).expect("bands");
    if let Some(cut) = band_cut {
        banded.set_cuts(&[cut]).expect("a cut inside the frame");
    }
    // Two threads even for the first (and only) frame: their shared steps
    // and meetings are what is checked.
    banded.set_one_thread_below(std::time::Duration::ZERO);
    let mut bands: Vec<Rows> = vec![Rows::new(); 2];
    let mut sinks: Vec<_> = bands
        .iter_mut()
        .map(|band| {
            FnSink(move |y: u16, colors: &[u32], depths: &[D::Value]| {
                band.push(row_of(y, colors, depths));
                Ok::<(), ()>(())
            })
        })
        .collect();
    banded
        .render_mesh(mesh, model, camera, cull, &mut sinks, |f| f.face + 1)
        .unwrap_or_else(|e| panic!("bands at one renderer's capacities {exact:?}: {e:?}"));
    drop(sinks);
    let banded_rows: Rows = bands.into_iter().flatten().collect();
    assert!(banded_rows == *rows, "the banded renderer's rows differ");
}

fn pipeline_check<D: DepthFormat, M: Mesh + Sync>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    other: &OtherMethods,
    caps: &Capacities,
) where
    D::Value: Into<u32> + Send,
{
    if mesh.vertex_count() > 4096 {
        return;
    }
    let mut renderer =
        host_renderer::<u32, D>(caps, camera.width, camera.height, 0).expect("frame size");
    let mut cache: Box<VertexCache<4096>> = Box::default();
    let shading = Shading::lambert();
    // Below the core's own limits (u16 vertex indices, 2^20 polygons,
    // 2^16 active polygons), the mesh's capacities hold every view.
    let uncapped = caps.vertices < 1 << 16 && caps.polygons < MAX_POLYGONS;
    let mut recorded = Recording::new(&mut renderer);
    let drawn = draw_mesh(&mut recorded, &mut *cache, mesh, model, camera, cull, |f| {
        // Lambert too (the integer path for a quantized mesh): any panic
        // or overflow in it is a finding.
        core::hint::black_box(shading.color(f));
        // And Gouraud's vertex colour, on the face's normal as a known
        // vertex normal (`VertexInfo::normal_dot`, `f32` path).
        core::hint::black_box(shading.vertex_color(&VertexInfo::new(0, Some(f.normal()), None)));
        f.face + 1
    });
    let queued = recorded.queued;
    let stats = match drawn {
        Ok(stats) => stats,
        Err(DrawError { error, face }) => {
            let capacity = matches!(
                error,
                Error::VertexTableFull | Error::PolygonTableFull | Error::EdgeTableFull
            );
            // A face too large to clip exactly is refused (documented).
            assert!(
                error == Error::ClipRange || (capacity && !uncapped),
                "face {face:?}: {error} at the mesh's capacities {caps:?}"
            );
            return;
        }
    };
    // Every face (every triangle of a split face, each of a convex quad's
    // two triangles) ends exactly one way.
    let parts: u32 = (0..mesh.face_count())
        .map(|f| {
            let n = mesh.face(f).len() as u32;
            if n > 3 && !mesh.face_is_planar(f) {
                n - 2
            } else {
                1
            }
        })
        .sum();
    let outcomes = stats.queued
        + stats.back_faces
        + stats.outside
        + stats.off_screen
        + stats.degenerate
        + stats.non_finite;
    assert_eq!(outcomes, parts + stats.convex_quads, "{stats:?}");
    assert_eq!(stats.faces as usize, mesh.face_count());
    let finite = |m: &Mat4| m.m.iter().flatten().all(|v| v.is_finite());
    if finite(model) && finite(&camera.view) && finite(&camera.projection) {
        // Finite positions (the reader's) and matrices: no corner is lost.
        assert_eq!(stats.non_finite, 0, "{stats:?}");
    }
    // (Every face drawn: no back face left out for a closed hull.)
    if cull == Cull::None && mesh.quantized().is_none() && stats.back_faces == 0 {
        clip_reference_check(mesh, model, camera, &queued);
    }
    let mut next_row = 0u16;
    let faces = mesh.face_count() as u32;
    let mut rows = Rows::new();
    let result = renderer.render(&mut FnSink(
        |y: u16, colors: &[u32], depths: &[D::Value]| {
            assert_eq!(y, next_row, "rows in order, once each");
            next_row += 1;
            assert_eq!(colors.len(), usize::from(camera.width));
            assert!(colors.iter().all(|&c| c <= faces), "a colour names no face");
            rows.push(row_of(y, colors, depths));
            Ok::<(), ()>(())
        },
    ));
    match result {
        Ok(frame) => {
            assert_eq!(next_row, camera.height);
            assert_eq!(frame.polygons, stats.queued);
            other_methods_check::<D, M>(mesh, model, camera, cull, other);
            let exact = Capacities::from_stats(&frame, usize::from(camera.width));
            projected_check::<D, M>(
                mesh,
                model,
                camera,
                cull,
                &rows,
                caps,
                &exact,
                other.band_cut,
            );
        }
        Err(RenderError::Table(e)) => assert!(
            !uncapped
                && matches!(
                    e,
                    Error::ActivePolygonsFull { .. } | Error::ActiveEdgesFull { .. }
                ),
            "{e} at the mesh's capacities {caps:?}"
        ),
        Err(RenderError::Sink(())) => unreachable!("the sink never fails"),
    }
    let _ = format!("{stats:?}");
}

/// Most triangle faces [`clip_reference_check`] judges in one input (each
/// costs a pass over the frame's samples).
const REFERENCE_FACES: usize = 48;

/// Largest face, in near distances, [`clip_reference_check`] judges:
/// `2^80`, where the reference's error is still below `2^-24` of `w`.
const REFERENCE_LIMIT: f64 = (1u128 << 80) as f64;

/// The triangle faces of a draw with no culling, each against the
/// double-double reference ([`crate::methods::clip_reference`]): up to
/// [`REFERENCE_LIMIT`] (and for corners whose transform does not cancel:
/// the `f32` front end's precision is relative to a corner's transform
/// terms, not its position), the corners within one sub-pixel step of the
/// reference's boundary, the depths within `2^-20`, and every pixel
/// sample the reference covers covered (samples within 1/128 pixel of
/// its boundary excused).
fn clip_reference_check<M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    queued: &[(Vec<ScreenVertex>, u32)],
) {
    use crate::methods::clip_reference::{clipped_face, compare_face, transform_terms};
    let judged = (0..mesh.face_count())
        .filter(|&f| mesh.face(f).len() == 3)
        .take(REFERENCE_FACES);
    for face in judged {
        let corners: Vec<[f32; 3]> = mesh
            .face(face)
            .iter()
            .map(|&i| mesh.position(usize::from(i)))
            .collect();
        let Some((size, cancellation)) = transform_terms(model, camera, &corners) else {
            continue;
        };
        // Beyond 2^80 near distances the reference's own 106 bits do not
        // judge a face to the sub-pixel grid. (Beyond the clipper's range
        // a face that needs clipping is refused; one drawn there, needing
        // none, must be right as any other.)
        if size > REFERENCE_LIMIT * near_distance(camera) || cancellation > 16.0 {
            continue;
        }
        let drawn: Vec<Vec<ScreenVertex>> = queued
            .iter()
            .filter(|(_, color)| *color == face as u32 + 1)
            .map(|(corners, _)| corners.clone())
            .collect();
        let reference = clipped_face(model, camera, &corners);
        let size_px = (camera.width, camera.height);
        let e = compare_face(&drawn, &[reference], size_px, 1.0 / 128.0);
        let step = 1.0 / f64::from(SUBPIXEL_STEPS);
        assert!(
            e.position_px <= step && e.depth <= 1.0 / f64::from(1u32 << 20) && e.wrong_samples == 0,
            "face {face} {corners:?} against the reference: {e:?}"
        );
    }
}

/// The clip-space `w` of a perspective projection's near plane, the
/// smallest `w` in its frustum: where `z = -w`, that is at view depth
/// `B / (1 - A)` for `z = A·depth + B`.
fn near_distance(camera: &Camera) -> f64 {
    let [a, b] = [camera.projection.m[2][2], camera.projection.m[2][3]].map(f64::from);
    -b / (1.0 - a)
}

/// Tables that forward everything to `inner` and keep a copy of each
/// polygon queued: its corners and its colour.
struct Recording<'a, T> {
    inner: &'a mut T,
    open: Vec<u16>,
    queued: Vec<(Vec<ScreenVertex>, u32)>,
}

impl<'a, T: PolygonTables<u32>> Recording<'a, T> {
    fn new(inner: &'a mut T) -> Self {
        Self {
            inner,
            open: Vec::new(),
            queued: Vec::new(),
        }
    }

    /// Records `ids` in `color` when `admission` queued them.
    fn record(&mut self, admission: Admission, ids: &[u16], color: Option<u32>) {
        if let (Admission::Queued(_), Some(color)) = (admission, color) {
            let corners = ids
                .iter()
                .map(|&i| self.inner.get_vertex(i).expect("a queued corner exists"))
                .collect();
            self.queued.push((corners, color));
        }
    }
}

impl<T: PolygonTables<u32>> PolygonTables<u32> for Recording<'_, T> {
    fn frame_width(&self) -> u16 {
        self.inner.frame_width()
    }

    fn frame_height(&self) -> u16 {
        self.inner.frame_height()
    }

    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.inner.add_vertex(vertex)
    }

    fn get_vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.inner.get_vertex(index)
    }

    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<u32>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        let ids: Vec<u16> = corners.into_iter().collect();
        let mut color = None;
        let admission = self.inner.offer_polygon(ids.iter().copied(), |outline| {
            color = decide(outline);
            color
        })?;
        self.record(admission, &ids, color);
        Ok(admission)
    }

    fn offer_triangle(
        &mut self,
        corners: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<u32>,
    ) -> Result<Admission, Error> {
        let mut color = None;
        let admission = self.inner.offer_triangle(corners, |outline| {
            color = decide(outline);
            color
        })?;
        self.record(admission, &corners, color);
        Ok(admission)
    }

    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        self.inner.share_plane(plane)
    }

    fn begin_polygon(&mut self) {
        self.open.clear();
        self.inner.begin_polygon();
    }

    fn discard_polygon(&mut self) {
        self.open.clear();
        self.inner.discard_polygon();
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        self.inner.add_corner(vertex)?;
        self.open.push(vertex);
        Ok(())
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<u32>,
    ) -> Result<Admission, Error> {
        let ids = core::mem::take(&mut self.open);
        // The corners' vertices, before a polygon left out removes them.
        let corners: Vec<ScreenVertex> = ids
            .iter()
            .filter_map(|&i| self.inner.get_vertex(i))
            .collect();
        let mut color = None;
        let admission = self.inner.finish_polygon(|outline| {
            color = decide(outline);
            color
        })?;
        if let (Admission::Queued(_), Some(color)) = (admission, color) {
            self.queued.push((corners, color));
        }
        Ok(admission)
    }
}

/// A sink that keeps every row.
struct KeepRows<'a>(&'a mut Vec<Vec<embedded_graphics_core::pixelcolor::Rgb888>>);

impl<Z> zline::RowSink<embedded_graphics_core::pixelcolor::Rgb888, Z> for KeepRows<'_> {
    type Error = ();

    fn write_row(
        &mut self,
        _y: u16,
        colors: &[embedded_graphics_core::pixelcolor::Rgb888],
        _depths: &[Z],
    ) -> Result<(), ()> {
        self.0.push(colors.to_vec());
        Ok(())
    }
}

/// Gouraud shading ([`zline::paint`]) on arbitrary screen-space polygons
/// (as [`core_scene`] decodes them, each corner with a colour anywhere in
/// `0..=65,535` per channel, values above 255.0 included): with one colour
/// at every corner of each polygon the painted frame is the flat frame
/// (the same admissions, visibility and background); with the decoded
/// colours every pixel of a visible triangle lies within its corners'
/// range, rounded (a plane between its corners' values, within its
/// bound), and nothing panics or overflows (the fuzzers run with overflow
/// checks).
pub fn painted(data: &[u8]) {
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
    use zline::host::HostPaintedRenderer;
    use zline::paint::{CHANNEL_MAX, Gouraud, Rgb8p8};
    let mut bytes = Bytes(data);
    let width = 1 + u16::from(bytes.u8()) % CORE_WIDTH as u16;
    let height = 1 + u16::from(bytes.u8()) % 40;
    let z24 = bytes.u8() % 2 == 0;
    let mut polygons: Vec<(Vec<ScreenVertex>, Vec<Rgb8p8>)> = Vec::new();
    while !bytes.is_empty() && polygons.len() < CORE_POLYGONS {
        let corners = 3 + usize::from(bytes.u8() % 6);
        let mut poly = Vec::new();
        let mut colors = Vec::new();
        for _ in 0..corners {
            let x = coordinate(&mut bytes, width);
            let y = coordinate(&mut bytes, height);
            poly.push(ScreenVertex::new(x, y, depth(&mut bytes)).expect("inside the guard band"));
            let mut channel = || match bytes.u8() % 4 {
                0 => 0,
                1 => CHANNEL_MAX as u16,
                _ => bytes.u16(),
            };
            colors.push(Rgb8p8 {
                r: channel(),
                g: channel(),
                b: channel(),
            });
        }
        polygons.push((poly, colors));
    }
    let corners: usize = polygons.iter().map(|(p, _)| p.len()).sum();
    let caps = Capacities {
        width: CORE_WIDTH,
        vertices: corners,
        polygons: CORE_POLYGONS,
        corners,
        active_polygons: CORE_POLYGONS,
        pooled_edges: corners,
        mesh_vertices: 0,
    };
    let background = Rgb888::new(1, 2, 3);
    let uniform = |k: usize| Rgb888::new((k * 37 + 11) as u8, (k * 91 + 5) as u8, 200 + k as u8);
    let run = |flat_rows: &mut Vec<Vec<Rgb888>>, painted_rows: &mut Vec<Vec<Rgb888>>, z24: bool| {
        macro_rules! frames {
            ($d:ty) => {{
                let mut flat =
                    host_renderer::<Rgb888, $d>(&caps, width, height, background).expect("size");
                let mut uniform_painted =
                    HostPaintedRenderer::<Gouraud<Rgb888>, $d>::with_capacities(
                        &caps,
                        (width, height),
                        Gouraud::new(),
                        background,
                    )
                    .expect("size");
                let mut painted = HostPaintedRenderer::<Gouraud<Rgb888>, $d>::with_capacities(
                    &caps,
                    (width, height),
                    Gouraud::new(),
                    background,
                )
                .expect("size");
                for (k, (poly, colors)) in polygons.iter().enumerate() {
                    let a = flat.push_polygon_vertices(poly, uniform(k));
                    let same = vec![Rgb8p8::from_rgb888(uniform(k)); poly.len()];
                    let b = uniform_painted.push_polygon_vertices(poly, &same);
                    let c = painted.push_polygon_vertices(poly, colors);
                    assert_eq!(a, b, "{poly:?}");
                    assert_eq!(a, c, "{poly:?}");
                }
                flat.render(&mut KeepRows(flat_rows)).expect("flat frame");
                let mut uniform_rows = Vec::new();
                uniform_painted
                    .render(&mut KeepRows(&mut uniform_rows))
                    .expect("painted frame");
                assert_eq!(
                    &uniform_rows, flat_rows,
                    "uniform corners paint the flat frame"
                );
                painted
                    .render(&mut KeepRows(painted_rows))
                    .expect("painted frame");
                // The same prepared scene painted in two bands, the lower
                // by a second renderer's scanner and slots (as a second
                // core paints): the same rows.
                let mut other = HostPaintedRenderer::<Gouraud<Rgb888>, $d>::with_capacities(
                    &caps,
                    (width, height),
                    Gouraud::new(),
                    background,
                )
                .expect("size");
                let cut = (corners as u16).wrapping_mul(7) % (height + 1);
                let mut band_rows = Vec::new();
                crate::two_bands::paint_in_two_bands(
                    &mut painted,
                    &mut other,
                    cut,
                    height,
                    &mut KeepRows(&mut band_rows),
                )
                .expect("two bands");
                assert_eq!(
                    &band_rows, painted_rows,
                    "two bands paint the one-scan frame"
                );
            }};
        }
        if z24 {
            frames!(Depth24)
        } else {
            frames!(Depth16)
        }
    };
    let (mut flat_rows, mut painted_rows) = (Vec::new(), Vec::new());
    run(&mut flat_rows, &mut painted_rows, z24);
    if z24 {
        textured(
            data,
            &polygons,
            (width, height),
            &caps,
            &flat_rows,
            &uniform,
        );
    }
    // Which polygon each pixel shows, from the flat frame's colours.
    for (flat_row, painted_row) in flat_rows.iter().zip(&painted_rows) {
        for (&f, &p) in flat_row.iter().zip(painted_row) {
            let Some(k) = (0..polygons.len()).find(|&k| uniform(k) == f) else {
                assert_eq!(p, background);
                continue;
            };
            let (poly, colors) = &polygons[k];
            if poly.len() != 3 {
                continue;
            }
            let channel = |c: &Rgb8p8, i: usize| [c.r, c.g, c.b][i].min(CHANNEL_MAX as u16);
            let got = [p.r(), p.g(), p.b()];
            for (i, &value) in got.iter().enumerate() {
                let lo = colors.iter().map(|c| channel(c, i)).min().unwrap_or(0) >> 8;
                let hi = (colors.iter().map(|c| channel(c, i)).max().unwrap_or(0) + 255) >> 8;
                assert!(
                    u16::from(value) + 1 >= lo && u16::from(value) <= hi + 1,
                    "{poly:?} {colors:?}: channel {i} = {value} outside {lo}..={hi}"
                );
            }
        }
    }
}

/// The textured half of [`painted`] (z24 inputs): the same polygons mapped with
/// texture coordinates drawn from a generator seeded by the input (any
/// `uv`, `w` over many decades, nearest texels of a texture of distinct
/// colours, repeat or clamp). Every pixel a polygon wins shows one of the
/// texture's texels; a polygon whose corners share one coordinate shows
/// that coordinate's texel at every pixel it wins; nothing panics or
/// overflows.
fn textured(
    data: &[u8],
    polygons: &[(Vec<ScreenVertex>, Vec<zline::paint::Rgb8p8>)],
    (width, height): (u16, u16),
    caps: &Capacities,
    flat_rows: &[Vec<embedded_graphics_core::pixelcolor::Rgb888>],
    uniform: &dyn Fn(usize) -> embedded_graphics_core::pixelcolor::Rgb888,
) {
    use embedded_graphics_core::pixelcolor::Rgb888;
    use embedded_graphics_core::pixelcolor::raw::RawU16;
    use zline::host::HostPaintedRenderer;
    use zline::paint::{ClipW, TexCoord, Texture, Textured, UV_ONE, Wrap};
    let mut state = data.iter().fold(0x9E37_79B9_7F4A_7C15u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01B3)
    }) | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    const TW: u16 = 8;
    const TH: u16 = 4;
    let texels: Vec<u16> = (0..TW * TH)
        .map(|k| 0x0841u16.wrapping_mul(k + 1) ^ 0x8000)
        .collect();
    let color = |texel: u16| {
        Rgb888::from(embedded_graphics_core::pixelcolor::Rgb565::from(
            RawU16::new(texel),
        ))
    };
    let wrap = if next() % 2 == 0 {
        Wrap::Repeat
    } else {
        Wrap::Clamp
    };
    let texture = Texture::new(&texels, TW, TH).expect("size").with_wrap(wrap);
    let random_coord = |next: &mut dyn FnMut() -> u64| {
        let uv = |r: u64| match r % 4 {
            0 => (r >> 8) as i32,
            1 => ((r >> 8) as i32) % (4 * UV_ONE),
            2 => 0,
            _ => UV_ONE * ((r >> 8) % 9) as i32 - 4 * UV_ONE,
        };
        let w = match next() % 3 {
            0 => ClipW::from_f32(f32::from_bits((next() as u32) & 0x7FFF_FFFF)),
            1 => ClipW::from_i64((next() >> (next() % 64)) as i64),
            _ => ClipW::from_f32(0.1 + (next() % 1000) as f32 / 10.0),
        };
        TexCoord {
            uv: [uv(next()), uv(next())],
            w,
        }
    };
    // Each polygon's coordinates, and the texel of the uniform ones.
    let mut coords = Vec::new();
    let mut expected = Vec::new();
    for (poly, _) in polygons {
        if next() % 3 == 0 {
            let c = random_coord(&mut next);
            let corners: Vec<TexCoord> = poly
                .iter()
                .map(|_| TexCoord {
                    w: random_coord(&mut next).w,
                    ..c
                })
                .collect();
            let texel = |a: usize, size: u16| {
                let t = (i64::from(c.uv[a]) * i64::from(size)).div_euclid(i64::from(UV_ONE));
                match wrap {
                    Wrap::Repeat => t.rem_euclid(i64::from(size)),
                    Wrap::Clamp => t.clamp(0, i64::from(size) - 1),
                }
            };
            expected.push(Some(
                texels[(texel(1, TH) * i64::from(TW) + texel(0, TW)) as usize],
            ));
            coords.push(corners);
        } else {
            coords.push(poly.iter().map(|_| random_coord(&mut next)).collect());
            expected.push(None);
        }
    }
    let background = Rgb888::new(1, 2, 3);
    let mut rows = Vec::new();
    let mut painted = HostPaintedRenderer::<Textured<'_, Rgb888>, zline::Depth24>::with_capacities(
        caps,
        (width, height),
        Textured::new(texture),
        background,
    )
    .expect("size");
    for ((poly, _), corners) in polygons.iter().zip(&coords) {
        painted
            .push_polygon_vertices(poly, corners)
            .expect("admitted as the flat one");
    }
    painted
        .render(&mut KeepRows(&mut rows))
        .expect("textured frame");
    let palette: Vec<Rgb888> = texels.iter().map(|&t| color(t)).collect();
    for (flat_row, row) in flat_rows.iter().zip(&rows) {
        for (&f, &p) in flat_row.iter().zip(row) {
            let Some(k) = (0..polygons.len()).find(|&k| uniform(k) == f) else {
                assert_eq!(p, background);
                continue;
            };
            assert!(palette.contains(&p), "polygon {k}: {p:?} is no texel");
            if let Some(texel) = expected[k] {
                assert_eq!(
                    p,
                    color(texel),
                    "polygon {k} with one coordinate {:?}",
                    coords[k]
                );
            }
        }
    }
    lit_textured(
        polygons,
        &coords,
        (width, height),
        caps,
        texture,
        &rows,
        &mut next,
    );
}

/// The same polygons lit (`LitTextured`, undithered): under full light (or
/// brighter, clamped) every pixel is the unlit frame's; under random
/// corner lights no channel of any pixel is brighter than the unlit one.
fn lit_textured(
    polygons: &[(Vec<ScreenVertex>, Vec<zline::paint::Rgb8p8>)],
    coords: &[Vec<zline::paint::TexCoord>],
    (width, height): (u16, u16),
    caps: &Capacities,
    texture: zline::paint::Texture<'_>,
    unlit: &[Vec<embedded_graphics_core::pixelcolor::Rgb888>],
    next: &mut dyn FnMut() -> u64,
) {
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
    use zline::host::HostPaintedRenderer;
    use zline::paint::{CHANNEL_MAX, LitTexCoord, LitTextured, Rgb8p8};
    let background = Rgb888::new(1, 2, 3);
    for full in [true, false] {
        let mut lit =
            HostPaintedRenderer::<LitTextured<'_, Rgb888>, zline::Depth24>::with_capacities(
                caps,
                (width, height),
                LitTextured::with_dither(texture, false),
                background,
            )
            .expect("size");
        for ((poly, _), corners) in polygons.iter().zip(coords) {
            let values: Vec<LitTexCoord> = corners
                .iter()
                .map(|&c| {
                    let mut level = || {
                        let l = next() as u16;
                        if full { l.max(CHANNEL_MAX as u16) } else { l }
                    };
                    LitTexCoord::new(
                        c,
                        Rgb8p8 {
                            r: level(),
                            g: level(),
                            b: level(),
                        },
                    )
                })
                .collect();
            lit.push_polygon_vertices(poly, &values)
                .expect("admitted as the flat one");
        }
        let mut rows = Vec::new();
        lit.render(&mut KeepRows(&mut rows)).expect("lit frame");
        for (lit_row, row) in rows.iter().zip(unlit) {
            for (&l, &u) in lit_row.iter().zip(row) {
                if full {
                    assert_eq!(l, u, "full light");
                } else {
                    assert!(
                        l.r() <= u.r() && l.g() <= u.g() && l.b() <= u.b(),
                        "lit {l:?} brighter than unlit {u:?}"
                    );
                }
            }
        }
    }
}
