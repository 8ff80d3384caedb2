//! `DrawTargetSink::changed_only`: frame after frame, a display that is
//! sent only the changed part of each row shows exactly what one sent
//! whole rows shows, and it is sent no more pixels.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use proptest::prelude::*;
use zline::{Capacities, Depth16, DrawTargetSink, RowSpan, ScreenVertex};

const W: u16 = 40;
const H: u16 = 24;
const CAPS: Capacities = Capacities {
    width: W as usize,
    vertices: 24,
    polygons: 8,
    corners: 24,
    active_polygons: 8,
    pooled_edges: 0,
    mesh_vertices: 0,
};
type Zr = zline::renderer_type!(Rgb565, Depth16, CAPS);
const BACKGROUND: Rgb565 = Rgb565::new(0, 0, 8);

/// A display in memory that implements only `draw_iter`, counting the
/// pixels it is sent.
struct Plain {
    pixels: Vec<Rgb565>,
    sent: usize,
}

impl Plain {
    fn new() -> Self {
        // Not the background: a frame that leaves a pixel unsent shows.
        Self {
            pixels: vec![Rgb565::new(31, 0, 31); usize::from(W) * usize::from(H)],
            sent: 0,
        }
    }
}

impl OriginDimensions for Plain {
    fn size(&self) -> Size {
        Size::new(u32::from(W), u32::from(H))
    }
}

impl DrawTarget for Plain {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if Rectangle::new(Point::zero(), self.size()).contains(p) {
                self.pixels[p.y as usize * usize::from(W) + p.x as usize] = c;
                self.sent += 1;
            }
        }
        Ok(())
    }
}

/// One frame: triangles as (x, y) corners, each with a depth and a colour.
type Frame = Vec<([(f32, f32); 3], f32, u16)>;

fn draw(renderer: &mut Zr, frame: &Frame) {
    renderer.clear();
    for (corners, z, color) in frame {
        let v: Vec<ScreenVertex> = corners
            .iter()
            .map(|&(x, y)| ScreenVertex::from_f32(x, y, *z).unwrap())
            .collect();
        renderer
            .push_polygon_vertices(&v, Rgb565::from(RawU16::new(*color)))
            .unwrap();
    }
}

fn frames() -> impl Strategy<Value = Vec<Frame>> {
    let corner = (-4.0f32..44.0, -4.0f32..28.0);
    let triangle = (
        [corner.clone(), corner.clone(), corner],
        0.05f32..0.95,
        1u16..u16::MAX,
    );
    prop::collection::vec(prop::collection::vec(triangle, 0..6), 1..6)
}

proptest! {
    #[test]
    fn changed_rows_show_what_whole_rows_show(frames in frames()) {
        let mut renderer = Zr::new(W, H, BACKGROUND).unwrap();
        let (mut whole, mut changed) = (Plain::new(), Plain::new());
        let mut shown = [RowSpan::UNKNOWN; H as usize];
        for frame in &frames {
            draw(&mut renderer, frame);
            renderer.render(&mut DrawTargetSink::new(&mut whole)).unwrap();
            draw(&mut renderer, frame);
            let mut sink = DrawTargetSink::new(&mut changed).changed_only(&mut shown, BACKGROUND);
            renderer.render(&mut sink).unwrap();
            prop_assert!(whole.pixels == changed.pixels);
            prop_assert!(changed.sent <= whole.sent);
        }
    }
}

/// The first frame goes out whole (the display's old content is not
/// known); an unchanged frame after it sends only the lit span of each
/// row; an empty one then clears just those spans.
#[test]
fn what_is_sent_frame_by_frame() {
    let mut renderer = Zr::new(W, H, BACKGROUND).unwrap();
    let mut display = Plain::new();
    let mut shown = [RowSpan::UNKNOWN; H as usize];
    let frame: Frame = vec![([(10.0, 4.0), (20.0, 4.0), (10.0, 14.0)], 0.5, 0xFFFF)];
    let mut send = |frame: &Frame, display: &mut Plain, shown: &mut [RowSpan]| {
        draw(&mut renderer, frame);
        display.sent = 0;
        let mut sink = DrawTargetSink::new(display).changed_only(shown, BACKGROUND);
        renderer.render(&mut sink).unwrap();
        display.sent
    };
    assert_eq!(
        send(&frame, &mut display, &mut shown),
        usize::from(W) * usize::from(H)
    );
    let lit = display.pixels.iter().filter(|&&c| c != BACKGROUND).count();
    // A right triangle of legs 10: 45 pixel centres inside it, rows 4..14.
    assert_eq!(lit, 45);
    assert_eq!(send(&frame, &mut display, &mut shown), lit);
    assert_eq!(send(&Vec::new(), &mut display, &mut shown), lit);
    assert!(display.pixels.iter().all(|&c| c == BACKGROUND));
    assert!(shown.iter().all(|s| s.is_empty()));
    assert_eq!(send(&Vec::new(), &mut display, &mut shown), 0);
}
