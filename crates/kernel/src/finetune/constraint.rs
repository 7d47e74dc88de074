//! Linear constraints on the fine-tuning control values (docs/math.md §6, (T2)–(T4)).
//!
//! A constrained quantity (an end point, the chord of a closed curve) is
//! `A c` for a small matrix `A` (3 or 6 rows), met by the identity `c = 1`.
//! One streamline's values `c_u` are replaced by the nearest `c` with
//! `A c = A 1`: `c = c_u − Aᵀ (A Aᵀ)⁺ A (c_u − 1)` ([`nearest_meeting`]; the
//! pseudo-inverse by a symmetric Jacobi eigen-decomposition, eigenvalues
//! below [`RANK_TOLERANCE`]·λ_max dropped, handles a planar streamline, whose
//! `A` has rank 2; rows of rounding, [`ROW_NOISE`], are no equations). A
//! surface's streamlines share a smooth correction instead
//! (`super::surface`), built on the row space of each `A` (`row_space`,
//! a one-sided Jacobi SVD) and its complement.

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

/// Relative size below which a whole constraint row counts as zero: a row
/// shorter than `ROW_NOISE` times the longest row of the same system is
/// rounding noise (the out-of-plane row of a streamline that is planar up to
/// rounding, ~1e-18), not an equation. Normalised, such a row would be a
/// random direction, an equation the geometry never asked for (docs/math.md
/// §6, (T3)). Dropping it moves the constrained quantity by at most
/// `ROW_NOISE` × the longest row × the change of the values.
pub const ROW_NOISE: f64 = 1e-12;

/// The rows that are equations (longer than [`ROW_NOISE`] × the longest,
/// finite), each scaled to unit length.
pub(crate) fn clean_rows(rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let norms: Vec<f64> = rows.iter().map(|row| dot(row, row).sqrt()).collect();
    let longest = norms
        .iter()
        .copied()
        .filter(|n| n.is_finite())
        .fold(0.0f64, f64::max);
    rows.iter()
        .zip(&norms)
        .filter(|&(_, &n)| n > 0.0 && n.is_finite() && n > ROW_NOISE * longest)
        .map(|(row, &n)| row.iter().map(|x| x / n).collect())
        .collect()
}

/// The `c` nearest to `user` (least squares) with `rows · c = rows · reference`:
/// the constrained quantities keep the values a known `reference` gives them
/// (all ones, the identity function, for end points; zeros for a closed
/// curve's chord). Rows are scaled to unit length first (the same set of
/// solutions, but a short segment's equations are no longer mistaken for a
/// rank deficiency), and rows below [`ROW_NOISE`] of the longest are dropped
/// as rounding noise; the residual is computed from `user − reference`, so the
/// reference itself comes back unchanged, bit for bit. When the constraint
/// cannot be met (a direction `A` cannot move), the change is the
/// least-squares one.
pub fn nearest_meeting(user: &[f64], rows: &[Vec<f64>], reference: &[f64]) -> Vec<f64> {
    let scaled = clean_rows(rows);
    nearest_meeting_clean(user, &scaled, reference)
}

/// [`nearest_meeting`] on rows already cleaned ([`clean_rows`]) or of unit length.
pub(crate) fn nearest_meeting_clean(
    user: &[f64],
    scaled: &[Vec<f64>],
    reference: &[f64],
) -> Vec<f64> {
    // one projection and one step of iterative refinement
    let c = project(user, scaled, reference);
    project(&c, scaled, reference)
}

/// Singular values below this fraction of the largest are directions of no
/// equation at all (the rounding of an exact dependence among the rows, or
/// of a row that vanishes: ~1e-17 of the largest), not equations
/// (docs/math.md §6, (T4)). Leaving such a direction free moves the
/// constrained point by at most this fraction of the largest row times the
/// change of the values.
pub const NO_EQUATION: f64 = 1e-13;

/// An orthonormal basis of the row space of `rows` as they are (not scaled:
/// a vanishing row stays small) by a one-sided Jacobi SVD — the rows
/// orthogonalised by plane rotations, accurate to the rounding of the
/// largest singular value, where the Gram matrix `A Aᵀ` would square the
/// condition — keeping the directions whose singular values are above
/// [`NO_EQUATION`] of the largest. Every one of them is an equation the
/// values can meet with a bounded change (the constraint is consistent:
/// `c = 1` meets it), however small its singular value.
pub(crate) fn row_space(rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut w: Vec<Vec<f64>> = rows
        .iter()
        .filter(|r| r.iter().all(|x| x.is_finite()))
        .cloned()
        .collect();
    let k = w.len();
    for _sweep in 0..60 {
        let mut rotated = false;
        for p in 0..k {
            for q in p + 1..k {
                let a = dot(&w[p], &w[p]);
                let b = dot(&w[q], &w[q]);
                let g = dot(&w[p], &w[q]);
                if g == 0.0 || g.abs() <= 1e-16 * (a * b).sqrt() {
                    continue;
                }
                rotated = true;
                let zeta = (b - a) / (2.0 * g);
                let t = if zeta == 0.0 {
                    1.0
                } else {
                    zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt())
                };
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                let (wp, wq) = (w[p].clone(), w[q].clone());
                for (i, (x, y)) in wp.iter().zip(&wq).enumerate() {
                    w[p][i] = c * x - s * y;
                    w[q][i] = s * x + c * y;
                }
            }
        }
        if !rotated {
            break;
        }
    }
    let sigma: Vec<f64> = w.iter().map(|x| dot(x, x).sqrt()).collect();
    let top = sigma
        .iter()
        .copied()
        .filter(|s| s.is_finite())
        .fold(0.0f64, f64::max);
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| sigma[b].total_cmp(&sigma[a]));
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for i in order {
        let s = sigma[i];
        if !(top > 0.0 && s.is_finite() && s > NO_EQUATION * top) {
            continue;
        }
        // re-orthonormalise against rounding
        let mut u: Vec<f64> = w[i].iter().map(|x| x / s).collect();
        for q in &basis {
            let d = dot(&u, q);
            u.iter_mut().zip(q).for_each(|(a, b)| *a -= d * b);
        }
        let n = dot(&u, &u).sqrt();
        if !(n > 0.5 && n.is_finite()) {
            continue;
        }
        u.iter_mut().for_each(|x| *x /= n);
        basis.push(u);
    }
    basis
}

/// `x` with its components along the orthonormal `basis` removed
/// (`(I − U Uᵀ) x`), twice against rounding.
pub(crate) fn project_out(x: &[f64], basis: &[Vec<f64>]) -> Vec<f64> {
    let mut y = x.to_vec();
    for _ in 0..2 {
        for u in basis {
            let d = dot(&y, u);
            y.iter_mut().zip(u).for_each(|(a, b)| *a -= d * b);
        }
    }
    y
}

/// An orthonormal basis of the orthogonal complement of the orthonormal
/// `own` in `R^m` (the directions the constraint leaves free): unit vectors
/// projected off `own` and the directions already taken, the longest
/// residual first (so every one taken has length ≥ `1/√m` before scaling).
pub(crate) fn complement(own: &[Vec<f64>], m: usize) -> Vec<Vec<f64>> {
    let want = m.saturating_sub(own.len());
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(want);
    let residual = |j: usize, out: &[Vec<f64>]| {
        let mut x = vec![0.0; m];
        x[j] = 1.0;
        for _ in 0..2 {
            for q in own.iter().chain(out) {
                let d = dot(&x, q);
                x.iter_mut().zip(q).for_each(|(a, b)| *a -= d * b);
            }
        }
        x
    };
    while out.len() < want {
        let best = (0..m)
            .map(|j| residual(j, &out))
            .max_by(|a, b| dot(a, a).total_cmp(&dot(b, b)));
        let Some(mut x) = best else { break };
        let n = dot(&x, &x).sqrt();
        if !(n > 1e-8 && n.is_finite()) {
            break;
        }
        x.iter_mut().for_each(|v| *v /= n);
        out.push(x);
    }
    out
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
