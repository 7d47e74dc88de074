//! Linear constraints on the fine-tuning control values (docs/math.md §6).
//!
//! A constrained quantity (an end point, the chord of a closed curve) is
//! `A c` for a small matrix `A` (3 or 6 rows); the designer's values `c_u`
//! are replaced by the nearest `c` with `A c = b`:
//! `c = c_u − Aᵀ (A Aᵀ)⁺ (A c_u − b)`. The pseudo-inverse (symmetric Jacobi
//! eigen-decomposition, eigenvalues below [`RANK_TOLERANCE`]·λ_max dropped)
//! handles a planar streamline, whose `A` has rank 2.

/// What a fine-tuning edit must keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Constraint {
    /// Nothing: every streamline changes freely from its anchor.
    #[default]
    Free,
    /// Both end points of every streamline stay where they were.
    KeepEnds,
    /// The chord from the first to the last point stays, so a closed curve stays closed.
    KeepClosed,
}

impl Constraint {
    /// `free`, `keep-ends` or `keep-closed`.
    pub fn name(self) -> &'static str {
        match self {
            Constraint::Free => "free",
            Constraint::KeepEnds => "keep-ends",
            Constraint::KeepClosed => "keep-closed",
        }
    }
}

/// Relative size below which an eigenvalue of `A Aᵀ` (rows of unit length)
/// counts as zero: singular values below 1e-6 of the largest are directions
/// the constraint cannot move.
pub const RANK_TOLERANCE: f64 = 1e-12;

/// The `c` nearest to `user` (least squares) with `rows · c = rows · reference`:
/// the constrained quantities keep the values a known `reference` gives them
/// (all ones, the identity function, for end points; zeros for a closed
/// curve's chord). Rows are scaled to unit length first (the same set of
/// solutions, but a short segment's equations are no longer mistaken for a
/// rank deficiency); the residual is computed from `user − reference`, so the
/// reference itself comes back unchanged, bit for bit. When the constraint
/// cannot be met (a direction `A` cannot move), the change is the
/// least-squares one.
pub fn nearest_meeting(user: &[f64], rows: &[Vec<f64>], reference: &[f64]) -> Vec<f64> {
    let scaled: Vec<Vec<f64>> = rows
        .iter()
        .filter_map(|row| {
            let n = dot(row, row).sqrt();
            (n > 0.0 && n.is_finite()).then(|| row.iter().map(|x| x / n).collect())
        })
        .collect();
    // one projection and one step of iterative refinement
    let c = project(user, &scaled, reference);
    project(&c, &scaled, reference)
}

/// One projection of `user` onto `rows · c = rows · reference`.
fn project(user: &[f64], rows: &[Vec<f64>], reference: &[f64]) -> Vec<f64> {
    let k = rows.len();
    let d: Vec<f64> = user.iter().zip(reference).map(|(u, r)| u - r).collect();
    if k == 0 || d.iter().all(|&x| x == 0.0) {
        return user.to_vec();
    }
    // residual r = A (c_u − c_ref), normal matrix M = A Aᵀ
    let r: Vec<f64> = rows.iter().map(|row| dot(row, &d)).collect();
    let mut mat = vec![vec![0.0; k]; k];
    for i in 0..k {
        for j in 0..=i {
            let v = dot(&rows[i], &rows[j]);
            mat[i][j] = v;
            mat[j][i] = v;
        }
    }
    let (vals, vecs) = jacobi_eigen(mat);
    let top = vals.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    // y = M⁺ r = Σ over kept eigenpairs of (vᵀ r / λ) v
    let mut y = vec![0.0; k];
    for (e, &lam) in vals.iter().enumerate() {
        if top > 0.0 && lam > top * RANK_TOLERANCE {
            let coef: f64 = (0..k).map(|i| vecs[i][e] * r[i]).sum::<f64>() / lam;
            for (i, yi) in y.iter_mut().enumerate() {
                *yi += coef * vecs[i][e];
            }
        }
    }
    let mut c = user.to_vec();
    for (row, yi) in rows.iter().zip(&y) {
        for (cj, aij) in c.iter_mut().zip(row) {
            *cj -= aij * yi;
        }
    }
    c
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Eigenvalues and eigenvectors (columns) of a small symmetric matrix, by
/// cyclic Jacobi rotations.
fn jacobi_eigen(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut v = vec![vec![0.0; n]; n];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _sweep in 0..64 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..n).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-32 * diag || off == 0.0 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (rp, rq) = (a[p].clone(), a[q].clone());
                for (k, (apk, aqk)) in rp.into_iter().zip(rq).enumerate() {
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for row in v.iter_mut() {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i][i]).collect(), v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_meeting_meets_and_is_nearest() {
        let rows = vec![
            vec![1.0, 2.0, 0.5, -1.0, 0.3],
            vec![0.0, 1.0, 1.0, 1.0, 2.0],
        ];
        // a reference meeting the constraint: b = A · reference
        let reference = vec![0.5, -0.2, 1.0, 2.0, 0.1];
        let b: Vec<f64> = rows.iter().map(|r| dot(r, &reference)).collect();
        let user = vec![1.0, 1.0, 1.0, 1.0, 1.0];
        let c = nearest_meeting(&user, &rows, &reference);
        for (row, bi) in rows.iter().zip(&b) {
            assert!(
                (dot(row, &c) - bi).abs() < 1e-12,
                "constraint {}",
                dot(row, &c)
            );
        }
        // nearest: the change is orthogonal to every direction that keeps A c
        for e in 0..5 {
            let mut unit = vec![0.0; 5];
            unit[e] = 1.0;
            let null = nearest_meeting(&unit, &rows, &[0.0; 5]); // unit projected on ker A
            let d: f64 = c
                .iter()
                .zip(&user)
                .zip(&null)
                .map(|((a, b), n)| (a - b) * n)
                .sum();
            assert!(d.abs() < 1e-12, "change · kernel direction {e} = {d}");
        }
    }

    #[test]
    fn rank_deficient_rows_are_handled() {
        // a planar case: the third row is zero
        let rows = vec![
            vec![1.0, 0.5, 0.2],
            vec![0.3, 1.0, 0.1],
            vec![0.0, 0.0, 0.0],
        ];
        let one = vec![1.0; 3];
        let b: Vec<f64> = rows.iter().map(|r| dot(r, &one)).collect();
        let c = nearest_meeting(&[2.0, 0.5, 1.0], &rows, &one);
        assert!(c.iter().all(|v| v.is_finite()));
        for (row, bi) in rows.iter().zip(&b) {
            assert!((dot(row, &c) - bi).abs() < 1e-12);
        }
    }
}
