//! The analysis maps' colours and coordinates, pure: the textures' ramps
//! (curvature, zebra stripes, distance to the reference; the deviation
//! map's bands are [`BANDS`]) and the `u` coordinate of each vertex that
//! picks a colour (docs/math.md §4).

use super::deviation::BANDS;
use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use streamline_kernel::DVec3;
use streamline_kernel::analysis::zebra_coordinate;

/// The colour map: blue (negative) – white (zero) – red (positive), 256 texels.
pub fn diverging(u: f64) -> [u8; 3] {
    let u = u.clamp(0.0, 1.0);
    let (lo, mid, hi) = ([0.15, 0.3, 0.85], [0.97, 0.97, 0.97], [0.85, 0.15, 0.15]);
    let (a, b, t) = if u < 0.5 {
        (lo, mid, u * 2.0)
    } else {
        (mid, hi, (u - 0.5) * 2.0)
    };
    let c = |i: usize| ((a[i] + (b[i] - a[i]) * t) * 255.0).round() as u8;
    [c(0), c(1), c(2)]
}

/// The reference map's ramp: green (0) through yellow to red (1), the
/// deviation map's three colours ([`BANDS`]) blended.
pub fn reference_ramp(u: f64) -> [u8; 3] {
    let u = u.clamp(0.0, 1.0);
    let (a, b, t) = if u < 0.5 {
        (BANDS[0], BANDS[1], u * 2.0)
    } else {
        (BANDS[1], BANDS[2], (u - 0.5) * 2.0)
    };
    let c = |i: usize| (a[i] as f64 + (b[i] as f64 - a[i] as f64) * t).round() as u8;
    [c(0), c(1), c(2)]
}

pub(super) fn texture(pixels: Vec<[u8; 3]>, repeat: bool) -> Image {
    let w = pixels.len() as u32;
    let data: Vec<u8> = pixels
        .iter()
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: w,
            height: 1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::default(),
    );
    let mode = if repeat {
        ImageAddressMode::Repeat
    } else {
        ImageAddressMode::ClampToEdge
    };
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: mode,
        address_mode_v: ImageAddressMode::ClampToEdge,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        ..default()
    });
    image
}

/// The zebra texture's two colours (dark, light), half its width each.
pub(super) const STRIPES: [[u8; 3]; 2] = [[20, 20, 24], [245, 245, 245]];

/// The colour map's `u` of curvature values: `[−limit, limit]` onto the
/// ramp, clamped beyond.
pub(super) fn colormap_uv(values: &[f64], limit: f64) -> Vec<[f32; 2]> {
    values
        .iter()
        .map(|&x| [(0.5 + 0.5 * (x / limit).clamp(-1.0, 1.0)) as f32, 0.5])
        .collect()
}

/// The reference map's `u` of distances: `[0, tolerance]` onto the ramp,
/// clamped beyond.
pub(super) fn ramp_uv(distances: &[f64], tolerance: f64) -> Vec<[f32; 2]> {
    let t = tolerance.max(f64::MIN_POSITIVE);
    distances
        .iter()
        .map(|&d| [(d / t).clamp(0.0, 1.0) as f32, 0.5])
        .collect()
}

/// Zebra `u` coordinates of points with their unit normals for an eye point
/// (kernel coordinates): `stripes` stripes over the half circle of
/// reflected directions.
pub(super) fn zebra_uv(
    points: &[DVec3],
    normals: &[DVec3],
    stripes: f64,
    eye: DVec3,
) -> Vec<[f32; 2]> {
    points
        .iter()
        .zip(normals)
        .map(|(&p, &n)| {
            let view = (p - eye).normalize_or(DVec3::NEG_Z);
            let z = zebra_coordinate(n, view, DVec3::Z, stripes);
            [(z * 0.5) as f32, 0.5]
        })
        .collect()
}
