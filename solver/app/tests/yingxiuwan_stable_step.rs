//! `dcfm mesh yingxiuwan --stable-step shared_mass`: the case it writes bounds its step with
//! the nodal masses shared among the elements, and the step it writes — taken from the
//! model before the static stage — is still admitted by the dynamic stage after the
//! excavation and the anchors' steel have changed the nodal masses.

use dcfm::case::load_case;
use dcfm::model::StepBound;
use dcfm::stage::static_stage;
use dcfm_app::mesh_cmd::{mesh_yingxiuwan, MeshRequest};

fn mesh(dir: &std::path::Path, stable_step: Option<&str>) -> dcfm::Result<std::path::PathBuf> {
    let _ = std::fs::remove_dir_all(dir);
    Ok(mesh_yingxiuwan(&MeshRequest {
        variant: "ci",
        measure: "none",
        end: Some(0.1),
        stable_step,
        out: dir,
    })?
    .case_file)
}

#[test]
fn the_shared_mass_case_takes_a_larger_step_that_the_dynamic_stage_admits() {
    let root = std::env::temp_dir().join(format!("dcfm-yx-step-{}", std::process::id()));
    let element = load_case(&mesh(&root.join("element"), Some("element")).unwrap()).unwrap();
    let file = mesh(&root.join("shared"), Some("shared_mass")).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("stable_step = \"shared_mass\""), "{text}");
    let shared = load_case(&file).unwrap();
    assert_eq!(element.model.step_bound, StepBound::Element);
    assert_eq!(shared.model.step_bound, StepBound::SharedMass);
    assert!(
        shared.dt > element.dt,
        "shared-mass step {:e} s not above the elements' {:e} s",
        shared.dt,
        element.dt
    );
    // The static stage excavates the caverns and places the linings; the anchors' steel
    // joins the host nodes at the hand-over. The step written before must still pass the
    // check against the bound of that model.
    let plan = shared.static_plan.as_ref().unwrap();
    let (model, result) = static_stage::run(shared.model, plan).unwrap();
    let sim = static_stage::start_dynamic(model, &result, shared.dt, shared.safety).unwrap();
    assert!(sim.dt <= shared.safety * sim.model.critical_step_with_damping() * (1.0 + 1e-12));
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn an_unknown_stable_step_is_refused_naming_the_option() {
    let dir = std::env::temp_dir().join(format!("dcfm-yx-step-bad-{}", std::process::id()));
    let e = mesh(&dir, Some("global")).unwrap_err().to_string();
    assert!(
        e.contains("--stable-step") && e.contains("global") && e.contains("shared_mass"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn without_the_option_the_full_case_shares_the_masses_and_the_ci_case_keeps_its_bound() {
    use dcfm::mesh::generators::yingxiuwan::Variant;
    use dcfm_app::mesh_cmd::default_step_bound;
    assert_eq!(default_step_bound(Variant::Full), StepBound::SharedMass);
    assert_eq!(default_step_bound(Variant::Ci), StepBound::Element);
    let dir = std::env::temp_dir().join(format!("dcfm-yx-step-default-{}", std::process::id()));
    let file = mesh(&dir, None).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(!text.contains("shared_mass"), "{text}");
    assert_eq!(
        load_case(&file).unwrap().model.step_bound,
        StepBound::Element
    );
    let _ = std::fs::remove_dir_all(&dir);
}
