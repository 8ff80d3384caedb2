//! The frame the peers draw into: a plain `Vec<u16>` of Rgb565 pixels,
//! row-major from the top, usable both as an embedded-graphics
//! `DrawTarget` (embedded-3dgfx) and as an euc `Target`.

use core::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;

/// A W×H Rgb565 frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frame565 {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Raw Rgb565 per pixel, row-major from the top.
    pub pixels: Vec<u16>,
}

impl Frame565 {
    /// A black frame.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![0; width * height],
        }
    }

    /// Fills the whole frame with one raw colour.
    pub fn fill(&mut self, raw: u16) {
        self.pixels.fill(raw);
    }
}

impl OriginDimensions for Frame565 {
    fn size(&self) -> Size {
        Size::new(self.width as u32, self.height as u32)
    }
}

impl DrawTarget for Frame565 {
    type Color = Rgb565;
    type Error = Infallible;

    #[inline]
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, color) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as usize) < self.width && (p.y as usize) < self.height {
                self.pixels[p.y as usize * self.width + p.x as usize] =
                    RawU16::from(color).into_inner();
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let raw = RawU16::from(color).into_inner();
        let area = area.intersection(&self.bounding_box());
        if area.size == self.size() {
            self.fill(raw);
            return Ok(());
        }
        let Some(bottom_right) = area.bottom_right() else {
            return Ok(());
        };
        for y in area.top_left.y..=bottom_right.y {
            let row = y as usize * self.width;
            self.pixels[row + area.top_left.x as usize..=row + bottom_right.x as usize].fill(raw);
        }
        Ok(())
    }

    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        self.fill(RawU16::from(color).into_inner());
        Ok(())
    }
}

impl euc::Target for Frame565 {
    type Item = u16;

    #[inline(always)]
    fn size(&self) -> [usize; 2] {
        [self.width, self.height]
    }

    #[inline(always)]
    unsafe fn set(&mut self, [x, y]: [usize; 2], item: u16) {
        // SAFETY: euc only sets positions inside `size()`.
        unsafe { *self.pixels.get_unchecked_mut(y * self.width + x) = item }
    }

    #[inline(always)]
    unsafe fn get(&self, [x, y]: [usize; 2]) -> u16 {
        // SAFETY: euc only reads positions inside `size()`.
        unsafe { *self.pixels.get_unchecked(y * self.width + x) }
    }

    fn clear(&mut self, fill: u16) {
        self.fill(fill);
    }
}

/// Expands raw Rgb565 to 8-bit RGB (for image dumps).
pub fn rgb888(raw: u16) -> [u8; 3] {
    let r = ((raw >> 11) & 0x1f) as u8;
    let g = ((raw >> 5) & 0x3f) as u8;
    let b = (raw & 0x1f) as u8;
    [
        (r << 3) | (r >> 2),
        (g << 2) | (g >> 4),
        (b << 3) | (b >> 2),
    ]
}
