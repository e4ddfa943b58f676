//! Peak values (PGA, PGV, PGD) and when they occur.

/// The largest |x| of a series and its time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Peak {
    /// max |xᵢ|.
    pub value: f64,
    /// t of the first sample that reaches it (s).
    pub time: f64,
    /// Its index.
    pub index: usize,
}

/// max |xᵢ| over a series of step `dt`.
pub fn peak(x: &[f64], dt: f64) -> Peak {
    let mut p = Peak::default();
    for (i, &v) in x.iter().enumerate() {
        if v.abs() > p.value {
            p = Peak {
                value: v.abs(),
                time: i as f64 * dt,
                index: i,
            };
        }
    }
    p
}
