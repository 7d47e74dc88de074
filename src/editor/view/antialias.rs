//! Multisample anti-aliasing of the 3D views, chosen for the graphics
//! adapter: on a software renderer (Mesa's llvmpipe, an adapter of type
//! `Cpu`) every sample is rasterised by the CPU, and 4× MSAA made llvmpipe
//! draw the car at 1.2 frames a second on a 2-core machine (818 ms between
//! frames) against one every 219 ms without it, while it also took the cores
//! our systems run on. So the editor starts without MSAA there and with 4×
//! on a GPU; `--msaa N` and the Display panel choose otherwise.

use bevy::prelude::*;
use bevy::render::render_resource::TextureFormat;
use bevy::render::renderer::{RenderAdapter, RenderAdapterInfo};

/// Samples per pixel of the 3D views (1 = off).
#[derive(Resource, Debug, Clone, PartialEq, Eq)]
pub struct AntiAliasing {
    /// 1, 2, 4 or 8.
    pub samples: u32,
    /// Asked for on the command line (`None`: chosen for the adapter).
    pub asked: Option<u32>,
    /// Whether the adapter is a software renderer.
    pub software: bool,
    /// The sample counts the adapter offers for the views' colour and depth
    /// formats (llvmpipe: 1 and 4 only; WebGPU promises no more).
    pub supported: Vec<u32>,
}

impl AntiAliasing {
    /// The samples counts a user may choose.
    pub const CHOICES: [u32; 4] = [1, 2, 4, 8];

    /// Starts with `asked`, or (when `None`) what the adapter is found to suit.
    pub fn new(asked: Option<u32>) -> Self {
        AntiAliasing {
            samples: asked.unwrap_or(4),
            asked,
            software: false,
            supported: vec![1, 4],
        }
    }

    /// `want` if the adapter offers it, else the nearest it offers (ties: fewer).
    pub fn nearest_supported(want: u32, supported: &[u32]) -> u32 {
        supported
            .iter()
            .copied()
            .min_by_key(|&n| (n.abs_diff(want), n))
            .unwrap_or(1)
    }

    /// The default for an adapter: off on a software renderer, else 4×.
    pub fn for_adapter(software: bool) -> u32 {
        if software { 1 } else { 4 }
    }

    /// The component the cameras take.
    pub fn msaa(&self) -> Msaa {
        match self.samples {
            0 | 1 => Msaa::Off,
            2 => Msaa::Sample2,
            8 => Msaa::Sample8,
            _ => Msaa::Sample4,
        }
    }
}

/// Parses a `--msaa` value: 1 (off), 2, 4 or 8.
pub fn parse_samples(s: &str) -> Result<u32, String> {
    match s.trim() {
        "off" | "0" | "1" => Ok(1),
        "2" => Ok(2),
        "4" => Ok(4),
        "8" => Ok(8),
        _ => Err(format!(
            "'{s}' is not a sample count: give 1 (off), 2, 4 or 8"
        )),
    }
}

pub struct AntiAliasPlugin;

impl Plugin for AntiAliasPlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<AntiAliasing>() {
            app.insert_resource(AntiAliasing::new(None));
        }
        app.add_systems(PostStartup, choose)
            .add_systems(Update, apply.run_if(resource_changed::<AntiAliasing>));
    }
}

/// Reads the adapter once the renderer is up.
fn choose(
    mut aa: ResMut<AntiAliasing>,
    info: Option<Res<RenderAdapterInfo>>,
    adapter: Option<Res<RenderAdapter>>,
) {
    aa.software = info.is_some_and(|i| is_software(&format!("{:?}", i.device_type), &i.name));
    if let Some(adapter) = adapter {
        // the views draw to Rgba8UnormSrgb with a Depth32Float depth buffer
        let offers = |n: u32| {
            [TextureFormat::Rgba8UnormSrgb, TextureFormat::Depth32Float]
                .into_iter()
                .all(|f| {
                    adapter
                        .get_texture_format_features(f)
                        .flags
                        .sample_count_supported(n)
                })
        };
        aa.supported = AntiAliasing::CHOICES
            .into_iter()
            .filter(|&n| n == 1 || offers(n))
            .collect();
    }
    let want = aa.asked.unwrap_or(AntiAliasing::for_adapter(aa.software));
    let samples = AntiAliasing::nearest_supported(want, &aa.supported);
    if aa.asked.is_some_and(|n| n != samples) {
        warn!(
            "--msaa {want}: this graphics adapter offers {:?} samples; using {samples}",
            aa.supported
        );
    }
    aa.samples = samples;
    if aa.software && aa.samples == 1 {
        info!("software renderer: multisampling is off (--msaa 4 turns it on)");
    }
}

/// Whether an adapter (wgpu's device type, as `Debug` writes it, and name)
/// rasterises on the CPU.
fn is_software(device_type: &str, name: &str) -> bool {
    let name = name.to_lowercase();
    device_type == "Cpu"
        || ["llvmpipe", "lavapipe", "softpipe", "swiftshader"]
            .iter()
            .any(|s| name.contains(s))
}

/// Gives the 3D views (the main view and the sphere inset) the chosen sample count.
fn apply(aa: Res<AntiAliasing>, mut commands: Commands, cams: Query<Entity, With<Camera3d>>) {
    for e in &cams {
        commands.entity(e).insert(aa.msaa());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_parse_and_map() {
        assert_eq!(parse_samples("off"), Ok(1));
        assert_eq!(parse_samples("4"), Ok(4));
        assert!(
            parse_samples("3")
                .unwrap_err()
                .contains("1 (off), 2, 4 or 8")
        );
        for n in AntiAliasing::CHOICES {
            let aa = AntiAliasing::new(Some(n));
            assert_eq!(aa.msaa().samples(), n);
        }
        assert_eq!(AntiAliasing::for_adapter(true), 1);
        assert_eq!(AntiAliasing::for_adapter(false), 4);
        assert_eq!(AntiAliasing::nearest_supported(2, &[1, 4]), 1);
        assert_eq!(AntiAliasing::nearest_supported(8, &[1, 4]), 4);
        assert_eq!(AntiAliasing::nearest_supported(3, &[1, 2, 4]), 2);
        assert_eq!(AntiAliasing::nearest_supported(4, &[1, 2, 4, 8]), 4);
        assert_eq!(AntiAliasing::nearest_supported(4, &[]), 1);
        assert!(is_software("Cpu", "whatever"));
        assert!(is_software("Other", "llvmpipe (LLVM 19.1.7, 256 bits)"));
        assert!(!is_software("DiscreteGpu", "NVIDIA H200"));
    }
}
