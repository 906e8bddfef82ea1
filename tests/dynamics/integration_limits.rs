//! Where an integration stops: fixed steps above the critical step, impossible steps and loads
//! named as errors, prescribed motions, the Dormand–Prince stability polynomial, cancellation.

use flexmodes::dynamics::{DivergenceCause, DynamicsError};
use flexmodes::{
    Progress,
    dynamics::{IntegratorParameters, Motion, simulate},
    error::CoreError as Error,
    fem::{SlabParameters, slab},
    models::{Scenario, slab_body, slab_system},
    reduction::Method,
};

use super::integrations::{BOUNDARY, nodal};

/// Highest circular frequency of the reduced body, rad/s: $\max\sqrt{\lambda}$ of
/// $K_{zz}\phi = \lambda M_{zz}\phi$ by a Cholesky factor of $M_{zz}$ and a symmetric eigensolve.
fn highest_circular_frequency(body: &flexmodes::dynamics::FlexibleBody) -> f64 {
    let l = body.m_zz.clone().cholesky().unwrap().l();
    let li = l.clone().try_inverse().unwrap();
    let a = &li * &body.k_zz * li.transpose();
    let a = (&a + a.transpose()) * 0.5;
    a.symmetric_eigenvalues().max().sqrt()
}

#[test]
fn fixed_steps_diverge_above_the_critical_step_and_not_below() {
    // The critical step of Dormand–Prince on an undamped system is y_c / omega_max with y_c
    // the end of its stability interval on the imaginary axis, where |R(iy)| first exceeds 1:
    // R = 1 + z + z²/2 + z³/6 + z⁴/24 + z⁵/120 + z⁶/600 gives |R(i)|² - 1 = 2.78e-6 > 0 and
    // |R(0.99 i)| < 1. Just above y_c the growth is slow (|R(1.5 i)| = 1.003 per step); at
    // 3 y_c it is 1.44 per step. The held slab's CB body is integrated with fixed steps 10 %
    // below y_c / omega_max and three times above it.
    let y_c = flexmodes::dynamics::imaginary_stability_limit();
    assert!((0.99..1.0).contains(&y_c), "DP5 imaginary-axis limit {y_c}");
    let model = slab(&SlabParameters::default());
    let body = slab_body(&model, Method::CraigBampton, nodal(), &BOUNDARY, 6).unwrap();
    let omega = highest_circular_frequency(&body);
    let critical = flexmodes::dynamics::critical_step(omega);
    let (system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
    let run = |factor: f64| {
        let p = IntegratorParameters {
            end_time: 4.0,
            output_interval: 0.2,
            fixed_step: Some(factor * critical),
            ..Default::default()
        };
        // Steps per output interval stay well above one, so the fixed step, not the output
        // grid, sets the step.
        assert!(p.output_interval > 10.0 * factor * critical);
        simulate(&system, &state, &p, &Progress::default())
    };
    eprintln!("omega_max {omega} rad/s, critical step {critical:e} s");
    let below = run(0.9).expect("10 % below the critical step stays bounded");
    assert_eq!(below.rejected, 0);
    assert!(below.steps as f64 >= 4.0 / (0.9 * critical) - 1.0);
    let energy: Vec<f64> = below.samples.iter().map(|s| s.energy).collect();
    let spread = energy
        .iter()
        .fold(0.0f64, |m, e| m.max((e - energy[0]).abs()));
    match run(3.0) {
        Err(Error::Dynamics(DynamicsError::Diverged { time, cause })) => {
            assert!(time < 4.0 && time > 0.0, "{time}: {cause}");
            assert!(
                matches!(
                    cause,
                    DivergenceCause::FixedStepBeyondBound { .. }
                        | DivergenceCause::FixedStepSingular { .. }
                ),
                "{cause}"
            );
            assert!(cause.to_string().contains("fixed step"), "{cause}");
        }
        other => panic!(
            "expected Diverged at three times the critical step {critical:e} s, got {other:?}",
            other = other.map(|s| s.steps)
        ),
    }
    // Below the limit the (slightly dissipative) scheme keeps the energy.
    assert!(
        spread < 1e-3 * energy[0].abs().max(1.0),
        "energy spread {spread:e}"
    );
}

/// A force at a node the slab does not have (it has 45) is refused before any step, naming
/// the body and the node, never integrated or indexed out of range.
#[test]
fn a_load_at_a_node_the_body_lacks_is_a_named_error() {
    let model = slab(&SlabParameters::default());
    let body = slab_body(&model, Method::CraigBampton, nodal(), &BOUNDARY, 6).unwrap();
    let (mut system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
    let nodes = model.node_count();
    system.nodal_forces.push((
        0,
        flexmodes::fem::NodeIndex(nodes),
        nalgebra::Vector3::new(0.0, 0.0, -1.0),
    ));
    let p = IntegratorParameters {
        end_time: 0.01,
        ..Default::default()
    };
    match simulate(&system, &state, &p, &Progress::default()) {
        Err(Error::Dynamics(DynamicsError::BadAttachment { what, place })) => {
            assert_eq!(what, "force");
            assert_eq!(
                place,
                flexmodes::error::AttachmentProblem::NoSuchNode {
                    body: 0,
                    node: nodes + 1
                }
            );
        }
        other => panic!(
            "expected BadAttachment, got {other:?}",
            other = other.map(|s| s.steps)
        ),
    }
}

#[test]
fn an_impossible_step_size_is_a_named_error() {
    let model = slab(&SlabParameters::default());
    let body = slab_body(&model, Method::CraigBampton, nodal(), &BOUNDARY, 6).unwrap();
    let (system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
    let p = IntegratorParameters {
        end_time: 0.5,
        rtol: 1e-14,
        atol: 1e-16,
        min_step: 1e-4,
        ..Default::default()
    };
    match simulate(&system, &state, &p, &Progress::default()) {
        Err(Error::Dynamics(DynamicsError::Diverged { time, cause })) => {
            assert!(time < 0.5);
            assert_eq!(cause, DivergenceCause::StepTooSmall { min_step: 1e-4 });
            assert!(cause.to_string().contains("fell below"), "{cause}");
        }
        other => panic!(
            "expected Diverged, got {other:?}",
            other = other.map(|s| s.steps)
        ),
    }
}

#[test]
fn prescribed_tables_integrate_exactly() {
    // Linear acceleration a(t) = 1 + 2t sampled every 0.1 s: x = x0 + v0 t + t²/2 + t³/3.
    let values: Vec<f64> = (0..=20).map(|i| 1.0 + 2.0 * 0.1 * i as f64).collect();
    let m = Motion::table(0.1, values);
    for &t in &[0.0, 0.05, 0.7, 1.234, 1.99] {
        let (x, v, a) = m.at(t, 0.5, -1.0);
        assert!((a - (1.0 + 2.0 * t)).abs() < 1e-12);
        assert!((v - (-1.0 + t + t * t)).abs() < 1e-12, "v({t})");
        assert!(
            (x - (0.5 - t + t * t / 2.0 + t * t * t / 3.0)).abs() < 1e-12,
            "x({t})"
        );
    }
    // Eq. (7.10) components: derivatives consistent by central differences.
    for sine in [false, true] {
        let m = Motion::Harmonic {
            a: 4.0 * std::f64::consts::TAU.powi(2),
            omega: std::f64::consts::TAU,
            c2: 0.25,
            sine,
        };
        let h = 1e-5;
        for &t in &[0.1, 0.37, 0.8] {
            let (xp, vp, _) = m.at(t + h, 4.0, 1.0);
            let (xm, vm, _) = m.at(t - h, 4.0, 1.0);
            let (_, v, a) = m.at(t, 4.0, 1.0);
            assert!(((xp - xm) / (2.0 * h) - v).abs() < 1e-5 * v.abs().max(1.0));
            assert!(((vp - vm) / (2.0 * h) - a).abs() < 1e-5 * a.abs().max(1.0));
        }
        assert_eq!(m.at(0.0, 4.0, 1.0).0, 4.0);
        assert_eq!(m.at(0.0, 4.0, 1.0).1, 1.0);
    }
}

#[test]
fn dormand_prince_stability_polynomial() {
    // Hairer & Wanner: R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 + z⁵/120 + z⁶/600 for DOPRI5.
    let c = flexmodes::dynamics::stability_polynomial();
    let expected = [
        1.0,
        1.0,
        0.5,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 600.0,
        0.0,
    ];
    assert_eq!(c.len(), expected.len());
    for (k, (a, b)) in c.iter().zip(expected).enumerate() {
        assert!((a - b).abs() < 1e-15, "c_{k} = {a}, expected {b}");
    }
    let y = flexmodes::dynamics::imaginary_stability_limit();
    assert!(y > 0.9 && y < 1.05, "{y}");
}

/// A superseded request stops its time integration with a named error; a run nobody cancels
/// reports reaching its end time.
#[test]
fn cancelled_integration_stops_with_named_error() {
    let run = flexmodes::scenes::find("slab-sim1").unwrap().run;
    let options = |progress: &Progress| flexmodes::scenes::SceneOptions {
        methods: Some(vec![Method::CraigBampton]),
        end_time: Some(0.5),
        progress: progress.clone(),
        ..Default::default()
    };

    let done = Progress::new();
    run(&options(&done)).unwrap();
    let r = done.reading().unwrap();
    assert_eq!(r.simulations, 1);
    assert!((r.time - 0.5).abs() < 1e-12 && r.end_time == 0.5, "{r:?}");

    // Cancelled before it starts: not one step.
    let early = Progress::new();
    early.cancel();
    assert!(matches!(run(&options(&early)), Err(ref e) if e.is_cancelled()));
    // The scene stops at its first phase boundary, before the integration starts.
    assert!(
        early.reading().is_none_or(|r| r.time == 0.0),
        "{:?}",
        early.reading()
    );

    // Cancelled from another thread once past 0.05 s: stops before the end.
    let mid = Progress::new();
    let watcher = mid.clone();
    let cancel_thread = std::thread::spawn(move || {
        let start = std::time::Instant::now();
        while watcher.reading().is_none_or(|r| r.time < 0.05)
            && start.elapsed() < std::time::Duration::from_secs(120)
        {
            std::thread::sleep(std::time::Duration::from_micros(200));
        }
        watcher.cancel();
    });
    let result = run(&options(&mid));
    cancel_thread.join().unwrap();
    assert!(
        matches!(result, Err(ref e) if e.is_cancelled()),
        "{:?}",
        result.as_ref().err()
    );
    let r = mid.reading().unwrap();
    assert!(r.time >= 0.05 && r.time < 0.5, "{r:?}");

    // Handles compare equal only when they share their state.
    assert_eq!(Progress::default(), Progress::default());
    assert_eq!(mid, mid.clone());
    assert_ne!(mid, Progress::new());
    assert!(Progress::default().reading().is_none());
}
