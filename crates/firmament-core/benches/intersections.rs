//! Intersection benchmarks (in progress).

fn main() {}
