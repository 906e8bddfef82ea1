//! `flexmodes campbell`: a user's body spun about an axis through its driven interface, its
//! lowest frequencies at each rate by the full body and each reduced model
//! (models::body_campbell), with the stiffening of its preloaded stiffness or without; the
//! full body only when `--method` names `nr`.

use super::arguments::{CampbellArgs, OnOff, SpinningBodyArgs};
use crate::{
    Error, Progress, Result, TerminalProgress,
    body_file::ImportedBody,
    models::{BodyCampbell, BodyCampbellCurve, BodyCampbellParameters, body_campbell},
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
                residual_vectors,
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
        full: method.contains(&Method::NoReduction),
        residual_vectors: residual_vectors == OnOff::On,
    };
    let handle = Progress::new();
    let bar = TerminalProgress::start(&handle, "campbell");
    let table = body_campbell(&body, &parameters, &handle)?;
    drop(bar);
    if json {
        println!("{}", campbell_json(&body, &table));
    } else {
        println!("{}", campbell_text(&body, &parameters, &table, count));
    }
    Ok(())
}

/// `NR`, `CB 20`, or `CB 20 + 12 RV`.
fn label(c: &BodyCampbellCurve) -> String {
    match c.method {
        None => "NR".to_string(),
        Some(m) if c.residual_vectors > 0 => format!(
            "{} {} + {} RV",
            m.id().to_uppercase(),
            c.modes,
            c.residual_vectors
        ),
        Some(m) => format!("{} {}", m.id().to_uppercase(), c.modes),
    }
}

/// `--json`'s object: the body, rates, stiffening, axis point and every curve.
fn campbell_json(body: &ImportedBody, table: &BodyCampbell) -> serde_json::Value {
    let stiffening = match (table.stiffened, &body.preload) {
        (true, _) => "on",
        (false, Some(_)) => "off",
        (false, None) => "none",
    };
    let curves: Vec<serde_json::Value> = table
        .curves
        .iter()
        .map(|c| {
            serde_json::json!({
                "model": label(c),
                "coordinates": c.coordinates,
                "residual_vectors": c.residual_vectors,
                "route": c.route,
                "hz": c.hz,
                "mac": c.mac,
                "unstable": c.unstable,
                "unstable_from_rad_s": c.unstable_from(&table.rates),
            })
        })
        .collect();
    serde_json::json!({
        "body": body.model.name,
        "rates_rad_s": table.rates,
        "stiffening": stiffening,
        "axis_point": {"point": table.axis_point.0, "from": table.axis_point.1},
        "curves": curves,
    })
}

/// One row per rate and model: the `count` frequencies, "lost" or "unstable" where they are
/// not known, and the row's least MAC.
fn campbell_table(table: &BodyCampbell, count: usize) -> Table {
    let mut header = vec!["rate, rad/s".to_string(), "model".into()];
    header.extend((1..=count).map(|k| format!("f{k}, Hz")));
    header.push("least MAC".into());
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut out = Table::new(&header);
    for (r, rate) in table.rates.iter().enumerate() {
        for c in &table.curves {
            let mut row = vec![Cell::text(format!("{rate}")), Cell::text(label(c))];
            if c.unstable[r] > 0 && c.hz[r].iter().all(|f| f.is_nan()) {
                row.extend((0..count).map(|k| {
                    if k == 0 {
                        Cell::text(format!(
                            "unstable: {} negative eigenvalue(s)",
                            c.unstable[r]
                        ))
                    } else {
                        Cell::text(String::new())
                    }
                }));
            } else {
                row.extend(c.hz[r].iter().map(|&f| {
                    if f.is_nan() {
                        Cell::text("lost".to_string())
                    } else if f < 0.0 {
                        Cell::number(f, format!("unstable ({:.4})", -f))
                    } else {
                        Cell::number(f, crate::report::sig6(f))
                    }
                }));
            }
            let least = c.mac[r].iter().cloned().fold(f64::INFINITY, f64::min);
            row.push(if least.is_finite() {
                Cell::number(least, format!("{least:.3}"))
            } else {
                Cell::text("–".to_string())
            });
            out.push(row);
        }
    }
    out
}

/// The printed result: what was spun and how, the table, the routes and the unstable rates.
fn campbell_text(
    body: &ImportedBody,
    parameters: &BodyCampbellParameters,
    table: &BodyCampbell,
    count: usize,
) -> String {
    let unstable: Vec<String> = table
        .curves
        .iter()
        .filter_map(|c| {
            c.unstable_from(&table.rates)
                .map(|r| format!("{} unstable from Ω = {r} rad/s", label(c)))
        })
        .collect();
    let routes: Vec<String> = table
        .curves
        .iter()
        .map(|c| format!("{} {}", label(c), c.route))
        .collect();
    format!(
        "# campbell `{}`: spun about ({}) through {} ({}), {}\n\n{}\nFrequencies in the \
         turning frame, ring clamped, Coriolis coupling left out (as the FE codes' prestressed \
         frequency steps leave it). Each column follows one mode shape from rate to rate (MAC \
         against the rate before; `least MAC` is the row's smallest; `lost`: none of the pairs \
         solved (four more than shown) has the shape, MAC below 0.5); `unstable`: the spin's \
         softening passed the stiffness. RV: inertia-load residual vectors. Solved: {}.{}",
        body.model.name,
        parameters.axis.map(|a| a.to_string()).join(", "),
        table.axis_point.0.map(crate::report::sig6).join(", "),
        table.axis_point.1,
        match (table.stiffened, &body.preload) {
            (true, Some(p)) => format!(
                "dynamic stiffening on, from the body's [preload] spun at {} rad/s",
                crate::report::sig6(p.load.rate)
            ),
            (false, Some(_)) => "dynamic stiffening OFF (--stiffening off)".into(),
            _ => "no dynamic stiffening: the body file gives no [preload]".into(),
        },
        campbell_table(table, count).markdown(),
        routes.join("; "),
        if unstable.is_empty() {
            String::new()
        } else {
            format!("\n{}.", unstable.join("; "))
        }
    )
}
