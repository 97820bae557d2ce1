//! Benchmarks of the dynamics crate.
fn main() {
    divan::main();
}
