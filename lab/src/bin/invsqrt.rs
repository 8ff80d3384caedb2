//! `micromath`'s fast square roots against `libm` and the exact value: the
//! choice of how zline's float front end normalises a vertex normal
//! (`Vec3::normalized`, once per vertex per frame for Gouraud shading).
//!
//! For every `f32` in `[1, 4)` (every mantissa at both exponent parities,
//! so every input up to a power of 4), the relative error of
//! `1 / libm::sqrtf(x)`, `micromath`'s `invsqrt` and `1 / sqrt` against
//! `1 / sqrt(x)` in `f64`; and what it does to a vertex's Lambert term,
//! `255 · n·l` for a unit `n` and `l`: a normal scaled by `1 + ε` is off
//! by up to `255·|ε|` 8-bit steps.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin invsqrt
//! ```

use micromath::F32Ext;

/// An inverse square root under test.
type InverseRoot = fn(f32) -> f32;

/// Largest relative error of `f` against `1/sqrt(x)` over `[1, 4)`.
fn worst(f: impl Fn(f32) -> f32) -> (f64, f32) {
    let (mut worst, mut at) = (0.0f64, 1.0f32);
    let (start, end) = (1.0f32.to_bits(), 4.0f32.to_bits());
    for bits in start..end {
        let x = f32::from_bits(bits);
        let exact = 1.0 / f64::from(x).sqrt();
        let error = (f64::from(f(x)) - exact).abs() / exact;
        if error > worst {
            (worst, at) = (error, x);
        }
    }
    (worst, at)
}

fn main() {
    println!(
        "| inverse square root | largest relative error over [1, 4) | at | Lambert error (8-bit steps, 255·ε) |"
    );
    println!("|---|---:|---:|---:|");
    let rows: [(&str, InverseRoot); 3] = [
        ("1 / libm::sqrtf(x) (zline)", |x| 1.0 / libm::sqrtf(x)),
        ("micromath x.invsqrt()", |x| x.invsqrt()),
        ("1 / micromath x.sqrt()", |x| 1.0 / F32Ext::sqrt(x)),
    ];
    for (name, f) in rows {
        let (error, at) = worst(f);
        println!("| {name} | {error:.3e} | {at} | {:.4} |", 255.0 * error);
    }
}
