//! The file's specifications as the kernel's types and back: scheme, blend
//! order, fine-tuning constraint and function, initial curve.

use super::format::*;
use streamline_kernel::finetune::bspline::TensorBSpline;
use streamline_kernel::finetune::{Constraint, SurfaceTuning};
use streamline_kernel::streamline::initial_curve::InitialCurve;
use streamline_kernel::{BlendOrder, DVec3, Grid, KernelError, SurfaceScheme};

impl SchemeSpec {
    /// The kernel's scheme.
    pub fn to_kernel(self) -> SurfaceScheme {
        match self {
            SchemeSpec::Kobbelt { omega } => SurfaceScheme::Kobbelt { omega: omega.0 },
            SchemeSpec::CatmullClark => SurfaceScheme::CatmullClark,
            SchemeSpec::DooSabin => SurfaceScheme::DooSabin,
        }
    }

    /// From the kernel's scheme.
    pub fn from_kernel(s: SurfaceScheme) -> Self {
        match s {
            SurfaceScheme::Kobbelt { omega } => SchemeSpec::Kobbelt {
                omega: Omega(omega),
            },
            SurfaceScheme::CatmullClark => SchemeSpec::CatmullClark,
            SurfaceScheme::DooSabin => SchemeSpec::DooSabin,
        }
    }
}

impl OrderSpec {
    /// The kernel's blend order.
    pub fn to_kernel(self) -> BlendOrder {
        match self {
            OrderSpec::SFirst => BlendOrder::SFirst,
            OrderSpec::TFirst => BlendOrder::TFirst,
        }
    }

    /// From the kernel's.
    pub fn from_kernel(o: BlendOrder) -> Self {
        match o {
            BlendOrder::SFirst => OrderSpec::SFirst,
            BlendOrder::TFirst => OrderSpec::TFirst,
        }
    }
}

impl ConstraintSpec {
    /// The kernel's constraint.
    pub fn to_kernel(self) -> Constraint {
        match self {
            ConstraintSpec::Free => Constraint::Free,
            ConstraintSpec::KeepEnds => Constraint::KeepEnds,
            ConstraintSpec::KeepClosed => Constraint::KeepClosed,
        }
    }

    /// From the kernel's.
    pub fn from_kernel(c: Constraint) -> Self {
        match c {
            Constraint::Free => ConstraintSpec::Free,
            Constraint::KeepEnds => ConstraintSpec::KeepEnds,
            Constraint::KeepClosed => ConstraintSpec::KeepClosed,
        }
    }
}

impl TuningSpec {
    /// The kernel's surface tuning, or what is wrong and what to do.
    pub fn to_kernel(&self) -> Result<SurfaceTuning, String> {
        let rows = self.values.len();
        let cols = self.values.first().map_or(0, Vec::len);
        if let Some(r) = self.values.iter().position(|r| r.len() != cols) {
            return Err(format!(
                "fine tuning: row {r} of values has {} entries but row 0 has {cols}; every row needs the same number",
                self.values[r].len()
            ));
        }
        if rows == 0 || cols == 0 {
            return Err(
                "fine tuning: values is empty; give rows of control values, e.g. [[1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0]]"
                    .into(),
            );
        }
        let grid = Grid::new(
            rows,
            cols,
            self.values.iter().flatten().map(|v| v.0).collect(),
        )
        .map_err(|e| e.to_string())?;
        let function = TensorBSpline::new(self.degree_s, self.degree_t, grid)
            .map_err(|e| format!("fine tuning: {e}"))?;
        Ok(SurfaceTuning {
            function,
            constraint: self.constraint.to_kernel(),
        })
    }

    /// The file form of a kernel surface tuning.
    pub fn from_kernel(t: &SurfaceTuning) -> Self {
        let v = t.function.values();
        TuningSpec {
            degree_s: t.function.degree_s(),
            degree_t: t.function.degree_t(),
            values: (0..v.rows())
                .map(|r| v.row(r).iter().map(|&x| Finite(x)).collect())
                .collect(),
            constraint: ConstraintSpec::from_kernel(t.constraint),
        }
    }
}

impl InitialSpec {
    /// The kernel's initial curve.
    pub fn to_kernel(&self) -> Result<InitialCurve, KernelError> {
        let ts: Vec<DVec3> = self.tangents.iter().map(|d| d.vec()).collect();
        InitialCurve::new(&ts, self.order, self.length.0, self.origin.vec())
    }

    /// The description of a kernel initial curve.
    pub fn from_kernel(c: &InitialCurve) -> Self {
        InitialSpec {
            tangents: c
                .qi()
                .tangents()
                .iter()
                .map(|&v| Dir::from_vec(v))
                .collect(),
            order: c.qi().order(),
            length: Finite(c.length()),
            origin: Point::from_vec(c.origin()),
        }
    }
}
