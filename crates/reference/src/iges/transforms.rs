//! Transformation matrices (entity 124): an entry's matrix, composed with
//! the matrices it points to in turn, and the `[R | T]` arithmetic.

use super::records::REEXPORT;
use super::{File, MAX_CHAIN};
use crate::error::ReferenceError;
use streamline_kernel::DVec3;

impl File<'_> {
    /// The matrix `[R | T]` of entry `k`'s transformation (entity 124),
    /// composed with the matrix of that entity in turn; `None` for none.
    pub(super) fn transform(
        &self,
        k: usize,
        depth: usize,
    ) -> Result<Option<[[f64; 4]; 3]>, ReferenceError> {
        let de = &self.des[k];
        if de.transform == 0 {
            return Ok(None);
        }
        let t = de.transform.unsigned_abs() as usize;
        if t.is_multiple_of(2) || t / 2 >= self.des.len() || self.des[t / 2].etype != 124 {
            return Err(self.de_err(
                de,
                49,
                format!("its transformation matrix pointer {t} is not the DE of a transformation matrix (124); {REEXPORT}"),
            ));
        }
        if depth >= MAX_CHAIN {
            return Err(self.de_err(
                de,
                49,
                format!("its transformation matrices chain more than {MAX_CHAIN} deep (a cycle?); {REEXPORT}"),
            ));
        }
        let p = self.params(t / 2)?;
        let mut m = [[0.0; 4]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x = p.real(1 + 4 * r + c, "matrix entry")?;
            }
        }
        Ok(Some(match self.transform(t / 2, depth + 1)? {
            None => m,
            Some(parent) => compose(&parent, &m),
        }))
    }
}

/// `m x` for the matrix `[R | T]`.
pub(super) fn apply(m: &[[f64; 4]; 3], x: DVec3) -> DVec3 {
    let r = |i: usize| m[i][0] * x.x + m[i][1] * x.y + m[i][2] * x.z + m[i][3];
    DVec3::new(r(0), r(1), r(2))
}

/// `a ∘ b` (first `b`, then `a`) for matrices `[R | T]`.
fn compose(a: &[[f64; 4]; 3], b: &[[f64; 4]; 3]) -> [[f64; 4]; 3] {
    let mut out = [[0.0; 4]; 3];
    for i in 0..3 {
        for j in 0..4 {
            let mut s: f64 = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            if j == 3 {
                s += a[i][3];
            }
            out[i][j] = s;
        }
    }
    out
}
