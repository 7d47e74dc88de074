//! The rows a fit measured, kept for the next net (`docs/math.md §12`,
//! "Deviation, both ways"): a mesh row's key, bit for bit what its
//! measurement depends on, and the cache of the last net's rows.

use super::RowResult;
use crate::levels::design::Level;
use glam::DVec3;
use std::collections::HashMap;

/// What a mesh row's measurement depends on: its `t`, the stride, and its
/// points, level tangents and arc lengths, bit for bit.
#[derive(Clone, PartialEq)]
pub(super) struct RowKey {
    t: u64,
    stride: usize,
    every: usize,
    points: Vec<[u64; 3]>,
    tangents: Vec<[u64; 3]>,
    s: Vec<u64>,
}

impl RowKey {
    pub(super) fn new(
        level: &Level,
        points: &[DVec3],
        r: usize,
        stride: usize,
        every: usize,
    ) -> Self {
        let bits = |p: &DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let width = level.tangents.cols() + 1;
        RowKey {
            t: level.params.t[r].to_bits(),
            stride,
            every,
            points: points[r * width..(r + 1) * width]
                .iter()
                .map(bits)
                .collect(),
            tangents: level.tangents.row(r).iter().map(bits).collect(),
            s: level.params.s.row(r).iter().map(|x| x.to_bits()).collect(),
        }
    }

    /// A quick hash (multiply and rotate over the bits; the key itself is
    /// compared on a hit).
    pub(super) fn hash(&self) -> u64 {
        let mut h = 0x9e37_79b9_7f4a_7c15u64;
        let mut mix = |x: u64| h = (h ^ x).wrapping_mul(0x0100_0000_01b3).rotate_left(29);
        mix(self.t);
        mix(self.stride as u64);
        mix(self.every as u64);
        self.points
            .iter()
            .chain(&self.tangents)
            .flatten()
            .for_each(|&x| mix(x));
        self.s.iter().for_each(|&x| mix(x));
        h
    }
}

/// The rows measured by the last net, kept for the next one: a row that
/// the insertion of a row elsewhere left bit for bit as it was (the
/// subdivision is local) is not measured again. Its results are the same
/// numbers, so the cache changes nothing but the time.
#[derive(Default)]
pub(crate) struct RowCache {
    pub(super) rows: HashMap<u64, (RowKey, RowResult)>,
}
