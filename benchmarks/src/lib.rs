//! Benchmark support for dcfm.
