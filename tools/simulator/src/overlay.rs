//! The text overlay: what is drawn, how, and what it costs, in a mono font
//! on top of the frame.

use embedded_graphics::mono_font::MonoTextStyleBuilder;
use embedded_graphics::mono_font::ascii::FONT_6X10;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};
use embedded_graphics_simulator::SimulatorDisplay;
use zline::Cull;

use crate::frame::{FrameReport, Method, View, shading_name};

/// Height of one text line in pixels.
const LINE: i32 = 10;

/// The overlay's lines for `view` and the last frame's `report`.
pub fn lines(view: &View, report: &FrameReport) -> Vec<String> {
    let mut lines = Vec::new();
    match view.method {
        Method::Scanline | Method::ZBuffer | Method::Bands8 => {
            lines.push(format!(
                "{} {}  {:.2} ms",
                view.method.name(),
                view.depth.name(),
                report.ms
            ));
            let ram = report.ram_bytes.unwrap_or(0) as f64 / 1024.0;
            lines.push(format!("polygons {}  RAM {ram:.1} KiB", report.polygons));
        }
        Method::Interval | Method::Painter => {
            lines.push(format!("{}  {:.2} ms", view.method.name(), report.ms));
            let ram = report.ram_bytes.unwrap_or(0) as f64 / 1024.0;
            lines.push(format!("polygons {}  RAM {ram:.1} KiB", report.polygons));
        }
        Method::Reference => {
            lines.push(format!("{} f64  {:.1} ms", view.method.name(), report.ms));
            lines.push(format!("faces seen {}", report.polygons));
        }
    }
    let cull = match view.cull {
        Cull::None => "none",
        Cull::Back => "back",
    };
    lines.push(format!("{}  cull {cull}", shading_name(view)));
    let zoom = if view.zoom != 0 && view.method == Method::Reference {
        " (not the reference)"
    } else {
        ""
    };
    lines.push(format!(
        "yaw {:.0} pitch {:.0} zoom {:.2}{zoom}",
        view.yaw,
        view.pitch,
        1.1f64.powi(view.zoom)
    ));
    lines
}

/// Draws the overlay in the top-left corner, and a key hint at the bottom.
pub fn draw(display: &mut SimulatorDisplay<Rgb888>, view: &View, report: &FrameReport) {
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb888::WHITE)
        .background_color(Rgb888::new(0, 0, 64))
        .build();
    let hint = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(Rgb888::new(160, 160, 160))
        .build();
    for (k, line) in lines(view, report).iter().enumerate() {
        let at = Point::new(2, 2 + LINE * k as i32);
        let Ok(_) = Text::with_baseline(line, at, style, Baseline::Top).draw(display);
    }
    let bottom = display.bounding_box().size.height as i32 - 2;
    let at = Point::new(2, bottom);
    let Ok(_) =
        Text::with_baseline("arrows +/- space s c d m q", at, hint, Baseline::Bottom).draw(display);
}
