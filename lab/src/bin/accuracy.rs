//! Accuracy of the scanline core against the float64 reference, for every
//! mesh in a folder at three views, for both depth formats.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin accuracy -- ../shared/meshes [--size WxH] [--cull none|back]
//! ```
//!
//! For each mesh, view and format it prints: pixels, mismatches (face id
//! differs from the reference), excused at edges (the sample lies within
//! 1/16 px of the boundary of the drawn or the reference face), excused as
//! depth ties (the drawn face's plane is within 0.1 % of the nearest
//! depth along the pixel's ray), and hard mismatches (the rest). It exits
//! non-zero when any z24 frame has a hard mismatch. z16 is reported, not
//! enforced.
//!
//! Gouraud shading ([`zline::paint::Gouraud`], per-vertex Lambert of
//! [`Shading::lambert`]) is measured on each mesh read smooth
//! (`HostMesh::from_obj_smooth`, 60° crease) at the same views, z24: face
//! ids against the reference (hard mismatches as above), and over the
//! pixels whose face id matches, each channel's error in 8-bit steps
//! against the reference's vertex colours (Lambert in `f64` from the
//! mesh's normals turned by the view) interpolated as the reference
//! defines it ([`ReferenceFrame::interpolated`]): of the 8-bit colour the
//! core paints without dither, which is what a display gets before
//! dithering. It exits non-zero
//! unless every frame has no hard mismatch, its 8-bit error at most 1
//! step on 99.9 % of its matched pixels and at most 2 steps on every pixel
//! more than 1/16 px from its face's boundary (the tolerance of face ids
//! at edges: there, corners snapped to 1/256 px can move a sliver's
//! values by more; the largest error of all pixels is printed too), and
//! at most 2 steps on every pixel against the reference's values over the
//! corners rounded to the 1/256 px grid the core is given
//! ([`ReferenceFrame::interpolated_on_grid`]).
//!
//! Each mesh runs twice through the scanline core: in `f32` (`z16`,
//! `z24`), and quantized (`QuantizedHostMesh`: `i16` positions in its
//! bounding sphere, a unit normal per face) through the integer front end
//! (`z16 int`, `z24 int`), the path a microcontroller without an FPU
//! takes. Both are compared with the reference of the original mesh.

use std::path::PathBuf;
use std::process::ExitCode;

use embedded_graphics_core::pixelcolor::RgbColor;
use zline::Mat4;
use zline::Mesh;
use zline::Shading;
use zline::host::HostPaintedRenderer;
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::paint::{
    CHANNEL_MAX, Filter, Gouraud, LitTexCoord, LitTextured, PaintColor, PaintMode, Textured,
};
use zline::{Camera, Cull, VertexInfo, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline::{FnSink, Lambert};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, obj_files};
use zline_lab::methods::EDGE_TOLERANCE;
use zline_lab::methods::{
    BACKGROUND, Comparison, Method, MethodRenderer, ReferenceCamera, ReferenceFrame, ReferenceView,
    compare, rotate,
};
use zline_lab::textures::{Rgb565Texture, white_light};

/// (yaw, pitch) of the three views, degrees.
const VIEWS: [(f32, f32); 3] = [(30.0, 20.0), (135.0, -30.0), (250.0, 65.0)];

struct Options {
    dir: PathBuf,
    width: u16,
    height: u16,
    cull: Cull,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        dir: PathBuf::new(),
        width: 320,
        height: 240,
        cull: Cull::None,
    };
    let mut dir = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--size" => (o.width, o.height) = parse_size(it.next().ok_or("--size needs WxH")?)?,
            "--cull" => {
                o.cull = match it.next().map(String::as_str) {
                    Some("none") => Cull::None,
                    Some("back") => Cull::Back,
                    _ => return Err("--cull needs none or back".into()),
                }
            }
            s if dir.is_none() && !s.starts_with("--") => dir = Some(PathBuf::from(s)),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    o.dir = dir.ok_or("usage: accuracy MESH_DIR [--size WxH] [--cull none|back]")?;
    Ok(o)
}

/// One configuration of the run: a method, a depth format, and whether the
/// mesh goes through the integer front end (quantized).
struct Config {
    label: &'static str,
    method: Method,
    z24: bool,
    quantized: bool,
    /// Whether CI fails on a hard mismatch (every method but the painter).
    enforced: bool,
}

const CONFIGS: [Config; 8] = [
    Config {
        label: "scanline z16",
        method: Method::Scanline,
        z24: false,
        quantized: false,
        enforced: false,
    },
    Config {
        label: "scanline z24",
        method: Method::Scanline,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "scanline z16 int",
        method: Method::Scanline,
        z24: false,
        quantized: true,
        enforced: false,
    },
    Config {
        label: "scanline z24 int",
        method: Method::Scanline,
        z24: true,
        quantized: true,
        enforced: true,
    },
    Config {
        label: "zbuffer z24",
        method: Method::ZBuffer,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "bands:8 z24",
        method: Method::Bands(8),
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "interval",
        method: Method::Interval,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "painter",
        method: Method::Painter,
        z24: true,
        quantized: false,
        enforced: false,
    },
];

fn ids<D: DepthFormat, M: Mesh>(
    r: &mut MethodRenderer<D>,
    method: Method,
    mesh: &M,
    model: &Mat4,
    o: &Options,
    view: &ReferenceView,
) -> Result<Vec<u32>, String>
where
    D::Value: Into<u32>,
{
    let camera = Camera::reference(o.width, o.height);
    Ok(
        r.render(method, mesh, model, &camera, o.cull, &Shading::FaceId, view)?
            .faces,
    )
}

/// A painted pixel's channels (8.8): a bilinear texel as the core blended
/// it, before any quantisation; a Gouraud pixel's 8-bit level, as the
/// core rounds it without dither.
#[derive(Debug, Clone, Copy, Default)]
struct Channels([u32; 3]);

impl PaintColor for Channels {
    const MAX: [u32; 3] = [255; 3];
    const COARSE: bool = false;
    fn from_levels(levels: [u32; 3]) -> Self {
        Self(levels.map(|c| c << 8))
    }
    fn from_channels(rgb: [u32; 3], _: Option<u32>) -> Self {
        Self(rgb.map(|c| c.min(CHANNEL_MAX)))
    }
}

/// Colour errors of one Gouraud frame over its matched pixels, in 8-bit
/// steps.
#[derive(Default)]
struct ColorErrors {
    matched: u64,
    /// Largest and summed error of the 8-bit colours.
    max_8bit: f64,
    sum_8bit: f64,
    /// Pixels whose 8-bit colour is more than 1 step off.
    over_one: u64,
    /// Largest 8-bit error of pixels whose sample is more than
    /// [`EDGE_TOLERANCE`] from the face's boundary (nearer, corners
    /// snapped to the sub-pixel grid can move a sliver's values by more).
    max_8bit_inside: f64,
    /// Largest 8-bit error of all pixels against the reference's values
    /// over corners rounded to the sub-pixel grid, as the core is given
    /// them ([`ReferenceFrame::interpolated_on_grid`]).
    max_8bit_on_grid: f64,
}

impl ColorErrors {
    fn add(&mut self, other: &Self) {
        self.matched += other.matched;
        self.max_8bit = self.max_8bit.max(other.max_8bit);
        self.sum_8bit += other.sum_8bit;
        self.over_one += other.over_one;
        self.max_8bit_inside = self.max_8bit_inside.max(other.max_8bit_inside);
        self.max_8bit_on_grid = self.max_8bit_on_grid.max(other.max_8bit_on_grid);
    }

    /// Share of matched pixels within 1 step (8-bit).
    fn within_one(&self) -> f64 {
        1.0 - self.over_one as f64 / self.matched.max(1) as f64
    }

    /// The bar: at most 1 step on 99.9 % of the matched pixels, at most 2
    /// on every pixel more than [`EDGE_TOLERANCE`] from its face's
    /// boundary (the tolerance that excuses face-id mismatches at edges),
    /// and at most 2 on every pixel against the values over the corners
    /// on the sub-pixel grid.
    fn meets_the_bar(&self) -> bool {
        self.max_8bit_inside <= 2.0 && self.max_8bit_on_grid <= 2.0 && self.within_one() >= 0.999
    }
}

/// The reference's vertex colours for `lambert` (8-bit units, `f64`): its
/// Lambert of each vertex normal turned by the view, one-sided; a vertex
/// with no normal lit as if it faced the light.
fn reference_vertex_colors<'a>(
    mesh: &'a HostMesh,
    view: &'a ReferenceView,
    lambert: &'a Lambert,
) -> impl Fn(usize) -> [f64; 3] + 'a {
    let l = lambert.light();
    let l = [l.x, l.y, l.z].map(f64::from);
    let len = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let l = l.map(|c| c / len);
    let ambient = f64::from(lambert.ambient());
    let base = lambert.base();
    let base = [base.r(), base.g(), base.b()].map(f64::from);
    move |v| {
        let d = mesh.vertex_normal(v).map_or(1.0, |n| {
            let n = rotate(view, n.map(f64::from));
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len
        });
        let k = ambient + (1.0 - ambient) * d.max(0.0);
        base.map(|c| c * k)
    }
}

/// One Gouraud frame of `mesh` (read smooth) against the reference:
/// face-id comparison and colour errors.
fn gouraud_frame(
    mesh: &HostMesh,
    view: (f32, f32),
    reference_view: &ReferenceView,
    o: &Options,
    ids_renderer: &mut MethodRenderer<Depth24>,
) -> Result<(Comparison, ColorErrors), String> {
    let Shading::Lambert(lambert) = Shading::lambert() else {
        return Err("Shading::lambert() is not Lambert".into());
    };
    let colors = reference_vertex_colors(mesh, reference_view, &lambert);
    let reference = ReferenceFrame::render_with_values(
        mesh,
        reference_view,
        &ReferenceCamera::STANDARD,
        &colors,
    );
    let model = reference_model(mesh, view.0, view.1).map_err(|e| e.to_string())?;
    let faces = ids(
        ids_renderer,
        Method::Scanline,
        mesh,
        &model,
        o,
        reference_view,
    )?;
    let comparison = compare(&reference, &faces);
    let shading = Shading::Lambert(lambert);
    let values = painted_values(mesh, Gouraud::new(), &model, o, |v| shading.vertex_color(v))?;
    let mut errors = ColorErrors::default();
    let width = usize::from(o.width);
    for (k, (&id, value)) in faces.iter().zip(&values).enumerate() {
        if id == BACKGROUND || id != reference.ids[k] {
            continue;
        }
        let Some(exact) = reference.interpolated(id, k % width, k / width) else {
            continue;
        };
        let on_grid = reference
            .interpolated_on_grid(id, k % width, k / width)
            .unwrap_or(exact);
        let (mut worst_8bit, mut worst_on_grid) = (0.0f64, 0.0f64);
        for c in 0..3 {
            let eight_bit = f64::from(value.0[c] >> 8);
            let error = |exact: f64| (eight_bit - exact.clamp(0.0, 255.0)).abs();
            worst_8bit = worst_8bit.max(error(exact[c]));
            worst_on_grid = worst_on_grid.max(error(on_grid[c]));
        }
        errors.max_8bit_on_grid = errors.max_8bit_on_grid.max(worst_on_grid);
        errors.matched += 1;
        errors.max_8bit = errors.max_8bit.max(worst_8bit);
        errors.sum_8bit += worst_8bit;
        errors.over_one += u64::from(worst_8bit > 1.0);
        if reference.boundary_distance(id, k % width, k / width) > EDGE_TOLERANCE {
            errors.max_8bit_inside = errors.max_8bit_inside.max(worst_8bit);
        }
    }
    Ok((comparison, errors))
}

fn gouraud_row(name: &str, view: (f32, f32), c: &Comparison, e: &ColorErrors) {
    let mean = |sum: f64| sum / e.matched.max(1) as f64;
    println!(
        "| {name} | {:.0}/{:.0} | {} | {} | {:.3} | {:.3} | {:.3} | {:.4} | {:.4} % |",
        view.0,
        view.1,
        c.hard,
        e.matched,
        e.max_8bit,
        e.max_8bit_inside,
        e.max_8bit_on_grid,
        mean(e.sum_8bit),
        100.0 * e.within_one()
    );
}

/// The Gouraud table: every mesh read smooth, at the three views, z24.
fn gouraud(o: &Options) -> Result<bool, String> {
    let mut ids_renderer = MethodRenderer::<Depth24>::new(o.width, o.height)?;
    println!();
    println!(
        "Gouraud, z24: colour error in 8-bit steps (largest channel) over pixels whose face id matches the reference"
    );
    println!();
    println!(
        "| mesh | yaw/pitch | hard mismatches | matched pixels | max (8-bit) | max (8-bit) beyond 1/16 px of an edge | max (8-bit), corners on the 1/256 px grid | mean (8-bit) | within 1 step (8-bit) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let (mut ok, mut hard) = (true, 0);
    let mut all = ColorErrors::default();
    for path in obj_files(&o.dir)? {
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = HostMesh::from_obj_smooth(&bytes, zline::host::DEFAULT_CREASE_DEGREES)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        for view in VIEWS {
            let reference_view = ReferenceView {
                width: usize::from(o.width),
                height: usize::from(o.height),
                yaw_deg: f64::from(view.0),
                pitch_deg: f64::from(view.1),
                cull_back: o.cull == Cull::Back,
            };
            let (c, e) = gouraud_frame(&mesh, view, &reference_view, o, &mut ids_renderer)?;
            gouraud_row(&name, view, &c, &e);
            ok &= c.hard == 0 && e.meets_the_bar();
            hard += c.hard;
            all.add(&e);
        }
    }
    let total = Comparison {
        hard,
        ..Comparison::default()
    };
    gouraud_row("**all**", (0.0, 0.0), &total, &all);
    println!(
        "gouraud: hard mismatches {hard}, largest 8-bit error {:.3} ({:.3} beyond 1/16 px of an edge, {:.3} against corners on the 1/256 px grid), within 1 step {:.4} % ({})",
        all.max_8bit,
        all.max_8bit_inside,
        all.max_8bit_on_grid,
        100.0 * all.within_one(),
        if ok { "ok" } else { "FAILED" }
    );
    Ok(ok)
}

/// How far (texels) the core's texture coordinates may be from the exact
/// ones: its stated bound (`CHORD_TOLERANCE + 2` units of `2^-8` texel,
/// see `zline::paint::Textured`) and the rounding of each vertex's
/// coordinates to `2^-16` of the texture (`2^-17 · 1024` texels for
/// Spot's), below `1/32`.
const TEXEL_TOLERANCE: f64 = 1.0 / 32.0;

/// Colour errors of one textured frame over its matched pixels.
#[derive(Default)]
struct TextureErrors {
    matched: u64,
    /// Pixels whose nearest texel is not the one holding the exact
    /// coordinates.
    other_texel: u64,
    /// Largest and summed 8-bit error (largest channel) against the
    /// nearest texel closest in colour among those within
    /// [`TEXEL_TOLERANCE`] of the exact coordinates.
    max_nearest: f64,
    sum_nearest: f64,
    /// Pixels more than 1 step off by that measure.
    over_one: u64,
    /// Largest and summed error of bilinear sampling (8.8 values, in 8-bit
    /// steps) against the exact coordinates' bilinear blend in `f64`.
    max_bilinear: f64,
    sum_bilinear: f64,
    /// Lit (`LitTextured`, nearest): largest and summed 8-bit error
    /// against the exact light (the Gouraud reference's, on a white
    /// surface) times the nearest texel closest in result among those
    /// within [`TEXEL_TOLERANCE`], and pixels more than 1 step off.
    max_lit: f64,
    sum_lit: f64,
    lit_over_one: u64,
}

impl TextureErrors {
    fn add(&mut self, other: &Self) {
        self.matched += other.matched;
        self.other_texel += other.other_texel;
        self.max_nearest = self.max_nearest.max(other.max_nearest);
        self.sum_nearest += other.sum_nearest;
        self.over_one += other.over_one;
        self.max_bilinear = self.max_bilinear.max(other.max_bilinear);
        self.sum_bilinear += other.sum_bilinear;
        self.max_lit = self.max_lit.max(other.max_lit);
        self.sum_lit += other.sum_lit;
        self.lit_over_one += other.lit_over_one;
    }

    fn lit_within_one(&self) -> f64 {
        1.0 - self.lit_over_one as f64 / self.matched.max(1) as f64
    }

    fn within_one(&self) -> f64 {
        1.0 - self.over_one as f64 / self.matched.max(1) as f64
    }

    /// The issue's bar for nearest sampling: at most 1 step on 99.9 % of
    /// matched pixels and at most 2 on all.
    fn meets_the_bar(&self) -> bool {
        self.max_nearest <= 2.0
            && self.within_one() >= 0.999
            && self.max_lit <= 2.0
            && self.lit_within_one() >= 0.999
    }
}

/// A texel's 8-bit channels as the core widens them (embedded-graphics'
/// Rgb565 to Rgb888).
fn texel_rgb(texture: &Rgb565Texture, i: i64, j: i64) -> [f64; 3] {
    let (w, h) = (i64::from(texture.width), i64::from(texture.height));
    let t = texture.texels[(j.rem_euclid(h) * w + i.rem_euclid(w)) as usize];
    let widen = |c: u16, max: u32| f64::from((u32::from(c) * 255 + max / 2) / max);
    [
        widen(t >> 11, 31),
        widen((t >> 5) & 0x3F, 63),
        widen(t & 0x1F, 31),
    ]
}

/// A painted frame's pixels (8.8 channels) drawn by the core in `mode`
/// (z24), each vertex's source from `shade`.
fn painted_values<M: PaintMode<Color = Channels>>(
    mesh: &HostMesh,
    mode: M,
    model: &Mat4,
    o: &Options,
    shade: impl Fn(&VertexInfo<'_>) -> M::Source,
) -> Result<Vec<Channels>, String> {
    let camera = Camera::reference(o.width, o.height);
    let mut painted = HostPaintedRenderer::<M, Depth24>::for_mesh(
        mesh,
        o.width,
        o.height,
        mode,
        Channels::default(),
    )
    .map_err(|e| e.to_string())?;
    painted
        .draw_mesh(mesh, model, &camera, o.cull, shade)
        .map_err(|e| e.to_string())?;
    let mut values = Vec::with_capacity(usize::from(o.width) * usize::from(o.height));
    painted
        .render(&mut FnSink(|_: u16, row: &[Channels], _: &[u32]| {
            values.extend_from_slice(row);
            Ok::<(), ()>(())
        }))
        .map_err(|e| format!("{e:?}"))?;
    Ok(values)
}

/// One textured frame of `mesh` against the reference: face ids, and the
/// colours of nearest and bilinear sampling at the exact
/// perspective-correct coordinates.
fn textured_frame(
    mesh: &HostMesh,
    png: &Rgb565Texture,
    view: (f32, f32),
    reference_view: &ReferenceView,
    o: &Options,
    ids_renderer: &mut MethodRenderer<Depth24>,
) -> Result<(Comparison, TextureErrors), String> {
    let uv = |v: usize| {
        let [u, v] = mesh.vertex_uv(v).unwrap_or([0.0; 2]);
        [f64::from(u), f64::from(v), 0.0]
    };
    let reference =
        ReferenceFrame::render_with_values(mesh, reference_view, &ReferenceCamera::STANDARD, &uv);
    let model = reference_model(mesh, view.0, view.1).map_err(|e| e.to_string())?;
    let faces = ids(
        ids_renderer,
        Method::Scanline,
        mesh,
        &model,
        o,
        reference_view,
    )?;
    let comparison = compare(&reference, &faces);
    let texture = png.texture()?;
    let textured =
        |texture| painted_values(mesh, Textured::new(texture), &model, o, |v| v.tex_coord());
    let nearest = textured(texture)?;
    let bilinear = textured(texture.with_filter(Filter::Bilinear))?;
    // Lit: Lambert of a white surface per vertex, as the render tool's
    // `--shade lit-texture` lights.
    let white = white_light();
    let lights = ReferenceFrame::render_with_values(
        mesh,
        reference_view,
        &ReferenceCamera::STANDARD,
        &reference_vertex_colors(mesh, reference_view, &white),
    );
    let lit = painted_values(mesh, LitTextured::new(texture), &model, o, |v| {
        LitTexCoord::new(v.tex_coord(), white.vertex_color(v))
    })?;
    let (tw, th) = (f64::from(png.width), f64::from(png.height));
    let mut errors = TextureErrors::default();
    let width = usize::from(o.width);
    for (k, &id) in faces.iter().enumerate() {
        if id == BACKGROUND || id != reference.ids[k] {
            continue;
        }
        let Some([u, v]) = reference.interpolated_perspective(id, k % width, k / width) else {
            continue;
        };
        // Texel units, rows down from the top (OBJ's v is up).
        let (x, y) = (u * tw, (1.0 - v) * th);
        let distance = |got: [u32; 3], want: [f64; 3]| {
            (0..3)
                .map(|c| (f64::from(got[c]) / 256.0 - want[c]).abs())
                .fold(0.0, f64::max)
        };
        // Nearest: the texel holding the point, or any within the
        // tolerance of it.
        let got = nearest[k].0;
        let exact_texel = texel_rgb(png, x.floor() as i64, y.floor() as i64);
        let same = distance(got, exact_texel) == 0.0;
        let mut best = f64::INFINITY;
        for i in [(x - TEXEL_TOLERANCE).floor(), (x + TEXEL_TOLERANCE).floor()] {
            for j in [(y - TEXEL_TOLERANCE).floor(), (y + TEXEL_TOLERANCE).floor()] {
                best = best.min(distance(got, texel_rgb(png, i as i64, j as i64)));
            }
        }
        // Bilinear: the four centres around the point, weighted exactly.
        let (bx, by) = (x - 0.5, y - 0.5);
        let (i0, j0) = (bx.floor(), by.floor());
        let (fx, fy) = (bx - i0, by - j0);
        let (i0, j0) = (i0 as i64, j0 as i64);
        let blend: [f64; 3] = std::array::from_fn(|c| {
            let t = |i, j| texel_rgb(png, i, j)[c];
            (t(i0, j0) * (1.0 - fx) + t(i0 + 1, j0) * fx) * (1.0 - fy)
                + (t(i0, j0 + 1) * (1.0 - fx) + t(i0 + 1, j0 + 1) * fx) * fy
        });
        let bilinear_error = distance(bilinear[k].0, blend);
        // Lit: the exact light (affine in screen space, as Gouraud's)
        // times the candidate texels, the closest taken.
        let light = lights
            .interpolated(id, k % width, k / width)
            .unwrap_or([255.0; 3])
            .map(|c| c.clamp(0.0, 255.0) / 255.0);
        let mut lit_best = f64::INFINITY;
        for i in [(x - TEXEL_TOLERANCE).floor(), (x + TEXEL_TOLERANCE).floor()] {
            for j in [(y - TEXEL_TOLERANCE).floor(), (y + TEXEL_TOLERANCE).floor()] {
                let t = texel_rgb(png, i as i64, j as i64);
                let want: [f64; 3] = std::array::from_fn(|c| t[c] * light[c]);
                // The 8-bit value the core rounds to without dither.
                let got = lit[k].0.map(|c| ((c + 128) >> 8) << 8);
                lit_best = lit_best.min(distance(got, want));
            }
        }
        errors.max_lit = errors.max_lit.max(lit_best);
        errors.sum_lit += lit_best;
        errors.lit_over_one += u64::from(lit_best > 1.0);
        errors.matched += 1;
        errors.other_texel += u64::from(!same);
        errors.max_nearest = errors.max_nearest.max(best);
        errors.sum_nearest += best;
        errors.over_one += u64::from(best > 1.0);
        errors.max_bilinear = errors.max_bilinear.max(bilinear_error);
        errors.sum_bilinear += bilinear_error;
    }
    Ok((comparison, errors))
}

fn textured_row(name: &str, view: (f32, f32), c: &Comparison, e: &TextureErrors) {
    let mean = |sum: f64| sum / e.matched.max(1) as f64;
    println!(
        "| {name} | {:.0}/{:.0} | {} | {} | {} ({:.4} %) | {:.3} | {:.4} | {:.4} % | {:.3} | {:.4} | {:.3} | {:.4} | {:.4} % |",
        view.0,
        view.1,
        c.hard,
        e.matched,
        e.other_texel,
        100.0 * e.other_texel as f64 / e.matched.max(1) as f64,
        e.max_nearest,
        mean(e.sum_nearest),
        100.0 * e.within_one(),
        e.max_bilinear,
        mean(e.sum_bilinear),
        e.max_lit,
        mean(e.sum_lit),
        100.0 * e.lit_within_one(),
    );
}

/// The texture table: every mesh of the folder with a texture beside it
/// (`NAME_texture.png` for `NAME.obj`), read smooth (its `vt` kept), at
/// the three views, z24.
fn textured(o: &Options) -> Result<bool, String> {
    let mut ids_renderer = MethodRenderer::<Depth24>::new(o.width, o.height)?;
    println!();
    println!(
        "Textured, perspective-correct, z24: colour error in 8-bit steps (largest channel) over pixels whose face id matches the reference; nearest texels within 1/32 texel of the exact coordinates allowed"
    );
    println!();
    println!(
        "| mesh | yaw/pitch | hard mismatches | matched pixels | other texel than the exact one | max (nearest) | mean (nearest) | within 1 step (nearest) | max (bilinear) | mean (bilinear) | max (lit) | mean (lit) | within 1 step (lit) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut ok, mut hard, mut meshes) = (true, 0, 0);
    let mut all = TextureErrors::default();
    for path in obj_files(&o.dir)? {
        let Some(stem) = path.file_stem().map(|s| s.to_string_lossy().into_owned()) else {
            continue;
        };
        let texture_path = path.with_file_name(format!("{stem}_texture.png"));
        if !texture_path.exists() {
            continue;
        }
        meshes += 1;
        let png = Rgb565Texture::read(&texture_path, 1)?;
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = HostMesh::from_obj_smooth(&bytes, zline::host::DEFAULT_CREASE_DEGREES)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let name = format!("{stem}.obj");
        for view in VIEWS {
            let reference_view = ReferenceView {
                width: usize::from(o.width),
                height: usize::from(o.height),
                yaw_deg: f64::from(view.0),
                pitch_deg: f64::from(view.1),
                cull_back: o.cull == Cull::Back,
            };
            let (c, e) = textured_frame(&mesh, &png, view, &reference_view, o, &mut ids_renderer)?;
            textured_row(&name, view, &c, &e);
            ok &= c.hard == 0 && e.meets_the_bar();
            hard += c.hard;
            all.add(&e);
        }
    }
    let total = Comparison {
        hard,
        ..Comparison::default()
    };
    textured_row("**all**", (0.0, 0.0), &total, &all);
    println!(
        "textured: meshes {meshes}, hard mismatches {hard}, other texel {:.4} %, largest 8-bit error (nearest) {:.3}, within 1 step {:.4} %, largest bilinear error {:.3}, lit: largest {:.3}, within 1 step {:.4} % ({})",
        100.0 * all.other_texel as f64 / all.matched.max(1) as f64,
        all.max_nearest,
        100.0 * all.within_one(),
        all.max_bilinear,
        all.max_lit,
        100.0 * all.lit_within_one(),
        if ok { "ok" } else { "FAILED" }
    );
    Ok(ok)
}

fn row(name: &str, view: (f32, f32), format: &str, c: &Comparison) {
    println!(
        "| {name} | {:.0}/{:.0} | {format} | {} | {} | {} | {} | {} |",
        view.0, view.1, c.pixels, c.mismatches, c.excused_at_edges, c.excused_as_ties, c.hard
    );
}

fn run(args: &[String]) -> Result<bool, String> {
    let o = parse(args)?;
    let mut z16 = MethodRenderer::<Depth16>::new(o.width, o.height)?;
    let mut z24 = MethodRenderer::<Depth24>::new(o.width, o.height)?;
    println!(
        "| mesh | yaw/pitch | method | pixels | mismatches | excused at edges | excused as ties | hard |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut totals = [(); CONFIGS.len()].map(|()| Comparison::default());
    for path in obj_files(&o.dir)? {
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = HostMesh::from_obj(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        let quantized =
            QuantizedHostMesh::new(&mesh).map_err(|e| format!("{}: {e}", path.display()))?;
        let quantized = quantized
            .mesh()
            .map_err(|e| format!("{}: {e:?}", path.display()))?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        for view in VIEWS {
            let reference_view = ReferenceView {
                width: usize::from(o.width),
                height: usize::from(o.height),
                yaw_deg: f64::from(view.0),
                pitch_deg: f64::from(view.1),
                cull_back: o.cull == Cull::Back,
            };
            let reference = ReferenceFrame::render(&mesh, &reference_view);
            let model = reference_model(&mesh, view.0, view.1).map_err(|e| e.to_string())?;
            for (config, totals) in CONFIGS.iter().zip(&mut totals) {
                let v = &reference_view;
                let faces = match (config.z24, config.quantized) {
                    (false, false) => ids(&mut z16, config.method, &mesh, &model, &o, v)?,
                    (true, false) => ids(&mut z24, config.method, &mesh, &model, &o, v)?,
                    (false, true) => ids(&mut z16, config.method, &quantized, &model, &o, v)?,
                    (true, true) => ids(&mut z24, config.method, &quantized, &model, &o, v)?,
                };
                let c = compare(&reference, &faces);
                row(&name, view, config.label, &c);
                totals.pixels += c.pixels;
                totals.mismatches += c.mismatches;
                totals.excused_at_edges += c.excused_at_edges;
                totals.excused_as_ties += c.excused_as_ties;
                totals.hard += c.hard;
            }
        }
    }
    let mut ok = true;
    let mut summary = Vec::new();
    for (config, t) in CONFIGS.iter().zip(&totals) {
        row("**all**", (0.0, 0.0), config.label, t);
        if config.enforced && t.hard > 0 {
            ok = false;
        }
        summary.push(format!("{} {}", config.label, t.hard));
    }
    println!(
        "accuracy: hard mismatches (0 required for every method but the painter and z16): {}",
        summary.join(", ")
    );
    let gouraud_ok = gouraud(&o)?;
    let textured_ok = textured(&o)?;
    Ok(ok && gouraud_ok && textured_ok)
}

const USAGE: &str = "usage: accuracy MESH_DIR [--size WxH] [--cull none|back]
Every method against the float64 reference on every mesh of MESH_DIR at three views, both depth
formats; prints Markdown tables and exits non-zero on a hard mismatch of any method but the painter.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("accuracy", USAGE, move || match run(&args)? {
        true => Ok(()),
        false => Err("hard mismatches, or Gouraud or texture colour errors above the bar".into()),
    })
}
