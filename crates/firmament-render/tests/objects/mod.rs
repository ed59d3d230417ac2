//! Shared pieces of the object-pass tests.

pub(crate) mod reference;
