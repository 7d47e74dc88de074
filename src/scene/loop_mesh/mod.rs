//! The Loop mesh's files (docs/loop.md): triangle meshes from and to OBJ
//! ([`obj`]) and a Loop control mesh as USD ([`usd`]).

pub mod obj;
pub mod usd;
