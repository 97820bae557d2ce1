//! Benchmarks of the loom model.

fn main() {
    divan::main();
}
