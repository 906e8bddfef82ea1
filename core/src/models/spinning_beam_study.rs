//! The spinning cantilever with and without dynamic stiffening (Lin's thesis §1, the open
//! problem of its refs. [16], [18]): the Campbell diagram of the rotating beam against the
//! published tables (Wright, Smith, Thresher & Wang 1982; Hodges & Rutkowski 1981), and Kane,
//! Ryan & Banerjee's (1987) spin-up against an independent geometrically nonlinear reference
//! (a co-rotational beam, `assets/generate/spinning_beam_reference.py`).
//!
//! Each model is the driven frame's linear equations ([`DrivenFrameBody`]) of the full FE
//! beam (NR) or of its $k$ lowest clamped modes at rest (CB: the hub's clamp is the only
//! interface, and its constraint modes are the rigid motions the clamp holds still), with
//! the geometric stiffness of the frame's loads ([`FrameStiffening`]) or without it.

use std::time::Instant;

use super::spinning_model_label::model_label;

use faer::Mat;
use nalgebra::{DMatrix, Vector3};

use crate::{
    Error, Result,
    dynamics::{
        DenseDrivenOperators, DivergenceCause, DrivenFrameBody, DrivenIntegration, Driving,
        DynamicsError, FrameStiffening, SpinUp, integrate_driven,
    },
    fem::{BendingPlane, SpinningBeam, SpinningBeamParameters},
    linalg::{PairSelection, generalized_eigen, generalized_eigen_selected},
    progress::Progress,
};

/// The dimensionless speeds $\lambda$ of the Campbell diagram.
pub const CAMPBELL_SPEEDS: [f64; 13] = [
    0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0,
];

/// Largest relative difference from the published flapwise frequencies that NR and CB with
/// [`CampbellParameters::reduced_modes`] modes meet for λ = 0…10 (the tables print four
/// decimals: half a unit of the last is 1.4e-5 of the first frequency at rest).
pub const PUBLISHED_TOLERANCE: f64 = 1e-3;

/// Relative peak-normalised difference from the nonlinear reference that NR and CB with
/// stiffening meet over 0–20 s.
pub const SPIN_UP_TOLERANCE: f64 = 0.05;

/// The Campbell diagram's set-up.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellParameters {
    /// The beam (the frequencies are dimensionless: any uniform beam gives the same).
    pub beam: SpinningBeamParameters,
    /// Dimensionless speeds λ.
    pub speeds: Vec<f64>,
    /// Modes of the reduced model (CB).
    pub reduced_modes: usize,
}

impl Default for CampbellParameters {
    fn default() -> Self {
        Self {
            beam: SpinningBeamParameters {
                elements: 40,
                ..Default::default()
            },
            speeds: CAMPBELL_SPEEDS.to_vec(),
            reduced_modes: 6,
        }
    }
}

/// One model's two lowest bending frequencies over the speeds, in one plane.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellCurve {
    /// Kept modes (0: NR, the full FE beam).
    pub modes: usize,
    /// With the geometric stiffness of the centrifugal load.
    pub stiffening: bool,
    /// Flapwise or lagwise.
    pub plane: BendingPlane,
    /// $\mu^2 = \omega^2\rho AL^4/EI$ of the two lowest pairs at each speed (negative: the
    /// model is unstable there, its coordinates grow like $e^{\sqrt{-\mu^2}\,\tau}$).
    pub mu_squared: Vec<[f64; 2]>,
}

impl CampbellCurve {
    /// `NR` or `CB 6`, and `, no stiffening`.
    pub fn label(&self) -> String {
        model_label(self.modes, self.stiffening)
    }

    /// $\mu$ of the two lowest pairs ($0$ where $\mu^2 \le 0$).
    pub fn mu(&self) -> Vec<[f64; 2]> {
        self.mu_squared
            .iter()
            .map(|p| p.map(|m| m.max(0.0).sqrt()))
            .collect()
    }

    /// The lowest speed at which the model has lost its first frequency ($\mu_1^2 \le 0$).
    pub fn unstable_from(&self, speeds: &[f64]) -> Option<f64> {
        assert_eq!(speeds.len(), self.mu_squared.len(), "a pair per speed");
        speeds
            .iter()
            .zip(&self.mu_squared)
            .find(|(_, m)| m[0] <= 0.0)
            .map(|(s, _)| *s)
    }
}

/// The Campbell diagram of the rotating cantilever.
#[derive(Debug, Clone)]
pub struct CampbellStudy {
    /// The set-up.
    pub parameters: CampbellParameters,
    /// NR and CB, with and without stiffening, flapwise then lagwise.
    pub curves: Vec<CampbellCurve>,
    /// The published flapwise table: (λ, μ₁, μ₂).
    pub published: Vec<[f64; 3]>,
    /// The largest relative residual of every eigenpair shown.
    pub max_residual: f64,
}

impl CampbellStudy {
    /// The curve of `modes`, `stiffening`, `plane`.
    pub fn curve(
        &self,
        modes: usize,
        stiffening: bool,
        plane: BendingPlane,
    ) -> Option<&CampbellCurve> {
        self.curves
            .iter()
            .find(|c| c.modes == modes && c.stiffening == stiffening && c.plane == plane)
    }

    /// The largest relative difference of a flapwise curve from the published table over the
    /// published speeds up to `up_to`.
    pub fn published_difference(&self, curve: &CampbellCurve, up_to: f64) -> f64 {
        let speeds = &self.parameters.speeds;
        let mu = curve.mu();
        let mut worst = 0.0f64;
        for row in self.published.iter().filter(|r| r[0] <= up_to) {
            if let Some(i) = speeds.iter().position(|&s| s == row[0]) {
                for m in 0..2 {
                    worst = worst.max((mu[i][m] - row[1 + m]).abs() / row[1 + m]);
                }
            }
        }
        worst
    }
}

/// The published flapwise table (`assets/papers/rotating-cantilever-flapwise.csv`).
pub fn published_flapwise() -> Vec<[f64; 3]> {
    let text = crate::assets::text("papers/rotating-cantilever-flapwise.csv")
        .expect("the rotating-cantilever table is embedded");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("lambda"))
        .map(|l| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().expect("the embedded table is numbers"))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// A beam's operators in one plane with the centrifugal case's geometric stiffness, and the
/// clamped modes at rest (mass-normalised, ascending).
struct PlaneModel {
    beam: SpinningBeam,
    centrifugal: DMatrix<f64>,
    modes: DMatrix<f64>,
    max_residual: f64,
}

fn to_faer(a: &DMatrix<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}

fn plane_model(p: &SpinningBeamParameters, plane: BendingPlane, keep: usize) -> Result<PlaneModel> {
    let beam = SpinningBeam::new(p, plane);
    let [centrifugal, ..] = beam.unit_geometric_stiffnesses()?;
    let centrifugal = centrifugal.ok_or(Error::Dynamics(DynamicsError::Misuse {
        what: "a spinning beam's centrifugal load stresses it axially",
    }))?;
    let e = generalized_eigen(
        to_faer(&beam.k).as_ref(),
        to_faer(&beam.m).as_ref(),
        "clamped spinning beam",
    )?;
    let keep = keep.min(beam.dim());
    let modes = DMatrix::from_fn(beam.dim(), keep, |i, j| e.vectors[(i, j)]);
    Ok(PlaneModel {
        max_residual: e.residuals.iter().copied().fold(0.0, f64::max),
        beam,
        centrifugal,
        modes,
    })
}

/// A plane's operators on one basis (the full beam's DOF, or Ψ), projected once:
/// $\Psi^TK\Psi$, $\Psi^TH\Psi$, $\Psi^TK_\sigma\Psi$, $\Psi^TM\Psi$.
struct Projected {
    k: DMatrix<f64>,
    h: DMatrix<f64>,
    centrifugal: DMatrix<f64>,
    m: DMatrix<f64>,
}

impl Projected {
    fn of(model: &PlaneModel, psi: Option<&DMatrix<f64>>) -> Self {
        let b = &model.beam;
        let project = |a: &DMatrix<f64>| match psi {
            Some(p) => {
                let r = p.transpose() * a * p;
                (&r + r.transpose()) * 0.5
            }
            None => a.clone(),
        };
        Self {
            k: project(&b.k),
            h: project(&b.h),
            centrifugal: project(&model.centrifugal),
            m: project(&b.m),
        }
    }

    /// The two lowest eigenvalues of $K + \Omega^2(H + sK_\sigma)$ with $M$, in units of
    /// $EI/(\rho AL^4)$, and the larger of their two residuals.
    fn lowest_pair(&self, rate: f64, stiffening: bool, unit: f64) -> Result<([f64; 2], f64)> {
        let mut k = &self.k + &self.h * (rate * rate);
        if stiffening {
            k += &self.centrifugal * (rate * rate);
        }
        let e = generalized_eigen_selected(
            to_faer(&k).as_ref(),
            to_faer(&self.m).as_ref(),
            "spinning beam",
            PairSelection::Lowest(2),
        )?;
        let r = e.residuals.iter().copied().fold(0.0, f64::max);
        Ok((
            [e.values[0] / (unit * unit), e.values[1] / (unit * unit)],
            r,
        ))
    }
}

/// The Campbell diagram: NR and CB, with and without the centrifugal geometric stiffness,
/// flapwise and lagwise (Coriolis coupling to the axial motion left out, as in the published
/// tables), every pair's residual checked by the eigensolver.
pub fn campbell_study(parameters: &CampbellParameters) -> Result<CampbellStudy> {
    let unit = parameters.beam.frequency_unit();
    let mut curves = Vec::new();
    let mut max_residual = 0.0f64;
    for plane in [BendingPlane::Flapwise, BendingPlane::Lagwise] {
        let model = plane_model(&parameters.beam, plane, parameters.reduced_modes)?;
        max_residual = max_residual.max(model.max_residual);
        for modes in [0, parameters.reduced_modes] {
            let projected = Projected::of(&model, (modes > 0).then_some(&model.modes));
            for stiffening in [true, false] {
                let mut mu_squared = Vec::with_capacity(parameters.speeds.len());
                for &lambda in &parameters.speeds {
                    let (pair, r) = projected.lowest_pair(lambda * unit, stiffening, unit)?;
                    max_residual = max_residual.max(r);
                    mu_squared.push(pair);
                }
                curves.push(CampbellCurve {
                    modes,
                    stiffening,
                    plane,
                    mu_squared,
                });
            }
        }
    }
    Ok(CampbellStudy {
        parameters: parameters.clone(),
        curves,
        published: published_flapwise(),
        max_residual,
    })
}

/// Kane's spin-up: the set-up.
#[derive(Debug, Clone, PartialEq)]
pub struct SpinUpParameters {
    /// The beam (Kane et al.'s by default, 20 elements).
    pub beam: SpinningBeamParameters,
    /// Steady rates $\omega_s$, rad/s.
    pub rates: Vec<f64>,
    /// Ramp time $T_s$, s.
    pub ramp: f64,
    /// The integration (generalized-α).
    pub integration: DrivenIntegration,
    /// Modes of the reduced model (CB).
    pub reduced_modes: usize,
}

impl Default for SpinUpParameters {
    fn default() -> Self {
        Self {
            beam: SpinningBeamParameters::default(),
            rates: vec![4.0, 10.0],
            ramp: 15.0,
            integration: DrivenIntegration {
                step: 1e-2,
                end: 20.0,
                spectral_radius: 0.9,
                output_every: 5,
            },
            reduced_modes: 6,
        }
    }
}

/// Where a run left the small-deformation range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Divergence {
    /// Time the tip's deflection passed the beam's length, s.
    pub time: f64,
    /// The hub's rate then, rad/s.
    pub rate: f64,
    /// The time the hub's rate passed the first bending frequency at rest, s (`None`: it
    /// never did).
    pub rate_passed_first_frequency: Option<f64>,
}

/// One model's run at one steady rate.
#[derive(Debug, Clone, PartialEq)]
pub struct SpinUpRun {
    /// Steady rate, rad/s.
    pub rate: f64,
    /// Kept modes (0: NR).
    pub modes: usize,
    /// With the geometric stiffness of the frame's loads.
    pub stiffening: bool,
    /// Sample times, s.
    pub times: Vec<f64>,
    /// The tip's transverse deflection in the hub frame, m.
    pub tip: Vec<f64>,
    /// Where it diverged, if it did.
    pub divergence: Option<Divergence>,
    /// Integration time (the observer's left out), s.
    pub online_s: f64,
}

impl SpinUpRun {
    /// `NR` or `CB 6`, and `, no stiffening`.
    pub fn label(&self) -> String {
        model_label(self.modes, self.stiffening)
    }

    /// $\max_t |y(t) - y_{ref}(t)| / \max_t |y_{ref}(t)|$ against a reference sampled at
    /// `times` (linear interpolation), over this run's samples.
    pub fn difference(&self, reference: &[(f64, f64)]) -> f64 {
        let peak = reference.iter().map(|r| r.1.abs()).fold(0.0, f64::max);
        let worst = self
            .times
            .iter()
            .zip(&self.tip)
            .map(|(&t, &y)| (y - interpolate(reference, t)).abs())
            .fold(0.0, f64::max);
        worst / peak.max(f64::MIN_POSITIVE)
    }

    /// The largest |tip deflection|, m.
    pub fn peak(&self) -> f64 {
        self.tip.iter().map(|y| y.abs()).fold(0.0, f64::max)
    }
}

fn interpolate(table: &[(f64, f64)], t: f64) -> f64 {
    let i = table.partition_point(|r| r.0 < t);
    if i == 0 {
        return table.first().map_or(0.0, |r| r.1);
    }
    if i >= table.len() {
        return table.last().map_or(0.0, |r| r.1);
    }
    let (a, b) = (table[i - 1], table[i]);
    a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0)
}

/// The reference tip history at rate `rate` (4 or 10 rad/s) written by the generator, as
/// (time s, deflection m); `None` for another rate.
pub fn spin_up_reference(rate: f64) -> Option<Vec<(f64, f64)>> {
    let path = match rate {
        4.0 => "papers/kane-spin-up-4.csv",
        10.0 => "papers/kane-spin-up-10.csv",
        _ => return None,
    };
    let text = crate::assets::text(path)?;
    Some(
        text.lines()
            .skip(1)
            .filter_map(|l| {
                let (t, y) = l.split_once(',')?;
                Some((t.trim().parse().ok()?, y.trim().parse().ok()?))
            })
            .collect(),
    )
}

/// Kane's spin-up study.
#[derive(Debug, Clone)]
pub struct SpinUpStudy {
    /// The set-up.
    pub parameters: SpinUpParameters,
    /// The beam's first bending frequency at rest, rad/s.
    pub first_frequency: f64,
    /// Every run: per rate, NR and CB, with and without stiffening.
    pub runs: Vec<SpinUpRun>,
}

/// The driven beam of `p` with its unit geometric stiffnesses (lagwise: the hub turns in the
/// beam's plane).
pub fn spinning_beam_body(p: &SpinningBeamParameters) -> Result<(SpinningBeam, DrivenFrameBody)> {
    let beam = SpinningBeam::new(p, BendingPlane::Lagwise);
    let cases = beam.unit_geometric_stiffnesses()?;
    let stiffening = Some(FrameStiffening::new(cases)?);
    let v = |x: &nalgebra::DVector<f64>| x.as_slice().to_vec();
    let zero = vec![0.0; beam.dim()];
    let body = DrivenFrameBody::dense(DenseDrivenOperators {
        m: beam.m.clone(),
        k: beam.k.clone(),
        g: beam.g.clone(),
        h: beam.h.clone(),
        g_s: v(&beam.g_s),
        h_s: v(&beam.h_s),
        unit_gravity: [v(&beam.unit_gravity[0]), v(&beam.unit_gravity[1]), zero],
        stiffening,
    })?;
    Ok((beam, body))
}

/// Kane's beam and its reduced model, built once, run at any rate with or without
/// stiffening.
pub struct SpinUpModels {
    parameters: SpinUpParameters,
    beam: SpinningBeam,
    full: DrivenFrameBody,
    reduced: DrivenFrameBody,
    /// The reduced model's tip row of Ψ.
    tip_row: Vec<f64>,
    /// The first bending frequency at rest, rad/s.
    pub first_frequency: f64,
}

impl SpinUpModels {
    /// The full beam and CB with [`SpinUpParameters::reduced_modes`] clamped modes.
    pub fn new(parameters: &SpinUpParameters) -> Result<Self> {
        let (beam, full) = spinning_beam_body(&parameters.beam)?;
        let e = generalized_eigen(
            to_faer(&beam.k).as_ref(),
            to_faer(&beam.m).as_ref(),
            "clamped spinning beam",
        )?;
        let keep = parameters.reduced_modes.clamp(1, beam.dim());
        let psi = Mat::from_fn(beam.dim(), keep, |i, j| e.vectors[(i, j)]);
        let reduced = DrivenFrameBody::reduced(&full, psi.as_ref())?;
        let tip = beam.tip_deflection_dof();
        Ok(Self {
            parameters: parameters.clone(),
            tip_row: (0..keep).map(|j| psi[(tip, j)]).collect(),
            first_frequency: e.values[0].sqrt(),
            beam,
            full,
            reduced,
        })
    }

    /// Kept modes of the reduced model.
    pub fn reduced_modes(&self) -> usize {
        self.tip_row.len()
    }

    /// One run at steady rate `rate` (rad/s): NR (`modes` 0) or CB, with or without
    /// stiffening. A run whose tip deflection passes the beam's length stops there: the
    /// linear model has diverged, and the run says when and at what hub rate.
    pub fn run(
        &self,
        rate: f64,
        modes: usize,
        stiffening: bool,
        progress: &Progress,
    ) -> Result<SpinUpRun> {
        let spin = SpinUp {
            axis: Vector3::z_axis(),
            rate,
            ramp: self.parameters.ramp,
        };
        let driving = Driving {
            spin,
            shake: None,
            gravity: Vector3::zeros(),
        };
        let (base, modes) = if modes == 0 {
            (&self.full, 0)
        } else {
            (&self.reduced, self.reduced_modes())
        };
        let mut body = base.dense_copy(stiffening)?;
        let tip = self.beam.tip_deflection_dof();
        let bound = self.parameters.beam.length;
        let (mut times, mut tips) = (Vec::new(), Vec::new());
        let started = Instant::now();
        let outcome = integrate_driven(
            &mut body,
            &driving,
            &self.parameters.integration,
            progress,
            |t, u, _, _| {
                let y = if modes == 0 {
                    u[tip]
                } else {
                    self.tip_row.iter().zip(u).map(|(a, b)| a * b).sum()
                };
                if y.is_nan() || y.abs() > bound {
                    return Err(DynamicsError::Diverged {
                        time: t,
                        cause: DivergenceCause::StateBeyondBound { bound },
                    }
                    .into());
                }
                times.push(t);
                tips.push(y);
                Ok(())
            },
        );
        let online_s = started.elapsed().as_secs_f64();
        let divergence = match outcome {
            Ok(_) => None,
            Err(Error::Dynamics(DynamicsError::Diverged { time, .. })) => Some(Divergence {
                time,
                rate: spin.at(time).1,
                rate_passed_first_frequency: passing_time(&spin, self.first_frequency),
            }),
            Err(other) => return Err(other),
        };
        Ok(SpinUpRun {
            rate,
            modes,
            stiffening,
            times,
            tip: tips,
            divergence,
            online_s,
        })
    }
}

/// Runs Kane's spin-up at each rate by NR and CB, with and without stiffening.
pub fn spin_up_study(parameters: &SpinUpParameters, progress: &Progress) -> Result<SpinUpStudy> {
    let models = SpinUpModels::new(parameters)?;
    let mut runs = Vec::new();
    for &rate in &parameters.rates {
        for modes in [0, models.reduced_modes()] {
            for stiffening in [true, false] {
                let label = model_label(modes, stiffening);
                progress.phase(&format!("spin-up {rate} rad/s: {label}"))?;
                runs.push(models.run(rate, modes, stiffening, progress)?);
            }
        }
    }
    Ok(SpinUpStudy {
        parameters: parameters.clone(),
        first_frequency: models.first_frequency,
        runs,
    })
}

/// The first time the spin-up's rate reaches `frequency` (bisection on the monotone ramp).
fn passing_time(spin: &SpinUp, frequency: f64) -> Option<f64> {
    if spin.rate < frequency {
        return None;
    }
    let (mut a, mut b) = (0.0, spin.ramp);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if spin.at(m).1 < frequency {
            a = m;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}
