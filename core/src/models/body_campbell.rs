//! The Campbell table of a user's body spun about an axis through its driven interface: the
//! lowest natural frequencies in the turning frame, $(K + \Omega^2(H + K_{\sigma,1}))\phi =
//! \omega^2 M\phi$ on the DOF outside the clamped ring (Coriolis coupling left out, as the
//! FE codes' prestressed frequency steps leave it), at each rate, for the full body (sparse,
//! whatever its size) and each reduced model, with the preloaded stiffness' stiffening
//! (`[preload]`) or without it. Each curve follows one mode shape from rate to rate by MAC
//! (modes cross and veer), and a rate past divergence says so.

use faer::Mat;
use nalgebra::{Unit, Vector3};

use crate::{
    Result,
    analysis::count_zero_energy_modes,
    body_file::ImportedBody,
    dynamics::{Combination, DrivenFrameBody, DynamicsError},
    progress::Progress,
    reduction::Method,
};

use super::{
    BodyInterfaces, BodyReducer,
    driven_setup::{apply_preload, drive_interface, free_columns, spin_axis_point},
    spinning_pairs::{spinning_pairs, track_by_mac},
};

/// A Campbell table's set-up.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCampbellParameters {
    /// The driven interface (`rbe2:SET` or an rbe2 interface of the body file).
    pub drive: String,
    /// The spin axis (body axes).
    pub axis: [f64; 3],
    /// A point of the axis (`None`: the preload's axis when the drive's ring is coaxial with
    /// it, else the drive's master).
    pub axis_point: Option<[f64; 3]>,
    /// Rates, rad/s.
    pub rates: Vec<f64>,
    /// Frequencies per rate.
    pub count: usize,
    /// Reduced models: method and kept modes.
    pub models: Vec<(Method, usize)>,
    /// With the preloaded stiffness' stiffening (when the body has one).
    pub stiffening: bool,
    /// The full body's curves too (its sparse solve at every rate); reduced models need none.
    pub full: bool,
    /// Inertia-load residual vectors in the reduced bases.
    pub residual_vectors: bool,
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
    /// Inertia-load residual vectors in the basis.
    pub residual_vectors: usize,
    /// Frequencies (Hz) at each rate, curve by curve: the k-th value at every rate belongs
    /// to one mode shape, carried from rate to rate by MAC (modes cross and veer), in the
    /// ascending order of the first rate; a negative value is an unstable pair
    /// ($-\sqrt{-\omega^2}/2\pi$); NaN where the pairs are unknown (an unstable full body)
    /// or the curve's shape is lost (no candidate with a MAC of [`LOST_MAC`]).
    pub hz: Vec<Vec<f64>>,
    /// The MAC with which each curve was carried to each rate (1 at the first).
    pub mac: Vec<Vec<f64>>,
    /// Negative eigenvalues of the spun stiffness at each rate (0: stable).
    pub unstable: Vec<usize>,
    /// How the pairs were solved (`dense`, `sparse Lanczos, Sturm-checked`).
    pub route: &'static str,
}

impl BodyCampbellCurve {
    /// The lowest rate (rad/s) of `rates` at which the model is unstable.
    pub fn unstable_from(&self, rates: &[f64]) -> Option<f64> {
        rates
            .iter()
            .zip(&self.unstable)
            .find(|(_, u)| **u > 0)
            .map(|(r, _)| *r)
    }
}

/// The Campbell table of a body.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyCampbell {
    /// Rates, rad/s.
    pub rates: Vec<f64>,
    /// Whether the stiffening of a preloaded stiffness was applied.
    pub stiffened: bool,
    /// The point of the spin axis the frame turns about, and where it came from.
    pub axis_point: ([f64; 3], &'static str),
    /// The full body first (when asked for).
    pub curves: Vec<BodyCampbellCurve>,
}

/// The lowest `count` frequencies (Hz) of `body` spun at `rate` (rad/s), Coriolis left out
/// ([`spinning_pairs`]).
pub fn spinning_frequencies(body: &DrivenFrameBody, rate: f64, count: usize) -> Result<Vec<f64>> {
    Ok(spinning_pairs(body, rate, count)?.hz())
}

/// One model's curves: frequencies and MACs per rate, unstable counts, the route.
type Curve = (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<usize>, &'static str);

/// The curves of one model over `rates`, tracked by MAC.
fn curve(
    body: &DrivenFrameBody,
    rates: &[f64],
    count: usize,
    progress: &Progress,
    what: &str,
) -> Result<Curve> {
    let mut hz = Vec::new();
    let mut macs = Vec::new();
    let mut unstable = Vec::new();
    // The shape each curve had when last found.
    let mut previous: Option<Mat<f64>> = None;
    let mut route = "dense";
    // Candidates beyond the curves shown: a mode that climbs past a higher one stays found.
    let wanted = (count + TRACKING_SPARE).min(body.dim());
    for &rate in rates {
        progress.phase(&format!("{what} at {rate} rad/s"))?;
        let pairs = spinning_pairs(body, rate, wanted)?;
        route = pairs.route;
        unstable.push(pairs.unstable);
        let f = pairs.hz();
        let shown = count.min(f.len());
        if f.is_empty() {
            hz.push(vec![f64::NAN; count]);
            macs.push(vec![f64::NAN; count]);
            continue;
        }
        let Some(prev) = previous.as_ref().filter(|p| p.ncols() == shown) else {
            macs.push(vec![1.0; shown]);
            hz.push(f[..shown].to_vec());
            previous = Some(pairs.vectors.subcols(0, shown).to_owned());
            continue;
        };
        let m_current = mass_times(body, &pairs.vectors);
        let order = track_by_mac(prev, &m_current);
        let mut row = vec![f64::NAN; shown];
        let mut mac_row = vec![0.0; shown];
        let mut next = prev.clone();
        for (c, o) in order.iter().enumerate() {
            let Some((j, v)) = o else { continue };
            mac_row[c] = *v;
            if *v < LOST_MAC {
                // No candidate has this curve's shape: not drawn at this rate.
                continue;
            }
            row[c] = f[*j];
            // The sign that keeps the shape's orientation.
            let dot: f64 = (0..next.nrows())
                .map(|i| prev[(i, c)] * m_current[(i, *j)])
                .sum();
            let sign = if dot < 0.0 { -1.0 } else { 1.0 };
            for i in 0..next.nrows() {
                next[(i, c)] = sign * pairs.vectors[(i, *j)];
            }
        }
        hz.push(row);
        macs.push(mac_row);
        previous = Some(next);
    }
    Ok((hz, macs, unstable, route))
}

/// Pairs solved beyond the curves shown, for tracking.
const TRACKING_SPARE: usize = 4;

/// A curve whose best MAC falls below this is lost at that rate (its value not given).
pub const LOST_MAC: f64 = 0.5;

fn mass_times(body: &DrivenFrameBody, x: &Mat<f64>) -> Mat<f64> {
    let mass = Combination {
        m: 1.0,
        ..Default::default()
    };
    let mut out = Mat::<f64>::zeros(x.nrows(), x.ncols());
    for j in 0..x.ncols() {
        let col: Vec<f64> = (0..x.nrows()).map(|i| x[(i, j)]).collect();
        for (i, v) in body.mul(mass, &col).into_iter().enumerate() {
            out[(i, j)] = v;
        }
    }
    out
}

/// The spin axis of `parameters` (a unit vector; zero is refused) and the point it passes
/// through, with where that point came from.
fn spin_axis(
    body: &ImportedBody,
    drive: &crate::reduction::RigidInterface,
    parameters: &BodyCampbellParameters,
) -> Result<(Unit<Vector3<f64>>, super::driven_setup::AxisPoint)> {
    let axis = Unit::try_new(Vector3::from(parameters.axis), 1e-12).ok_or(
        DynamicsError::ZeroDirection {
            setting: "spin axis",
        },
    )?;
    let axis_point = spin_axis_point(
        body,
        drive,
        axis,
        parameters.axis_point,
        parameters.stiffening,
    )?;
    Ok((axis, axis_point))
}

/// The Campbell table of `body` under `parameters`: the full body (when asked) and each
/// reduced model (its drive's columns removed, as the driven runs remove them).
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
    let (axis, axis_point) = spin_axis(body, &drive, parameters)?;
    let origin = axis_point.0;
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
    let mut curves = Vec::new();
    if parameters.full {
        let (hz, mac, unstable, route) =
            curve(&full, &parameters.rates, parameters.count, progress, "NR")?;
        curves.push(BodyCampbellCurve {
            method: None,
            modes: 0,
            coordinates: full.dim(),
            residual_vectors: 0,
            hz,
            mac,
            unstable,
            route,
        });
    }
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
        )?
        .with_residual_vectors(parameters.residual_vectors);
        for &(method, kept) in &parameters.models {
            progress.phase(&format!("{} {kept}", method.name()))?;
            let reduced = reducer.reduce(method, kept)?;
            let keep = free_columns(&reduced.basis, &drive.name, &[]);
            let psi_all = &reduced.basis.psi;
            let psi = Mat::from_fn(psi_all.nrows(), keep.len(), |i, j| psi_all[(i, keep[j])]);
            let psi_free = coords.coordinates_of(psi.as_ref())?;
            let reduced_body = DrivenFrameBody::reduced(&full, psi_free.as_ref())?;
            let label = format!("{} {kept}", method.id().to_uppercase());
            let (hz, mac, unstable, route) = curve(
                &reduced_body,
                &parameters.rates,
                parameters.count,
                progress,
                &label,
            )?;
            curves.push(BodyCampbellCurve {
                method: Some(method),
                modes: kept,
                coordinates: reduced_body.dim(),
                residual_vectors: reduced
                    .residual_vectors
                    .as_ref()
                    .map_or(0, |r| r.kept.len()),
                hz,
                mac,
                unstable,
                route,
            });
        }
    }
    Ok(BodyCampbell {
        rates: parameters.rates.clone(),
        stiffened,
        axis_point,
        curves,
    })
}
