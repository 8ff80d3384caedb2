//! The standard sink issues exactly one `fill_contiguous` per scanline,
//! top to bottom, each one full row.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use zline::{Depth16, DrawTargetSink, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};

#[derive(Default)]
struct Recorder {
    fills: Vec<(Rectangle, Vec<Rgb565>)>,
    other_calls: usize,
}

impl OriginDimensions for Recorder {
    fn size(&self) -> Size {
        Size::new(24, 10)
    }
}

impl DrawTarget for Recorder {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        self.other_calls += 1;
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.fills.push((*area, colors.into_iter().collect()));
        Ok(())
    }

    fn fill_solid(&mut self, _: &Rectangle, _: Rgb565) -> Result<(), Self::Error> {
        self.other_calls += 1;
        Ok(())
    }

    fn clear(&mut self, _: Rgb565) -> Result<(), Self::Error> {
        self.other_calls += 1;
        Ok(())
    }
}

#[test]
fn one_fill_contiguous_per_row() {
    let mut renderer: Renderer<
        TableArrays<Rgb565, 8, 2, 8>,
        ScanArrays<Rgb565, Depth16, 24, 2, 8>,
    > = Renderer::with_height(10, Rgb565::BLUE).unwrap();
    let v = |x, y| ScreenVertex::from_f32(x, y, 0.5).unwrap();
    renderer
        .push_polygon_vertices(&[v(2.0, 2.0), v(20.0, 3.0), v(8.0, 9.0)], Rgb565::RED)
        .unwrap();
    let mut recorder = Recorder::default();
    renderer
        .render(&mut DrawTargetSink::new(&mut recorder))
        .unwrap();
    assert_eq!(recorder.other_calls, 0);
    assert_eq!(recorder.fills.len(), 10);
    for (y, (area, colors)) in recorder.fills.iter().enumerate() {
        assert_eq!(
            *area,
            Rectangle::new(Point::new(0, y as i32), Size::new(24, 1))
        );
        assert_eq!(colors.len(), 24);
    }
    // Background where nothing is drawn, the triangle where it is.
    assert_eq!(recorder.fills[0].1, vec![Rgb565::BLUE; 24]);
    assert_eq!(recorder.fills[4].1[8], Rgb565::RED);
}

#[test]
fn origin_offsets_every_row() {
    let mut renderer: Renderer<
        TableArrays<Rgb565, 8, 2, 8>,
        ScanArrays<Rgb565, Depth16, 24, 2, 8>,
    > = Renderer::with_height(3, Rgb565::BLACK).unwrap();
    let mut recorder = Recorder::default();
    renderer
        .render(&mut DrawTargetSink::with_origin(
            &mut recorder,
            Point::new(5, 7),
        ))
        .unwrap();
    let tops: Vec<Point> = recorder.fills.iter().map(|(a, _)| a.top_left).collect();
    assert_eq!(tops, [Point::new(5, 7), Point::new(5, 8), Point::new(5, 9)]);
}

#[test]
fn runtime_width_below_capacity() {
    // Row capacity 24, frame 10 wide: rows are 10 long and a triangle
    // reaching past x = 10 is clipped there.
    let mut renderer: Renderer<
        TableArrays<Rgb565, 8, 2, 8>,
        ScanArrays<Rgb565, Depth16, 24, 2, 8>,
    > = Renderer::new(10, 4, Rgb565::BLACK).unwrap();
    let v = |x, y| ScreenVertex::from_f32(x, y, 0.5).unwrap();
    renderer
        .push_polygon_vertices(&[v(0.0, 0.0), v(30.0, 0.0), v(0.0, 30.0)], Rgb565::RED)
        .unwrap();
    let mut recorder = Recorder::default();
    renderer
        .render(&mut DrawTargetSink::new(&mut recorder))
        .unwrap();
    assert_eq!(recorder.fills.len(), 4);
    for (area, colors) in &recorder.fills {
        assert_eq!(area.size, Size::new(10, 1));
        assert_eq!(colors, &vec![Rgb565::RED; 10]);
    }
}
