//! Spectral (principal) decomposition of symmetric Voigt tensors: the values in closed
//! form, the vectors from them without iteration (stack only, no allocation).

use crate::element::lanes::{F64s, Lane, VoigtLanes, LANES};
use crate::material::Voigt;
use nalgebra::{Matrix3, Vector3};

/// Stress-like Voigt (tensor shear components) → symmetric 3×3.
#[inline]
fn to_matrix(s: &Voigt) -> Matrix3<f64> {
    Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2])
}

/// Principal values σ̂₁ ≥ σ̂₂ ≥ σ̂₃ of a stress-like Voigt vector, in closed form
/// (trigonometric solution of the characteristic cubic, Smith 1961, Commun. ACM 4(4) 168):
/// with q = tr/3, p = √(|A − qI|²/6), B = (A − qI)/p and φ = acos(det B/2)/3, the values are
/// q + 2p cos φ, q + 2p cos(φ + 2π/3) and the rest of the trace. The two cosines come from
/// a polynomial without libm calls ([`angle_cosines`]). About 10× faster than the iterative
/// solver; used where only the values are needed (yield check, weight r). Near a double
/// root the values lose digits (r = det B/2 is then rounded near ±1, where φ(r) has an
/// infinite slope): the error is then up to ~1e-11 of the largest component, far below
/// the 1e-10 f_c0 tolerance of the return mapping.
#[inline]
pub fn principal_values(s: &Voigt) -> [f64; 3] {
    let (q, p2, values) = closed_form(s);
    if p2 == 0.0 {
        [q; 3]
    } else {
        values
    }
}

/// [`principal_values`] of eight stress-like Voigt vectors, one per lane, bit for bit: the
/// same IEEE operations in the same order ([`closed_form`]), in lane arithmetic (no libm
/// call, so every lane is evaluated: a lane that needs no values costs a few vector
/// operations).
#[inline(always)]
pub fn principal_values_lanes(s: &VoigtLanes) -> [F64s; 3] {
    let (q, p2, values) = closed_form(s);
    let isotropic: [bool; LANES] = std::array::from_fn(|l| p2[l] == 0.0);
    values.map(|v| F64s::select(&isotropic, q, v))
}

/// Coefficients a₀ … a₁₉ of P(s) = 2 cos(⅔ acos s) on s ∈ [0, 1] in powers of u = 2s − 1:
/// the degree-19 Chebyshev interpolant of P at 20 Chebyshev points, formed in 40-digit
/// arithmetic (mpmath 1.4) and rounded to f64. P is analytic on [0, 1] (its nearest
/// singularity is s = −1), so its Chebyshev coefficients fall by ≈ 6× per degree and the
/// truncation error is ≈ 4e-17; evaluated by [`two_cos_third`] in f64 the error is at most
/// 4.7 half-ulps of P (20,001 points of [0, 1] against the 40-digit P).
const TWO_COS_THIRD: [f64; 20] = [
    1.532088886237956,
    0.4948181326457061,
    -0.031018376872972823,
    0.00493270563017358,
    -0.0010082493822507533,
    0.00023285090588889628,
    -5.783987287367384e-05,
    1.5082157125947237e-05,
    -4.071737975570475e-06,
    1.1283026026324727e-06,
    -3.190906481892157e-07,
    9.171913393720147e-08,
    -2.6690561548999752e-08,
    7.861582684791152e-09,
    -2.3758598700102196e-09,
    7.125864137824722e-10,
    -1.8265569427152695e-10,
    5.529152712005641e-11,
    -3.2157946341090994e-11,
    9.908277512981742e-12,
];

/// P(s) = 2 cos(⅔ acos s) for s ∈ [0, 1] from [`TWO_COS_THIRD`], by Estrin's scheme (the
/// pairs, then powers u², u⁴, u⁸, u¹⁶: a dependency chain of 6 multiply-adds instead of
/// Horner's 19).
#[inline(always)]
fn two_cos_third<T: Lane>(s: T) -> T {
    let a = |k: usize| T::splat(TWO_COS_THIRD[k]);
    let u = T::splat(2.0) * s - T::splat(1.0);
    let u2 = u * u;
    let u4 = u2 * u2;
    let u8 = u4 * u4;
    let pairs: [T; 10] = std::array::from_fn(|i| a(2 * i) + a(2 * i + 1) * u);
    let quads: [T; 5] = std::array::from_fn(|i| pairs[2 * i] + pairs[2 * i + 1] * u2);
    let low = quads[0] + quads[1] * u4;
    let high = quads[2] + quads[3] * u4;
    (low + high * u8) + quads[4] * (u8 * u8)
}

/// 2 cos φ and 2 cos(φ + 2π/3) for φ = acos(r)/3, r clamped to [−1, 1] (a NaN r, where p³
/// underflows, is taken as −1), without trigonometry: with 1 + r = 2 cos²(3φ/2), 2 cos φ =
/// P(√((1 + r)/2)), and since φ(−r) = π/3 − φ(r), 2 cos(φ + 2π/3) = −2 cos(π/3 − φ) =
/// −P(√((1 − r)/2)) ([`two_cos_third`]). The square roots take the infinite slope of φ(r)
/// at r = ±1 (the double roots), where a polynomial in r could not follow it.
#[inline(always)]
fn angle_cosines<T: Lane>(ratio: T) -> (T, T) {
    let r = ratio.max(T::splat(-1.0)).min(T::splat(1.0));
    let half = T::splat(0.5);
    let s_first = (half + half * r).sqrt();
    let s_third = (half - half * r).sqrt();
    (two_cos_third(s_first), -two_cos_third(s_third))
}

/// The closed form's arithmetic for one tensor or one per lane: q = tr/3, p² and the sorted
/// values q + p·2cos φ, q + p·2cos(φ + 2π/3) and the rest of the trace, the cosines from
/// r = det(A − qI)/(2p³) ([`angle_cosines`]; the values are meaningless where p² = 0: the
/// tensor is then qI).
#[inline(always)]
fn closed_form<T: Lane>(s: &[T; 6]) -> (T, T, [T; 3]) {
    let (d, e, f) = (s[3], s[4], s[5]);
    let q = (s[0] + s[1] + s[2]) / T::splat(3.0);
    let (a0, b0, c0) = (s[0] - q, s[1] - q, s[2] - q);
    let p2 = a0 * a0 + b0 * b0 + c0 * c0 + T::splat(2.0) * (d * d + e * e + f * f);
    let p = (p2 / T::splat(6.0)).sqrt();
    let det = a0 * (b0 * c0 - e * e) - d * (d * c0 - e * f) + f * (d * e - b0 * f);
    let two_p = T::splat(2.0) * p;
    let (two_cos1, two_cos3) = angle_cosines(det / (two_p * p * p));
    let l1 = q + p * two_cos1;
    let l3 = q + p * two_cos3;
    let three_q = T::splat(3.0) * q;
    let l2 = three_q - l1 - l3;
    // Guard the order against rounding.
    let hi = l1.max(l2).max(l3);
    let lo = l1.min(l2).min(l3);
    (q, p2, [hi, three_q - hi - lo, lo])
}

/// Signs of the principal values, known without computing them ([`definiteness`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Definiteness {
    /// Every principal value ≥ 0.
    NonNegative,
    /// Every principal value ≤ 0.
    NonPositive,
    /// Some of each sign (or too close to zero to tell from the invariants).
    Indefinite,
}

/// Signs of the principal values of a stress-like Voigt vector from its invariants
/// I₁ = tr A, I₂ = ½[(tr A)² − tr A²], I₃ = det A. The characteristic polynomial
/// λ³ − I₁λ² + I₂λ − I₃ of a symmetric matrix has only real roots, so by Descartes' rule of
/// signs they are all ≤ 0 exactly when I₁ ≤ 0, I₂ ≥ 0 and I₃ ≤ 0, and all ≥ 0 exactly
/// when I₁, I₂, I₃ ≥ 0. No square root, no trigonometry. Rounding can only misclassify a
/// tensor whose I₂ or I₃ is within rounding of zero, i.e. one whose values of the other
/// sign are themselves within rounding of zero.
#[inline]
pub fn definiteness(s: &Voigt) -> Definiteness {
    let (d, e, f) = (s[3], s[4], s[5]);
    let i1 = s[0] + s[1] + s[2];
    let i2 = s[0] * s[1] + s[1] * s[2] + s[2] * s[0] - d * d - e * e - f * f;
    if i2 < 0.0 {
        return Definiteness::Indefinite;
    }
    let i3 = s[0] * (s[1] * s[2] - e * e) - d * (d * s[2] - e * f) + f * (d * e - s[1] * f);
    if i1 <= 0.0 && i3 <= 0.0 {
        Definiteness::NonPositive
    } else if i1 >= 0.0 && i3 >= 0.0 {
        Definiteness::NonNegative
    } else {
        Definiteness::Indefinite
    }
}

/// Principal values (descending) and the matching unit eigenvectors (columns).
#[derive(Clone, Copy, Debug)]
pub struct Spectral {
    /// σ̂₁ ≥ σ̂₂ ≥ σ̂₃.
    pub values: [f64; 3],
    /// Eigenvector of each value.
    pub vectors: [Vector3<f64>; 3],
}

impl Spectral {
    /// Decompose a stress-like Voigt vector A. The values λ₁ ≥ λ₂ ≥ λ₃ from
    /// [`principal_values`]; then the vector of the value farther from the middle one
    /// (λ₁ when λ₁ − λ₂ ≥ λ₂ − λ₃, else λ₃) as the largest cross product of two rows of
    /// A − λI (the rows of a rank-2 matrix span the plane normal to its null vector), and
    /// the other two by rotating A restricted to the plane normal to it to its principal
    /// axes ([`plane_vectors`]). The vectors are orthonormal to rounding whatever the
    /// multiplicities (a double root leaves its plane's basis arbitrary, as with any
    /// solver); the values returned are the Rayleigh quotients nᵢ·A nᵢ, as accurate as an
    /// iterative solver's (the closed form alone loses digits near a double root, see
    /// [`principal_values`]). Non-iterative and several times faster than nalgebra's
    /// `SymmetricEigen`, which the tests compare it with.
    #[cfg(test)]
    pub fn of(s: &Voigt) -> Self {
        Self::with_values(s, principal_values(s))
    }

    /// [`Self::of`] for a caller that already has `values` = [`principal_values`]`(s)`.
    #[inline]
    pub fn with_values(s: &Voigt, values: [f64; 3]) -> Self {
        let a = to_matrix(s);
        let [l1, l2, l3] = values;
        let (first, second, third) = if l1 - l2 >= l2 - l3 {
            let n1 = isolated_vector(&a, l1);
            let (n2, n3) = plane_vectors(&a, &n1);
            (n1, n2, n3)
        } else {
            let n3 = isolated_vector(&a, l3);
            let (n1, n2) = plane_vectors(&a, &n3);
            (n1, n2, n3)
        };
        let mut values = [
            first.dot(&(a * first)),
            second.dot(&(a * second)),
            third.dot(&(a * third)),
        ];
        let mut vectors = [first, second, third];
        // Keep the order descending against rounding of the quotients.
        for i in [0, 1, 0] {
            if values[i] < values[i + 1] {
                values.swap(i, i + 1);
                vectors.swap(i, i + 1);
            }
        }
        Self { values, vectors }
    }

    /// Σ cᵢ nᵢ⊗nᵢ as a strain-like Voigt vector (engineering shear = 2 × tensor shear).
    #[inline]
    pub fn strain_voigt(&self, c: &[f64; 3]) -> Voigt {
        let mut t = [0.0; 6];
        for (n, &ck) in self.vectors.iter().zip(c.iter()) {
            t[0] += ck * n[0] * n[0];
            t[1] += ck * n[1] * n[1];
            t[2] += ck * n[2] * n[2];
            t[3] += 2.0 * ck * n[0] * n[1];
            t[4] += 2.0 * ck * n[1] * n[2];
            t[5] += 2.0 * ck * n[2] * n[0];
        }
        t
    }

    /// Σ cᵢ nᵢ⊗nᵢ as a stress-like Voigt vector (tensor shear).
    #[inline]
    pub fn stress_voigt(&self, c: &[f64; 3]) -> Voigt {
        let mut t = self.strain_voigt(c);
        for v in t[3..].iter_mut() {
            *v *= 0.5;
        }
        t
    }
}

/// The projector n⊗n (stress-like Voigt, tensor shear) onto the unit eigenvector n of `s`
/// for its principal value `l`, `l` a simple root at least as far from the others as they
/// are from each other ([`isolated_vector`]).
#[inline]
pub fn eigenprojector(s: &Voigt, l: f64) -> Voigt {
    let n = isolated_vector(&to_matrix(s), l);
    [
        n[0] * n[0],
        n[1] * n[1],
        n[2] * n[2],
        n[0] * n[1],
        n[1] * n[2],
        n[2] * n[0],
    ]
}

/// Unit eigenvector of the symmetric `a` for its value `l`, `l` a simple root at least as
/// far from the others as they are from each other: the largest of the cross products of
/// the rows of a − lI (its rank is 2, its rows span the plane normal to the vector). For
/// a = lI (no such plane) any unit vector is one: e_x.
#[inline]
fn isolated_vector(a: &Matrix3<f64>, l: f64) -> Vector3<f64> {
    let r0 = Vector3::new(a[(0, 0)] - l, a[(0, 1)], a[(0, 2)]);
    let r1 = Vector3::new(a[(1, 0)], a[(1, 1)] - l, a[(1, 2)]);
    let r2 = Vector3::new(a[(2, 0)], a[(2, 1)], a[(2, 2)] - l);
    let candidates = [r0.cross(&r1), r0.cross(&r2), r1.cross(&r2)];
    let mut best = candidates[0];
    let mut best_norm = best.norm_squared();
    for c in &candidates[1..] {
        let n = c.norm_squared();
        if n > best_norm {
            best = *c;
            best_norm = n;
        }
    }
    if best_norm > 0.0 {
        best / best_norm.sqrt()
    } else {
        Vector3::x()
    }
}

/// The two unit eigenvectors of the symmetric `a` normal to its unit eigenvector `n`, the
/// larger value's first: with an orthonormal basis (u, w) of the plane normal to `n`, the
/// 2×2 [u·a u, u·a w; u·a w, w·a w] is rotated to its principal axes by
/// θ = ½ atan2(2 u·a w, u·a u − w·a w) (accurate however close its two values are; a
/// double root gives θ = 0, any basis of the plane being one).
#[inline]
fn plane_vectors(a: &Matrix3<f64>, n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    // u: the unit vector normal to n built from n's two largest components.
    let u = if n[0].abs() > n[1].abs() {
        Vector3::new(-n[2], 0.0, n[0]) / (n[0] * n[0] + n[2] * n[2]).sqrt()
    } else {
        Vector3::new(0.0, n[2], -n[1]) / (n[1] * n[1] + n[2] * n[2]).sqrt()
    };
    let w = n.cross(&u);
    let au = a * u;
    let aw = a * w;
    let (p, q, r) = (u.dot(&au), u.dot(&aw), w.dot(&aw));
    let theta = 0.5 * (2.0 * q).atan2(p - r);
    let (sin, cos) = theta.sin_cos();
    (u * cos + w * sin, w * cos - u * sin)
}

/// R diag(values) Rᵀ as a stress-like Voigt vector (tests: a tensor with known principal
/// values and axes).
#[cfg(test)]
pub fn rotated_voigt(r: &Matrix3<f64>, values: [f64; 3]) -> Voigt {
    let m = r * Matrix3::from_diagonal(&Vector3::from(values)) * r.transpose();
    [
        m[(0, 0)],
        m[(1, 1)],
        m[(2, 2)],
        m[(0, 1)],
        m[(1, 2)],
        m[(0, 2)],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Indices of three values in descending order.
    #[inline]
    fn descending(v: &Vector3<f64>) -> [usize; 3] {
        let mut idx = [0usize, 1, 2];
        if v[idx[0]] < v[idx[1]] {
            idx.swap(0, 1);
        }
        if v[idx[1]] < v[idx[2]] {
            idx.swap(1, 2);
        }
        if v[idx[0]] < v[idx[1]] {
            idx.swap(0, 1);
        }
        idx
    }

    /// nalgebra's iterative solution: values descending and their vectors.
    fn iterative(s: &Voigt) -> ([f64; 3], [Vector3<f64>; 3]) {
        let e = to_matrix(s).symmetric_eigen();
        let i = descending(&e.eigenvalues);
        (
            [
                e.eigenvalues[i[0]],
                e.eigenvalues[i[1]],
                e.eigenvalues[i[2]],
            ],
            [
                e.eigenvectors.column(i[0]).into_owned(),
                e.eigenvectors.column(i[1]).into_owned(),
                e.eigenvectors.column(i[2]).into_owned(),
            ],
        )
    }

    /// Random tensors, and tensors with double, triple and nearly double roots, rotated:
    /// the vectors are orthonormal, they and the values are eigenpairs and reconstruct the
    /// tensor, and the values are the iterative solver's, all to 1e-12 of the largest
    /// component.
    #[test]
    fn decomposition_matches_the_iterative_solver() {
        let mut lcg = crate::test_random::Lcg(0x5eed_1234_abcd_0001);
        let mut rand = move || lcg.next() - 0.5;
        let mut cases: Vec<Voigt> = Vec::new();
        for k in 0..2000 {
            // A rotation R from a random unit quaternion, and values with multiplicities.
            let q = [rand(), rand(), rand(), rand()];
            let qn = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            let [w, x, y, z] = q.map(|c| c / qn);
            let r = Matrix3::new(
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - z * w),
                2.0 * (x * z + y * w),
                2.0 * (x * y + z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - x * w),
                2.0 * (x * z - y * w),
                2.0 * (y * z + x * w),
                1.0 - 2.0 * (x * x + y * y),
            );
            let scale = 10f64.powi(k % 13 - 3) * 1e3;
            let a = scale * rand();
            let b = scale * rand();
            let values = match k % 5 {
                0 => [a, b, scale * rand()],
                1 => [a, a, b],
                2 => [a, b, b],
                3 => [a, a, a],
                _ => [a, a * (1.0 + 1e-9 * rand()), b],
            };
            cases.push(rotated_voigt(&r, values));
        }
        cases.push([0.0; 6]);
        cases.push([2.9e6, 0.0, 0.0, 0.0, 0.0, 0.0]);
        cases.push([0.0, 0.0, 0.0, 7e6, 0.0, 0.0]);
        for s in cases {
            let sp = Spectral::of(&s);
            let (values, _) = iterative(&s);
            let scale = s.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
            assert!(
                sp.values[0] >= sp.values[1] && sp.values[1] >= sp.values[2],
                "{s:?}"
            );
            for i in 0..3 {
                assert!(
                    (sp.values[i] - values[i]).abs() <= 1e-12 * scale,
                    "{s:?}: {:?} vs {values:?}",
                    sp.values
                );
                for j in 0..3 {
                    let d = sp.vectors[i].dot(&sp.vectors[j]);
                    let expect = if i == j { 1.0 } else { 0.0 };
                    assert!((d - expect).abs() < 1e-12, "{s:?}: n{i}·n{j} = {d}");
                }
            }
            let back = sp.stress_voigt(&sp.values);
            for k in 0..6 {
                assert!(
                    (back[k] - s[k]).abs() <= 1e-12 * scale,
                    "{s:?}: reconstructed {back:?}"
                );
            }
            // Each pair is an eigenpair: |A nᵢ − λᵢ nᵢ| ≤ 1e-12 of the largest component.
            // (Not compared with nalgebra's vectors: for one tensor here with a double root,
            // [2.47e8, −3.72e9, −2.01e10, −9.11e8, −9.25e9, −2.02e9], its simple root's
            // vector is 0.021 rad off, a residual ≈ 5e8 where this one's is ≤ 2e-2.)
            let a = to_matrix(&s);
            for i in 0..3 {
                let res = (a * sp.vectors[i] - sp.vectors[i] * sp.values[i]).norm();
                assert!(res <= 1e-12 * scale, "{s:?}: residual of pair {i}: {res:e}");
            }
        }
    }

    /// The lane form of the closed-form values is the scalar one bit for bit in every
    /// lane: random tensors, isotropic ones (p² = 0), double roots and zeros.
    #[test]
    fn principal_values_in_lanes_are_the_scalar_values_bit_for_bit() {
        let mut rng = crate::test_random::Lcg(0x9a1e_5c0d_0002);
        for draw in 0..2000 {
            let mag = 10f64.powf(-3.0 + 9.0 * rng.next());
            let s: VoigtLanes = std::array::from_fn(|i| {
                F64s(std::array::from_fn(|l| match ((draw + l) % 5, i) {
                    (0, 0..=2) => -mag,
                    (1, 0..=1) => mag,
                    (0..=2, _) => 0.0,
                    _ => mag * rng.sym(),
                }))
            });
            let got = principal_values_lanes(&s);
            for l in 0..LANES {
                let want = principal_values(&std::array::from_fn(|i| s[i][l]));
                let got_l = [got[0][l], got[1][l], got[2][l]];
                assert_eq!(
                    got_l.map(f64::to_bits),
                    want.map(f64::to_bits),
                    "draw {draw}, lane {l}"
                );
            }
        }
    }

    /// The polynomial of the cosines against libm's 2 cos(⅔ acos s) (each call within an ulp
    /// or so, so the two agree to a few ulps where the polynomial is right), on a fine grid
    /// of [0, 1] with its ends, and the closed form's cosines at r = −1, 0, 1 (φ = π/3, π/6,
    /// 0) against their exact values.
    #[test]
    fn the_cosine_polynomial_is_libm_to_a_few_ulps() {
        for i in 0..=100_000 {
            let s = f64::from(i) / 100_000.0;
            let want = 2.0 * ((2.0 / 3.0) * s.acos()).cos();
            let got = two_cos_third(s);
            assert!(
                (got - want).abs() <= 2e-15 * want,
                "s = {s}: {got} against libm {want}"
            );
        }
        let sqrt3 = 3f64.sqrt();
        for (r, first, third) in [(-1.0, 1.0, -2.0), (0.0, sqrt3, -sqrt3), (1.0, 2.0, -1.0)] {
            let (c1, c3) = angle_cosines(r);
            assert!((c1 - first).abs() <= 4e-16 * first, "r = {r}: {c1}");
            assert!((c3 - third).abs() <= 4e-16 * third.abs(), "r = {r}: {c3}");
        }
        // Out of range and NaN ratios (rounding; p³ underflowing) stay finite.
        for r in [-1.5, 1.5, f64::NAN] {
            let (c1, c3) = angle_cosines(r);
            assert!(c1.is_finite() && c3.is_finite(), "r = {r}");
        }
    }

    #[test]
    fn definiteness_matches_the_signs_of_the_principal_values() {
        use nalgebra::{Rotation3, Unit, Vector3};
        // Every sign pattern, with zero and repeated values, in rotated frames.
        let sets: [[f64; 3]; 10] = [
            [-1.0, -2.0, -3.0],
            [0.0, -2.0, -2.0],
            [0.0, 0.0, -5.0],
            [1.0, 2.0, 3.0],
            [4.0, 0.0, 0.0],
            [1.0, -1.0, 0.0],
            [3.0, -0.2, -4.0],
            [0.3, 2.0, -1e-3],
            [-0.3, -2.0, 1e-3],
            [2.0, 2.0, -2.0],
        ];
        let axes = [
            Vector3::x_axis(),
            Unit::new_normalize(Vector3::new(1.0, 2.0, -0.5)),
            Unit::new_normalize(Vector3::new(-0.3, 0.1, 0.9)),
        ];
        for (n, v) in sets.iter().enumerate() {
            let want = if v.iter().all(|&x| x <= 0.0) {
                Definiteness::NonPositive
            } else if v.iter().all(|&x| x >= 0.0) {
                Definiteness::NonNegative
            } else {
                Definiteness::Indefinite
            };
            for (k, axis) in axes.iter().enumerate() {
                let scale = 1e7;
                let r = Rotation3::from_axis_angle(axis, 0.37 * (k as f64 + 1.0));
                let s = rotated_voigt(r.matrix(), [v[0] * scale, v[1] * scale, v[2] * scale]);
                let got = definiteness(&s);
                // Rotation rounds exact zeros to rounding noise: a zero value then counts
                // as either sign, nothing else may differ.
                if v.contains(&0.0) {
                    assert!(
                        got == want || got == Definiteness::Indefinite,
                        "set {n}, axis {k}: {got:?}, want {want:?}"
                    );
                } else {
                    assert_eq!(got, want, "set {n}, axis {k}");
                }
            }
        }
        // The unrotated uniaxial and zero states are exact.
        assert_eq!(
            definiteness(&[-3e7, 0.0, 0.0, 0.0, 0.0, 0.0]),
            Definiteness::NonPositive
        );
        assert_eq!(
            definiteness(&[3e6, 0.0, 0.0, 0.0, 0.0, 0.0]),
            Definiteness::NonNegative
        );
        assert_eq!(definiteness(&[0.0; 6]), Definiteness::NonPositive);
        // Pure shear is indefinite.
        assert_eq!(
            definiteness(&[0.0, 0.0, 0.0, 1e6, 0.0, 0.0]),
            Definiteness::Indefinite
        );
    }

    #[test]
    fn reconstructs_the_tensor() {
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 1.1];
        let sp = Spectral::of(&s);
        assert!(sp.values[0] >= sp.values[1] && sp.values[1] >= sp.values[2]);
        let back = sp.strain_voigt(&sp.values);
        let expect = [3.0, -1.0, 2.0, 1.0, -1.4, 2.2];
        for i in 0..6 {
            assert!((back[i] - expect[i]).abs() < 1e-12, "{i}");
        }
        let v = principal_values(&s);
        for (a, b) in v.iter().zip(sp.values.iter()) {
            assert!((a - b).abs() < 1e-12);
        }
    }

    #[test]
    fn closed_form_values_match_the_iterative_solver() {
        let cases: [Voigt; 7] = [
            [3.0e7, -1.0e7, 2.0e7, 0.5e7, -0.7e7, 1.1e7],
            [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
            [5e6, 5e6, 5e6, 1e-3, 0.0, 0.0],
            [2e6, 2e6 + 1e-4, -4e6, 0.0, 1e-5, 0.0],
            [0.0, 0.0, 0.0, 7e6, 0.0, 0.0],
            [-1e8, -1e8, -1e8 + 1.0, 0.1, 0.2, 0.3],
            [1e-30, 0.0, 0.0, 0.0, 0.0, 0.0],
        ];
        for s in cases {
            let v = principal_values(&s);
            let it = iterative(&s).0;
            let scale = s.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for i in 0..3 {
                assert!(
                    (v[i] - it[i]).abs() <= 1e-10 * scale,
                    "{s:?}: {v:?} vs {it:?}"
                );
            }
            assert!(v[0] >= v[1] && v[1] >= v[2]);
        }
    }
}
