//! `flexmodes campbell`: a user's body spun about an axis through its driven interface, its
//! lowest frequencies at each rate by the full body and each reduced model
//! (models::body_campbell), with the stiffening of its preloaded stiffness or without.

use super::arguments::{CampbellArgs, OnOff, SpinningBodyArgs};
use crate::{
    Error, Progress, Result, TerminalProgress,
    body_file::ImportedBody,
    models::{BodyCampbellParameters, body_campbell},
    reduction::Method,
    report::{Cell, Table},
};

/// Runs `campbell` with its arguments.
pub(super) fn run(arguments: CampbellArgs) -> Result<()> {
    let CampbellArgs {
        spin:
            SpinningBodyArgs {
                body,
                drive,
                axis,
                axis_point,
                stiffening,
            },
        rates,
        count,
        method,
        modes,
        json,
    } = arguments;
    let three = super::arguments::three_numbers;
    if let Some(r) = rates.iter().find(|r| !(r.is_finite() && **r >= 0.0)) {
        return Err(Error::InvalidOption {
            option: "--rates",
            scene: None,
            reason: format!("rates are rad/s, finite and not negative, not {r}"),
        });
    }
    let body = ImportedBody::load(&body)?;
    let models: Vec<(Method, usize)> = method
        .iter()
        .filter(|m| **m != Method::NoReduction)
        .flat_map(|&m| modes.iter().map(move |&k| (m, k)))
        .collect();
    let parameters = BodyCampbellParameters {
        drive,
        axis: three("--axis", &axis)?,
        axis_point: axis_point.map(|p| three("--axis-point", &p)).transpose()?,
        rates,
        count,
        models,
        stiffening: stiffening == OnOff::On,
    };
    let handle = Progress::new();
    let bar = TerminalProgress::start(&handle, "campbell");
    let table = body_campbell(&body, &parameters, &handle)?;
    drop(bar);
    let label = |c: &crate::models::BodyCampbellCurve| match c.method {
        None => "NR".to_string(),
        Some(m) => format!("{} {}", m.id().to_uppercase(), c.modes),
    };
    if json {
        let curves: Vec<serde_json::Value> = table
            .curves
            .iter()
            .map(|c| serde_json::json!({"model": label(c), "coordinates": c.coordinates, "hz": c.hz}))
            .collect();
        let value = serde_json::json!({
            "body": body.model.name,
            "rates_rad_s": table.rates,
            "stiffening": match (table.stiffened, &body.preload) {
                (true, _) => "on",
                (false, Some(_)) => "off",
                (false, None) => "none",
            },
            "curves": curves,
        });
        println!("{value}");
        return Ok(());
    }
    let mut header = vec!["rate, rad/s".to_string(), "model".into()];
    header.extend((1..=count).map(|k| format!("f{k}, Hz")));
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut out = Table::new(&header);
    for (r, rate) in table.rates.iter().enumerate() {
        for c in &table.curves {
            let mut row = vec![Cell::text(format!("{rate}")), Cell::text(label(c))];
            row.extend(c.hz[r].iter().map(|&f| {
                if f < 0.0 {
                    Cell::number(f, format!("unstable ({:.4})", -f))
                } else {
                    Cell::number(f, crate::report::sig6(f))
                }
            }));
            out.push(row);
        }
    }
    println!(
        "# campbell `{}`: spun about ({}) through `{}`, {}\n\n{}\nFrequencies in the turning \
         frame, ring clamped, Coriolis coupling left out (as the FE codes' prestressed \
         frequency steps leave it); `unstable`: the spin's softening passed the stiffness.",
        body.model.name,
        parameters.axis.map(|a| a.to_string()).join(", "),
        parameters.drive,
        match (table.stiffened, &body.preload) {
            (true, Some(p)) => format!(
                "dynamic stiffening on, from the body's [preload] spun at {} rad/s",
                crate::report::sig6(p.load.rate)
            ),
            (false, Some(_)) => "dynamic stiffening OFF (--stiffening off)".into(),
            _ => "no dynamic stiffening: the body file gives no [preload]".into(),
        },
        out.markdown()
    );
    Ok(())
}
