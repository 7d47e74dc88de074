//! The edits of the first patch's own surface: its control net and
//! details, lengths, scheme, blend order, initial curve, fine tuning and
//! tangent interpolation, applied to its scene ([`apply`]).

use crate::ecs::components::LevelData;
use crate::ecs::edit_error::EditError;
use crate::ecs::messages::Edit;
use crate::scene::Scene;
use bevy::prelude::*;
use streamline_kernel::finetune::SurfaceTuning;
use streamline_kernel::levels::incremental::check_params;
use streamline_kernel::levels::multires::{self};
use streamline_kernel::{DQuat, DVec3, Design, Tangent};

use super::EditCtx;

pub(super) fn apply(
    ctx: &mut EditCtx,
    scene: &mut Scene,
    edit: &Edit,
) -> Result<String, EditError> {
    match edit {
        Edit::SetDirection { row, col, dir } => set_direction(ctx, scene, *row, *col, *dir),
        Edit::Rotate {
            row,
            col,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            let cur = current_direction(ctx, scene, *row, *col)?;
            let dir = q * cur;
            set_direction(ctx, scene, *row, *col, dir)
        }
        Edit::SetLength {
            row,
            col,
            coefficient,
        } => set_length(scene, *row, *col, *coefficient),
        Edit::ClearDetail { row, col } => {
            let level = scene.edit_depth;
            let key = (level, *row, *col);
            if scene.details.remove(&key).is_none() {
                return Err(EditError::NoDetail {
                    row: *row,
                    col: *col,
                    level,
                });
            }
            Ok(format!("cleared detail ({row}, {col}) at level {level}"))
        }
        Edit::SetScheme(s) => {
            let s = s.validate()?;
            let mut d = scene.design.clone();
            d.set_scheme(s)?;
            check_design(&d, scene.max_depth(), scene.mirror)?;
            scene.design = d;
            let dropped = prune_details(scene);
            Ok(format!("scheme {}{dropped}", s.name()))
        }
        Edit::SetBlendOrder(o) => {
            scene.design.set_order(*o);
            Ok(format!("blend order {}", o.name()))
        }
        Edit::SetDisplayDepth(n) => {
            let depth = (*n).max(scene.edit_depth);
            check_design(&scene.design, depth, scene.mirror)?;
            scene.display_depth = *n;
            Ok(format!("display depth {n}"))
        }
        Edit::SetEditDepth(n) => {
            if *n > 0 && scene.mirror {
                return Err(EditError::MirrorDepth);
            }
            let depth = (*n).max(scene.display_depth);
            check_design(&scene.design, depth, scene.mirror)?;
            scene.edit_depth = *n;
            Ok(format!("edit depth {n}"))
        }
        Edit::SetTuning(t) => {
            scene.tuning = t.clone();
            Ok(if t.is_some() {
                "fine tuning on".into()
            } else {
                "fine tuning off".into()
            })
        }
        Edit::SetTuningValue { row, col, value } => {
            let tuning = scene.tuning.get_or_insert_with(SurfaceTuning::identity);
            tuning
                .function
                .set(*row, *col, *value)
                .map_err(EditError::TuningValue)?;
            Ok(format!("fine-tuning value ({row}, {col}) = {value}"))
        }
        Edit::SetTuningConstraint(c) => {
            scene
                .tuning
                .get_or_insert_with(SurfaceTuning::identity)
                .constraint = *c;
            Ok(format!("fine-tuning constraint {}", c.name()))
        }
        Edit::SetInterpolateTangents(on) => {
            scene.interpolate_tangents = *on;
            Ok(
                if *on
                    && !streamline_kernel::levels::tangent_interpolation::applies(
                        scene.design.scheme(),
                    )
                {
                    "interpolate control tangents on (Kobbelt interpolates them already)".into()
                } else {
                    format!("interpolate control tangents {on}")
                },
            )
        }
        Edit::Save(_) | Edit::Export(_) => Ok(String::new()),
        Edit::RotateMany {
            handles,
            axis,
            radians,
        } => {
            let q = rotation(*axis, *radians)?;
            if handles.is_empty() {
                return Err(EditError::NoHandles);
            }
            // every handle checked before any is turned: all or nothing
            let dirs = handles
                .iter()
                .map(|&(r, c)| current_direction(ctx, scene, r, c).map(|d| q * d))
                .collect::<Result<Vec<_>, _>>()?;
            for (&(r, c), d) in handles.iter().zip(dirs) {
                set_direction(ctx, scene, r, c, d)?;
            }
            Ok(format!(
                "rotated {} handles by {:.3}°",
                handles.len(),
                radians.to_degrees()
            ))
        }
        Edit::Author(a) => Ok(crate::ecs::authoring::apply(scene, a)?.0),
        // the document's edits (apply_doc)
        Edit::Undo
        | Edit::Redo
        | Edit::CancelGroup(_)
        | Edit::Load(_)
        | Edit::Replace(_)
        | Edit::Recover { .. }
        | Edit::Import { .. }
        | Edit::SetReference(_)
        | Edit::Patch(_) => Ok(String::new()),
    }
}

/// `d` can be built to `depth`; mirrored, its doubled design too
/// (`docs/math.md §9`: the levels are the doubled net's).
fn check_design(d: &Design, depth: u32, mirror: bool) -> Result<(), EditError> {
    d.scheme()
        .check_depth(d.net().rows(), d.net().cols(), depth)?;
    check_params(d, depth)?;
    if mirror {
        let m = d.mirrored()?;
        m.scheme()
            .check_depth(m.net().rows(), m.net().cols(), depth)
            .and_then(|_| check_params(&m, depth))
            .map_err(EditError::MirroredSurface)?;
    }
    Ok(())
}

/// Drops details that no longer fit their level (after a scheme change).
fn prune_details(scene: &mut Scene) -> String {
    let d = &scene.design;
    let c = d.scheme().curve();
    let before = scene.details.len();
    let shape = |level: u32| {
        let (mut r, mut k) = (d.net().rows(), d.net().cols());
        for _ in 0..level {
            r = c.refined_len(r);
            k = c.refined_len(k);
        }
        (r, k)
    };
    scene.details.retain(|&(l, r, k), _| {
        let (rows, cols) = shape(l);
        r < rows && k < cols
    });
    let dropped = before - scene.details.len();
    if dropped > 0 {
        format!(" ({dropped} details outside the new levels were dropped)")
    } else {
        String::new()
    }
}

fn level_data<'a>(ctx: &'a EditCtx, level: u32) -> Result<&'a LevelData, EditError> {
    ctx.levels
        .iter()
        .find(|(l, _)| l.0 == level)
        .map(|(_, d)| d)
        .ok_or(EditError::LevelNotBuilt { level })
}

pub(super) fn check_cell(
    rows: usize,
    cols: usize,
    row: usize,
    col: usize,
    level: u32,
) -> Result<(), EditError> {
    if row >= rows || col >= cols {
        return Err(EditError::OutsideLevel {
            row,
            col,
            level,
            rows,
            cols,
        });
    }
    Ok(())
}

fn current_direction(
    ctx: &EditCtx,
    scene: &Scene,
    row: usize,
    col: usize,
) -> Result<DVec3, EditError> {
    let level = scene.edit_depth;
    if level == 0 {
        let net = scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        return Ok(net.get(row, col));
    }
    let l = &level_data(ctx, level)?.0;
    let (rows, cols) = l.shape();
    check_cell(rows, cols, row, col, level)?;
    Ok(l.tangents.get(row, col))
}

fn set_direction(
    ctx: &mut EditCtx,
    scene: &mut Scene,
    row: usize,
    col: usize,
    dir: DVec3,
) -> Result<String, EditError> {
    let dir = Tangent::new(dir)
        .map_err(|_| EditError::BadDirection { dir })?
        .get();
    let level = scene.edit_depth;
    if scene.mirror && level > 0 {
        return Err(EditError::MirrorDepth);
    }
    if level == 0 {
        let net = scene.design.net();
        check_cell(net.rows(), net.cols(), row, col, 0)?;
        // mirrored: a seam (row 0) tangent stays in the mirror plane
        let dir = if scene.mirror && row == 0 {
            let plane = scene.design.mirror_plane();
            plane.project_dir(dir, col)?
        } else {
            dir
        };
        if net.get(row, col) != dir {
            scene.design.set_tangent(row, col, dir)?;
        }
        return Ok(format!(
            "control ({row}, {col}) set to ({:.4}, {:.4}, {:.4})",
            dir.x, dir.y, dir.z
        ));
    }
    let l = &level_data(ctx, level)?.0;
    let (rows, cols) = l.shape();
    check_cell(rows, cols, row, col, level)?;
    let local = multires::to_local(l.base(), row, col, dir);
    scene.details.insert((level, row, col), local);
    Ok(format!("detail ({row}, {col}) at level {level}"))
}

/// The rotation of a `Rotate` or `RotateMany` edit, its axis and angle checked.
pub(super) fn rotation(axis: DVec3, radians: f64) -> Result<DQuat, EditError> {
    let axis = Tangent::new(axis).map_err(|_| EditError::BadAxis)?.get();
    if !radians.is_finite() {
        return Err(EditError::BadAngle);
    }
    Ok(DQuat::from_axis_angle(axis, radians))
}

fn set_length(scene: &mut Scene, row: usize, col: usize, k: f64) -> Result<String, EditError> {
    if !(k.is_finite() && k > 0.0) {
        return Err(EditError::BadLength { k });
    }
    let net = scene.design.net();
    check_cell(net.rows(), net.cols(), row, col, 0)?;
    let mut d = scene.design.clone();
    let old = d.params().s.row(row).to_vec();
    let mut s = old.clone();
    for i in 1..s.len() {
        let f = if i == col || i == col + 1 { k } else { 1.0 };
        s[i] = s[i - 1] + (old[i] - old[i - 1]) * f;
    }
    if s.iter().any(|v| !v.is_finite()) {
        return Err(EditError::LengthOverflow { k });
    }
    let refused = |e: EditError| EditError::LengthRefused {
        k,
        row,
        col,
        reason: Box::new(e),
    };
    d.set_s_row(row, &s).map_err(|e| refused(e.into()))?;
    check_design(&d, scene.max_depth(), scene.mirror).map_err(refused)?;
    scene.design = d;
    Ok(format!("length coefficient {k} at ({row}, {col})"))
}
