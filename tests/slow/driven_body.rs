//! A body no flexmodes code made (the steel rod: gmsh + scikit-fem, consistent mass), driven
//! through a rigid interface, against SciPy (`assets/generate/driven_reference.py`: its clamped
//! frequencies by eigsh, the steady spin by spsolve, and the spin-up of its 20 lowest clamped
//! modes integrated by DOP853 at rtol 1e-11).

use std::path::PathBuf;

use flexmodes::{
    Progress,
    body_file::ImportedBody,
    dynamics::{AxisKind, DrivenIntegration},
    error::DynamicsError,
    models::{DrivenBodyParameters, DrivenStudy, driven_body_study, history_error},
    reduction::Method,
};
use serde_json::Value;

fn rod() -> (ImportedBody, Value) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bodies/steel-rod");
    let body = ImportedBody::load(dir.join("body.toml").to_str().unwrap()).unwrap();
    let reference: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("driven_reference.json")).unwrap())
            .unwrap();
    (body, reference)
}

/// The reference's set-up with step `dt`, sampled at its eight intervals.
fn parameters(reference: &Value, dt: f64) -> DrivenBodyParameters {
    let f = |k: &str| reference[k].as_f64().unwrap();
    let axis: Vec<f64> = reference["axis"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let steps = (f("end") / dt).round() as usize;
    assert_eq!(steps % 8, 0, "the samples fall on the reference's times");
    DrivenBodyParameters {
        drive: format!("rbe2:{}", reference["drive"].as_str().unwrap()),
        axis: [axis[0], axis[1], axis[2]],
        rate: f("rate"),
        ramp: f("ramp"),
        integration: DrivenIntegration {
            step: dt,
            end: f("end"),
            spectral_radius: 0.9,
            output_every: steps / 8,
        },
        ..Default::default()
    }
}

/// The reference's modal history of its one output set, per sample.
fn modal_history(reference: &Value) -> Vec<Vec<[f64; 3]>> {
    let name = reference["outputs"][0].as_str().unwrap();
    vec![
        reference["modal_history"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                let v = s[name].as_array().unwrap();
                [0, 1, 2].map(|a| v[a].as_f64().unwrap())
            })
            .collect(),
    ]
}

fn study(parameters: &DrivenBodyParameters, methods: &[Method], full: bool) -> DrivenStudy {
    let (body, _) = rod();
    driven_body_study(
        &body,
        parameters,
        methods,
        &[20],
        full,
        &Progress::new().muted(),
    )
    .unwrap()
}

/// Modal truncation on the 20 lowest clamped modes spans SciPy's modal model: its natural
/// frequencies on the frame equal eigsh's to 1e-8, and its history converges to DOP853's at
/// second order in the step (generalized-α), 1.1e-4 at 0.1 ms.
#[test]
fn the_spin_up_of_twenty_clamped_modes_converges_to_scipys_at_second_order() {
    let (_, reference) = rod();
    let hz: Vec<f64> = reference["clamped_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let modal = modal_history(&reference);
    let mut errors = Vec::new();
    for dt in [1e-4, 5e-5] {
        let s = study(
            &parameters(&reference, dt),
            &[Method::ModalTruncation],
            false,
        );
        let run = &s.runs[0];
        let (lowest, _) = run.hz_range.unwrap();
        assert!(
            (lowest - hz[0]).abs() <= 1e-8 * hz[0],
            "{lowest} vs {}",
            hz[0]
        );
        assert_eq!(run.outputs[0].len(), modal[0].len(), "samples");
        errors.push(history_error(&modal, &run.outputs));
    }
    assert!(errors[0] < 2e-4, "{errors:?}");
    let order = (errors[0] / errors[1]).log2();
    assert!((1.7..2.3).contains(&order), "order {order} from {errors:?}");
}

/// The full body (sparse) runs the same spin-up: within the modal model's truncation and the
/// step's error of SciPy's history, Craig–Bampton and mode condensation equal to round-off (one
/// subspace), and at the end of the spin the axial stretch of the far end is SciPy's steady
/// state of the full body (spsolve) to 1e-3.
#[test]
fn the_full_body_and_its_reductions_follow_scipys_spin_up() {
    let (_, reference) = rod();
    let s = study(
        &parameters(&reference, 2e-4),
        &[Method::CraigBampton, Method::ModeCondensation],
        true,
    );
    let [nr, cb, mc] = &s.runs[..] else {
        panic!("three runs: {}", s.runs.len())
    };
    assert!(nr.method.is_none());
    let modal = modal_history(&reference);
    let to_scipy = history_error(&modal, &nr.outputs);
    assert!(
        to_scipy < 1e-3,
        "NR against SciPy's modal history: {to_scipy:e}"
    );
    let cb_error = cb.history_error.unwrap();
    assert!(cb_error < 1e-4, "CB 20 against NR: {cb_error:e}");
    let same = history_error(&cb.outputs, &mc.outputs);
    assert!(same < 1e-8, "CB against MC: {same:e}");
    let name = reference["outputs"][0].as_str().unwrap();
    let steady = reference["steady"][name][0].as_f64().unwrap();
    let last = nr.outputs[0].last().unwrap()[0];
    assert!(
        (last - steady).abs() < 1e-3 * steady.abs(),
        "axial stretch {last:e} against the steady {steady:e}"
    );
    // The reaction at the steady rate: the centripetal force of the whole rod,
    // F = -m Ω² (c - x_master)⊥ (mass and centre from the full M), to 1e-3: what is left is
    // the elastic part (the stretch moves c by 1e-5 of its arm, the vibration adds M ü).
    let (body, _) = rod();
    let props = body.model.mass_properties();
    let master = s.drive.1;
    let rate = reference["rate"].as_f64().unwrap();
    let force = nr.reaction.last().unwrap();
    let expected = [0, 1].map(|a| -props.mass * rate * rate * (props.centre[a] - master[a]));
    let size = expected[0].hypot(expected[1]);
    for a in 0..2 {
        assert!(
            (force[a] - expected[a]).abs() < 1e-3 * size,
            "reaction {force:?} against the rigid rod's {expected:?}"
        );
    }
    assert!(
        force[2].abs() < 1e-3 * size,
        "no force along the axis: {force:?}"
    );
}

/// Bad set-ups are named errors: a drive that is no rigid interface, a method whose basis moves
/// the driven ring, Guyan with nothing but the drive.
#[test]
fn a_driven_body_refuses_what_it_cannot_simulate() {
    let (body, reference) = rod();
    let progress = Progress::new().muted();
    let mut p = parameters(&reference, 1e-3);
    p.drive = reference["drive"].as_str().unwrap().into();
    let e = driven_body_study(&body, &p, &[], &[], true, &progress).unwrap_err();
    assert!(e.to_string().contains("rigid interface"), "{e}");
    let p = parameters(&reference, 1e-3);
    let e =
        driven_body_study(&body, &p, &[Method::MacNealRubin], &[5], false, &progress).unwrap_err();
    assert!(e.to_string().contains("held still"), "{e}");
    // Guyan on the drive alone keeps nothing but the drive; its residual vectors would be
    // the only coordinates.
    let mut plain = parameters(&reference, 1e-3);
    plain.residual_vectors = false;
    let e = driven_body_study(&body, &plain, &[Method::Guyan], &[5], false, &progress).unwrap_err();
    assert!(e.to_string().contains("rigid"), "{e}");
    let s = driven_body_study(&body, &p, &[Method::Guyan], &[5], false, &progress).unwrap();
    assert_eq!(s.runs[0].coordinates, s.runs[0].residual_vectors);
}

/// The explicit scheme on the twenty clamped modes: below its predicted critical step it
/// follows SciPy's DOP853 far closer than generalized-α at a millisecond does, and at three
/// times the step it diverges, as the stability region of Dormand–Prince says.
#[test]
fn the_explicit_scheme_follows_scipy_below_its_critical_step_and_diverges_above() {
    let (_, reference) = rod();
    let mut p = parameters(&reference, 1e-3);
    p.explicit = true;
    // SciPy's reference integrates the twenty modes alone.
    p.residual_vectors = false;
    let s = study(&p, &[Method::ModalTruncation], false);
    let [implicit, explicit] = &s.runs[..] else {
        panic!("two runs: {}", s.runs.len())
    };
    assert!(implicit.explicit_step.is_none());
    let check = &s.stability[0];
    let (_, highest) = explicit.hz_range.unwrap();
    assert_eq!(check.highest_hz, highest);
    let step = explicit.explicit_step.unwrap();
    assert!(
        step <= 0.9 * check.critical_s && step > 0.8 * check.critical_s,
        "{step:e}"
    );
    let time = check.diverged_at.expect("3x the critical step diverges");
    assert!(time < 2000.0 * check.above_step_s);
    let modal = modal_history(&reference);
    let dp5 = history_error(&modal, &explicit.outputs);
    let gen_alpha = history_error(&modal, &implicit.outputs);
    assert!(dp5 < 1e-6, "DP5 against DOP853: {dp5:e}");
    assert!(
        gen_alpha > 100.0 * dp5,
        "gen-α at 1 ms {gen_alpha:e}, DP5 {dp5:e}"
    );
}

/// Gravity alone (no turning): the body starts and stays in SciPy's static deflection
/// K u = M(1 ⊗ g); and a spin-up about an axis through another point (the drive orbits it)
/// ends in SciPy's steady state of that spin.
#[test]
fn gravity_and_an_orbit_match_scipys_static_and_steady_states() {
    let (_, reference) = rod();
    let name = reference["outputs"][0].as_str().unwrap();
    let three = |v: &Value| [0, 1, 2].map(|a| v[a].as_f64().unwrap());
    let mut p = parameters(&reference, 1e-3);
    p.rate = 0.0;
    p.gravity = Some(three(&reference["gravity"]));
    let s = study(&p, &[], true);
    let expected = three(&reference["gravity_static"][name]);
    let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (t, u) in s.times.iter().zip(&s.runs[0].outputs[0]) {
        for a in 0..3 {
            assert!(
                (u[a] - expected[a]).abs() < 1e-8 * scale,
                "t = {t}: {u:?} against {expected:?}"
            );
        }
    }
    let mut p = parameters(&reference, 1e-3);
    p.axis_point = Some(three(&reference["orbit_point"]));
    let s = study(&p, &[], true);
    let steady = reference["steady_orbit"][name][0].as_f64().unwrap();
    let last = s.runs[0].outputs[0].last().unwrap()[0];
    assert!(
        (last - steady).abs() < 2e-3 * steady.abs(),
        "axial stretch {last:e} against the steady {steady:e}"
    );
}

/// The same spin-up seen from the body's mean axes ends in SciPy's steady state with its
/// rigid part in the mass metric taken out; principal axes are refused by name.
#[test]
fn the_spin_up_seen_from_mean_axes_ends_in_scipys_mean_axis_steady_state() {
    let (body, reference) = rod();
    let name = reference["outputs"][0].as_str().unwrap();
    let mut p = parameters(&reference, 1e-3);
    p.axes = AxisKind::Mean;
    let s = study(&p, &[], true);
    let steady = reference["steady_mean_axes"][name][0].as_f64().unwrap();
    let last = s.runs[0].outputs[0].last().unwrap()[0];
    assert!(
        (last - steady).abs() < 2e-3 * steady.abs(),
        "mean-axis stretch {last:e} against SciPy's {steady:e}"
    );
    p.axes = AxisKind::Principal;
    let e = driven_body_study(&body, &p, &[], &[], true, &Progress::new().muted()).unwrap_err();
    assert!(e.to_string().contains("principal"), "{e}");
}

/// The far ring pinned to the carrier (its ring turns about its centroid, which keeps its
/// place): the full body ends near SciPy's steady state of the pinned spin at the node
/// farthest from the drive (radial and axial parts to 3e-3, the tangential one within the
/// residual vibration), and Craig–Bampton keeps the pinned master's three rotations.
#[test]
fn a_pinned_ring_turns_about_its_place_as_in_scipys_steady_state() {
    let (_, reference) = rod();
    let mut p = parameters(&reference, 1e-3);
    p.pinned = vec![reference["pinned"].as_str().unwrap().into()];
    let node = reference["pinned_output_node"].as_u64().unwrap();
    p.outputs = vec![format!("node:{node}")];
    let s = study(&p, &[Method::CraigBampton], true);
    let steady: Vec<f64> = reference["steady_pinned"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let size = steady.iter().map(|x| x * x).sum::<f64>().sqrt();
    let last = s.runs[0].outputs[0].last().unwrap();
    for a in [0, 2] {
        assert!(
            (last[a] - steady[a]).abs() < 3e-3 * size,
            "component {a}: {last:?} against {steady:?}"
        );
    }
    assert!(
        (last[1] - steady[1]).abs() < 2e-2 * size,
        "{last:?} against {steady:?}"
    );
    assert_eq!(
        s.runs[1].coordinates,
        20 + 3 + s.runs[1].residual_vectors,
        "20 modes, the pinned master's rotations and the residual vectors"
    );
    assert!(s.runs[1].history_error.unwrap() < 1e-2);
}

/// The explorer keeps the full body's run and each method's apart and joins them: the joined
/// study is the one study of all of them, run for run and error for error (to the bit), and
/// studies sampled at other times are refused, never zipped.
#[test]
fn studies_of_one_drive_join_into_the_study_of_all_their_runs() {
    let (_, reference) = rod();
    let p = parameters(&reference, 1e-3);
    let methods = [Method::ModalTruncation, Method::CraigBampton];
    let whole = study(&p, &methods, true);
    let full = study(&p, &[], true);
    let mt = study(&p, &methods[..1], false);
    let cb = study(&p, &methods[1..], false);
    // The order of the parts does not matter: the full body's run comes first.
    let joined = DrivenStudy::joined(&[&mt, &full, &cb]).unwrap();
    assert_eq!(joined.runs.len(), whole.runs.len());
    for (a, b) in joined.runs.iter().zip(&whole.runs) {
        assert_eq!(a.label(), b.label());
        assert_eq!(a.outputs, b.outputs, "{}", a.label());
        assert_eq!(a.reaction, b.reaction, "{}", a.label());
        assert_eq!(a.history_error, b.history_error, "{}", a.label());
        assert_eq!(a.reaction_error, b.reaction_error, "{}", a.label());
    }
    assert!(joined.runs[1].history_error.unwrap() > 0.0);
    assert_eq!(joined.times, whole.times);
    // Without the full body, no errors.
    let reduced = DrivenStudy::joined(&[&mt, &cb]).unwrap();
    assert!(reduced.runs.iter().all(|r| r.history_error.is_none()));
    let mut every_step = p.clone();
    every_step.integration.output_every = 1;
    let other = study(&every_step, &methods[..1], false);
    let refused = |studies: &[&DrivenStudy], expected: &str| match DrivenStudy::joined(studies) {
        Err(flexmodes::error::CoreError::Dynamics(DynamicsError::StudiesDiffer { what })) => {
            assert_eq!(what, expected)
        }
        other => panic!("{expected}: {:?}", other.map(|s| s.runs.len())),
    };
    refused(&[&full, &other], "sample times");
    // The same samples of a faster spin: another motion, another rigid reaction.
    let mut faster = p.clone();
    faster.rate *= 2.0;
    refused(
        &[&full, &study(&faster, &methods[..1], false)],
        "motion (the rigid reaction)",
    );
    refused(&[], "number: there are none");
}
