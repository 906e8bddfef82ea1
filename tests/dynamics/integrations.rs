//! Floating-frame dynamics (§7.2, §5.3.3): accuracy ordering of the methods, invariants of the
//! integration, the symmetry study and errors.

use flexmodes::{
    Progress,
    analysis::relative_rms,
    dynamics::{
        AxisType, Body, IntegrationScheme, IntegratorParameters, Simulation, System, simulate,
    },
    fem::{SlabParameters, plank, slab},
    models::{
        PROBE_NODE, PlankVariant as Variant, Scenario, plank_body, plank_nodal_fixed, plank_system,
        probe_history, slab_body, slab_system, symmetry_history,
    },
    reduction::{Method, NodalFixedAxes},
};

pub(crate) const BOUNDARY: [usize; 4] = [16, 18, 28, 30];

pub(crate) fn run_slab(
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

pub(crate) fn nodal() -> AxisType {
    AxisType::NodalFixed(NodalFixedAxes::slab_default())
}

pub(crate) fn params(end: f64) -> IntegratorParameters {
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
