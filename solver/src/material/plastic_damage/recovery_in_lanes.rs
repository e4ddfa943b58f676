//! The stiffness recovery of eight effective stresses at once, one per lane (issue 11),
//! under both rules of `recovery.rs`:
//!
//! * the consistent rule ([`recovery::consistent_stress_of`], the module doc of
//!   `recovery.rs`): the isotropic and pure-compression cases, the principal values, the
//!   choice of the tension set P and the linear map g_k(σ̄) as lane arithmetic; the one
//!   eigenprojector of a lone direction and the rare split of a close pair (every
//!   eigenvector) lane by lane with the scalar functions;
//! * the Lee–Fenves rule of eq. (24) ([`recovery::lee_fenves_damage`]): the weight r(σ̄) from
//!   the signs where they settle it, from the principal values in lanes for a mixed state,
//!   and σ = (1 − D) σ̄ as lane arithmetic.
//!
//! Each lane performs the scalar rule's IEEE operations in the same order, so the stresses
//! are those of the scalar rules bit for bit (tested below and through the element kernels).

use super::principal::principal_values_lanes;
use super::recovery::{
    self, cracked_damage, linear_map, lone_correction, map_coefficients, recovery_factors, set_map,
    weight_by_signs, SetMap, SetTerms,
};
use super::yield_surface::{invariants, largest_value_bound, tension_weight};
use crate::element::lanes::{F64s, VoigtLanes, LANES};
use crate::material::Voigt;

/// Nominal stresses of the consistent rule for the effective stresses `eff` (lane l: point
/// l), tensile and compressive damage `d_t`, `d_c` (D_t, D_c of eq. 24 per lane), recovery
/// floor `s0` and Poisson's ratio `nu`: lane l is
/// `consistent_stress_of(Classified::new(eff_l), d_t[l], d_c[l], s0, nu)` bit for bit for
/// every lane in `wanted` (the others are unspecified, and skip the spectral branch's
/// lane-by-lane work).
#[inline(always)]
pub fn consistent_stress_lanes(
    eff: &VoigtLanes,
    d_t: F64s,
    d_c: F64s,
    (s0, nu): (f64, f64),
    wanted: &[bool; LANES],
) -> VoigtLanes {
    let (a, phi) = recovery_factors(d_t, s0);
    let one_minus_dc = F64s::splat(1.0) - d_c;
    // σ = (1 − D_c)(1 − s₀D_t) σ̄ where φ is NaN or ≤ 0 (D_t = 0 or s₀ = 1) and in pure
    // compression by the invariant bound of `Classified::surely_compressed`.
    let mut iso_stress = [F64s::ZERO; 6];
    for i in 0..6 {
        iso_stress[i] = eff[i] * one_minus_dc / a;
    }
    let (i1, q) = invariants(eff);
    let bound = largest_value_bound(i1, q);
    let mut spectral = [false; LANES];
    let mut any = false;
    for l in 0..LANES {
        // (A NaN bound is not `compressed`: the spectral branch, as in the scalar rule.)
        let isotropic = phi[l].is_nan() || phi[l] <= 0.0;
        let compressed = bound[l] <= 0.0;
        spectral[l] = wanted[l] && !isotropic && !compressed;
        any |= spectral[l];
    }
    if !any {
        return iso_stress;
    }
    let p = principal_values_lanes(eff);
    let (m_set, sig) = select_lanes(&p, d_c, a, phi, nu);
    let (a1, offset, k0) = map_coefficients(&p, &sig, d_c, a, nu);
    let k_tension = k0 + phi;
    // Per lane: k of its map g_k, its lone direction, or the split pair.
    let mut k = k0;
    let mut lone = [None; LANES];
    let mut split = [false; LANES];
    for l in (0..LANES).filter(|&l| spectral[l]) {
        match set_map(m_set[l], &[p[0][l], p[1][l], p[2][l]]) {
            SetMap::Linear { tension, lone: i } => {
                if tension {
                    k[l] = k_tension[l];
                }
                lone[l] = i;
            }
            SetMap::Split => split[l] = true,
        }
    }
    let mut out = linear_map(eff, a1 / k, offset / k);
    for l in 0..LANES {
        let replace = if !spectral[l] {
            Some(lane_of(&iso_stress, l))
        } else if split[l] {
            // The scalar rule (every eigenvector), from the same principal values.
            let eff_l = lane_of(eff, l);
            let pl = [p[0][l], p[1][l], p[2][l]];
            let mut classified = recovery::Classified::new(&eff_l).with_values(pl);
            Some(recovery::consistent_stress_of(
                &mut classified,
                d_t[l],
                d_c[l],
                s0,
                nu,
            ))
        } else {
            None
        };
        if let Some(v) = replace {
            for (o, v) in out.iter_mut().zip(v) {
                o[l] = v;
            }
        } else if let Some(i) = lone[l] {
            let pl = [p[0][l], p[1][l], p[2][l]];
            let map = (a1[l], offset[l], k[l]);
            let correction = lone_correction(&lane_of(eff, l), &pl, i, sig[i][l], map);
            for (o, v) in out.iter_mut().zip(correction) {
                o[l] += v;
            }
        }
    }
    out
}

/// Nominal stresses σ = (1 − D) σ̄ (eq. 23) and D of eq. (24), D = 1 − (1 − D_c)(1 − s D_t)
/// with s = s₀ + (1 − s₀) r(σ̄), for the effective stresses `eff` (lane l: point l) and
/// the damage `d_t`, `d_c` per lane: lane l is
/// `lee_fenves_damage(Classified::new(eff_l), d_t[l], d_c[l], s0)` and σ̄ scaled by 1 − D,
/// bit for bit, for every lane in `wanted` (the others are unspecified, and skip the
/// lane-by-lane weight). r(σ̄) only where D_t ≠ 0, from the principal values only for a
/// mixed state.
#[inline(always)]
pub fn lee_fenves_stress_lanes(
    eff: &VoigtLanes,
    d_t: F64s,
    d_c: F64s,
    s0: f64,
    wanted: &[bool; LANES],
) -> (VoigtLanes, F64s) {
    let (i1, q) = invariants(eff);
    let mut weight = F64s::ZERO;
    let mut mixed = [false; LANES];
    let mut any_mixed = false;
    for l in 0..LANES {
        if !wanted[l] || d_t[l] == 0.0 {
            continue;
        }
        match weight_by_signs(i1[l], q[l], &lane_of(eff, l)) {
            Some(r) => weight[l] = r,
            None => {
                mixed[l] = true;
                any_mixed = true;
            }
        }
    }
    if any_mixed {
        let p = principal_values_lanes(eff);
        for l in (0..LANES).filter(|&l| mixed[l]) {
            weight[l] = tension_weight(&[p[0][l], p[1][l], p[2][l]]);
        }
    }
    let uncracked: [bool; LANES] = std::array::from_fn(|l| d_t[l] == 0.0);
    let d = F64s::select(&uncracked, d_c, cracked_damage(weight, d_t, d_c, s0));
    let keep = F64s::splat(1.0) - d;
    (std::array::from_fn(|i| keep * eff[i]), d)
}

/// [`recovery`]'s `select` lane-wise: the tension set P (its size m per lane) and the
/// principal stresses of each lane, the first set whose stresses have the signs it assumes
/// or, when rounding leaves none, the least violating one (the first of equals). The four
/// candidate sets ([`SetTerms`]) are formed in lanes for every lane.
#[inline(always)]
fn select_lanes(
    p: &[F64s; 3],
    dc: F64s,
    a: F64s,
    phi: F64s,
    nu: f64,
) -> ([usize; LANES], [F64s; 3]) {
    let terms = SetTerms::new(p, dc, a, phi, nu);
    let mut chosen = [usize::MAX; LANES];
    // (m, violation) of the least violating set so far; none while every violation is
    // NaN, where the scalar function returns m = 0 with zero stresses.
    let mut best: [Option<(usize, f64)>; LANES] = [None; LANES];
    let mut stresses = [[F64s::ZERO; 3]; 4];
    for m in 0..=3 {
        let (s, violation) = terms.candidate(m);
        for l in 0..LANES {
            if chosen[l] != usize::MAX {
                continue;
            }
            if violation[l] == 0.0 {
                chosen[l] = m;
            } else if violation[l] < best[l].map_or(f64::INFINITY, |b| b.1) {
                best[l] = Some((m, violation[l]));
            }
        }
        stresses[m] = s;
    }
    let mut m_set = [0usize; LANES];
    let mut sig = [F64s::ZERO; 3];
    for l in 0..LANES {
        m_set[l] = match (chosen[l], best[l]) {
            (usize::MAX, Some((m, _))) => m,
            (usize::MAX, None) => continue,
            (m, _) => m,
        };
        for i in 0..3 {
            sig[i][l] = stresses[m_set[l]][i][l];
        }
    }
    (m_set, sig)
}

/// The Voigt vector of lane `l`.
#[inline(always)]
fn lane_of(v: &VoigtLanes, l: usize) -> Voigt {
    [v[0][l], v[1][l], v[2][l], v[3][l], v[4][l], v[5][l]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_random::Lcg;

    /// Effective stresses of every sign pattern, one per lane (isotropic compression, pure
    /// compression, a double root, pure tension, a zero stress, general states), of
    /// magnitude 10² to 10⁷, with s₀ from 0 to 1, D_t from none to full and D_c to 0.9.
    fn random_lanes(rng: &mut Lcg, draw: usize) -> (VoigtLanes, f64, F64s, F64s) {
        let mag = 10f64.powf(2.0 + 5.0 * rng.next());
        let eff: VoigtLanes = std::array::from_fn(|i| {
            F64s(std::array::from_fn(|l| match (draw + l) % 7 {
                0 if i < 3 => -mag,
                0 => 0.0,
                1 if i < 3 => -mag * (1.0 + rng.next()),
                1 => 0.1 * mag * rng.sym(),
                2 if i < 2 => mag,
                2 => 0.0,
                3 if i < 3 => mag * (1.0 + rng.next()),
                3 => 0.1 * mag * rng.sym(),
                4 => 0.0,
                _ => mag * rng.sym(),
            }))
        });
        let s0 = [0.0, 0.2, 1.0, 0.7][draw % 4];
        let d_t = F64s(std::array::from_fn(|l| {
            [rng.next(), 0.0, 1.0, 1.0 - 1e-13][(draw + l) % 4]
        }));
        let d_c = F64s(std::array::from_fn(|_| 0.9 * rng.next()));
        (eff, s0, d_t, d_c)
    }

    /// Lane `l` of `got` is `want` bit for bit.
    fn assert_lane_is(got: &VoigtLanes, l: usize, want: &Voigt, what: &str) {
        let got_l: Voigt = std::array::from_fn(|i| got[i][l]);
        assert_eq!(got_l.map(f64::to_bits), want.map(f64::to_bits), "{what}");
    }

    /// The consistent rule in lanes against the scalar rule for [`random_lanes`]: each lane
    /// bit for bit, and every branch of the lane function taken.
    #[test]
    fn lanes_are_the_scalar_consistent_stress_bit_for_bit() {
        let mut rng = Lcg(0x1a4e_5c0d_0001);
        let mut lone_or_split = 0;
        for draw in 0..4000 {
            let (eff, s0, d_t, d_c) = random_lanes(&mut rng, draw);
            let nu = 0.1 + 0.3 * rng.next();
            let wanted = std::array::from_fn(|l| (draw + l) % 9 != 0);
            let got = consistent_stress_lanes(&eff, d_t, d_c, (s0, nu), &wanted);
            for l in 0..LANES {
                if !wanted[l] {
                    continue;
                }
                let eff_l: Voigt = std::array::from_fn(|i| eff[i][l]);
                let want = recovery::consistent_stress_of(
                    &mut recovery::Classified::new(&eff_l),
                    d_t[l],
                    d_c[l],
                    s0,
                    nu,
                );
                let what = format!(
                    "draw {draw}, lane {l}: {eff_l:?} d_t {} d_c {} s0 {s0}",
                    d_t[l], d_c[l]
                );
                assert_lane_is(&got, l, &want, &what);
                let mixed = eff_l[..3].iter().any(|&v| v > 0.0) && d_t[l] > 0.0 && s0 < 1.0;
                lone_or_split += usize::from(mixed);
            }
        }
        assert!(lone_or_split > 1000, "{lone_or_split} mixed lanes");
    }

    /// The Lee–Fenves rule in lanes against the scalar D of eq. (24) and σ = (1 − D) σ̄ for
    /// [`random_lanes`]: bit for bit, with the mixed states (principal values), the states
    /// the signs settle and the uncracked lanes (D = D_c) all taken many times.
    #[test]
    fn lanes_are_the_scalar_lee_fenves_stress_bit_for_bit() {
        let mut rng = Lcg(0x1ee_fe5e_0002);
        let mut taken = [0usize; 3];
        for draw in 0..4000 {
            let (eff, s0, d_t, d_c) = random_lanes(&mut rng, draw);
            let wanted = std::array::from_fn(|l| (draw + l) % 9 != 0);
            let (got, got_d) = lee_fenves_stress_lanes(&eff, d_t, d_c, s0, &wanted);
            for l in 0..LANES {
                if !wanted[l] {
                    continue;
                }
                let eff_l: Voigt = std::array::from_fn(|i| eff[i][l]);
                let mut classified = recovery::Classified::new(&eff_l);
                let d = recovery::lee_fenves_damage(&mut classified, d_t[l], d_c[l], s0);
                let want = eff_l.map(|v| (1.0 - d) * v);
                assert_eq!(got_d[l].to_bits(), d.to_bits(), "draw {draw}, lane {l}: D");
                let what = format!(
                    "draw {draw}, lane {l}: {eff_l:?} d_t {} d_c {} s0 {s0}",
                    d_t[l], d_c[l]
                );
                assert_lane_is(&got, l, &want, &what);
                let (i1, q) = invariants(&eff_l);
                let branch = if d_t[l] == 0.0 {
                    0
                } else if weight_by_signs(i1, q, &eff_l).is_some() {
                    1
                } else {
                    2
                };
                taken[branch] += 1;
            }
        }
        assert!(
            taken.iter().all(|&n| n > 2000),
            "uncracked, by signs, mixed: {taken:?}"
        );
    }
}
