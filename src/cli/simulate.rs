//! `flexmodes simulate`: a body driven through a rigid interface (models::driven_body_study),
//! printed as a table or JSON and written as a recording.

use super::{
    arguments::{SimulateArgs, SpinningBodyArgs},
    stderr::progress,
};
use crate::{
    Progress, Result, TerminalProgress, body_file::ImportedBody, record::Recorder, scenes,
};

/// Runs `simulate` with its arguments.
pub(super) fn run(arguments: SimulateArgs) -> Result<()> {
    let SimulateArgs {
        spin:
            SpinningBodyArgs {
                body,
                drive,
                axis,
                axis_point,
                stiffening,
                residual_vectors,
            },
        boundary,
        output,
        pinned,
        method,
        modes,
        motion,
        direction,
        amplitude,
        frequency,
        rate,
        ramp,
        end,
        dt,
        rho,
        samples,
        gravity,
        json,
        save,
        explicit,
        axes,
    } = arguments;
    let shaking = motion == super::arguments::Motion::Shake;
    let three = super::arguments::three_numbers;
    let axis = three("--axis", &axis)?;
    let direction = three("--direction", &direction)?;
    let axis_point = axis_point.map(|p| three("--axis-point", &p)).transpose()?;
    let gravity = gravity.map(|g| three("--gravity", &g)).transpose()?;
    let body = ImportedBody::load(&body)?;
    let steps = (end / dt).round().max(1.0) as usize;
    let parameters = crate::models::DrivenBodyParameters {
        drive,
        boundary,
        outputs: output,
        pinned,
        axis,
        rate: if shaking { 0.0 } else { rate },
        ramp,
        axis_point: axis_point.map(|p| [p[0], p[1], p[2]]),
        shake: shaking.then(|| {
            (
                [direction[0], direction[1], direction[2]],
                amplitude,
                frequency,
            )
        }),
        gravity,
        integration: crate::dynamics::DrivenIntegration {
            step: dt,
            end,
            spectral_radius: rho,
            output_every: (steps / samples.max(1)).max(1),
        },
        explicit,
        axes,
        stiffening: stiffening == super::arguments::OnOff::On,
        residual_vectors: residual_vectors == super::arguments::OnOff::On,
    };
    let full = method.contains(&crate::reduction::Method::NoReduction);
    let reduced: Vec<_> = method
        .into_iter()
        .filter(|m| *m != crate::reduction::Method::NoReduction)
        .collect();
    let handle = Progress::new();
    let bar = TerminalProgress::start(&handle, "simulate");
    let simulation = scenes::body_simulation::BodySimulation {
        parameters,
        full_body: full,
    };
    // The explorer's path without its cache: one study of every model.
    let study = scenes::body_simulation::simulated_study(
        &body,
        &simulation,
        (&reduced, &modes),
        &handle,
        &scenes::RunCache::default(),
        1,
    )?;
    drop(bar);
    print_study(
        &body,
        &simulation.parameters,
        &study,
        (save.as_deref(), json),
    )
}

/// The study's table (or JSON with `json`) on standard output, and its recording written to
/// `save` when asked.
fn print_study(
    body: &ImportedBody,
    parameters: &crate::models::DrivenBodyParameters,
    study: &crate::models::DrivenStudy,
    (save, json): (Option<&std::path::Path>, bool),
) -> Result<()> {
    let (value, text) = scenes::body_simulation::summary(body, parameters, study);
    if let Some(path) = save {
        let content =
            scenes::body_simulation::recording(&body.model, study, &text, &body.units.length);
        Recorder::default().save(&content, path)?;
        progress(&format!("wrote {}", path.display()));
    }
    if json {
        println!("{value}");
    } else {
        println!("{text}");
    }
    Ok(())
}
