//! The initial curve and the parameters as handles (`docs/math.md §9`):
//! its control tangents, order, length and origin; the anchor column; a
//! control row's streamline length `L_s(t)`.
//!
//! None of these touches a tangent of the net: by Eq. 1 every streamline
//! `S(s, t) = S(s_a, t) + ∫ t dσ` is the same polyline, moved rigidly to the
//! initial curve's new point `S(s_a, t)` (an initial-curve edit), or placed at
//! another arc length `σ` (an anchor edit), or with its intervals scaled (a
//! length edit). Each returns a new design and leaves this one as it was.

use super::check_length;
use crate::error::{KernelError, Place};
use crate::levels::design::Design;
use crate::sphere::tangent::normalize_at;
use crate::streamline::initial_curve::InitialCurve;
use glam::DVec3;

impl Design {
    fn with_initial(&self, initial: InitialCurve) -> Design {
        Design {
            initial,
            ..self.clone()
        }
    }

    /// The initial curve's control tangent `index` set to `dir` (normalised).
    /// Refused: an index past the last tangent, a zero or non-finite direction.
    pub fn with_initial_direction(&self, index: usize, dir: DVec3) -> Result<Design, KernelError> {
        let c = &self.initial;
        let mut ts = c.qi().tangents().to_vec();
        if index >= ts.len() {
            return Err(KernelError::IndexOutOfRange {
                what: "initial curve tangent",
                index,
                len: ts.len(),
            });
        }
        ts[index] = normalize_at(dir, Place::Curve(index))?;
        let curve = InitialCurve::new(&ts, c.qi().order(), c.length(), c.origin())?;
        Ok(self.with_initial(curve))
    }

    /// The initial curve of arc length `length` (the rows keep their `t`).
    pub fn with_initial_length(&self, length: f64) -> Result<Design, KernelError> {
        let c = &self.initial;
        let length = check_length("initial curve length", length)?;
        let curve = InitialCurve::new(c.qi().tangents(), c.qi().order(), length, c.origin())?;
        Ok(self.with_initial(curve))
    }

    /// The initial curve starting at `origin`: every streamline moves by the same vector.
    pub fn with_initial_origin(&self, origin: DVec3) -> Result<Design, KernelError> {
        let c = &self.initial;
        let curve = InitialCurve::new(c.qi().tangents(), c.qi().order(), c.length(), origin)?;
        Ok(self.with_initial(curve))
    }

    /// The initial curve's QI order `k` (2 ..= its number of tangents, at most 8).
    pub fn with_initial_order(&self, order: usize) -> Result<Design, KernelError> {
        let c = &self.initial;
        let curve = InitialCurve::new(c.qi().tangents(), order, c.length(), c.origin())?;
        Ok(self.with_initial(curve))
    }

    /// The anchor column `col`: each streamline meets the initial curve at its
    /// tangent of that column (000 Fig. 1(b)); `σ_j = s_{col, j}`, or where
    /// the row's limit starts or ends at a first or last column
    /// ([`crate::levels::params::anchor_sigma`]).
    pub fn with_anchor(&self, col: usize) -> Result<Design, KernelError> {
        self.with_net(
            self.net.clone(),
            self.params.s.clone(),
            self.params.t.clone(),
            col,
        )
    }

    /// The arc length of control row `row`'s streamline, `s_last − s_first`
    /// (exactly the length of its polyline, Eq. 65).
    pub fn streamline_length(&self, row: usize) -> Option<f64> {
        (row < self.net.rows()).then(|| {
            let s = self.params.s.row(row);
            s[s.len() - 1] - s[0]
        })
    }

    /// Control row `row`'s streamline made `length` long: its `s` values, and
    /// so its `σ`, are multiplied by one factor `length / (s_last − s_first)`,
    /// so by Eq. 65 its polyline is exactly `length` long (to rounding) and
    /// keeps its shape, scaled about its anchor point.
    pub fn with_streamline_length(&self, row: usize, length: f64) -> Result<Design, KernelError> {
        let Some(now) = self.streamline_length(row) else {
            return Err(KernelError::IndexOutOfRange {
                what: "row",
                index: row,
                len: self.net.rows(),
            });
        };
        let length = check_length("streamline length", length)?;
        let f = length / now;
        let mut s = self.params.s.clone();
        for v in s.row_mut(row) {
            *v *= f;
        }
        self.with_net(self.net.clone(), s, self.params.t.clone(), self.anchor)
    }
}
