//! The run's peak nodal displacement and velocity (`summary.json`): updated at every
//! history row, carried in the checkpoint so that a resumed run keeps the maxima over the
//! whole run.
//!
//! The scan runs over every node at every row (every step by default), so it is a
//! parallel reduction: each node's |u| and |v| (the same `sqrt` as a serial loop), the
//! largest value with the lowest node among equal ones — an order that does not depend on
//! how rayon splits the nodes, so the peaks are the same on any number of threads and
//! the same as the serial scan's (the first node, in node order, to exceed the peak so
//! far with the largest value). A NaN norm is never a peak, as in the serial `>` test.

use rayon::prelude::*;
use serde::Serialize;

/// Peak of a nodal quantity.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Peak {
    pub value: f64,
    pub node: usize,
    pub time: f64,
}

/// Nodes per parallel task of the scan.
const NODES_PER_TASK: usize = 8192;

/// Magic of the run driver's block at the end of a checkpoint: the peaks so far.
const PEAKS_MAGIC: &[u8; 8] = b"DCFMPK01";

/// The largest of two (norm, node) candidates, the lower node on a tie: a total order
/// on non-NaN norms, so the reduction's result does not depend on its grouping.
#[inline]
fn larger(a: (f64, usize), b: (f64, usize)) -> (f64, usize) {
    if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
        b
    } else {
        a
    }
}

#[inline]
fn norm(x: &[f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

/// Raise `peaks` ([|u|, |v|]) to the largest nodal |u| and |v| at `time` where they
/// exceed the peaks so far.
pub fn update_peaks(peaks: &mut [Peak; 2], u: &[[f64; 3]], v: &[[f64; 3]], time: f64) {
    let none = (f64::NEG_INFINITY, usize::MAX);
    let (top_u, top_v) = u
        .par_iter()
        .zip(v)
        .enumerate()
        .with_min_len(NODES_PER_TASK)
        .map(|(i, (u, v))| {
            let (nu, nv) = (norm(u), norm(v));
            (
                if nu.is_nan() { none } else { (nu, i) },
                if nv.is_nan() { none } else { (nv, i) },
            )
        })
        .reduce(|| (none, none), |a, b| (larger(a.0, b.0), larger(a.1, b.1)));
    for (peak, (value, node)) in peaks.iter_mut().zip([top_u, top_v]) {
        if value > peak.value {
            *peak = Peak { value, node, time };
        }
    }
}

/// Append the peaks to a checkpoint (after the dynamic block), so that a resumed run keeps
/// the maxima over the whole run, not only over its resumed part.
pub fn write_peaks(w: &mut impl std::io::Write, peaks: &[Peak; 2]) -> std::io::Result<()> {
    w.write_all(PEAKS_MAGIC)?;
    for p in peaks {
        for x in [p.value, p.node as f64, p.time] {
            w.write_all(&x.to_le_bytes())?;
        }
    }
    Ok(())
}

/// The peaks at the end of a checkpoint written with [`write_peaks`]; zero peaks for a
/// checkpoint without that block.
pub fn read_peaks(bytes: &[u8]) -> [Peak; 2] {
    const LEN: usize = 8 + 6 * 8;
    let Some(tail) = bytes.len().checked_sub(LEN).map(|k| &bytes[k..]) else {
        return [Peak::default(); 2];
    };
    if &tail[..8] != PEAKS_MAGIC {
        return [Peak::default(); 2];
    }
    let x: Vec<f64> = tail[8..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect();
    [0, 3].map(|k| Peak {
        value: x[k],
        node: x[k + 1] as usize,
        time: x[k + 2],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The serial scan the parallel one replaces: the first node, in order, to exceed the
    /// peak so far.
    fn serial(peaks: &mut [Peak; 2], u: &[[f64; 3]], v: &[[f64; 3]], time: f64) {
        for (i, (u, v)) in u.iter().zip(v).enumerate() {
            for (peak, x) in peaks.iter_mut().zip([u, v]) {
                let n = norm(x);
                if n > peak.value {
                    *peak = Peak {
                        value: n,
                        node: i,
                        time,
                    };
                }
            }
        }
    }

    #[test]
    fn parallel_scan_is_the_serial_scan_on_any_thread_count() {
        // 50,000 nodes with repeated norms (ties far apart in node order), a NaN, and
        // values on both sides of an earlier peak.
        let n = 50_000;
        let field = |k: u64| -> Vec<[f64; 3]> {
            (0..n as u64)
                .map(|i| {
                    let h = (i.wrapping_mul(2654435761).wrapping_add(k)) % 997;
                    [h as f64 * 1e-3, -(h as f64) * 2e-3, 0.5e-3 * (h % 7) as f64]
                })
                .collect()
        };
        let (mut u, v) = (field(1), field(7));
        u[12_345] = [f64::NAN, 0.0, 0.0];
        for start in [0.0, 1.0, 1e9] {
            let init = [
                Peak {
                    value: start,
                    node: 3,
                    time: -1.0,
                },
                Peak {
                    value: 0.5 * start,
                    node: 4,
                    time: -1.0,
                },
            ];
            let mut expected = init;
            serial(&mut expected, &u, &v, 2.5);
            for threads in [1, 2, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut got = init;
                pool.install(|| update_peaks(&mut got, &u, &v, 2.5));
                assert_eq!(got, expected, "{threads} threads, start {start}");
            }
        }
    }

    #[test]
    fn peaks_survive_a_checkpoint_block() {
        let peaks = [
            Peak {
                value: 0.25,
                node: 17,
                time: 3.5,
            },
            Peak {
                value: 1.5,
                node: 9,
                time: 0.1,
            },
        ];
        let mut bytes = b"dynamic state".to_vec();
        write_peaks(&mut bytes, &peaks).unwrap();
        assert_eq!(read_peaks(&bytes), peaks);
        assert_eq!(read_peaks(b"short"), [Peak::default(); 2]);
    }
}
