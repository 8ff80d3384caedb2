//! The peer rasterisers zline is measured against, each behind
//! [`crate::renderer::Renderer`] and drawing the same view.

pub mod embedded_3dgfx;
pub mod euc;
