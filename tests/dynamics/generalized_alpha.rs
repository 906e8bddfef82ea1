//! The implicit generalized-α scheme: order, energy, constraints, agreement with the explicit
//! scheme, stability above the explicit critical step, and its named error.

use flexmodes::dynamics::DynamicsError;
use flexmodes::{
    Progress,
    analysis::relative_rms,
    dynamics::{
        Body, GeneralizedAlphaCoefficients, IntegrationScheme, IntegratorParameters, Simulation,
        State, System, simulate,
    },
    error::CoreError as Error,
    fem::{SlabParameters, slab},
    models::{
        PROBE_NODE, SLAB_BOUNDARY as BOUNDARY, Scenario, fixed, probe_history, slab_body,
        slab_system,
    },
    reduction::{Method, NodalFixedAxes},
};

fn alpha(spectral_radius: f64) -> IntegrationScheme {
    IntegrationScheme::GeneralizedAlpha { spectral_radius }
}

/// Generalized-α with spectral radius `rho` and fixed steps `h` over `end` seconds.
fn implicit(end: f64, rho: f64, h: f64) -> IntegratorParameters {
    IntegratorParameters {
        end_time: end,
        scheme: alpha(rho),
        fixed_step: Some(h),
        ..Default::default()
    }
}

/// The slab (Craig–Bampton, 6 modes) on nodal-fixed axes held at exactly its six anchored
/// coordinates (node 16 x y z, node 28 y z, node 18 z): the frame cannot move, so the
/// equations are linear, $M_{zz}\ddot z + K_{zz}z = \Psi^T f_g$, a multi-DOF oscillator
/// started at rest under gravity.
fn held_slab() -> (System, State) {
    let model = slab(&SlabParameters::default());
    let axes = flexmodes::dynamics::AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let body = slab_body(&model, Method::CraigBampton, axes, &BOUNDARY, 6).unwrap();
    let hold = |node: usize, axis: usize| fixed(&model, node, axis).unwrap();
    let constraints = vec![
        hold(16, 0),
        hold(16, 1),
        hold(16, 2),
        hold(28, 1),
        hold(28, 2),
        hold(18, 2),
    ];
    let origin = body.origin;
    let system = System::new(vec![Body::Flexible(Box::new(body))], constraints);
    let state = system.state_at(&[(origin, nalgebra::Matrix3::identity())]);
    (system, state)
}

fn run(system: &System, state: &State, p: &IntegratorParameters) -> Simulation {
    simulate(system, state, p, &Progress::default()).unwrap()
}

fn modal_history(system: &System, sim: &Simulation) -> Vec<f64> {
    sim.samples
        .iter()
        .flat_map(|s| {
            system
                .modal(0, &s.state)
                .iter()
                .copied()
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn coefficients_follow_chung_and_hulbert() {
    let c = GeneralizedAlphaCoefficients::from_spectral_radius(1.0);
    for (got, want) in [
        (c.alpha_m, 0.5),
        (c.alpha_f, 0.5),
        (c.gamma, 0.5),
        (c.beta, 0.25),
    ] {
        assert!((got - want).abs() < 1e-15, "{got} against {want}");
    }
    let c = GeneralizedAlphaCoefficients::from_spectral_radius(0.0);
    for (got, want) in [
        (c.alpha_m, -1.0),
        (c.alpha_f, 0.0),
        (c.gamma, 1.5),
        (c.beta, 1.0),
    ] {
        assert!((got - want).abs() < 1e-15, "{got} against {want}");
    }
}

#[test]
fn second_order_convergence_on_a_linear_oscillator() {
    let (system, state) = held_slab();
    let end = 0.2;
    let reference = run(
        &system,
        &state,
        &IntegratorParameters {
            end_time: end,
            rtol: 1e-11,
            atol: 1e-14,
            ..Default::default()
        },
    );
    let z_ref = modal_history(&system, &reference);
    let mut errors = Vec::new();
    for h in [1e-3, 5e-4, 2.5e-4] {
        let sim = run(&system, &state, &implicit(end, 0.8, h));
        let z = modal_history(&system, &sim);
        assert_eq!(z.len(), z_ref.len());
        errors.push(relative_rms(&z, &z_ref));
    }
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        assert!(
            (1.8..=2.2).contains(&order),
            "observed order {order} from errors {errors:?}"
        );
    }
}

#[test]
fn without_numerical_damping_the_energy_of_an_undamped_linear_system_is_kept() {
    let (system, state) = held_slab();
    let drift = |rho: f64| {
        let sim = run(&system, &state, &implicit(1.0, rho, 2e-3));
        assert_eq!(sim.samples.len(), 201);
        let e0 = sim.samples[0].energy;
        let swing = sim
            .samples
            .iter()
            .map(|s| (s.energy - e0).abs())
            .fold(0.0f64, f64::max);
        let kinetic = sim
            .samples
            .iter()
            .map(|s| system.kinetic_energy(&s.state))
            .fold(0.0f64, f64::max);
        (swing, kinetic)
    };
    let (kept, kinetic) = drift(1.0);
    assert!(kinetic > 0.0);
    assert!(
        kept <= 1e-8 * kinetic,
        "ρ∞ = 1: energy drift {kept:e} J of a kinetic energy up to {kinetic:e} J"
    );
    // Numerical damping: with ρ∞ = 0 the high modes lose energy at once.
    let (lost, _) = drift(0.0);
    assert!(
        lost >= 1e3 * kept.max(1e-14 * kinetic),
        "ρ∞ = 0 lost only {lost:e} J"
    );
}

#[test]
fn constraints_hold_on_the_driven_orbit() {
    let model = slab(&SlabParameters::default());
    let axes = flexmodes::dynamics::AxisType::Mean;
    let body = slab_body(&model, Method::NoReduction, axes, &BOUNDARY, 6).unwrap();
    let (system, state) = slab_system(&Scenario::Orbit, body).unwrap();
    let sim = run(&system, &state, &implicit(0.5, 0.8, 1e-3));
    assert_eq!(sim.samples.len(), 101);
    for s in &sim.samples {
        assert!(
            s.position_violation <= 1e-10,
            "t = {}: Φ {:e}",
            s.t,
            s.position_violation
        );
        assert!(
            s.velocity_violation <= 1e-9,
            "t = {}: Φ̇ {:e}",
            s.t,
            s.velocity_violation
        );
        let p = s.state.q.rows(3, 4).norm();
        assert!((p - 1.0).abs() <= 1e-12, "t = {}: |p| = {p}", s.t);
    }
    assert!(sim.newton_iterations >= sim.steps);
}

#[test]
fn both_integrators_give_one_simulation_1_history() {
    let model = slab(&SlabParameters::default());
    let axes = flexmodes::dynamics::AxisType::NodalFixed(NodalFixedAxes::slab_default());
    for method in [Method::NoReduction, Method::CraigBampton] {
        let body = slab_body(&model, method, axes, &BOUNDARY, 6).unwrap();
        let (system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
        let explicit = run(
            &system,
            &state,
            &IntegratorParameters {
                end_time: 1.0,
                ..Default::default()
            },
        );
        let generalized = run(&system, &state, &implicit(1.0, 0.8, 2.5e-4));
        let a = probe_history(&system, &explicit, PROBE_NODE);
        let b = probe_history(&system, &generalized, PROBE_NODE);
        for d in 0..3 {
            assert_eq!(a[d].len(), b[d].len());
            let e = relative_rms(&b[d], &a[d]);
            // Second order at 0.25 ms: ~1e-4 of node 8's deflection, 100 times below the
            // smallest reduction error simulation 1 prints (CB, 0.024).
            assert!(e <= 5e-4, "{} direction {d}: {e:e}", method.id());
        }
    }
}

#[test]
fn the_implicit_scheme_stays_bounded_where_the_explicit_one_diverges() {
    let model = slab(&SlabParameters::default());
    let axes = flexmodes::dynamics::AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let body = slab_body(&model, Method::NoReduction, axes, &BOUNDARY, 6).unwrap();
    let (system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
    // NR's explicit critical step is 2.21 ms (71.9 Hz); three times it:
    let step = 3.0 * 2.21e-3;
    let p = |scheme| IntegratorParameters {
        end_time: 0.5,
        output_interval: step,
        scheme,
        fixed_step: Some(step),
        ..Default::default()
    };
    let explicit = simulate(
        &system,
        &state,
        &p(IntegrationScheme::DormandPrince),
        &Progress::default(),
    );
    assert!(
        matches!(
            explicit,
            Err(Error::Dynamics(DynamicsError::Diverged { .. }))
        ),
        "{explicit:?}"
    );
    let generalized = simulate(&system, &state, &p(alpha(0.8)), &Progress::default()).unwrap();
    let adaptive = run(
        &system,
        &state,
        &IntegratorParameters {
            end_time: 0.5,
            ..Default::default()
        },
    );
    let largest = |sim: &Simulation| {
        sim.samples
            .iter()
            .map(|s| system.modal(0, &s.state).amax())
            .fold(0.0f64, f64::max)
    };
    let (big_step, reference) = (largest(&generalized), largest(&adaptive));
    assert!(
        big_step <= 1.5 * reference,
        "largest deflection {big_step:e} m against {reference:e} m with adaptive steps"
    );
}

#[test]
fn a_bad_spectral_radius_or_step_is_a_named_error() {
    let (system, state) = held_slab();
    for (rho, step) in [(1.5, 1e-3), (0.8, -1e-3), (0.8, f64::NAN)] {
        let r = simulate(
            &system,
            &state,
            &implicit(0.01, rho, step),
            &Progress::default(),
        );
        let named = match r {
            Err(Error::Dynamics(DynamicsError::InvalidSpectralRadius { rho: r })) => r == rho,
            Err(Error::Dynamics(DynamicsError::InvalidStep { step: h })) => {
                h == step || (h.is_nan() && step.is_nan())
            }
            _ => false,
        };
        assert!(named, "ρ∞ {rho}, h {step}: {r:?}");
    }
}

#[test]
fn newton_failing_on_a_step_too_long_for_the_swinging_plank_is_a_named_error() {
    use flexmodes::dynamics::AxisType;
    use flexmodes::models::{PlankVariant as Variant, plank_body, plank_system};
    let model = flexmodes::fem::plank(&SlabParameters::default());
    let variant = Variant {
        method: Method::CraigBampton,
        axes: AxisType::Mean,
    };
    let (system, state) = plank_system(plank_body(&model, variant, 6).unwrap()).unwrap();
    let r = simulate(
        &system,
        &state,
        &IntegratorParameters {
            end_time: 2.0,
            output_interval: 0.25,
            scheme: alpha(0.8),
            fixed_step: Some(0.25),
            ..Default::default()
        },
        &Progress::default(),
    );
    match r {
        Err(Error::Dynamics(DynamicsError::NewtonFailed {
            time, iterations, ..
        })) => {
            assert!(time > 0.0 && time <= 2.0);
            assert!(iterations > 1);
        }
        other => panic!("expected NewtonFailed, got {other:?}"),
    }
}

#[test]
fn a_rebuilt_iteration_matrix_lets_newton_converge_on_long_steps() {
    // Guyan on the refined 12 × 6 × 3 slab with 5.7 ms steps (3× its explicit critical step)
    // stalls at t ≈ 0.2 s and rebuilds its iteration matrix at the projected state; a matrix
    // built around the unprojected accelerations made Newton fail there.
    let model = slab(&SlabParameters::refined([12, 6, 3]).unwrap());
    let axes = flexmodes::dynamics::AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let boundary = flexmodes::models::default_boundary(&model);
    let body = slab_body(&model, Method::Guyan, axes, &boundary, 0).unwrap();
    let (system, state) = slab_system(&Scenario::HeldAtSix, body).unwrap();
    let sim = simulate(
        &system,
        &state,
        &implicit(0.3, 0.8, 5.7e-3),
        &Progress::default(),
    )
    .unwrap();
    assert!(sim.rejected >= 1, "no iteration matrix was rebuilt");
    assert_eq!(sim.samples.len(), 61);
}

/// The evaluations a generalized-α run counts are those it makes: the initial accelerations,
/// the finite-difference derivatives (a base point and two per velocity coordinate, again at
/// each rebuild) and one per Newton iteration; the projections solve with kept factors and
/// evaluate nothing.
#[test]
fn generalized_alpha_counts_its_evaluations() {
    let model = slab(&SlabParameters::default());
    let axes = flexmodes::dynamics::AxisType::Mean;
    let body = slab_body(&model, Method::CraigBampton, axes, &BOUNDARY, 6).unwrap();
    let (system, state) = slab_system(&Scenario::Orbit, body).unwrap();
    let sim = run(&system, &state, &implicit(0.1, 0.8, 1e-3));
    let nv = system.nv();
    assert!(sim.newton_iterations >= sim.steps);
    assert_eq!(
        sim.evaluations,
        2 + 2 * nv + sim.newton_iterations + sim.rejected * (1 + 2 * nv),
        "{} steps, {} Newton iterations, {} rebuilds",
        sim.steps,
        sim.newton_iterations,
        sim.rejected
    );
}
