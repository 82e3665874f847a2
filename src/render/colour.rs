//! Colour over alpha: straight and premultiplied alpha, and the box filter that averages
//! samples into pixels (the resolve).

use std::ops::{Add, Mul};

use glam::Vec4;

/// Straight alpha to premultiplied: `(α rgb, α)`.
#[inline]
#[must_use]
pub(super) fn premultiplied(c: Vec4) -> Vec4 {
    (c.truncate() * c.w).extend(c.w)
}

/// Premultiplied alpha back to straight: `(rgb / α, α)`, and zero where `α = 0`.
#[inline]
#[must_use]
pub(super) fn straight(p: Vec4) -> Vec4 {
    if p.w > 0.0 {
        (p.truncate() / p.w).extend(p.w)
    } else {
        Vec4::ZERO
    }
}

/// Resolves `k × k` samples per pixel by averaging premultiplied colour:
/// `α = mean(α_s)`, `rgb = mean(α_s rgb_s) / α`.
#[must_use]
pub(super) fn resolve(samples: &[Vec4], width: u32, height: u32, k: u32) -> Vec<Vec4> {
    let premultiplied: Vec<Vec4> = samples.iter().copied().map(premultiplied).collect();
    box_filter(&premultiplied, width, height, k)
        .into_iter()
        .map(straight)
        .collect()
}

/// The mean of each pixel's `k × k` samples, for an output of `width × height` pixels.
#[must_use]
pub(super) fn box_filter<T>(samples: &[T], width: u32, height: u32, k: u32) -> Vec<T>
where
    T: Copy + Default + Add<Output = T> + Mul<f32, Output = T>,
{
    let (width, k) = (width as usize, k as usize);
    let sample_width = width * k;
    let weight = 1.0 / (k * k) as f32;
    (0..width * height as usize)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let mut sum = T::default();
            for sy in 0..k {
                for sx in 0..k {
                    sum = sum + samples[(y * k + sy) * sample_width + x * k + sx];
                }
            }
            sum * weight
        })
        .collect()
}
