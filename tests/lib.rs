//! Cross-crate behaviour of covmap: one integration-test binary, one module per concern.

mod core;
mod sim;
