//! Registered verification cases: one file per case, each with a header giving its goal,
//! sketch, boundary conditions, parameters, reference and tolerance. The registry holds
//! what the report shows about each case as data: id, title, group, the requirement
//! sentence, the reference (with the section of `docs/verification_references.md` it
//! cites) and the tolerance with its reason.

use dcfm::Result;
use serde::Serialize;

use crate::record::CaseOutput;

pub mod contact_bonded_monolithic;
pub mod contact_drop_bounce;
pub mod convergence_w01;
pub mod energy_conservation;
pub mod patch_test;
pub mod static_geostatic;
pub mod static_relaxation;
pub mod static_sequence;
pub mod w01_wave_pulses;
pub mod w02_absorbing;
pub mod w03_site_response;
pub mod w04_kirsch;
pub mod w05_bar_impact;
pub mod w06_incline;
pub mod w07_newmark_block;
pub mod w08_cohesive_bond;
pub mod w09_pair_step;
pub mod w10_damaging_bar;
pub mod w10_one_point;
pub mod w10_plastic_damage;
pub mod w11_rock_bolt;
pub mod w13_mass_scaling;
pub mod w13_shared_mass_step;
pub mod w13_stable_step;
pub mod w14_free_field;
pub mod w15_arias;
pub mod w15_butterworth;
pub mod w15_integration;
pub mod w15_records;
pub mod w15_response_spectrum;
pub mod w15_synthetic;
pub mod w16_stick_slip;

/// What the report says about a case (written to `results.json` under `cases`).
#[derive(Clone, Copy, Debug, Serialize, PartialEq, Eq)]
pub struct CaseInfo {
    /// Short id (W1, W1-conv, patch, ...).
    pub id: &'static str,
    /// Title: the `case` of its rows in `results.json`.
    pub title: &'static str,
    /// Report group (the summary counts passes per group).
    pub group: &'static str,
    /// What the solver must do, as one sentence.
    pub requirement: &'static str,
    /// The reference solution and where it is stated (a section of
    /// `docs/verification_references.md` or a cited work).
    pub reference: &'static str,
    /// The tolerance and why it is that.
    pub tolerance: &'static str,
}

/// A registered case: what it is and the function that runs it.
pub struct Case {
    pub info: CaseInfo,
    pub run: fn() -> Result<CaseOutput>,
}

impl Case {
    /// Short id.
    pub fn id(&self) -> &'static str {
        self.info.id
    }
}

/// Every case the runner executes, in report order.
pub fn all() -> Vec<Case> {
    vec![
        Case {
            info: CaseInfo {
                id: "W1",
                title: w01_wave_pulses::TITLE,
                group: "Wave propagation",
                requirement: "Plane P and S pulses travel up a hex8 column with the wave \
                    speed, amplitude ρcv0 and net displacement of d'Alembert's solution, and \
                    double in velocity at a free end and in stress at a fixed end; the energy \
                    balance closes.",
                reference: "d'Alembert's solution of the 1D wave equation for a half-sine \
                    velocity pulse (docs/verification_references.md §W1; energy §W12).",
                tolerance: "Peaks ±3 % (lumped-mass central difference disperses ≤ 2 % with \
                    ≥ 20 elements per pulse), arrival ±2Δt, doubling 2.00 ± 0.06, net \
                    displacement ±1 %, energy residual ≤ 1 % of the largest energy.",
            },
            run: w01_wave_pulses::run,
        },
        Case {
            info: CaseInfo {
                id: "W1-conv",
                title: convergence_w01::TITLE,
                group: "Wave propagation",
                requirement: "Under refinement at a fixed Courant number the displacement \
                    error of a smooth pulse falls at second order in h.",
                reference: "Order 2 of central difference in time and lumped hex8 in space \
                    (docs/verification_references.md §W1, convergence).",
                tolerance: "Fitted log–log slope 2 ± 0.25: four meshes give a slope to a few \
                    hundredths; 0.25 separates order 2 from order 1.5.",
            },
            run: convergence_w01::run,
        },
        Case {
            info: CaseInfo {
                id: "patch",
                title: patch_test::TITLE,
                group: "Elements and time integration",
                requirement: "A distorted patch of hex8 elements reproduces a linear \
                    displacement field exactly (stress E0:ε in every element, no force on \
                    the free interior node), with one-point and full integration.",
                reference: "The imposed linear field (constant-strain patch test, MacNeal & \
                    Harder 1985).",
                tolerance: "1e-10 relative: the field is represented exactly, so only \
                    round-off remains.",
            },
            run: patch_test::run,
        },
        Case {
            info: CaseInfo {
                id: "energy",
                title: energy_conservation::TITLE,
                group: "Elements and time integration",
                requirement: "In undamped free vibration the scheme neither creates nor \
                    destroys energy over 10⁴ steps.",
                reference: "Conservation of the leapfrog scheme's energy ½V^{n−½}·MV^{n+½} + \
                    ½UⁿKUⁿ for a linear system (Hairer, Lubich & Wanner 2006, §I.1).",
                tolerance: "1e-6 relative for the scheme's energy (exactly conserved: \
                    round-off only); 1e-4 for the full-step energy, whose O((ωΔt)²) \
                    oscillation a 1000-step window does not average out.",
            },
            run: energy_conservation::run,
        },
        Case {
            info: CaseInfo {
                id: "W13",
                title: w13_stable_step::TITLE,
                group: "Elements and time integration",
                requirement: "The element matrices have the hex8 spectrum (free cube limit \
                    0.775 h/c_p), the step the driver allows is stable and a step beyond \
                    the mesh's limit is caught as an instability; selective mass scaling \
                    (time.mass_scaling) lifts a thin element's step to the one asked for, \
                    stays stable there, and its added mass acts as a mass; the \
                    shared-mass bound (time.stable_step) never exceeds the exact critical \
                    step of a graded mesh and is stable where the elements' own bound \
                    refuses.",
                reference: "Lumped-mass hex8 stable step; a point mass between two rods, \
                    M dv/dt = 2Z(v_i − v) (Graff 1975 §1.6), in closed form for a sin² \
                    pulse; the largest eigenvalue of the assembled M⁻¹K by a dense \
                    eigensolve (docs/verification_references.md §W13).",
                tolerance: "1 % on 0.775 h/c_p (an eigenvalue, computed to round-off); \
                    stability itself is pass/fail over 3000 (20,000 with mass scaling) \
                    steps; 1e-9 on the scaled step and added mass; 2 % of the incident \
                    amplitude on the transmitted peak (1 m cells, 20 m pulse); the \
                    shared-mass step at most the exact one (round-off, 1e-12), stability \
                    pass/fail over 20,000 steps.",
            },
            run: w13_stable_step::run,
        },
        Case {
            info: CaseInfo {
                id: "W10",
                title: w10_plastic_damage::TITLE,
                group: "Material",
                requirement: "The Lee–Fenves plastic-damage model, driven through a hex8 \
                    element and the explicit driver, follows the closed-form uniaxial \
                    softening laws, dissipates G_t per crack area whatever the element \
                    size, unloads with slope (1−D)E0, recovers stiffness on crack closure \
                    and has Kupfer's biaxial strength ratio.",
                reference: "Lee & Fenves (1998) closed forms \
                    (docs/verification_references.md §W10).",
                tolerance: "Curve 1 %, dissipated energy 2 %, unloading slope 1 %, biaxial \
                    ratio 1 % (W10): the closed forms are exact for one uniformly strained \
                    element, the margin covers the slow-loading inertia.",
            },
            run: w10_plastic_damage::run,
        },
        Case {
            info: CaseInfo {
                id: "W10-1pt",
                title: w10_one_point::TITLE,
                group: "Material",
                requirement: "A one-point (centroid) plastic-damage element with \
                    Flanagan–Belytschko hourglass control follows the same closed-form \
                    uniaxial laws as the fully integrated one: softening curve, G_t per \
                    crack area for several element sizes, unloading and crack-closure \
                    slopes (eq. (24) recovery).",
                reference: "Lee & Fenves (1998) closed forms \
                    (docs/verification_references.md §W10).",
                tolerance: "Those of W10: curve 1 %, dissipated energy 2 %, slopes 1 % (the \
                    closed forms are exact for one uniformly strained element).",
            },
            run: w10_one_point::run,
        },
        Case {
            info: CaseInfo {
                id: "W10-bar",
                title: w10_damaging_bar::TITLE,
                group: "Material",
                requirement: "A row of five plastic-damage elements pulled past the peak \
                    localises in its weakest element with one-point and with full \
                    integration alike: the same peak force, dissipated energy and \
                    post-peak forces, the hourglass energy a small share of the internal \
                    work.",
                reference: "Peak force 0.95 f_t0 a² (uniaxial stress, \
                    docs/verification_references.md §W10); the fully integrated bar for the \
                    one-point one (post-peak forces and dissipated energy).",
                tolerance: "Peak 1 % (W10); one-point vs full: peak 1 %, energy \
                    2 %, post-peak force 2 % of the peak (homogeneous strain but for the \
                    lateral mismatch at the crack, a second-order effect); hourglass energy \
                    ≤ 10 % of the internal work (the usual bound).",
            },
            run: w10_damaging_bar::run,
        },
        Case {
            info: CaseInfo {
                id: "W5",
                title: w05_bar_impact::TITLE,
                group: "Contact",
                requirement: "Point-to-point contact transmits the impact force of 1D wave \
                    theory between two bars for 2L/c and lets them separate, and a bar \
                    rebounds from a rigid wall.",
                reference: "1D elastic impact (docs/verification_references.md §W5).",
                tolerance: "Plateau ±3 %, duration ±2Δt, momentum ±0.5 %, energy ±2 % \
                    (W5); energy residual ≤ 2 % (W12).",
            },
            run: w05_bar_impact::run,
        },
        Case {
            info: CaseInfo {
                id: "W6",
                title: w06_incline::TITLE,
                group: "Contact",
                requirement: "A block on an incline sticks when gravity along the slope \
                    is below static friction and otherwise slides with a = g(sinθ − μd \
                    cosθ), with pairs and with point-to-surface contact; the friction work \
                    closes the energy balance.",
                reference: "Coulomb friction on a rigid block \
                    (docs/verification_references.md §W6).",
                tolerance: "±1 % (W6); 'sticks' means a slide below 1 % of the 0.7534 m \
                    slide; energy residual ≤ 2 % (W12).",
            },
            run: w06_incline::run,
        },
        Case {
            info: CaseInfo {
                id: "W7",
                title: w07_newmark_block::TITLE,
                group: "Contact",
                requirement: "A block on a base with prescribed acceleration slips as \
                    Newmark's rigid-plastic sliding block: the slip of a rectangular pulse \
                    and the per-cycle slip of one-way sliding.",
                reference: "Newmark (1965) sliding block \
                    (docs/verification_references.md §W7).",
                tolerance: "±3 % (W7): the elastic plate approximates a rigid block.",
            },
            run: w07_newmark_block::run,
        },
        Case {
            info: CaseInfo {
                id: "W16",
                title: w16_stick_slip::TITLE,
                group: "Contact",
                requirement: "A block on a belt started impulsively, held by a spring, with \
                    μs > μd, runs the rigid stick–slip limit cycle: its period, minimum \
                    velocity, dissipation per cycle and slip onset at μs m g; the energy \
                    balance closes with the belt's impulsive start.",
                reference: "Closed form of the rigid stick–slip oscillator \
                    (docs/verification_references.md §W16).",
                tolerance: "±2 % (the elastic block, damped to ξ ≈ 1 at its first mode, \
                    approximates a rigid one); energy residual ≤ 1e-5 of the largest \
                    energy (an O(Δt²) term, 2e-7 measured).",
            },
            run: w16_stick_slip::run,
        },
        Case {
            info: CaseInfo {
                id: "W8",
                title: w08_cohesive_bond::TITLE,
                group: "Contact",
                requirement: "A cohesive bond debonds at cA in tension and carries no \
                    tension after, transmits recompression, and in shear holds cA + μs N \
                    until the first slip, then μd N.",
                reference: "The bond-slip law of the paper's eqs. (12)–(15) \
                    (docs/verification_references.md §W8).",
                tolerance: "±1 % on forces, event times within 2Δt, zero tension after \
                    debonding to 1e-9 N: the law is exact (W9), the margin covers the \
                    plate's ride.",
            },
            run: w08_cohesive_bond::run,
        },
        Case {
            info: CaseInfo {
                id: "W9",
                title: w09_pair_step::TITLE,
                group: "Contact",
                requirement: "One contact pair over one step gives the pair-law table \
                    exactly: stick force, bond, tension, sliding and separation.",
                reference: "Eqs. (6)–(15) of the paper for an isolated pair \
                    (docs/verification_references.md §W9).",
                tolerance: "1e-10 relative (absolute 1e-10 N for zero references): the \
                    answer is exact, so only round-off remains.",
            },
            run: w09_pair_step::run,
        },
        Case {
            info: CaseInfo {
                id: "bonded",
                title: contact_bonded_monolithic::TITLE,
                group: "Contact",
                requirement: "A bonded split interface reproduces the merged-node mesh \
                    while a P pulse crosses it twice (compression, then tension).",
                reference: "The same model without the split (merged nodes).",
                tolerance: "1e-12 relative: the two updates differ only by floating-point \
                    association.",
            },
            run: contact_bonded_monolithic::run,
        },
        Case {
            info: CaseInfo {
                id: "drop",
                title: contact_drop_bounce::TITLE,
                group: "Contact",
                requirement: "A block dropped on a base through point-to-surface contact \
                    impacts at √(2gd), bounces, never penetrates and comes to rest \
                    carrying its weight at its static sag.",
                reference: "Free fall and static equilibrium of an elastic block under \
                    self-weight (uniaxial stress, ν = 0).",
                tolerance: "Own: rest force ±1 %, rest position ±1 % of the drop, \
                    penetration ≤ the contact tolerance, sag ±3 % (8 linear elements), \
                    energy residual ≤ 2 % (W12), impact time ±2Δt.",
            },
            run: contact_drop_bounce::run,
        },
        Case {
            info: CaseInfo {
                id: "W2",
                title: w02_absorbing::TITLE,
                group: "Boundaries and seismic input",
                requirement: "Lysmer dashpots absorb normally incident P and S waves; the \
                    viscous-spring base brings a vertically incident wave into a model through \
                    the equivalent nodal forces A(K u_ff + C v_ff + σ_ff·n) so that the free \
                    surface sees twice the incident motion whatever the springs; a Ricker wave \
                    enters and leaves through a transmitting base; a line load's response near \
                    viscous-spring boundaries matches an extended mesh.",
                reference: "Lysmer & Kuhlemeyer 1969; Deeks & Randolph 1994; Liu et al. 2006; \
                    d'Alembert (docs/verification_references.md §W2).",
                tolerance: "Reflection < 1 % (the extended-mesh difference isolates the \
                    boundary's reflection from the scheme's dispersion); absorbed energy ±1 %; \
                    surface/incident 2.00 ± 2 % and its spread over K ≤ 2 %; Ricker peaks ±2 %; \
                    peak response vs extended mesh ±5 %.",
            },
            run: || Ok(w02_absorbing::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W3",
                title: w03_site_response::TITLE,
                group: "Boundaries and seismic input",
                requirement: "A soil layer on an elastic half-space under vertical SH has \
                    Kramer's transfer function through the free-field column alone and through \
                    a 3D model with free-field sides, undamped and with 5 % damping.",
                reference: "Kramer 1996, §7.2: |H| = 1/√(cos² kH + (α sin kH)²) \
                    (docs/verification_references.md §W3).",
                tolerance: "Resonances ±2 % (≥ 10 elements per wavelength), |H| ±5 %, \
                    damped peaks ±5 % (Rayleigh damping tuned to 5 % at each resonance).",
            },
            run: || Ok(w03_site_response::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W14",
                title: w14_free_field::TITLE,
                group: "Boundaries and seismic input",
                requirement: "A laterally uniform layered model with free-field sides \
                    reproduces its own 1D column at every node, corners included, under P, SV \
                    and SH at once; a model truncated below the ground surface, its free field \
                    continued through the overburden, matches the full-height model.",
                reference: "The 1D free-field column of the same layering; the full-height \
                    model (docs/verification_references.md §W14).",
                tolerance: "2 % of the peak velocity at every node and every instant.",
            },
            run: || Ok(w14_free_field::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W11",
                title: "W11 rock bolt",
                group: "Anchor bars",
                requirement: "An anchor bar superposed on its host elements adds its axial \
                    stiffness EA/L, yields at f_y A, and with bond–slip follows the pull-out \
                    solution N(x) = P sinh(λ(L−x))/sinh(λL); its stable step is accounted for.",
                reference: "Composite stiffness and pull-out closed forms \
                    (docs/verification_references.md §W11).",
                tolerance: "±1 % (closed forms of the discrete bar; mesh-independent for the \
                    perfect bond).",
            },
            run: || Ok(w11_rock_bolt::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15a",
                title: "W15a response spectrum (Nigam–Jennings)",
                group: "Ground motions",
                requirement: "The response-spectrum oscillator reproduces closed-form \
                    undamped harmonic and damped impulse SDOF responses.",
                reference: "SDOF closed forms (docs/verification_references.md §W15).",
                tolerance: "1e-6 relative: the recursion is exact for piecewise-linear input.",
            },
            run: || Ok(w15_response_spectrum::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15b",
                title: "W15b Arias intensity of a sine",
                group: "Ground motions",
                requirement: "Arias intensity and the Husid times of a sine equal their \
                    closed forms.",
                reference: "I_a = π A² nT/(4g) (docs/verification_references.md §W15).",
                tolerance: "1e-12 on I_a (exact trapezoid over whole periods); 1e-4 s on \
                    t₅, t₉₅.",
            },
            run: || Ok(w15_arias::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15c",
                title: "W15c Butterworth filter",
                group: "Ground motions",
                requirement: "The Butterworth filters have the textbook gain at their corners \
                    (−3 dB one pass, −6 dB forward–backward) and the zero-phase pass keeps a \
                    symmetric pulse symmetric.",
                reference: "Butterworth magnitude |H| = 1/√(1 + (f/f_c)^{2n}) with the bilinear \
                    pre-warp (docs/verification_references.md §W15).",
                tolerance: "1e-9 on the designed gain, 1e-3 on the applied gain, 1e-9 \
                    asymmetry.",
            },
            run: || Ok(w15_butterworth::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15d",
                title: "W15d integration after baseline correction",
                group: "Ground motions",
                requirement: "Baseline correction and integration give the analytic velocity \
                    and displacement of an offset sine.",
                reference: "Analytic integrals (docs/verification_references.md §W15).",
                tolerance: "1e-6 of the peak (trapezoid error (ωΔt)²/12 ≈ 2e-7).",
            },
            run: || Ok(w15_integration::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15e",
                title: "W15e real records vs their headers",
                group: "Ground motions",
                requirement: "Each reader gets npts, dt, units and the peak of real files \
                    that packages ship (PEER AT2, USGS SMC, K-NET) and of a COSMOS V2 file.",
                reference: "The files' own headers (docs/verification_references.md §W15).",
                tolerance: "Exact counts and steps; the peak to the header's rounding.",
            },
            run: || Ok(w15_records::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W15f",
                title: "W15f synthetic motion (Wolong-like preset)",
                group: "Ground motions",
                requirement: "The synthetic generator is bit-reproducible for a seed and the \
                    Wolong-like preset has the specified peaks, peak time, two strong phases \
                    and ends at rest.",
                reference: "Issue 8's specification of the preset (EW 957.7, NS ≈ 653, UD ≈ \
                    948 cm/s²; phases 2.6–20 s and 30–40 s).",
                tolerance: "Peaks and peak time exact to the sample; phase energy ratios ≥ 2.",
            },
            run: || Ok(w15_synthetic::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "W4",
                title: "W4 Kirsch opening (static stage)",
                group: "Static stage",
                requirement: "A circular opening excavated through the static stage in a \
                    plate under in-situ stress has Kirsch's wall hoop stress and \
                    excavation-induced wall displacement for K0 = 0.5, 1 and 1.5.",
                reference: "Kirsch 1898 (docs/verification_references.md §W4).",
                tolerance: "Wall stress ±5 % (extrapolated from the first two rings), \
                    displacement ±2 % (truncation at 40a changes it by ≈ 0.1 %).",
            },
            run: || Ok(w04_kirsch::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "static-geo",
                title: "Static stage: geostatic states",
                group: "Static stage",
                requirement: "The gravity in-situ step gives σ_zz = −ρg(H − z) and the \
                    uniaxial-strain settlement for both integrations, by the direct solve and \
                    by dynamic relaxation; a given K0 field set as initial stress keeps \
                    σ_h/σ_v = K0 after equilibration.",
                reference: "Equilibrium and uniaxial strain of a confined column \
                    (analytic::ConfinedColumn).",
                tolerance: "Direct 1e-9 (round-off), relaxation 1e-6 of the settlement, K0 \
                    ratios ±1e-6 (issue 7).",
            },
            run: || Ok(static_geostatic::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "static-DR",
                title: "Static stage: dynamic relaxation",
                group: "Static stage",
                requirement: "Dynamic relaxation reaches the direct solve's equilibrium on the \
                    same elastic model, and solves a plastic-damage step the direct solve \
                    refuses.",
                reference: "The sparse Cholesky solution of the same model; statics of the \
                    loaded column.",
                tolerance: "1e-6 of the largest displacement (issue 7).",
            },
            run: || Ok(static_relaxation::run()?.into()),
        },
        Case {
            info: CaseInfo {
                id: "static-seq",
                title: "Static stage: sequences, activation, hand-over",
                group: "Static stage",
                requirement: "Excavating in one step or two gives the same state; placed \
                    concrete is stress-free and then carries its own weight; the static state \
                    handed to the dynamic stage stays at rest with zero input.",
                reference: "Uniqueness of the linear elastic solution; the placed body's own \
                    weight; rest (peak velocity ≤ 1e-6 m/s, docs/verification_references.md \
                    §W14).",
                tolerance: "1e-8 relative between sequences; stress-free to round-off; peak \
                    velocity ≤ 1e-6 m/s over 2 s.",
            },
            run: || Ok(static_sequence::run()?.into()),
        },
    ]
}

/// The metadata of every case (for `results.json`).
pub fn infos() -> Vec<CaseInfo> {
    all().iter().map(|c| c.info).collect()
}
