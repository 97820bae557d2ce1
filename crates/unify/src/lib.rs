//! No code: `loomkin-cli` depends on this crate so that `cargo run --release -p loomkin-cli` compiles
//! the crates it shares with `cargo test --release --workspace` with the same features, and the
//! second command reuses the first one's build (see `Cargo.toml`).
