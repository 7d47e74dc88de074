//! Designing from nothing (paper 000 §5: "the main design task … is to
//! specify tangent vectors … as well as the initial curve"; `docs/math.md §9`).
//!
//! Every authoring operation is a function on [`Design`](crate::Design):
//! * [`template`]: exact starting nets, `Flat(width)` and `Cylinder(radius, angle)`;
//! * [`structure`]: inserting and deleting a control row (a streamline) or a
//!   column, with the tangents and parameters the surface already has there;
//! * [`initial`]: the initial curve's tangents, order, length and origin, the
//!   anchor column, and a streamline's length `L_s(t)`;
//! * [`mirror`]: mirror symmetry about the plane through the initial curve's
//!   start, perpendicular to its first tangent (the doubled net).
//!
//! Each returns a new design or a [`KernelError`](crate::KernelError) that says
//! what to change; the design it was called on is never left half-edited.

pub mod initial;
pub mod mirror;
pub mod structure;
pub mod template;

pub use mirror::MirrorPlane;
pub use structure::Axis;
pub use template::Template;

/// The largest number of rows, and of columns, an authored net may have
/// (the new-design dialog and the inserts refuse more).
pub const MAX_NET_SIDE: usize = 64;

/// Checks an authored net's size: `2 ..= MAX_NET_SIDE` a side.
pub(crate) fn check_net_size(rows: usize, cols: usize) -> Result<(), crate::KernelError> {
    if rows > MAX_NET_SIDE || cols > MAX_NET_SIDE {
        return Err(crate::KernelError::NetTooLarge {
            rows,
            cols,
            max: MAX_NET_SIDE,
        });
    }
    if rows < 2 {
        return Err(crate::KernelError::NetTooSmall {
            what: "row",
            count: rows,
        });
    }
    if cols < 2 {
        return Err(crate::KernelError::NetTooSmall {
            what: "column",
            count: cols,
        });
    }
    Ok(())
}

/// A finite positive length within the kernel's coordinate range.
pub(crate) fn check_length(what: &'static str, v: f64) -> Result<f64, crate::KernelError> {
    if !(v.is_finite() && v > 0.0) {
        return Err(crate::KernelError::NotPositive { what, value: v });
    }
    if !crate::limits::in_range(v) {
        return Err(crate::KernelError::TooLargeValue { what, value: v });
    }
    Ok(v)
}
