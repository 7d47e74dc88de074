//! A design's patches as B-spline faces: one shell whose seams are shared
//! (STEP, and IGES as separate faces) or each patch alone ([`document`]), the one face of a design of one patch ([`surface`]), the
//! deviation map of a design of several patches ([`deviation`]), and a
//! design fitted to and measured against its reference ([`mod@reference`]).

pub mod deviation;
pub mod document;
pub mod reference;
pub mod surface;
