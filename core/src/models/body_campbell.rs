//! The Campbell table of a user's body spun about an axis through its driven interface: the
//! lowest natural frequencies in the turning frame, $(K + \Omega^2(H + K_{\sigma,1}))\phi =
//! \omega^2 M\phi$ on the DOF outside the clamped ring (Coriolis coupling left out, as the
//! FE codes' prestressed frequency steps leave it), at each rate, for the full body and each
//! reduced model, with the preloaded stiffness' stiffening (`[preload]`) or without it.

use faer::Mat;
use nalgebra::{Unit, Vector3};

use crate::{
    Result,
    analysis::count_zero_energy_modes,
    body_file::ImportedBody,
    dynamics::{Combination, DrivenFrameBody, DynamicsError},
    linalg::{PairSelection, generalized_eigen_selected},
    progress::Progress,
    reduction::Method,
};

use super::{
    BodyInterfaces, BodyReducer,
    driven_setup::{apply_preload, drive_interface, free_columns},
};

/// Coordinates above which the dense route refuses a model (its operators are formed
/// column by column and solved densely).
pub const CAMPBELL_DENSE_LIMIT: usize = 6000;

/// A Campbell table's set-up.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCampbellParameters {
    /// The driven interface (`rbe2:SET` or an rbe2 interface of the body file).
    pub drive: String,
    /// The spin axis (body axes).
    pub axis: [f64; 3],
    /// A point of the axis (`None`: the drive's master).
    pub axis_point: Option<[f64; 3]>,
    /// Rates, rad/s.
    pub rates: Vec<f64>,
    /// Frequencies per rate.
    pub count: usize,
    /// Reduced models: method and kept modes.
    pub models: Vec<(Method, usize)>,
    /// With the preloaded stiffness' stiffening (when the body has one).
    pub stiffening: bool,
}

/// One model's frequencies at each rate.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCampbellCurve {
    /// `None`: the full body.
    pub method: Option<Method>,
    /// Kept modes.
    pub modes: usize,
    /// Coordinates.
    pub coordinates: usize,
    /// Frequencies (Hz) at each rate, ascending; a negative value is an unstable pair
    /// ($-\sqrt{-\omega^2}/2\pi$).
    pub hz: Vec<Vec<f64>>,
}

/// The Campbell table of a body.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCampbell {
    /// Rates, rad/s.
    pub rates: Vec<f64>,
    /// Whether the stiffening of a preloaded stiffness was applied.
    pub stiffened: bool,
    /// The full body first.
    pub curves: Vec<BodyCampbellCurve>,
}

/// The lowest `count` frequencies (Hz) of `body` spun at `rate` (rad/s), Coriolis left out:
/// $(K + \Omega^2(H + K_{\sigma,1}))\phi = \omega^2 M\phi$, solved densely and checked pair by
/// pair; a body above [`CAMPBELL_DENSE_LIMIT`] coordinates is refused.
pub fn spinning_frequencies(body: &DrivenFrameBody, rate: f64, count: usize) -> Result<Vec<f64>> {
    let n = body.dim();
    if n > CAMPBELL_DENSE_LIMIT {
        return Err(DynamicsError::DenseRouteTooLarge {
            what: "a Campbell table's dense route",
            coordinates: n,
            limit: CAMPBELL_DENSE_LIMIT,
        }
        .into());
    }
    let mut stiffness = Combination {
        k: 1.0,
        h: rate * rate,
        ..Default::default()
    };
    stiffness.sigma[0] = rate * rate;
    let mass = Combination {
        m: 1.0,
        ..Default::default()
    };
    let symmetric = |a: Mat<f64>| Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let e = generalized_eigen_selected(
        symmetric(body.dense_matrix(stiffness)).as_ref(),
        symmetric(body.dense_matrix(mass)).as_ref(),
        "body spinning on the driven frame",
        PairSelection::Lowest(count),
    )?;
    Ok(e.values
        .iter()
        .map(|&l| l.signum() * l.abs().sqrt() / (2.0 * std::f64::consts::PI))
        .collect())
}

/// The Campbell table of `body` under `parameters`: the full body and each reduced model
/// (its drive's columns removed, as the driven runs remove them).
pub fn body_campbell(
    body: &ImportedBody,
    parameters: &BodyCampbellParameters,
    progress: &Progress,
) -> Result<BodyCampbell> {
    body.require_coordinates()?;
    let model = &body.model;
    let items = vec![parameters.drive.clone()];
    let interfaces = BodyInterfaces::of(body, &items, None)?;
    let drive = drive_interface(body, &parameters.drive, &interfaces)?;
    let axis = Unit::try_new(Vector3::from(parameters.axis), 1e-12).ok_or(
        DynamicsError::ZeroDirection {
            setting: "spin axis",
        },
    )?;
    let origin = parameters.axis_point.unwrap_or(drive.master);
    let ring = model.dofs_of_nodes(&drive.nodes)?;
    progress.phase("full body on the turning frame")?;
    let mut full = DrivenFrameBody::full(model, &ring, vec![], origin, axis)?;
    let stiffened = apply_preload(
        body,
        &mut full,
        parameters.stiffening,
        (axis, origin),
        &ring,
    )?;
    let coords = full
        .coordinates()
        .cloned()
        .expect("the full body has coordinates");
    let table = |b: &DrivenFrameBody| -> Result<Vec<Vec<f64>>> {
        parameters
            .rates
            .iter()
            .map(|&r| spinning_frequencies(b, r, parameters.count))
            .collect()
    };
    let mut curves = vec![BodyCampbellCurve {
        method: None,
        modes: 0,
        coordinates: full.dim(),
        hz: table(&full)?,
    }];
    if !parameters.models.is_empty() {
        progress.phase("the body's zero-energy modes (free-free eigen solve)")?;
        let started = std::time::Instant::now();
        let zero = count_zero_energy_modes(model, 1)?;
        let mut reducer = BodyReducer::new(
            model,
            interfaces,
            &zero,
            started.elapsed().as_secs_f64(),
            progress.clone(),
        )?;
        for &(method, kept) in &parameters.models {
            progress.phase(&format!("{} {kept}", method.name()))?;
            let reduced = reducer.reduce(method, kept)?;
            let keep = free_columns(&reduced.basis, &drive.name, &[]);
            let psi_all = &reduced.basis.psi;
            let psi = Mat::from_fn(psi_all.nrows(), keep.len(), |i, j| psi_all[(i, keep[j])]);
            let psi_free = coords.coordinates_of(psi.as_ref())?;
            let reduced_body = DrivenFrameBody::reduced(&full, psi_free.as_ref())?;
            curves.push(BodyCampbellCurve {
                method: Some(method),
                modes: kept,
                coordinates: reduced_body.dim(),
                hz: table(&reduced_body)?,
            });
        }
    }
    Ok(BodyCampbell {
        rates: parameters.rates.clone(),
        stiffened,
        curves,
    })
}
