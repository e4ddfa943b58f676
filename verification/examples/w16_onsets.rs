//! The numbers of docs/contact.md "Friction on elastic bodies": slip-onset spring forces of
//! the W16 stick–slip oscillator with and without damping in the block, with the spring on
//! the block's rear edge, and for a thicker block of 2 × 2 × 1 elements. A measurement, not
//! a check (the W16 case of the verification runner checks the closed form):
//!
//! ```sh
//! cargo run --release -p dcfm-verification --example w16_onsets
//! ```

fn main() {
    use dcfm_verification::cases::w16_stick_slip::{measure, Attachment, BlockSpec, PLATE};
    let undamped = BlockSpec { beta: 0.0, ..PLATE };
    // 0.1 × 0.1 × 0.05 m, 2 × 2 × 1 elements: ω₁ = √2 c_s/h = 1414 rad/s (E 10 MPa).
    let thick = BlockSpec {
        size: [0.1, 0.1, 0.05],
        divisions: [2, 2, 1],
        young: 1e7,
        beta: 1.4e-3,
    };
    // Ten times stiffer: ω₁ ×√10, β /√10 (ξ ≈ 1 again).
    let stiff = BlockSpec {
        young: 1e8,
        beta: 1.4e-3 / 10f64.sqrt(),
        ..thick
    };
    for (name, b, at) in [
        ("plate", PLATE, Attachment::ContactPlane),
        ("plate, undamped", undamped, Attachment::ContactPlane),
        ("plate", PLATE, Attachment::RearEdge),
        ("2x2x1", thick, Attachment::ContactPlane),
        ("2x2x1", thick, Attachment::RearEdge),
        (
            "2x2x1, undamped",
            BlockSpec { beta: 0.0, ..thick },
            Attachment::ContactPlane,
        ),
        ("2x2x1, E x10", stiff, Attachment::ContactPlane),
        ("2x2x1, E x10", stiff, Attachment::RearEdge),
    ] {
        let m = match measure(b, at) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{name} {at:?}: {e}");
                std::process::exit(1);
            }
        };
        // Every slip after a stick of at least 5 ms (the undamped block chatters).
        let mut stuck_from = None;
        let mut slips = Vec::new();
        for (i, (&t, &sl)) in m.times.iter().zip(&m.sliding).enumerate() {
            if sl {
                if stuck_from.is_some_and(|t0: f64| t - t0 >= 0.005) {
                    slips.push(format!("{t:.3} s {:.2} N", m.forces[i]));
                }
                stuck_from = None;
            } else if stuck_from.is_none() {
                stuck_from = Some(t);
            }
        }
        let full: Vec<String> = m
            .full_slides
            .iter()
            .map(|o| format!("{:.3} s {:.2} N", o.0, o.1))
            .collect();
        println!(
            "{name} {at:?}: slips after a stick >= 5 ms: {}\n    all pairs sliding: {}; residual {:.2e}",
            slips.join(", "),
            full.join(", "),
            m.residual
        );
    }
}
