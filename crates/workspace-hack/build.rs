//! Empty: a build script makes cargo resolve the `[build-dependencies]` of `Cargo.toml` (the
//! features of the crates proc-macros and build scripts use on the host).
fn main() {}
