//! Empty: it only gives the host dependencies in `Cargo.toml` (syn's features) a place.
fn main() {}
