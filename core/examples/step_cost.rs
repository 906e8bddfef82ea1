//! Per-evaluation cost of slab-sim1's integrations (profiling aid): `cargo run --release
//! --example step_cost -- [method] [modes] [dp5|gen-alpha|loose] [repeats]`.

use flexmodes_core::{
    Progress,
    dynamics::{
        AxisType, DEFAULT_SPECTRAL_RADIUS, IntegrationScheme, IntegratorParameters, simulate,
    },
    fem::{SlabParameters, slab},
    models::{Scenario, default_boundary, slab_body, slab_system},
    reduction::{Method, NodalFixedAxes},
};

fn main() -> flexmodes_core::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let method = match args.get(1).map(String::as_str).unwrap_or("cb") {
        "nr" => Method::NoReduction,
        "gr" => Method::Guyan,
        "mt" => Method::ModalTruncation,
        "mc" => Method::ModeCondensation,
        _ => Method::CraigBampton,
    };
    let modes: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(6);
    let scheme = args.get(3).map(String::as_str).unwrap_or("dp5");
    let repeats: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(5);
    let model = slab(&SlabParameters::default());
    let boundary = default_boundary(&model);
    let axes = AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let body = slab_body(&model, method, axes, &boundary, modes)?;
    let scenario = Scenario::HeldAtSix;
    let (system, state) = slab_system(&scenario, body)?;
    let mut p = IntegratorParameters {
        end_time: scenario.end_time(),
        ..Default::default()
    };
    match scheme {
        "gen-alpha" => {
            p.scheme = IntegrationScheme::GeneralizedAlpha {
                spectral_radius: DEFAULT_SPECTRAL_RADIUS,
            }
        }
        "loose" => {
            p.rtol = 1e-3;
            p.atol = 1e-6;
        }
        _ => {}
    }
    let mut best = f64::INFINITY;
    let mut evaluations = 0;
    let mut steps = 0;
    for _ in 0..repeats {
        let sim = simulate(&system, &state, &p, &Progress::new())?;
        best = best.min(sim.wall_time_s);
        evaluations = sim.evaluations;
        steps = sim.steps;
    }
    println!(
        "{} {modes} {scheme}: {steps} steps, {evaluations} evaluations, best {:.4} s, {:.3} µs per evaluation",
        method.id(),
        best,
        1e6 * best / evaluations as f64
    );
    Ok(())
}
