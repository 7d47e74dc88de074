//! The output stage: saving and exporting, after the mesh is up to date.

use super::messages::{Edit, EditMessage};
use super::resources::*;
use crate::scene::{export, io};
use bevy::prelude::*;

pub(crate) fn write_files(
    meter: Res<super::meter::CpuMeter>,
    mut reader: MessageReader<EditMessage>,
    mut model: ResMut<Model>,
    surface: Res<SurfaceData>,
    mut log: ResMut<EditLog>,
) {
    let _meter = meter.start();
    for msg in reader.read() {
        match &msg.edit {
            Edit::Save(path) => match io::save(&model.scene, path) {
                Ok(()) => {
                    model.path = Some(path.clone());
                    model.unsaved = false;
                    log.entries.push(Ok(format!("saved {}", path.display())));
                }
                Err(e) => log.entries.push(Err(e.to_string())),
            },
            Edit::Export(path) => {
                let name = model.scene.name.clone();
                match export::export(&surface.mesh(), &name, path) {
                    Ok(f) => log.entries.push(Ok(format!(
                        "exported {} ({f:?}, {} triangles)",
                        path.display(),
                        surface.triangle_count()
                    ))),
                    Err(e) => log.entries.push(Err(e.to_string())),
                }
            }
            _ => {}
        }
    }
}
