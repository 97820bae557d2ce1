//! Benchmarks of the servo crate (filled in below).

fn main() {
    divan::main();
}
