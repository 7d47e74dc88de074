//! The colours a map shows, as a glTF export carries them (`COLOR_0`,
//! docs/cad.md): the texel each vertex's `u` picks, as linear light.

use super::super::analysis_display::SurfaceMode;
use super::super::colour_maps::{STRIPES, diverging, reference_ramp};
use super::super::deviation::BANDS;

/// The colour a map's texture shows at `u` (the texel the sampler picks,
/// nearest), as linear RGBA: what glTF's `COLOR_0` holds.
pub(super) fn vertex_color(mode: SurfaceMode, u: f32) -> [f32; 4] {
    let srgb = match mode {
        SurfaceMode::Gaussian | SurfaceMode::Mean => diverging(u as f64),
        SurfaceMode::Zebra => {
            if u.rem_euclid(1.0) < 0.5 {
                STRIPES[0]
            } else {
                STRIPES[1]
            }
        }
        SurfaceMode::Deviation => BANDS[((u * 3.0) as usize).min(2)],
        SurfaceMode::Reference => reference_ramp(u as f64),
        SurfaceMode::Shaded => [255, 255, 255],
    };
    let linear = srgb_to_linear();
    [
        linear[srgb[0] as usize],
        linear[srgb[1] as usize],
        linear[srgb[2] as usize],
        1.0,
    ]
}

/// Each 8-bit sRGB channel value as linear light, made once (a map's
/// colours are looked up for every vertex in every frame of a drag).
fn srgb_to_linear() -> &'static [f32; 256] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let c = i as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table's colours are the sRGB transfer function's, bit for bit
    /// (IEC 61966-2-1), at every `u` of every map.
    #[test]
    fn vertex_colours_are_the_textures_as_linear_light() {
        let linear = |c: u8| {
            let c = c as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        for mode in SurfaceMode::ALL {
            for i in 0..=1000 {
                let u = i as f32 / 1000.0;
                let got = vertex_color(mode, u);
                let srgb = match mode {
                    SurfaceMode::Gaussian | SurfaceMode::Mean => diverging(u as f64),
                    SurfaceMode::Zebra => STRIPES[usize::from(u.rem_euclid(1.0) >= 0.5)],
                    SurfaceMode::Deviation => BANDS[((u * 3.0) as usize).min(2)],
                    SurfaceMode::Reference => reference_ramp(u as f64),
                    SurfaceMode::Shaded => [255, 255, 255],
                };
                let want = [linear(srgb[0]), linear(srgb[1]), linear(srgb[2]), 1.0];
                assert_eq!(
                    got.map(f32::to_bits),
                    want.map(f32::to_bits),
                    "{mode:?} at {u}"
                );
            }
        }
        assert_eq!(linear(0), 0.0);
        assert_eq!(linear(255), 1.0);
    }
}
