//! The design in memory: one surface ([`model::Scene`]) and a document of
//! several patches ([`document::Document`]), with their checks
//! ([`document_check`]), their building through the kernel's joins
//! ([`document_build`]), their mirror ([`document_mirror`]), the shipped
//! scenes ([`builtin`]), and their reading and saving ([`document_io`]).

pub mod builtin;
pub mod document;
pub mod document_build;
pub mod document_check;
pub mod document_io;
pub mod document_mirror;
pub mod model;
