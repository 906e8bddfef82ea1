//! Floating-frame dynamics (§7.2, §5.3.3): accuracy ordering of the methods, invariants of the
//! integration, the symmetry study and errors.

use flexmodes::dynamics::{DivergenceCause, DynamicsError};
use flexmodes::{
    Progress,
    analysis::relative_rms,
    dynamics::{
        AxisType, Body, IntegrationScheme, IntegratorParameters, Motion, Simulation, System,
        simulate,
    },
    error::CoreError as Error,
    fem::{SlabParameters, plank, slab},
    models::{
        PROBE_NODE, PlankVariant as Variant, Scenario, plank_body, plank_nodal_fixed, plank_system,
        probe_history, slab_body, slab_system, symmetry_history,
    },
    reduction::{Method, NodalFixedAxes},
};

const BOUNDARY: [usize; 4] = [16, 18, 28, 30];

fn run_slab(
    scenario: &Scenario,
    method: Method,
    axes: AxisType,
    p: &IntegratorParameters,
) -> (System, Simulation) {
    let model = slab(&SlabParameters::default());
    let body = slab_body(&model, method, axes, &BOUNDARY, 6).unwrap();
    let (system, state) = slab_system(scenario, body).unwrap();
    let sim = simulate(&system, &state, p, &Progress::default()).unwrap();
    (system, sim)
}

fn nodal() -> AxisType {
    AxisType::NodalFixed(NodalFixedAxes::slab_default())
}

fn params(end: f64) -> IntegratorParameters {
    IntegratorParameters {
        end_time: end,
        ..Default::default()
    }
}

#[test]
fn craig_bampton_and_mode_condensation_give_one_history() {
    // With a tight tolerance the two integrations differ only by round-off and step control.
    let p = IntegratorParameters {
        end_time: 0.3,
        rtol: 1e-10,
        atol: 1e-13,
        ..Default::default()
    };
    let (sc, cb) = run_slab(&Scenario::HeldAtSix, Method::CraigBampton, nodal(), &p);
    let (sm, mc) = run_slab(&Scenario::HeldAtSix, Method::ModeCondensation, nodal(), &p);
    let a = probe_history(&sc, &cb, PROBE_NODE);
    let b = probe_history(&sm, &mc, PROBE_NODE);
    for d in 0..3 {
        assert_eq!(a[d].len(), b[d].len());
        let scale = a[d].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = a[d]
            .iter()
            .zip(&b[d])
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff <= 1e-7 * scale, "direction {d}: {diff:e} of {scale:e}");
    }
}

/// Generalized-α's fixed steps, Newton iterations to 1e-10 and mass-metric projections do
/// not depend on the basis: CB and MC, one space in two sets of coordinates, give node 8 one
/// history to 1e-8 of its largest deflection in every simulation and frame (before the
/// position projection was made mass-weighted, slab-sim3's ξ errors differed by 1e-3), but
/// one: Simulation 3 (driven) on mean axes, where the two differ by 2.2e-6 after 300 steps,
/// and by 1.7e-4 after 3 000 steps of 0.1 ms. Dormand–Prince at rtol 1e-10 gives that case
/// one history to 5e-13, and Newton's tolerance (1e-10 or 1e-12) does not change the
/// difference, so the equations are the same for both bases and generalized-α amplifies
/// round-off there (mean axes' rotational conditions are velocity-level rows, which no
/// position projection holds): an open problem, bounded here so that it cannot grow
/// unnoticed.
#[test]
fn generalized_alpha_gives_craig_bampton_and_mode_condensation_one_history() {
    let tables =
        flexmodes::models::record_driving_tables(nodal(), 0.3, &Progress::default()).unwrap();
    let scenarios = [
        Scenario::HeldAtSix,
        Scenario::Orbit,
        Scenario::Driven(tables),
    ];
    let p = IntegratorParameters {
        end_time: 0.3,
        scheme: IntegrationScheme::GeneralizedAlpha {
            spectral_radius: 0.9,
        },
        ..Default::default()
    };
    for scenario in &scenarios {
        for axes in [nodal(), AxisType::Mean, AxisType::Principal] {
            let (sc, cb) = run_slab(scenario, Method::CraigBampton, axes, &p);
            let (sm, mc) = run_slab(scenario, Method::ModeCondensation, axes, &p);
            let a = probe_history(&sc, &cb, PROBE_NODE);
            let b = probe_history(&sm, &mc, PROBE_NODE);
            let scale = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(scale > 0.0);
            let open = matches!(scenario, Scenario::Driven(_)) && axes == AxisType::Mean;
            let tolerance = if open { 1e-5 } else { 1e-8 };
            for d in 0..3 {
                assert_eq!(a[d].len(), b[d].len());
                let diff = a[d]
                    .iter()
                    .zip(&b[d])
                    .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
                assert!(
                    diff <= tolerance * scale,
                    "{axes:?} direction {d}: {diff:e} of {scale:e}"
                );
            }
        }
    }
}

/// The rel. RMS errors of node 8 the scene reports, per method and direction.
fn reported_errors(
    scene: &str,
    axes: &str,
    integrator: IntegrationScheme,
) -> serde_json::Map<String, serde_json::Value> {
    let options = flexmodes::scenes::SceneOptions {
        methods: Some(vec![
            Method::NoReduction,
            Method::CraigBampton,
            Method::ModeCondensation,
        ]),
        axes: Some(axes.parse().unwrap()),
        integrator: Some(integrator),
        ..Default::default()
    };
    let output = (flexmodes::scenes::find(scene).unwrap().run)(&options).unwrap();
    output.report.results["rel_rms_error"]
        .as_object()
        .unwrap()
        .clone()
}

/// CB and MC span one space, so the errors every simulation reports are one under every
/// integrator (to 1e-4 of the error: an error is relative to its own direction's signal, which
/// is small in ξ on mean axes, so history differences at the solver's tolerance show larger
/// here; the history test above holds generalized-α to 1e-8). Every simulation on `axes`.
fn craig_bampton_and_mode_condensation_agree_on(axes: &[&str]) {
    let integrators = [
        (IntegrationScheme::DormandPrince, 1e-4),
        (
            IntegrationScheme::GeneralizedAlpha {
                spectral_radius: 0.9,
            },
            1e-4,
        ),
    ];
    for (integrator, tolerance) in integrators {
        for scene in ["slab-sim1", "slab-sim2", "slab-sim3"] {
            for &axes in axes {
                let errors = reported_errors(scene, axes, integrator);
                let (cb, mc) = (&errors["cb"], &errors["mc"]);
                for direction in ["xi", "eta", "zeta"] {
                    let (a, b) = (
                        cb[direction].as_f64().unwrap(),
                        mc[direction].as_f64().unwrap(),
                    );
                    assert!(
                        a > 1e-3,
                        "{scene} {axes} {direction}: CB error {a} is not an error"
                    );
                    assert!(
                        (a - b).abs() <= tolerance * a.max(1.0),
                        "{integrator:?} {scene} {axes} {direction}: CB {a} against MC {b}"
                    );
                }
            }
        }
    }
}

/// Mean axes, where the two bases' histories are most sensitive (ξ's small signal).
#[test]
fn craig_bampton_and_mode_condensation_report_one_error_in_every_simulation() {
    craig_bampton_and_mode_condensation_agree_on(&["mean"]);
}

/// The other two axes (~25 s in the debug build).
#[test]
#[ignore = "slow: CI runs cargo test --test dynamics -- --ignored"]
fn craig_bampton_and_mode_condensation_agree_on_nodal_fixed_and_principal_axes() {
    craig_bampton_and_mode_condensation_agree_on(&["nodal_fixed", "principal"]);
}

#[test]
#[ignore = "slow (~19 s in the debug build): CI runs cargo test --test dynamics -- --ignored"]
fn the_reference_integration_error_is_a_hundred_times_below_the_reduction_errors() {
    let tight = |end: f64| IntegratorParameters {
        end_time: end,
        rtol: 1e-10,
        atol: 1e-13,
        ..Default::default()
    };
    let tables =
        flexmodes::models::record_driving_tables(nodal(), 1.0, &Progress::default()).unwrap();
    for (name, scenario) in [
        ("simulation 1", Scenario::HeldAtSix),
        ("simulation 2", Scenario::Orbit),
        ("simulation 3", Scenario::Driven(tables)),
    ] {
        let end = scenario.end_time();
        let histories = |method: Method, p: &IntegratorParameters| {
            let (system, sim) = run_slab(&scenario, method, nodal(), p);
            probe_history(&system, &sim, PROBE_NODE)
        };
        let reference = histories(Method::NoReduction, &params(end));
        let converged = histories(Method::NoReduction, &tight(end));
        let integration = (0..3)
            .map(|d| relative_rms(&reference[d], &converged[d]))
            .fold(0.0f64, f64::max);
        // The smallest error the table prints: Craig–Bampton's, whose basis is the best.
        let cb = histories(Method::CraigBampton, &params(end));
        let reduction = (0..3)
            .map(|d| relative_rms(&cb[d], &reference[d]))
            .fold(f64::INFINITY, f64::min);
        assert!(
            integration > 0.0 && 100.0 * integration <= reduction,
            "{name}: integration error {integration:e}, smallest reduction error \
             {reduction:e}"
        );
    }
}

fn first_peak_time(sim: &Simulation, v: &[f64]) -> f64 {
    let sign = v
        .iter()
        .fold(0.0f64, |a, &x| if x.abs() > a.abs() { x } else { a })
        .signum();
    for i in 1..v.len() - 1 {
        if sign * v[i] > sign * v[i - 1] && sign * v[i] >= sign * v[i + 1] && sign * v[i] > 0.0 {
            return sim.samples[i].t;
        }
    }
    f64::INFINITY
}

#[test]
fn simulation_1_ranks_the_methods_as_the_thesis() {
    let p = params(1.0);
    let mut hist = Vec::new();
    for m in [
        Method::NoReduction,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::Guyan,
    ] {
        let (s, sim) = run_slab(&Scenario::HeldAtSix, m, nodal(), &p);
        hist.push((m, probe_history(&s, &sim, PROBE_NODE), sim));
    }
    let nr = &hist[0].1;
    let err = |i: usize, d: usize| relative_rms(&hist[i].1[d], &nr[d]);
    for d in 0..3 {
        // CB within a few percent of NR, MT the poorest, GR in between.
        assert!(err(2, d) < 0.05, "CB direction {d}: {}", err(2, d));
        assert!(
            err(1, d) > err(3, d),
            "MT must be poorer than GR in direction {d}"
        );
        assert!(
            err(3, d) > err(2, d),
            "GR must be poorer than CB in direction {d}"
        );
    }
    // Guyan leads: its raised frequencies bring the first peak of the sag (ζ) earlier.
    let t_nr = first_peak_time(&hist[0].2, &nr[2]);
    let t_gr = first_peak_time(&hist[3].2, &hist[3].1[2]);
    assert!(t_gr < t_nr, "GR first peak {t_gr} s, NR {t_nr} s");
    assert!(t_nr < 1.0);
}

#[test]
fn constraints_hold_and_the_frame_turns_with_the_orbit() {
    let (system, sim) = run_slab(
        &Scenario::Orbit,
        Method::CraigBampton,
        nodal(),
        &params(0.5),
    );
    for s in &sim.samples {
        assert!(
            s.position_violation < 1e-9,
            "t = {}: {:e}",
            s.t,
            s.position_violation
        );
        assert!(
            s.velocity_violation < 1e-9,
            "t = {}: {:e}",
            s.t,
            s.velocity_violation
        );
    }
    // The frame turns with the body: the rotation its Euler parameters describe is that of
    // the line from node 16 to node 28 (the nodal-fixed ξ axis, Eq. 4.1), and by 0.5 s the
    // line from node 16 to node 30, whose ends the constraints place, has turned half a turn
    // about y (node 28 lags it by the slab's deflection).
    let (qo, _) = system.offsets(0);
    let last_state = &sim.samples.last().unwrap().state;
    let p = last_state.q.rows(qo + 3, 4).into_owned();
    let angle = 2.0 * p[0].abs().min(1.0).acos();
    let axis = p.rows(1, 3).normalize();
    assert!(axis[1].abs() > 0.999, "axis {axis:?}");
    let turn = |node: usize| {
        let chord = |s: &flexmodes::dynamics::State| {
            let d = system.node_position(0, flexmodes::fem::NodeIndex(node - 1), s)
                - system.node_position(0, flexmodes::fem::NodeIndex(15), s);
            d.z.atan2(d.x)
        };
        let t = (chord(last_state) - chord(&sim.samples[0].state)).abs();
        t.min(2.0 * std::f64::consts::PI - t)
    };
    assert!(turn(30) > 3.1, "the line 16-30 turned {} rad", turn(30));
    assert!(
        (angle - turn(28)).abs() < 1e-6,
        "frame {angle} rad, line 16-28 {} rad",
        turn(28)
    );
    // Node 30 follows Eq. (7.10): back near its start after one period T = 1 s would need
    // 1 s; at 0.5 s it is on the far side of the orbit, x = R cos(π) + R/16 cos(2π) - R/16.
    let last = sim.samples.last().unwrap();
    let x30 = system
        .node_position(0, flexmodes::fem::NodeIndex(29), &last.state)
        .x;
    assert!((x30 - (-4.0)).abs() < 1e-8, "x30 = {x30}");
}

#[test]
fn energy_is_conserved_without_damping_or_driving() {
    // The plank under its links is conservative (fixed anchors, gravity, a constant force).
    let model = plank(&SlabParameters::default());
    let body = plank_body(
        &model,
        Variant {
            method: Method::CraigBampton,
            axes: AxisType::Mean,
        },
        4,
    )
    .unwrap();
    let (system, state) = plank_system(body).unwrap();
    let sim = simulate(&system, &state, &params(0.4), &Progress::default()).unwrap();
    let e0 = sim.samples[0].energy;
    // Scale: the potential energy released by the fall, m g h ~ 60 kg · 9.8 · 1 m.
    let scale = 600.0;
    for s in &sim.samples {
        assert!(
            (s.energy - e0).abs() < 1e-6 * scale,
            "t = {}: ΔE = {:e}",
            s.t,
            s.energy - e0
        );
    }
    // The plank did fall: energy moved from potential to kinetic.
    let z0 = system
        .node_position(0, flexmodes::fem::NodeIndex(7), &sim.samples[0].state)
        .z;
    let z1 = system
        .node_position(
            0,
            flexmodes::fem::NodeIndex(7),
            &sim.samples.last().unwrap().state,
        )
        .z;
    assert!(z0 - z1 > 0.5, "fell {} m", z0 - z1);
}

#[test]
fn mean_axes_keep_the_plank_symmetric_and_nodal_fixed_axes_do_not() {
    let model = plank(&SlabParameters::default());
    let p = params(0.8);
    let mut defects = Vec::new();
    let mut early_positions = Vec::new();
    for axes in [AxisType::NodalFixed(plank_nodal_fixed()), AxisType::Mean] {
        let body = plank_body(
            &model,
            Variant {
                method: Method::NoReduction,
                axes,
            },
            0,
        )
        .unwrap();
        let (system, state) = plank_system(body).unwrap();
        let sim = simulate(&system, &state, &p, &Progress::default()).unwrap();
        let h = symmetry_history(&system, &sim);
        assert_eq!(h[2].len(), sim.samples.len());
        let before = sim
            .samples
            .iter()
            .zip(&h[2])
            .filter(|(s, _)| s.t <= 0.45)
            .fold(0.0f64, |m, (_, d)| m.max(*d));
        let after = h[2].iter().copied().fold(0.0f64, f64::max);
        defects.push((before, after));
        let system = &system;
        let positions: Vec<_> = sim
            .samples
            .iter()
            .filter(|s| s.t <= 0.45)
            .flat_map(|s| {
                (0..model.node_count())
                    .map(move |j| system.node_position(0, flexmodes::fem::NodeIndex(j), &s.state))
            })
            .collect();
        early_positions.push(positions);
    }
    // Before the snap both frames describe one motion: every node at one place (all three
    // coordinates, not only the x the defect measures).
    assert_eq!(early_positions[0].len(), early_positions[1].len());
    let early_gap = early_positions[0]
        .iter()
        .zip(&early_positions[1])
        .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
    assert!(
        early_gap < 1e-3,
        "nodal-fixed and mean planks {early_gap} m apart"
    );
    let (nf, mean) = (defects[0], defects[1]);
    assert!(mean.1 < 1e-7, "mean axes defect {:e}", mean.1);
    assert!(nf.1 > 1e-3, "nodal-fixed defect after the snap {:e}", nf.1);
    assert!(nf.1 > 1e4 * mean.1);
    // Before the chains snap taut the nodal-fixed frame is nearly symmetric too.
    assert!(nf.0 < 1e-2 * nf.1, "before {:e}, after {:e}", nf.0, nf.1);
}

#[test]
fn a_frame_change_leaves_absolute_positions_unchanged_to_second_order() {
    let p = params(0.3);
    let model = slab(&SlabParameters::default());
    let mut runs = Vec::new();
    for axes in [nodal(), AxisType::Mean, AxisType::Principal] {
        let (s, sim) = run_slab(&Scenario::HeldAtSix, Method::NoReduction, axes, &p);
        runs.push((s, sim));
    }
    let (s0, sim0) = &runs[0];
    let mut deform = 0.0f64;
    for smp in &sim0.samples {
        let z = s0.modal(0, &smp.state);
        let Body::Flexible(fb) = &s0.bodies[0] else {
            unreachable!()
        };
        for j in 0..model.node_count() {
            deform = deform.max(fb.deflection(j, &z).norm());
        }
    }
    assert!(deform > 1e-3, "the slab deforms ({deform} m)");
    for (s, sim) in &runs[1..] {
        let mut diff = 0.0f64;
        assert_eq!(sim0.samples.len(), sim.samples.len());
        for (a, b) in sim0.samples.iter().zip(&sim.samples) {
            for j in 0..model.node_count() {
                let d = (s0.node_position(0, flexmodes::fem::NodeIndex(j), &a.state)
                    - s.node_position(0, flexmodes::fem::NodeIndex(j), &b.state))
                .norm();
                diff = diff.max(d);
            }
        }
        // Second order in the deformation relative to the body size (4 m), with margin 10.
        let bound = 10.0 * deform * deform / 4.0;
        assert!(
            diff < bound,
            "frame change moved nodes by {diff:e} (bound {bound:e})"
        );
    }
}

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

/// The explorer's cache integrates only what a request changed, and gives the numbers a fresh
/// run gives.
#[test]
fn a_kept_simulation_is_not_integrated_again() {
    use flexmodes::scenes::{RunCache, SceneOptions, find};
    let run = find("slab-sim1").unwrap().run;
    let cache = RunCache::new();
    let options = |methods: &[Method], modes: usize, cache: &RunCache| SceneOptions {
        methods: Some(methods.to_vec()),
        modes: Some(modes),
        end_time: Some(0.25),
        progress: Progress::new(),
        cache: cache.clone(),
        ..Default::default()
    };
    let integrations = |o: &SceneOptions| o.progress.reading().map_or(0, |r| r.simulations);
    let (nr, cb, gr) = (Method::NoReduction, Method::CraigBampton, Method::Guyan);

    let first = options(&[nr, cb], 6, &cache);
    run(&first).unwrap();
    assert_eq!(integrations(&first), 2);

    let second = options(&[nr, cb, gr], 6, &cache);
    let cached = run(&second).unwrap();
    assert_eq!(integrations(&second), 1, "only GR is new");
    assert_eq!(cache.len(), 3);

    let fresh = run(&options(&[nr, cb, gr], 6, &RunCache::default())).unwrap();
    assert_eq!(
        cached.report.results["rel_rms_error"],
        fresh.report.results["rel_rms_error"]
    );

    // Kept modes change CB's integration, not NR's or GR's.
    let third = options(&[nr, cb, gr], 4, &cache);
    run(&third).unwrap();
    assert_eq!(integrations(&third), 1);
    assert_eq!(cache.len(), 4);
}

/// The cache weighs what it keeps: without reduction the body's dense k × k blocks ($K_{zz}$,
/// $M_{zz}$ and Ψ = I) are at least 3·8·k² bytes; with Craig–Bampton only Ψ (n × 18) and
/// small blocks.
#[test]
fn the_cache_weighs_an_unreduced_integration_by_its_dense_blocks() {
    use flexmodes::scenes::{RunCache, SceneOptions, find};
    let run = find("slab-sim1").unwrap().run;
    let weigh = |m: Method| {
        let cache = RunCache::new();
        run(&SceneOptions {
            methods: Some(vec![m]),
            refine: Some([8, 4, 2]),
            end_time: Some(0.05),
            cache: cache.clone(),
            ..Default::default()
        })
        .unwrap();
        assert_eq!(cache.len(), 1);
        cache.bytes()
    };
    // 9 × 5 × 3 nodes.
    let n = 3 * 9 * 5 * 3;
    let k = n - 6;
    let nr = weigh(Method::NoReduction);
    assert!(nr >= 3 * 8 * k * k, "{nr} bytes for {n} DOF");
    assert!(nr <= 6 * 8 * n * n + (1 << 20), "{nr} bytes for {n} DOF");
    let cb = weigh(Method::CraigBampton);
    assert!(cb >= 8 * n * 12, "{cb}");
    assert!(cb < nr / 10, "{cb} against {nr}");
}

#[test]
fn the_drawn_deflection_is_automatic_or_as_asked() {
    let scene = flexmodes::scenes::find("slab-sim1").unwrap();
    let run = |scale: Option<f64>| {
        scene.execute(&flexmodes::scenes::SceneOptions {
            methods: Some(vec![Method::CraigBampton]),
            end_time: Some(0.2),
            deformation_scale: scale,
            ..Default::default()
        })
    };
    let auto = run(None).unwrap();
    let f = auto.report.results["deformation_scale"].as_f64().unwrap();
    // 1, 2 or 5 times a power of ten, at least 1.
    let mantissa = f / 10f64.powf(f.log10().floor());
    assert!(
        f >= 1.0 && [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
        "{f}"
    );
    let asked = run(Some(7.0)).unwrap();
    assert_eq!(asked.report.results["deformation_scale"], 7.0);
    assert!(matches!(
        run(Some(-1.0)).unwrap_err(),
        flexmodes::Error::InvalidOption { .. }
    ));
}

#[test]
fn a_refined_slab_simulation_runs_every_method_and_cb_stays_close_to_the_full_model() {
    let options = flexmodes::scenes::SceneOptions {
        refine: Some([8, 4, 2]),
        end_time: Some(0.3),
        ..Default::default()
    };
    let output = (flexmodes::scenes::find("slab-sim1").unwrap().run)(&options).unwrap();
    let report = &output.report;
    assert_eq!(report.parameters["dofs"], 405);
    assert_eq!(report.parameters["bricks"], serde_json::json!([8, 4, 2]));
    let errors = report.results["rel_rms_error"].as_object().unwrap();
    assert_eq!(errors.len(), 5);
    for d in ["xi", "eta", "zeta"] {
        let cb = errors["cb"][d].as_f64().unwrap();
        let mc = errors["mc"][d].as_f64().unwrap();
        let mt = errors["mt"][d].as_f64().unwrap();
        assert!(cb < 0.1, "{d}: CB {cb}");
        assert!((cb - mc).abs() <= 1e-4, "{d}: CB {cb}, MC {mc}");
        // Modal truncation cannot follow the supports (§7.2): far worse than CB.
        assert!(mt > 5.0 * cb, "{d}: MT {mt}, CB {cb}");
    }
}

#[test]
fn bodies_of_different_methods_are_drawn_in_lanes_that_do_not_overlap() {
    use flexmodes::record::Visual;
    let options = flexmodes::scenes::SceneOptions {
        methods: Some(vec![
            Method::NoReduction,
            Method::CraigBampton,
            Method::Guyan,
        ]),
        end_time: Some(0.2),
        ..Default::default()
    };
    let out = flexmodes::scenes::find("slab-sim1")
        .unwrap()
        .execute(&options)
        .unwrap();
    let offset = |lane: &str| {
        out.visuals.iter().find_map(|v| match v {
            Visual::Offset { path, translation } if path == lane => Some(*translation),
            _ => None,
        })
    };
    // The y extent of each lane's body over the whole run, shifted by its lane's offset.
    let mut extents = Vec::new();
    for m in ["nr", "cb", "gr"] {
        let lane = format!("world/slab/{m}");
        let shift = offset(&lane).unwrap_or_else(|| panic!("no offset for {lane}"));
        let mut first_frames: Option<Vec<[f64; 3]>> = None;
        for part in ["nodal_fixed", "undeformed_ghost"] {
            let path = format!("{lane}/{part}");
            // Node positions per time: logged for the deflected body, a rigid outline moved
            // by its frame's placement (rotation columns) for the ghost.
            let positions: Vec<Vec<[f64; 3]>> = out
                .visuals
                .iter()
                .find_map(|v| match v {
                    Visual::Trajectory {
                        path: p, positions, ..
                    } if *p == path => Some(positions.clone()),
                    Visual::RigidTrajectory {
                        path: p,
                        geometry,
                        translations,
                        rotations,
                        ..
                    } if *p == path => {
                        assert_eq!(translations.len(), rotations.len());
                        Some(
                            translations
                                .iter()
                                .zip(rotations)
                                .map(|(t, r)| {
                                    geometry
                                        .nodes
                                        .iter()
                                        .map(|x| {
                                            [0, 1, 2].map(|i| {
                                                t[i] + (0..3).map(|c| r[c][i] * x[c]).sum::<f64>()
                                            })
                                        })
                                        .collect()
                                })
                                .collect(),
                        )
                    }
                    _ => None,
                })
                .unwrap_or_else(|| panic!("no trajectory {path}"));
            assert!(!positions.is_empty());
            // At the start the slab is undeformed: the ghost, placed by its frame alone, lies
            // on the body drawn from every node's position.
            if let Some(body) = &first_frames {
                let ghost: &Vec<[f64; 3]> = &positions[0];
                assert_eq!(ghost.len(), Vec::len(body));
                for (g, b) in ghost.iter().zip(body) {
                    let gap = (0..3).map(|i| (g[i] - b[i]).abs()).fold(0.0, f64::max);
                    assert!(gap < 1e-9, "{path}: ghost {g:?}, body {b:?}");
                }
            }
            first_frames = Some(positions[0].clone());
            let ys = positions.iter().flatten().map(|p| p[1] + shift[1]);
            let lo = ys.clone().fold(f64::MAX, f64::min);
            let hi = ys.fold(f64::MIN, f64::max);
            extents.push((m, lo, hi));
        }
        assert!(
            out.visuals
                .iter()
                .any(|v| v.path() == format!("{lane}/label")),
            "{lane} has no label"
        );
    }
    for (i, a) in extents.iter().enumerate() {
        for b in &extents[i + 1..] {
            if a.0 != b.0 {
                assert!(a.2 < b.1 || b.2 < a.1, "lanes {a:?} and {b:?} overlap");
            }
        }
    }
}

/// The explorer integrates a scene's methods on several threads: the same errors, in the same
/// order, as one after the other; the scene text says so.
#[test]
fn concurrent_integrations_give_the_serial_results() {
    use flexmodes::scenes::{SceneOptions, find};
    let scene = find("slab-sim1").unwrap();
    let methods = vec![
        Method::NoReduction,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::Guyan,
    ];
    let options = |threads: usize| SceneOptions {
        methods: Some(methods.clone()),
        end_time: Some(0.2),
        concurrent_integrations: threads,
        ..Default::default()
    };
    let serial = scene.execute(&options(1)).unwrap();
    let concurrent = scene.execute(&options(3)).unwrap();
    let errors = |o: &flexmodes::scenes::SceneOutput| o.report.results["rel_rms_error"].clone();
    assert_eq!(errors(&serial).as_object().unwrap().len(), methods.len());
    assert_eq!(errors(&serial), errors(&concurrent));
    assert_eq!(
        serial.report.parameters["methods"],
        concurrent.report.parameters["methods"]
    );
    assert!(concurrent.markdown.contains("ran up to 3 at a time"));
    assert!(!serial.markdown.contains("at a time"));
}
