//! SIMD lanes for the element kernels (issue 11): [`LANES`] values are processed together,
//! each `f64` of the scalar kernel becoming an [`F64s`] — one value per Gauss point of a
//! fully integrated element in `hex8_full_lanes`, one element per lane in
//! `hex8_uniform_lanes`.
//!
//! The lane type is a plain array with element-wise operators. Inside [`run_lane_work`]
//! (pulp's runtime dispatch: the work is compiled once per instruction set — AVX-512
//! (x86-64-v4), AVX2 + FMA (x86-64-v3), or the baseline — and the best one the CPU offers
//! is chosen at run time), every operator on [`F64s`] compiles to vector instructions. Each
//! lane performs exactly the IEEE operations of the scalar kernel in the same order (Rust
//! never contracts a multiply and an add into an FMA by itself; where a kernel fuses one,
//! [`fused_sum3`], its scalar twin calls `mul_add`, correctly rounded on every target), so
//! the lane kernels give the scalar kernels' results bit for bit; the tests compare them on
//! random elements.
//!
//! Where many lane values are live at once, the choice LLVM makes for `F64s` arithmetic
//! can be poor (on AVX2 an `F64s` is two registers of sixteen: it spilled, and packed the
//! wrong dimension): such kernels are written in the vectors of the instruction set that
//! [`LaneWork::run`] receives, through [`part`], [`set_part`] and [`fused_sum3`] — once, for
//! AVX-512, AVX2 and pulp's scalar fallback alike (`hex8_full_lanes`).

use std::ops::{Add, Div, Index, IndexMut, Mul, Neg, Sub};

/// The instruction set a [`LaneWork`] is compiled for (pulp's), re-exported for the
/// implementations outside this crate.
pub use pulp::Simd;

/// Elements per lane block. 8 × f64: one AVX-512 register, two AVX2 registers.
pub const LANES: usize = 8;

/// One `f64` per lane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(64))]
pub struct F64s(pub [f64; LANES]);

impl F64s {
    /// Every lane 0.0.
    pub const ZERO: F64s = F64s([0.0; LANES]);

    /// Every lane `x`.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        F64s([x; LANES])
    }

    /// `f64::sqrt` of every lane (correctly rounded, like the scalar one).
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        F64s(self.0.map(f64::sqrt))
    }

    /// `f64::max` lane by lane.
    #[inline(always)]
    pub fn max(self, other: F64s) -> Self {
        F64s(std::array::from_fn(|l| self.0[l].max(other.0[l])))
    }

    /// `f64::min` lane by lane.
    #[inline(always)]
    pub fn min(self, other: F64s) -> Self {
        F64s(std::array::from_fn(|l| self.0[l].min(other.0[l])))
    }

    /// Lane `l` of `a` where `pick[l]`, else of `b`.
    #[inline(always)]
    pub fn select(pick: &[bool; LANES], a: F64s, b: F64s) -> Self {
        F64s(std::array::from_fn(
            |l| if pick[l] { a.0[l] } else { b.0[l] },
        ))
    }
}

impl Index<usize> for F64s {
    type Output = f64;
    #[inline(always)]
    fn index(&self, l: usize) -> &f64 {
        &self.0[l]
    }
}

impl IndexMut<usize> for F64s {
    #[inline(always)]
    fn index_mut(&mut self, l: usize) -> &mut f64 {
        &mut self.0[l]
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F64s {
            type Output = F64s;
            #[inline(always)]
            fn $f(self, rhs: F64s) -> F64s {
                let mut out = [0.0; LANES];
                for l in 0..LANES {
                    out[l] = self.0[l] $op rhs.0[l];
                }
                F64s(out)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl Mul<F64s> for f64 {
    type Output = F64s;
    #[inline(always)]
    fn mul(self, rhs: F64s) -> F64s {
        F64s::splat(self) * rhs
    }
}

impl Neg for F64s {
    type Output = F64s;
    #[inline(always)]
    fn neg(self) -> F64s {
        let mut out = [0.0; LANES];
        for l in 0..LANES {
            out[l] = -self.0[l];
        }
        F64s(out)
    }
}

/// Nodal vectors of a lane block: `[node][component]`, one value per element.
pub type NodalLanes = [[F64s; 3]; 8];

/// Voigt vector per lane.
pub type VoigtLanes = [F64s; 6];

/// Work compiled for the CPU's best instruction set by [`run_lane_work`]: implementations
/// mark [`LaneWork::run`] `#[inline(always)]` (and everything it calls that should use the
/// wide registers), so that the whole body is inlined into pulp's per-instruction-set entry
/// points. (A closure handed to pulp is not enough: its body is inlined only when the
/// compiler chooses to, and a large one stays baseline code — measured, docs/benchmarks.md.)
/// `simd` is the instruction set chosen: kernels that spell their arithmetic in its
/// vectors ([`part`], [`set_part`], [`fused_sum3`]) take it, the others ignore it; work run
/// outside the dispatch passes `pulp::Scalar::new()`.
pub trait LaneWork {
    /// What the work returns.
    type Output;
    /// Do the work (to be marked `#[inline(always)]`).
    fn run<S: Simd>(self, simd: S) -> Self::Output;
}

struct Dispatched<W>(W);

impl<W: LaneWork> pulp::WithSimd for Dispatched<W> {
    type Output = W::Output;
    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> W::Output {
        self.0.run(simd)
    }
}

/// Run `work` compiled for the best instruction set of the CPU: AVX-512 (x86-64-v4), AVX2
/// and FMA (x86-64-v3) or the baseline, chosen at run time by pulp. The lane operators
/// give the same bits under each (no contraction into FMA).
///
/// The baseline is [`run_scalar_work`], out of line, rather than pulp's fallback inlined
/// here: a caller that also runs the work without lanes then shares one scalar body with
/// it instead of holding two inlined copies of the whole kernel.
#[inline(always)]
pub fn run_lane_work<W: LaneWork>(work: W) -> W::Output {
    #[cfg(target_arch = "x86_64")]
    {
        match pulp::Arch::new() {
            pulp::Arch::V4(simd) => Simd::vectorize(simd, Dispatched(work)),
            pulp::Arch::V3(simd) => Simd::vectorize(simd, Dispatched(work)),
            // the baseline (`Arch` is non-exhaustive)
            _ => run_scalar_work(work),
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        pulp::Arch::new().dispatch(Dispatched(work))
    }
}

/// Run `work` in plain scalar code (pulp's `Scalar`): the lanes-off path of the element
/// passes and [`run_lane_work`]'s baseline. Kept out of line on purpose. The kernels
/// inlined into a work make each instance a large function. With two inlined scalar
/// copies in each caller (the lanes-off branch and pulp's fallback), the two element
/// passes' closures took 298 s of LLVM's optimisation. With their vector entry points,
/// that was 572 s of the crate's 603 s, all in one codegen unit. Out of line, the
/// crate's release build fell from 12.0 to 3.9 min (docs/benchmarks.md, stop 68).
///
/// Where the CPU has them, the scalar body is compiled for AVX2 and FMA (x86-64-v3, entered
/// through pulp's `V3`) while still handed the `Scalar` token: its vectors stay one value
/// wide, the same operations in the same order, but `f64::mul_add` becomes the `vfmadd`
/// instruction instead of a call of the C library's `fma` (4.13 against 1.12 ns a
/// dependent operation, docs/benchmarks.md, stop 69). Both are correctly rounded, so the
/// bits are the same on every CPU.
#[inline(never)]
pub fn run_scalar_work<W: LaneWork>(work: W) -> W::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(v3) = pulp::x86::V3::try_new() {
        return Simd::vectorize(v3, ScalarIn(work));
    }
    work.run(pulp::Scalar::new())
}

/// Scalar work run inside another instruction set's entry point (see [`run_scalar_work`]).
#[cfg(target_arch = "x86_64")]
struct ScalarIn<W>(W);

#[cfg(target_arch = "x86_64")]
impl<W: LaneWork> pulp::WithSimd for ScalarIn<W> {
    type Output = W::Output;
    #[inline(always)]
    fn with_simd<S: Simd>(self, _simd: S) -> W::Output {
        self.0.run(pulp::Scalar::new())
    }
}

/// Run `work` in lanes ([`run_lane_work`]) when `in_lanes`, else in plain scalar code
/// ([`run_scalar_work`]): the element passes' switch between their two paths, both
/// bodies shared with every other caller of the same work type.
#[inline(always)]
pub fn run_work<W: LaneWork>(work: W, in_lanes: bool) -> W::Output {
    if in_lanes {
        run_lane_work(work)
    } else {
        run_scalar_work(work)
    }
}

/// How many vectors of `S` an [`F64s`] is: 1 with AVX-512, 2 with AVX2, 8 without
/// vectors (pulp's scalar fallback).
#[inline(always)]
pub fn parts<S: Simd>() -> usize {
    assert!(
        LANES.is_multiple_of(S::F64_LANES),
        "an F64s is whole vectors"
    );
    LANES / S::F64_LANES
}

/// Vector `p` of `x` (lanes `p·n .. (p + 1)·n`, n = `S::F64_LANES`), for kernels written
/// in the vectors of the dispatched instruction set: with AVX2 an [`F64s`] is two 256-bit
/// vectors, and left to the compiler its element-wise operators spilled and packed the
/// wrong dimension where many are live at once (docs/benchmarks.md, stop 60).
#[inline(always)]
pub fn part<S: Simd>(x: &F64s, p: usize) -> S::f64s {
    S::as_simd_f64s(&x.0).0[p]
}

/// Write vector `p` of `x` (the inverse of [`part`]).
#[inline(always)]
pub fn set_part<S: Simd>(x: &mut F64s, p: usize, v: S::f64s) {
    S::as_mut_simd_f64s(&mut x.0).0[p] = v;
}

/// a₂ b₂ + (a₁ b₁ + a₀ b₀) in the vectors of `simd`: a product, then two fused
/// multiply-adds (one rounding each, hardware FMA under AVX2 and AVX-512, `f64::mul_add`
/// under pulp's scalar fallback), [`fused_sum3_scalar`] bit for bit in every lane. Fused,
/// the 8-point kernel's sums took 10–14 % less time than as separate multiplies and adds
/// (docs/benchmarks.md, stop 69).
#[inline(always)]
pub fn fused_sum3<S: Simd>(simd: S, a: [S::f64s; 3], b: [S::f64s; 3]) -> S::f64s {
    simd.mul_add_f64s(
        a[2],
        b[2],
        simd.mul_add_f64s(a[1], b[1], simd.mul_f64s(a[0], b[0])),
    )
}

/// [`fused_sum3`] of one value: a₂ b₂ + (a₁ b₁ + a₀ b₀) with the last two steps fused.
/// Correctly rounded on every target; where the code is not compiled for a CPU with FMA,
/// `mul_add` is a call to the C library's `fma` (≈ 4 ns against 1 ns, measured), so
/// callers on hot paths run under [`run_lane_work`]'s or [`run_scalar_work`]'s dispatch
/// (both compile their work for FMA where the CPU has it).
#[inline(always)]
pub fn fused_sum3_scalar(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[2].mul_add(b[2], a[1].mul_add(b[1], a[0] * b[0]))
}

/// An [`F64s`] whose lane `l` is `$e` (written out lane by lane: eight loads into one
/// vector).
#[macro_export]
#[doc(hidden)]
macro_rules! lanes8 {
    ($l:ident => $e:expr) => {
        $crate::element::lanes::F64s([
            {
                let $l = 0;
                $e
            },
            {
                let $l = 1;
                $e
            },
            {
                let $l = 2;
                $e
            },
            {
                let $l = 3;
                $e
            },
            {
                let $l = 4;
                $e
            },
            {
                let $l = 5;
                $e
            },
            {
                let $l = 6;
                $e
            },
            {
                let $l = 7;
                $e
            },
        ])
    };
}

/// The values of lane `l`.
#[inline(always)]
pub fn lane_of(x: &NodalLanes, l: usize) -> [[f64; 3]; 8] {
    std::array::from_fn(|a| [x[a][0].0[l], x[a][1].0[l], x[a][2].0[l]])
}

/// A number the shared formulas are written for once: one `f64` (the scalar kernels) or an
/// [`F64s`] (one value per lane), with the same IEEE operations in either.
pub trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `x` (in every lane).
    fn splat(x: f64) -> Self;
    /// Square root (correctly rounded).
    fn sqrt(self) -> Self;
    /// `f64::max` (lane by lane).
    fn max(self, other: Self) -> Self;
    /// `f64::min` (lane by lane).
    fn min(self, other: Self) -> Self;
    /// `self · a + b` with one rounding (`f64::mul_add`, lane by lane), in the vectors of
    /// `simd`: the CPU's FMA where the code is compiled for it (under [`run_lane_work`] or
    /// [`run_scalar_work`]), else a call of the C library's `fma`, with the same bits.
    fn mul_add<S: Simd>(self, simd: S, a: Self, b: Self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
    #[inline(always)]
    fn mul_add<S: Simd>(self, _simd: S, a: Self, b: Self) -> Self {
        f64::mul_add(self, a, b)
    }
}

impl Lane for F64s {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        F64s::splat(x)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F64s::sqrt(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        F64s::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        F64s::min(self, other)
    }
    #[inline(always)]
    fn mul_add<S: Simd>(self, simd: S, a: Self, b: Self) -> Self {
        // vector by vector, as the 8-point kernel's sums: left to the compiler, the lane
        // loop became scalar and 128-bit FMAs with shuffles between them (measured, stop 70)
        let mut out = F64s::ZERO;
        for p in 0..parts::<S>() {
            let v = simd.mul_add_f64s(part::<S>(&self, p), part::<S>(&a, p), part::<S>(&b, p));
            set_part::<S>(&mut out, p, v);
        }
        out
    }
}

/// Isotropic elastic stress σ = λ tr ε I + 2μ ε (engineering shear) in the vectors of
/// `simd`, one vector of points: the one spelling of it. Under `pulp::Scalar` (whose `f64s`
/// is `f64` and whose operations are the plain IEEE ones) it is `Elastic::stress` of one
/// point; in the dispatched vectors each lane performs the same operations in the same
/// order, so the same bits.
#[inline(always)]
pub fn elastic_stress_in<S: Simd>(simd: S, lambda: f64, mu: f64, e: &[S::f64s; 6]) -> [S::f64s; 6] {
    let tr = simd.add_f64s(simd.add_f64s(e[0], e[1]), e[2]);
    let l = simd.mul_f64s(simd.splat_f64s(lambda), tr);
    let m2 = simd.splat_f64s(2.0 * mu);
    let mu = simd.splat_f64s(mu);
    [
        simd.add_f64s(l, simd.mul_f64s(m2, e[0])),
        simd.add_f64s(l, simd.mul_f64s(m2, e[1])),
        simd.add_f64s(l, simd.mul_f64s(m2, e[2])),
        simd.mul_f64s(mu, e[3]),
        simd.mul_f64s(mu, e[4]),
        simd.mul_f64s(mu, e[5]),
    ]
}

/// [`elastic_stress_in`] of the eight lanes of `e`, one vector of `simd` at a time.
#[inline(always)]
pub fn elastic_stress_lanes<S: Simd>(simd: S, lambda: f64, mu: f64, e: &VoigtLanes) -> VoigtLanes {
    let mut out = [F64s::ZERO; 6];
    for p in 0..parts::<S>() {
        let mut strain = [simd.splat_f64s(0.0); 6];
        for (v, x) in strain.iter_mut().zip(e) {
            *v = part::<S>(x, p);
        }
        let stress = elastic_stress_in(simd, lambda, mu, &strain);
        for (o, s) in out.iter_mut().zip(stress) {
            set_part::<S>(o, p, s);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_are_lane_wise_and_aligned() {
        let a = F64s(std::array::from_fn(|l| l as f64 + 0.5));
        let b = F64s::splat(2.0);
        assert_eq!((a * b + a - b).0[3], 3.5 * 2.0 + 3.5 - 2.0);
        assert_eq!((-a).0[7], -7.5);
        assert_eq!((a / b).0[1], 1.5 / 2.0);
        assert_eq!(a.min(b).0[5], 2.0);
        let pick = std::array::from_fn(|l| l % 2 == 0);
        assert_eq!(F64s::select(&pick, a, b).0[..2], [0.5, 2.0]);
        assert_eq!(std::mem::align_of::<F64s>(), 64);
        assert_eq!(std::mem::size_of::<F64s>(), 8 * LANES);
        struct Square(F64s);
        impl LaneWork for Square {
            type Output = F64s;
            #[inline(always)]
            fn run<S: Simd>(self, _simd: S) -> F64s {
                self.0 * self.0
            }
        }
        assert_eq!(run_lane_work(Square(a)).0[2], 2.5 * 2.5);
    }

    /// The vector parts and the three-term sum give the scalar operations' bits, under
    /// the dispatched instruction set and under pulp's scalar fallback.
    #[test]
    fn parts_and_sums_are_the_scalar_operations() {
        // Lanes 0–3: a₀b₀ = 1e16 + l (ulp 2), the other products 1: (a₀b₀ + 1) + 1 and
        // a₀b₀ + (1 + 1) differ in their last bit in some lanes, so the association is
        // tested, not only the products. Lanes 4–7: a₁b₁ = (1 + 2⁻³⁰)(1 + k 2⁻³⁰) is not
        // a double and a₀b₀ = −1 cancels its leading part, so the fused sum keeps the
        // k 2⁻⁶⁰ that separate operations round away.
        let x: [F64s; 6] = std::array::from_fn(|i| {
            F64s(std::array::from_fn(|l| {
                let tiny = (-30f64).exp2();
                if l < 4 {
                    [1e16 + l as f64, 1.0, 1.0, 1.0, 1.0, 1.0][i]
                } else {
                    let k = (l - 3) as f64;
                    [-1.0, 1.0, 1.0 + tiny, 1.0 + k * tiny, 0.0, 0.0][i]
                }
            }))
        });
        let expected = F64s(std::array::from_fn(|l| {
            fused_sum3_scalar([x[0][l], x[2][l], x[4][l]], [x[1][l], x[3][l], x[5][l]])
        }));
        let unfused = F64s(std::array::from_fn(|l| {
            x[4][l] * x[5][l] + (x[2][l] * x[3][l] + x[0][l] * x[1][l])
        }));
        let other_order = F64s(std::array::from_fn(|l| {
            x[0][l] * x[1][l] + (x[2][l] * x[3][l] + x[4][l] * x[5][l])
        }));
        assert_ne!(
            expected, unfused,
            "the values must tell the fused sum from the separate operations"
        );
        assert_ne!(
            expected, other_order,
            "the values must tell the orders apart"
        );
        struct Sum<'a>(&'a [F64s; 6]);
        impl LaneWork for Sum<'_> {
            type Output = F64s;
            #[inline(always)]
            fn run<S: Simd>(self, simd: S) -> F64s {
                let x = self.0;
                let mut out = F64s::ZERO;
                for p in 0..parts::<S>() {
                    let v = |i: usize| part::<S>(&x[i], p);
                    set_part::<S>(
                        &mut out,
                        p,
                        fused_sum3(simd, [v(0), v(2), v(4)], [v(1), v(3), v(5)]),
                    );
                }
                out
            }
        }
        assert_eq!(run_lane_work(Sum(&x)), expected);
        assert_eq!(Sum(&x).run(pulp::Scalar::new()), expected);
    }

    /// `Lane::mul_add` rounds once, lane by lane, for eight lanes and for one value, under
    /// the dispatched instruction set, the scalar path compiled for the CPU
    /// ([`run_scalar_work`]) and pulp's scalar fallback alike.
    #[test]
    fn lane_mul_add_is_one_rounding_on_every_path() {
        // (1 + 2⁻³⁰)(1 + k 2⁻³⁰) − 1 = (1 + k) 2⁻³⁰ + k 2⁻⁶⁰: the last term is lost when
        // the product is rounded first.
        let tiny = (-30f64).exp2();
        let a = F64s(std::array::from_fn(|_| 1.0 + tiny));
        let b = F64s(std::array::from_fn(|l| 1.0 + (l + 1) as f64 * tiny));
        let c = F64s::splat(-1.0);
        let expected = F64s(std::array::from_fn(|l| a[l].mul_add(b[l], c[l])));
        let unfused = F64s(std::array::from_fn(|l| a[l] * b[l] + c[l]));
        for l in 0..LANES {
            assert_ne!(
                expected[l], unfused[l],
                "lane {l} must tell fused from unfused"
            );
        }
        struct MulAdd(F64s, F64s, F64s);
        impl LaneWork for MulAdd {
            type Output = (F64s, [f64; LANES]);
            #[inline(always)]
            fn run<S: Simd>(self, simd: S) -> Self::Output {
                let one =
                    std::array::from_fn(|l| Lane::mul_add(self.0[l], simd, self.1[l], self.2[l]));
                (Lane::mul_add(self.0, simd, self.1, self.2), one)
            }
        }
        for (path, (lanes, one)) in [
            ("dispatched", run_lane_work(MulAdd(a, b, c))),
            ("scalar work", run_scalar_work(MulAdd(a, b, c))),
            ("scalar token", MulAdd(a, b, c).run(pulp::Scalar::new())),
        ] {
            assert_eq!(lanes, expected, "{path}: lanes");
            assert_eq!(one, expected.0, "{path}: one value at a time");
        }
    }
}
