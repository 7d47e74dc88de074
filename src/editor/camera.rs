//! An orbit camera: right drag orbits, middle drag pans, the wheel zooms, `F` frames all.
//! Viewport input is ignored while the pointer is over an egui panel.

use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy_egui::input::egui_wants_any_pointer_input;

/// The orbit camera's state: a focus point, a distance and two angles.
#[derive(Component)]
pub struct OrbitCamera {
    pub focus: Vec3,
    pub distance: f32,
    pub yaw: f32,
    pub pitch: f32,
}

impl OrbitCamera {
    fn transform(&self) -> Transform {
        let rot = Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0);
        Transform::from_translation(self.focus + rot * Vec3::Z * self.distance)
            .looking_at(self.focus, Vec3::Y)
    }
}

pub struct OrbitCameraPlugin;

impl Plugin for OrbitCameraPlugin {
    fn build(&self, app: &mut App) {
        app.add_systems(Startup, spawn)
            .add_systems(Update, orbit.run_if(not(egui_wants_any_pointer_input)));
    }
}

fn spawn(mut commands: Commands) {
    let cam = OrbitCamera {
        focus: Vec3::new(2.1, 0.4, 0.0),
        distance: 6.5,
        yaw: 0.65,
        pitch: -0.42,
    };
    commands.spawn((Camera3d::default(), cam.transform(), cam));
}

fn orbit(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut q: Query<(&mut OrbitCamera, &mut Transform)>,
) {
    let Ok((mut cam, mut tf)) = q.single_mut() else {
        return;
    };
    let d = motion.delta;
    let mut changed = false;
    if buttons.pressed(MouseButton::Right) && d != Vec2::ZERO {
        cam.yaw -= d.x * 0.008;
        cam.pitch = (cam.pitch - d.y * 0.008).clamp(-1.5, 1.5);
        changed = true;
    }
    if buttons.pressed(MouseButton::Middle) && d != Vec2::ZERO {
        let right = tf.right();
        let up = tf.up();
        let k = cam.distance * 0.0015;
        cam.focus += (-right * d.x + up * d.y) * k;
        changed = true;
    }
    if scroll.delta.y != 0.0 {
        cam.distance = (cam.distance * (1.0 - scroll.delta.y * 0.1)).clamp(0.3, 200.0);
        changed = true;
    }
    if keys.just_pressed(KeyCode::KeyF) {
        cam.focus = Vec3::new(2.1, 0.4, 0.0);
        cam.distance = 6.5;
        changed = true;
    }
    if changed {
        *tf = cam.transform();
    }
}
