//! Unit tests of the contact system through `compute()`: W9's table on a real two-block
//! mesh, setup errors, point-to-surface balance, the pair → surface switch and W6.

use super::*;
use crate::mesh::{BlockSpec, BoxMeshSpec, Face};

const DT: f64 = 1e-3;

fn block(name: &str, origin: [f64; 3], size: [f64; 3], div: [usize; 3]) -> BlockSpec {
    BlockSpec {
        name: name.into(),
        region: None,
        origin,
        size,
        divisions: div,
        grading: [1.0; 3],
    }
}

/// Two 2 × 2 × 1 m single-element blocks, `top` on `base`, split: four node pairs, each
/// with control area 1 m², normal +z (surface a = top face of base).
fn two_blocks() -> Mesh {
    BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [2.0, 2.0, 1.0], [1, 1, 1]),
            block("top", [0.0, 0.0, 1.0], [2.0, 2.0, 1.0], [1, 1, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("t.toml")
    .unwrap()
}

fn w9_spec() -> InterfaceSpec {
    InterfaceSpec::new("w9", "base-top", "top-base", 0.5, 0.4, 5.0)
}

struct Rig {
    mesh: Mesh,
    sys: ContactSystem,
    w: Vec<f64>,
    r: Vec<[f64; 3]>,
}

impl Rig {
    fn w9() -> Rig {
        let mesh = two_blocks();
        let sys = ContactSystem::new(&mesh, &[w9_spec()], "t.toml").unwrap();
        let mut w = vec![1.0; mesh.n_nodes()];
        for (a, b, area, n) in sys.pairs(0) {
            assert!((area - 1.0).abs() < 1e-14);
            assert!((n[2] - 1.0).abs() < 1e-14);
            w[a as usize] = 1.0; // mass 1 on surface a
            w[b as usize] = 1.0 / 3.0; // mass 3 on surface b
        }
        let r = vec![[0.0; 3]; mesh.n_nodes()];
        Rig { mesh, sys, w, r }
    }

    /// One step from rest at the reference configuration with load `f` on every node of
    /// surface a; returns (force on a, force on b) per pair.
    fn step_from_rest(&mut self, f: [f64; 3]) -> Vec<([f64; 3], [f64; 3])> {
        let n = self.mesh.n_nodes();
        for &k in self.sys.touched_nodes() {
            self.r[k as usize] = [0.0; 3];
        }
        let zero = vec![[0.0; 3]; n];
        let mut u_pred = zero.clone();
        let mut v_pred = zero.clone();
        let pairs = self.sys.pairs(0);
        for &(a, _, _, _) in &pairs {
            let wa = self.w[a as usize];
            v_pred[a as usize] = geom::scale(DT * wa, f);
            u_pred[a as usize] = geom::scale(DT * DT * wa, f);
        }
        let inp = ContactStepInput {
            step: 1,
            time: 0.0,
            dt: DT,
            inv_mass: &self.w,
            coords: &self.mesh.coords,
            u_old: &zero,
            u_pred: &u_pred,
            v_pred: &v_pred,
        };
        self.sys.compute(&inp, &mut self.r).unwrap();
        pairs
            .iter()
            .map(|&(a, b, _, _)| (self.r[a as usize], self.r[b as usize]))
            .collect()
    }
}

fn rel_close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-10 * b.abs().max(1.0)
}

fn states(sys: &ContactSystem) -> [usize; 4] {
    sys.state_counts(0).0
}

#[test]
fn w9_table_through_compute() {
    // 20 N compressive: stick, R_n = 15 N, common acceleration 5 m/s².
    let mut rig = Rig::w9();
    for (ra, rb) in rig.step_from_rest([0.0, 0.0, 20.0]) {
        assert!(rel_close(-ra[2], 15.0) && rel_close(rb[2], 15.0), "{ra:?}");
        assert!(rel_close((20.0 + ra[2]) / 1.0, 5.0));
        assert!(rel_close(rb[2] / 3.0, 5.0));
    }
    assert_eq!(states(&rig.sys), [4, 0, 0, 0]);

    // 10 N pulling apart: separation (tensile demand 7.5 N > 5 N).
    let mut rig = Rig::w9();
    for (ra, rb) in rig.step_from_rest([0.0, 0.0, -10.0]) {
        assert_eq!((ra, rb), ([0.0; 3], [0.0; 3]));
    }
    assert_eq!(states(&rig.sys), [0, 0, 0, 4]);
    // 4 N pulling apart, unbonded: separation.
    for (ra, _) in rig.step_from_rest([0.0, 0.0, -4.0]) {
        assert_eq!(ra, [0.0; 3]);
    }
    assert_eq!(states(&rig.sys), [0, 0, 0, 4]);
    // 20 N + 16 N tangential, unbonded: slide, R_t = 6 N, accelerations 10 and 2 m/s².
    for (ra, rb) in rig.step_from_rest([0.0, 16.0, 20.0]) {
        assert!(rel_close(-ra[1], 6.0) && rel_close(-ra[2], 15.0), "{ra:?}");
        assert!(rel_close(16.0 + ra[1], 10.0));
        assert!(rel_close(rb[1] / 3.0, 2.0));
    }
    assert_eq!(states(&rig.sys), [0, 0, 4, 0]);
    // Friction work of that step: per pair R·Δrel = 6 N × 8 Δt² m.
    let w_before = rig.sys.friction_work();
    // 20 N + 8 N tangential, unbonded: stick, R_t = 6 N (and no dissipation).
    for (ra, _) in rig.step_from_rest([0.0, 8.0, 20.0]) {
        assert!(rel_close(-ra[1], 6.0));
    }
    assert_eq!(states(&rig.sys), [0, 4, 0, 0]);
    assert!(rel_close(rig.sys.friction_work(), w_before));
    assert!(
        rel_close(w_before / (DT * DT), 4.0 * 48.0),
        "{}",
        w_before / (DT * DT)
    );

    // 4 N pulling apart, bonded: stick (3 N < 5 N).
    let mut rig = Rig::w9();
    for (ra, _) in rig.step_from_rest([0.0, 0.0, -4.0]) {
        assert!(rel_close(ra[2], 3.0));
    }
    assert_eq!(states(&rig.sys), [4, 0, 0, 0]);
    // 20 N compressive + 8 N tangential: stick, R_t = 6 N.
    for (ra, _) in rig.step_from_rest([0.0, 8.0, 20.0]) {
        assert!(rel_close(-ra[1], 6.0));
    }
    // 20 N + 16 N tangential, bonded: stick (12 N < 7.5 + 5 N).
    for (ra, _) in rig.step_from_rest([0.0, 16.0, 20.0]) {
        assert!(rel_close(-ra[1], 12.0));
    }
    assert_eq!(states(&rig.sys), [4, 0, 0, 0]);
    // 20 N + 18 N tangential, bonded: slide (13.5 N > 12.5 N), cohesion gone for good.
    for (ra, _) in rig.step_from_rest([0.0, 18.0, 20.0]) {
        assert!(rel_close(-ra[1], 6.0));
    }
    assert_eq!(states(&rig.sys), [0, 0, 4, 0]);
    rig.step_from_rest([0.0, 0.0, -4.0]);
    assert_eq!(states(&rig.sys), [0, 0, 0, 4]);
    let areas = rig.sys.state_areas();
    assert_eq!(areas[0].0, "w9");
    let want = [0.0, 0.0, 4.0, 0.0];
    for (got, want) in areas[0].1.iter().zip(want) {
        assert!((got - want).abs() < 1e-12, "{areas:?}");
    }
}

#[test]
fn node_fields_have_the_right_shapes() {
    let mut rig = Rig::w9();
    rig.step_from_rest([0.0, 0.0, 20.0]);
    let n = rig.mesh.n_nodes();
    let f = rig.sys.node_fields(n);
    assert_eq!(f.len(), 6);
    for (name, comps, v) in &f {
        assert_eq!(v.len(), comps * n, "{name}");
    }
    let nf = &f[4].2;
    let (a, b, _, _) = rig.sys.pairs(0)[0];
    assert!(rel_close(nf[a as usize], 15.0) && rel_close(nf[b as usize], 15.0));
    assert_eq!(f[0].2.iter().filter(|&&s| s == -1.0).count(), n - 8);
}

/// Two hand-built unit cubes: element 0 = [0,1]³, element 1 = cube above, shifted by
/// `shift`. Face set "a" = top of element 0, "b" = bottom of element 1.
fn cubes(shift: [f64; 3], b_local: u8) -> Mesh {
    let mut coords = Vec::new();
    for dz in [0.0, 1.0] {
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            coords.push([x, y, dz]);
        }
    }
    for dz in [1.0, 2.0] {
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            coords.push([x + shift[0], y + shift[1], dz + shift[2]]);
        }
    }
    let mut m = Mesh {
        coords,
        elements: vec![[0, 1, 2, 3, 4, 5, 6, 7], [8, 9, 10, 11, 12, 13, 14, 15]],
        element_region: vec![0, 1],
        region_names: vec!["base".into(), "top".into()],
        ..Default::default()
    };
    m.face_sets.insert(
        "a".into(),
        vec![Face {
            element: 0,
            local: 1,
        }],
    );
    m.face_sets.insert(
        "b".into(),
        vec![Face {
            element: 1,
            local: b_local,
        }],
    );
    m
}

fn contact_message(e: DcfmError) -> String {
    match e {
        DcfmError::Contact { interface, message } => format!("{interface}: {message}"),
        other => panic!("expected a contact error, got {other}"),
    }
}

#[test]
fn setup_errors_name_the_culprit() {
    let spec = InterfaceSpec::new("i", "a", "b", 0.6, 0.5, 0.0);
    // Coincident cubes pair fine.
    let sys =
        ContactSystem::new(&cubes([0.0; 3], 0), std::slice::from_ref(&spec), "c.toml").unwrap();
    assert_eq!(sys.pairs(0).len(), 4);
    assert!(sys
        .pairs(0)
        .iter()
        .all(|p| p.1 != NONE && (p.2 - 0.25).abs() < 1e-14));

    let e = ContactSystem::new(
        &cubes([0.3, 0.0, 0.0], 0),
        std::slice::from_ref(&spec),
        "c.toml",
    )
    .unwrap_err();
    let m = contact_message(e);
    assert!(
        m.contains("node 4 of surface_a") && m.contains("no node of surface_b"),
        "{m}"
    );

    // b = top face of a cube sitting at the same place as element 0: normals not opposite.
    let e = ContactSystem::new(
        &cubes([0.0, 0.0, -1.0], 1),
        std::slice::from_ref(&spec),
        "c.toml",
    )
    .unwrap_err();
    let m = contact_message(e);
    assert!(m.contains("do not face each other"), "{m}");

    let mut bad = spec.clone();
    bad.surface_b = "nope".into();
    let e = ContactSystem::new(&cubes([0.0; 3], 0), &[bad], "c.toml").unwrap_err();
    assert!(
        e.to_string().contains("interfaces[0].surface_b = nope"),
        "{e}"
    );

    let mut bad = spec.clone();
    bad.mu_d = 0.7;
    let e = ContactSystem::new(&cubes([0.0; 3], 0), &[bad], "c.toml").unwrap_err();
    assert!(e.to_string().contains("interfaces[0].mu_d = 0.7"), "{e}");

    let e = ContactSystem::new(&cubes([0.0; 3], 0), &[spec.clone(), spec.clone()], "c.toml")
        .unwrap_err();
    assert!(e.to_string().contains("unique"), "{e}");

    // Same surface on both sides (shared nodes).
    let mut m = cubes([0.0; 3], 0);
    m.face_sets.insert(
        "a2".into(),
        vec![
            Face {
                element: 0,
                local: 1,
            },
            Face {
                element: 0,
                local: 3,
            },
        ],
    );
    let mut s2 = spec.clone();
    s2.surface_b = "a2".into();
    let e = ContactSystem::new(&m, &[s2], "c.toml").unwrap_err();
    assert!(contact_message(e).contains("belongs to both surfaces"));

    // Zero-area face.
    let mut m = cubes([0.0; 3], 0);
    m.coords[6] = m.coords[5];
    m.coords[7] = m.coords[4];
    let e = ContactSystem::new(&m, std::slice::from_ref(&spec), "c.toml").unwrap_err();
    let msg = contact_message(e);
    assert!(
        msg.contains("face (element 0, local 1)") && msg.contains("zero area"),
        "{msg}"
    );

    // Initial penetration in surface mode.
    let mut s = spec.clone();
    s.mode = ContactMode::Surface;
    let e = ContactSystem::new(&cubes([0.0, 0.0, -0.1], 0), &[s.clone()], "c.toml").unwrap_err();
    assert!(contact_message(e).contains("inside surface_b"));
    assert!(ContactSystem::new(&cubes([0.3, 0.2, 0.0], 0), &[s], "c.toml").is_ok());
}

#[test]
fn inconsistent_normals_are_reported() {
    // Element 0 = [0,1]³, element 1 = [1,2]×[0,1]×[1,2]; they share the edge x = 1, z = 1.
    let mut coords = Vec::new();
    for dz in [0.0, 1.0] {
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            coords.push([x, y, dz]);
        }
    }
    let e1 = [1, 16, 17, 2, 18, 19, 20, 21];
    for (x, y, z) in [
        (2.0, 0.0, 1.0),
        (2.0, 1.0, 1.0),
        (1.0, 0.0, 2.0),
        (2.0, 0.0, 2.0),
        (2.0, 1.0, 2.0),
        (1.0, 1.0, 2.0),
    ] {
        coords.push([x, y, z]);
    }
    // Fix node numbering: nodes 8..16 unused placeholders.
    let mut all = coords[..8].to_vec();
    all.extend((8..16).map(|i| [10.0 + i as f64, 0.0, 0.0]));
    all.extend_from_slice(&coords[8..]);
    // Element 1 bottom face uses nodes 5 (1,0,1) and 6 (1,1,1) of element 0.
    let e1 = [5, 16, 17, 6, e1[4], e1[5], e1[6], e1[7]];
    let mut m = Mesh {
        coords: all,
        elements: vec![[0, 1, 2, 3, 4, 5, 6, 7], e1],
        element_region: vec![0, 0],
        region_names: vec!["r".into()],
        ..Default::default()
    };
    m.face_sets.insert(
        "a".into(),
        vec![
            Face {
                element: 0,
                local: 1,
            },
            Face {
                element: 1,
                local: 0,
            },
        ],
    );
    m.face_sets.insert(
        "b".into(),
        vec![Face {
            element: 1,
            local: 1,
        }],
    );
    let e = ContactSystem::new(
        &m,
        &[InterfaceSpec::new("i", "a", "b", 0.5, 0.5, 0.0)],
        "c.toml",
    )
    .unwrap_err();
    let msg = contact_message(e);
    assert!(msg.contains("inconsistent normals at node"), "{msg}");
}

/// W6 block on an incline (frame along the incline: x down-slope, z normal): the block's
/// bottom nodes (surface a, 1000 kg shared by four nodes, no elastic coupling needed since
/// they move alike) on a fixed base. Returns (x displacement after `t_end`, friction work,
/// kinetic energy, gravity work, final state counts of pairs and surface nodes).
fn incline_run(
    mesh: &Mesh,
    spec: InterfaceSpec,
    theta_deg: f64,
    t_end: f64,
) -> (f64, f64, f64, f64, ([usize; 4], [usize; 4])) {
    let g = 9.81;
    let th = theta_deg.to_radians();
    let mut sys = ContactSystem::new(mesh, std::slice::from_ref(&spec), "w6.toml").unwrap();
    let n = mesh.n_nodes();
    let slaves: Vec<u32> = sys.pairs(0).iter().map(|p| p.0).collect();
    assert_eq!(slaves.len(), 4);
    let mut w = vec![0.0; n];
    let m_node = 250.0;
    for &k in &slaves {
        w[k as usize] = 1.0 / m_node;
    }
    let f = [m_node * g * th.sin(), 0.0, -m_node * g * th.cos()];
    let dt = 1e-3;
    let steps = (t_end / dt).round() as u64;
    let mut u = vec![[0.0; 3]; n];
    let mut v = vec![[0.0; 3]; n];
    let mut up = u.clone();
    let mut vp = v.clone();
    let mut r = vec![[0.0; 3]; n];
    let mut w_grav = 0.0;
    for step in 0..steps {
        for &k in sys.touched_nodes() {
            r[k as usize] = [0.0; 3];
        }
        for k in 0..n {
            let fk = if w[k] > 0.0 { f } else { [0.0; 3] };
            vp[k] = geom::axpy(v[k], dt * w[k], fk);
            up[k] = geom::axpy(u[k], dt, vp[k]);
        }
        let inp = ContactStepInput {
            step,
            time: step as f64 * dt,
            dt,
            inv_mass: &w,
            coords: &mesh.coords,
            u_old: &u,
            u_pred: &up,
            v_pred: &vp,
        };
        sys.compute(&inp, &mut r).unwrap();
        for k in 0..n {
            let un = geom::axpy(up[k], dt * dt * w[k], r[k]);
            if w[k] > 0.0 {
                w_grav += geom::dot(f, geom::sub(un, u[k]));
            }
            u[k] = un;
            v[k] = geom::axpy(vp[k], dt * w[k], r[k]);
        }
    }
    // Kinetic energy from the mid-step velocities averaged to the end time.
    let mut ke = 0.0;
    for &k in &slaves {
        let vv = v[k as usize];
        ke += 0.5 * m_node * geom::dot(vv, vv);
    }
    let x = slaves.iter().map(|&k| u[k as usize][0]).sum::<f64>() / 4.0;
    (x, sys.friction_work(), ke, w_grav, sys.state_counts(0))
}

fn within(got: f64, want: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs()
}

#[test]
fn w6_incline_point_to_point() {
    let mesh = two_blocks();
    // surface a = the block's bottom (top region), normal −z; base fixed.
    let mut spec = InterfaceSpec::new("w6", "top-base", "base-top", 0.6, 0.4, 0.0);
    spec.slip_threshold = Some(100.0);
    let (x, _, _, _, _) = incline_run(&mesh, spec.clone(), 30.0, 1.0);
    assert!(x.abs() < 1e-12, "30°, μs = 0.6 must stick: x = {x}");
    spec.mu_s = 0.5;
    let (x, wf, ke, wg, counts) = incline_run(&mesh, spec.clone(), 30.0, 1.0);
    assert!(within(x, 0.7534, 0.01), "x = {x}");
    assert!(within(wf, 2560.12, 0.01), "friction {wf}");
    assert!(within(ke, 1135.10, 0.01), "kinetic {ke}");
    assert!(within(wg, 3695.22, 0.01), "gravity {wg}");
    assert!((wg - wf - ke).abs() < 0.01 * wg, "balance {wg} {wf} {ke}");
    assert_eq!(counts.0, [0, 0, 4, 0]);
    spec.mu_s = 0.3;
    spec.mu_d = 0.25;
    let (x, ..) = incline_run(&mesh, spec, 20.0, 1.0);
    assert!(within(x, 0.5 * 1.0506, 0.01), "x = {x}");
}

/// Base 4 × 1 elements (x ∈ [0, 4]), block 1 × 1 at x ∈ [0.25, 1.25] resting on it:
/// nodes do not coincide; the block slides across face boundaries.
#[test]
fn w6_incline_point_to_surface() {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [4.0, 1.0, 1.0], [4, 1, 1]),
            block("top", [0.25, 0.0, 1.0], [1.0, 1.0, 1.0], [1, 1, 1]),
        ],
        split: vec![],
        merge_tolerance: 1e-6,
    }
    .build("w6.toml")
    .unwrap();
    let mut spec = InterfaceSpec::new("w6", "top.zmin", "base.zmax", 0.5, 0.4, 0.0);
    spec.mode = ContactMode::Surface;
    let (x, wf, ke, wg, counts) = incline_run(&mesh, spec.clone(), 30.0, 1.0);
    assert!(within(x, 0.7534, 0.01), "x = {x}");
    assert!(within(wf, 2560.12, 0.01), "friction {wf}");
    assert!(within(ke, 1135.10, 0.01), "kinetic {ke}");
    assert!((wg - wf - ke).abs() < 0.01 * wg, "balance {wg} {wf} {ke}");
    assert_eq!(counts.1, [0, 0, 4, 0]);
    spec.mu_s = 0.6;
    let (x, ..) = incline_run(&mesh, spec, 30.0, 0.5);
    assert!(x.abs() < 1e-9, "30°, μs = 0.6 must stick: x = {x}");
}

/// Paired block that slides past its threshold continues in point-to-surface contact over
/// a larger base (surface b extends beyond surface a).
#[test]
fn w6_pairs_switch_to_surface_after_large_slip() {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [4.0, 1.0, 1.0], [4, 1, 1]),
            block("top", [0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [1, 1, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("w6.toml")
    .unwrap();
    let mut spec = InterfaceSpec::new("w6", "top.zmin", "base.zmax", 0.5, 0.4, 0.0);
    let e = ContactSystem::new(&mesh, std::slice::from_ref(&spec), "w6.toml").unwrap_err();
    assert!(e.to_string().contains("b_may_extend"), "{e}");
    spec.b_may_extend = true;
    spec.slip_threshold = Some(0.05);
    let (x, wf, ke, _, counts) = incline_run(&mesh, spec, 30.0, 1.0);
    assert!(within(x, 0.7534, 0.01), "x = {x}");
    assert!(within(wf, 2560.12, 0.01), "friction {wf}");
    assert!(within(ke, 1135.10, 0.01), "kinetic {ke}");
    assert_eq!(counts, ([0; 4], [0, 0, 4, 0]));
}

#[test]
fn interface_spec_reads_from_toml_with_defaults() {
    let spec: InterfaceSpec = toml::from_str(
        r#"
        name = "lining"
        surface_a = "lining-rock"
        surface_b = "rock-lining"
        mu_s = 0.6
        mu_d = 0.5
        cohesion = 2.0e5
        "#,
    )
    .unwrap();
    assert_eq!(
        spec,
        InterfaceSpec::new("lining", "lining-rock", "rock-lining", 0.6, 0.5, 2e5)
    );
    let spec: InterfaceSpec = toml::from_str(
        r#"
        name = "w6"
        surface_a = "top.zmin"
        surface_b = "base.zmax"
        mu_s = 0.5
        mu_d = 0.4
        cohesion = 0.0
        tensile_strength = 1.0e5
        mode = "surface"
        slip_threshold = 0.1
        tolerance = 1e-3
        "#,
    )
    .unwrap();
    assert_eq!(spec.mode, ContactMode::Surface);
    assert_eq!(spec.tensile_strength, Some(1e5));
    assert_eq!(spec.slip_threshold, Some(0.1));
    let e = toml::from_str::<InterfaceSpec>(
        "name = \"x\"\nsurface_a = \"a\"\nsurface_b = \"b\"\nmu_s = 0.5\nmu_d = 0.4\ncohesion = 0.0\nfriction = 1.0\n",
    )
    .unwrap_err();
    assert!(e.to_string().contains("friction"), "{e}");
}

#[test]
fn compute_rejects_inconsistent_inputs() {
    let mut rig = Rig::w9();
    let n = rig.mesh.n_nodes();
    let zero = vec![[0.0; 3]; n];
    let short = vec![[0.0; 3]; n - 1];
    let mut inp = ContactStepInput {
        step: 7,
        time: 0.0,
        dt: DT,
        inv_mass: &rig.w,
        coords: &rig.mesh.coords,
        u_old: &zero,
        u_pred: &short,
        v_pred: &zero,
    };
    let e = rig.sys.compute(&inp, &mut rig.r).unwrap_err();
    assert!(contact_message(e).contains("step 7"));
    inp.u_pred = &zero;
    inp.dt = 0.0;
    let e = rig.sys.compute(&inp, &mut rig.r).unwrap_err();
    assert!(contact_message(e).contains("time step"));
    assert!(!rig.sys.is_empty());
    assert!(ContactSystem::new(&rig.mesh, &[], "t").unwrap().is_empty());
}

/// A block in the corner between a floor and a wall, three bodies split from one another:
/// floor x ∈ [0, 3], z ∈ [0, 1]; block x ∈ [0, 2], z ∈ [1, 2]; wall x ∈ [2, 3], z ∈ [1, 3].
/// Along the edge x = 2, z = 1 the floor, the block and the wall each have a node, and the
/// three interfaces (floor–block, floor–wall, block–wall) pair them in a triangle.
fn corner_mesh() -> Mesh {
    BoxMeshSpec {
        blocks: vec![
            block("floor", [0.0; 3], [3.0, 1.0, 1.0], [3, 1, 1]),
            block("block", [0.0, 0.0, 1.0], [2.0, 1.0, 1.0], [2, 1, 1]),
            block("wall", [2.0, 0.0, 1.0], [1.0, 1.0, 2.0], [1, 1, 2]),
        ],
        split: vec![
            ["floor".into(), "block".into()],
            ["floor".into(), "wall".into()],
            ["block".into(), "wall".into()],
        ],
        merge_tolerance: 1e-6,
    }
    .build("t.toml")
    .unwrap()
}

fn corner_specs(cohesion: f64) -> Vec<InterfaceSpec> {
    vec![
        InterfaceSpec::new(
            "floor_block",
            "floor-block",
            "block-floor",
            0.6,
            0.5,
            cohesion,
        ),
        InterfaceSpec::new("floor_wall", "floor-wall", "wall-floor", 0.6, 0.5, cohesion),
        InterfaceSpec::new("block_wall", "block-wall", "wall-block", 0.6, 0.5, cohesion),
    ]
}

/// A small deterministic pseudo-random number in [−1, 1) (splitmix64).
fn noise(seed: u64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

#[test]
fn interfaces_that_meet_are_solved_jointly() {
    let mesh = corner_mesh();
    // The direct solve (default) and the sweeps (its fallback) both hold every bonded pair.
    for direct in [true, false] {
        let mut sys = ContactSystem::new(&mesh, &corner_specs(1e12), "t.toml").unwrap();
        assert_eq!(sys.groups, vec![vec![0, 1, 2]]);
        sys.direct_joint = direct;
        let (joint, total, stats) = corner_step(&mesh, sys);
        assert!(
            joint <= 1e-13,
            "direct {direct}: largest relative displacement of a pair {joint:e} m"
        );
        assert!(
            total <= 1e-9,
            "direct {direct}: contact forces sum to {total:e} of the largest"
        );
        // The loop of three bonded pairs (a singular system) is solved directly.
        assert_eq!(stats.direct, u64::from(direct), "{stats:?}");
        assert_eq!(stats.fallbacks, 0, "{stats:?}");
    }
    // The same step with the interfaces solved one after the other (each its own group)
    // leaves the junction pairs apart: the test can tell the two solves apart.
    let mut sys = ContactSystem::new(&mesh, &corner_specs(1e12), "t.toml").unwrap();
    sys.groups = vec![vec![0], vec![1], vec![2]];
    let (sequential, _, _) = corner_step(&mesh, sys);
    assert!(sequential > 1e-6, "sequential solve: {sequential:e} m");
}

/// Unequal inverse masses and a random predicted motion from rest for the corner meshes
/// (each component ±0.1 mm), the nodes that `pressed` selects pushed 1 mm down more:
/// (w, Ū, V̄).
type Motion = (Vec<f64>, Vec<[f64; 3]>, Vec<[f64; 3]>);
fn corner_motion(mesh: &Mesh, pressed: impl Fn(usize) -> bool) -> Motion {
    let n = mesh.n_nodes();
    let w: Vec<f64> = (0..n).map(|k| 1.0 + 0.9 * noise(k as u64)).collect();
    let u_pred: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let mut u = [0, 1, 2].map(|d| 1e-4 * noise(1000 + 3 * k as u64 + d));
            if pressed(k) {
                u[2] -= 1e-3;
            }
            u
        })
        .collect();
    let v_pred: Vec<[f64; 3]> = u_pred.iter().map(|u| geom::scale(1.0 / DT, *u)).collect();
    (w, u_pred, v_pred)
}

/// One step of `sys` from rest with the motion `m`: the contact forces.
fn motion_step(mesh: &Mesh, sys: &mut ContactSystem, m: &Motion) -> Vec<[f64; 3]> {
    let n = mesh.n_nodes();
    let zero = vec![[0.0; 3]; n];
    let mut r = vec![[0.0; 3]; n];
    let inp = ContactStepInput {
        step: 1,
        time: 0.0,
        dt: DT,
        inv_mass: &m.0,
        coords: &mesh.coords,
        u_old: &zero,
        u_pred: &m.1,
        v_pred: &m.2,
    };
    sys.compute(&inp, &mut r).unwrap();
    r
}

/// One step of the corner from rest with random predicted motions and unequal masses:
/// (largest relative displacement of a pair after the step, |Σ R| / largest |R|, the work
/// counts of the joint solve).
fn corner_step(mesh: &Mesh, mut sys: ContactSystem) -> (f64, f64, JointStats) {
    // Junction pairs: the two edge nodes on each of the three interfaces.
    let junctions: usize = sys
        .interfaces
        .iter()
        .map(|i| i.slaves.iter().filter(|s| s.junction).count())
        .sum();
    assert_eq!(junctions, 6);
    // Every bonded pair must end with no relative displacement, whatever the order the
    // interfaces are visited in.
    let m = corner_motion(mesh, |_| false);
    let r = motion_step(mesh, &mut sys, &m);
    let (w, u_pred) = (&m.0, &m.1);
    let u = |k: u32| axpy(u_pred[k as usize], DT * DT * w[k as usize], r[k as usize]);
    let mut worst: f64 = 0.0;
    for k in 0..3 {
        assert_eq!(sys.state_counts(k).0[0], sys.pairs(k).len(), "all bonded");
        for (a, b, _, _) in sys.pairs(k) {
            worst = worst.max(norm(sub(u(b), u(a))));
        }
    }
    // The contact forces are internal: they sum to zero.
    let total = r.iter().fold([0.0; 3], |acc, f| geom::add(acc, *f));
    (
        worst,
        norm(total) / r.iter().map(|f| norm(*f)).fold(0.0, f64::max),
        sys.joint_stats(),
    )
}

/// The corner of [`corner_mesh`] at half the element size, so that the floor–block
/// interface has pairs away from the junction too: floor 6 × 2 × 1 elements, block 4 × 2 × 1,
/// wall 2 × 2 × 2.
fn fine_corner_mesh() -> Mesh {
    BoxMeshSpec {
        blocks: vec![
            block("floor", [0.0; 3], [3.0, 1.0, 1.0], [6, 2, 1]),
            block("block", [0.0, 0.0, 1.0], [2.0, 1.0, 1.0], [4, 2, 1]),
            block("wall", [2.0, 0.0, 1.0], [1.0, 1.0, 2.0], [2, 2, 2]),
        ],
        split: vec![
            ["floor".into(), "block".into()],
            ["floor".into(), "wall".into()],
            ["block".into(), "wall".into()],
        ],
        merge_tolerance: 1e-6,
    }
    .build("t.toml")
    .unwrap()
}

/// A junction with a node in large slip: on the fine corner, the floor node in the middle
/// of the edge x = 2, z = 1 (on all three interfaces) leaves its floor–block pair and
/// contacts the block's bottom (point-to-surface), while its pair with the wall and the
/// block–wall pair stay bonded. One step pressing the block and the wall onto the floor
/// with random motions and unequal masses: the group must settle with every pair and the
/// point-to-surface node on its contact law, in few sweeps, and after the first sweep each
/// sweep may solve only the pairs that the others change (at the junction, or sharing a
/// node with the point-to-surface system), not the whole floor–block interface.
#[test]
fn junction_with_a_point_to_surface_node_settles_in_few_sweeps() {
    let mesh = fine_corner_mesh();
    for direct in [true, false] {
        junction_with_a_point_to_surface_node(&mesh, direct);
    }
}

fn junction_with_a_point_to_surface_node(mesh: &Mesh, direct: bool) {
    let mut sys = ContactSystem::new(mesh, &corner_specs(1e12), "t.toml").unwrap();
    sys.direct_joint = direct;
    assert_eq!(sys.groups, vec![vec![0, 1, 2]]);
    let edge_mid = |p: [f64; 3]| {
        (p[0] - 2.0).abs() < 1e-9 && (p[1] - 0.5).abs() < 1e-9 && (p[2] - 1.0).abs() < 1e-9
    };
    let k = sys.interfaces[0]
        .slaves
        .iter()
        .position(|s| edge_mid(mesh.coords[s.node as usize]))
        .expect("floor node on the junction edge");
    let slave = sys.interfaces[0].slaves[k].node;
    assert!(sys.interfaces[0].slaves[k].junction);
    // Large slip: the switch of `apply_switches`.
    sys.interfaces[0].slaves[k].surface = true;
    sys.interfaces[0].slaves[k].partner = NONE;
    // Block and wall pressed down by 1 mm (with ±0.1 mm of noise), the floor by the noise.
    let floor = &sys.interfaces[0].slaves;
    let m = corner_motion(mesh, |k| {
        mesh.coords[k][2] > 1.0 - 1e-9 && !floor.iter().any(|s| s.node == k as u32)
    });
    let r = motion_step(mesh, &mut sys, &m);
    let (w, u_pred) = (&m.0, &m.1);
    assert_eq!(sys.unsettled_joint_steps().0, 0, "the group settled");
    let stats = sys.joint_stats();
    assert_eq!(stats.group_steps, 1);
    // Every bonded pair holds its nodes together.
    let u = |k: u32| axpy(u_pred[k as usize], DT * DT * w[k as usize], r[k as usize]);
    for i in 0..3 {
        for (a, b, _, _) in sys.pairs(i).into_iter().filter(|p| p.1 != NONE) {
            let d = norm(sub(u(b), u(a)));
            assert!(
                d <= 1e-12,
                "direct {direct}: interface {i}: pair {a}–{b} apart by {d:e} m"
            );
        }
    }
    // The point-to-surface node: in contact with the block's bottom, its gap closed, its
    // force compressive and inside the Coulomb cone.
    let s = &sys.interfaces[0].slaves[k];
    assert_eq!(s.state, PairState::Stick, "pressed, held by the bonds");
    let face = sys.interfaces[0].b_faces[s.face as usize];
    let phi = geom::face_shape(s.xi[0], s.xi[1]);
    let x = |k: u32| geom::add(mesh.coords[k as usize], u(k));
    let c = (0..4).fold([0.0; 3], |acc, j| axpy(acc, phi[j], x(face[j])));
    let gap = sub(c, x(slave))[2];
    assert!(gap.abs() <= 1e-12, "direct {direct}: gap {gap:e} m");
    let lambda = r_normal(s.force);
    assert!(lambda > 0.0, "normal force {lambda}");
    let t = norm([s.force[0], s.force[1], 0.0]);
    assert!(
        t <= 0.6 * lambda * (1.0 + 1e-9),
        "|T| = {t} > μs λ = {}",
        0.6 * lambda
    );
    // The contact forces are internal.
    let total = r.iter().fold([0.0; 3], |acc, f| geom::add(acc, *f));
    let fmax = r.iter().map(|f| norm(*f)).fold(0.0, f64::max);
    assert!(norm(total) <= 1e-9 * fmax, "sum {:e}", norm(total));
    // After the first sweep (or in the direct system), only the pairs at the junction or
    // sharing a node with the point-to-surface system are solved again: the old solve
    // restarted the whole floor–block interface (all its pairs, at least twice) in every
    // sweep.
    let faces = &sys.interfaces;
    let selected: u64 = faces
        .iter()
        .map(|i| {
            i.slaves
                .iter()
                .enumerate()
                .filter(|(k, s)| !s.surface && (s.junction || i.faces.coupled(sys.stamp, *k)))
                .count() as u64
        })
        .sum();
    let floor_block = faces[0].slaves.iter().filter(|s| !s.surface).count() as u64;
    assert!(selected < 2 * floor_block, "{selected} of {floor_block}");
    if direct {
        // One system of the selected pairs and the point-to-surface node, solved at once:
        // the active set needs no switch (all stick), the polish confirms it in ≤ 2 sweeps
        // (the first sweep moves nothing by more than the regularisation, 1e-11).
        assert_eq!((stats.direct, stats.fallbacks, stats.sweeps), (1, 0, 0));
        // The system: the junction pairs of every interface, and the floor–block pairs that
        // share a node with the point-to-surface node's face (the other two interfaces
        // have no point-to-surface node), plus that node.
        let in_system = |i: usize, k: usize, s: &SlaveNode| {
            !s.surface && (s.junction || (i == 0 && faces[0].faces.coupled(sys.stamp, k)))
        };
        let (mut system, mut pairs) = (0u64, 0u64);
        for (i, iface) in faces.iter().enumerate() {
            for (k, s) in iface.slaves.iter().enumerate() {
                pairs += u64::from(!s.surface);
                system += u64::from(in_system(i, k, s));
            }
        }
        assert!(system < selected, "{system} of {selected}");
        assert_eq!(stats.max_system, system + 1, "{stats:?}");
        assert_eq!(stats.max_active_set_solves, 1, "{stats:?}");
        assert!(stats.max_polish_sweeps <= 2, "{stats:?}");
        // Every other pair is solved once, on its own.
        assert_eq!(stats.pair_solves, pairs - system, "{stats:?}");
        return;
    }
    // Few sweeps: bonded pairs and a sticking node are linear constraints, and the sweeps
    // of the junction are alternating projections onto them in the mass metric; each sweep
    // here removes at least half of what is left, so the tolerance (1e-10) is reached well
    // within 40 sweeps (the old solve also settled in that many: the count guards against
    // a walk along the loop).
    assert!(stats.max_sweeps <= 40, "{} sweeps", stats.max_sweeps);
    assert!(
        stats.late_pair_solves <= (stats.sweeps - 1) * selected,
        "{} pair solves in {} sweeps after the first ({selected} selected)",
        stats.late_pair_solves,
        stats.sweeps - 1
    );
}

/// Normal (compressive, +z) part of a force on the floor node from the block above.
fn r_normal(f: [f64; 3]) -> f64 {
    -f[2]
}

/// The direct solve and the sweeps are two ways to the same joint solution: on the fine
/// corner with a weak bond (c = σt = 50 Pa, capacities of 12.5–50 N against forces of
/// ≈ 100 N from the ±0.1 mm random motion), so that some pairs hold, some lose their bond
/// in tension and separate and some slide, both must give every node the same net contact
/// force and every pair off the junction the same state.
#[test]
fn direct_solve_and_sweeps_agree_where_bonds_break() {
    let mesh = fine_corner_mesh();
    let m = corner_motion(&mesh, |_| false);
    let solve = |direct: bool| {
        let mut sys = ContactSystem::new(&mesh, &corner_specs(50.0), "t.toml").unwrap();
        sys.direct_joint = direct;
        let r = motion_step(&mesh, &mut sys, &m);
        let states: Vec<(PairState, bool)> = sys
            .interfaces
            .iter()
            .flat_map(|i| i.slaves.iter().map(|s| (s.state, s.junction)))
            .collect();
        (r, states, sys.joint_stats())
    };
    let (r_direct, s_direct, stats) = solve(true);
    assert_eq!((stats.direct, stats.fallbacks), (1, 0), "{stats:?}");
    let (r_sweeps, s_sweeps, _) = solve(false);
    let count = |s: &[(PairState, bool)], want: PairState| s.iter().filter(|x| x.0 == want).count();
    // The case exercises the laws: bonds that hold, bonds that broke.
    assert!(count(&s_direct, PairState::Bonded) > 0, "{s_direct:?}");
    assert!(count(&s_direct, PairState::Separated) > 0, "{s_direct:?}");
    assert!(count(&s_direct, PairState::Sliding) > 0, "{s_direct:?}");
    // Same state for every pair off the junction. At the junction, the three pairs that
    // join the three coincident nodes of a point of the edge close a loop whose split is
    // free (module `joint`): there a pair may carry a force in one solution (sliding, gap
    // closed) and none in the other (separated with a gap of 1e-14 m) — measured here at
    // one pair — with the same net forces (below).
    for (d, s) in s_direct.iter().zip(&s_sweeps) {
        assert!(d.1 || d.0 == s.0, "{s_direct:?}\n{s_sweeps:?}");
    }
    let fmax = r_sweeps.iter().map(|f| norm(*f)).fold(0.0, f64::max);
    let worst = r_direct
        .iter()
        .zip(&r_sweeps)
        .map(|(a, b)| norm(sub(*a, *b)))
        .fold(0.0, f64::max);
    assert!(
        worst <= 1e-8 * fmax,
        "net forces differ by {worst:e} of {fmax:e} N"
    );
}
