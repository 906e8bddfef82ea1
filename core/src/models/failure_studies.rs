//! Where each classical method fails, measured: Craig–Bampton with too few boundary DOF
//! (§6.4), Eitelberg without the output-feedback trick (§6.6, App. C), mode condensation's
//! complete interior eigenproblem (§6.5), mean axes with a Guyan-condensed mass (Eqs. 3.26,
//! 4.17), an explicit step above the critical one (§7.2), Guyan (b)'s broken symmetry
//! (§6.2.1) and modal truncation under boundary motion (§6.3, §7.1).

use crate::dynamics::DynamicsError;
use crate::reduction::ReductionError;
use crate::reduction::{ReductionRequest, reduce};
use std::time::Instant;

use faer::Mat;

use super::{PROBE_NODE, Scenario, default_boundary, probe_history, reduction_nodes, slab_body};
use crate::{
    Error, Progress, Result,
    analysis::{
        StaticLoadCase, full_static_response, reduced_modes, relative_error, ritz_static_response,
    },
    dynamics::{AxisType, IntegratorParameters, Simulation, System, critical_step, simulate},
    fem::{FeModel, SlabParameters, slab},
    linalg::principal_angles,
    reduction::{
        Basis, EitelbergParameters, Method, ModeCondensationRoute, ModeSelection, NodalFixedAxes,
        SolverPath, eitelberg, no_reduction,
    },
};

/// Kept normal modes wherever a failure needs them (the §7.2 count).
pub const KEPT_MODES: usize = 6;
/// Boundary sets too small or badly placed for Craig–Bampton on the slab: one corner (3 DOF)
/// and two corners (6 DOF on one line: the rotation about it stays free).
pub const TOO_FEW_BOUNDARIES: [&[usize]; 2] = [&[16], &[16, 18]];
/// Meshes (bricks along x, y, z) of the cost comparison: 90 to 594 DOF, the two largest 3.5×
/// apart so the growth exponent is read over a wide step. 1 092 DOF made MC alone 1.4 s of
/// the main job, 2 295 would add ~6 s.
pub const COST_MESHES: [[usize; 3]; 3] = [[4, 2, 1], [6, 3, 1], [10, 5, 2]];
/// The boundary node whose unit z displacement modal truncation is asked to follow.
pub const MOVED_NODE: usize = 30;
/// Fixed steps of the explicit runs as multiples of the critical step (below: bounded,
/// above: Dormand–Prince grows 1.44× per step on the highest mode).
pub const BELOW_CRITICAL: f64 = 0.9;
/// See [`BELOW_CRITICAL`].
pub const ABOVE_CRITICAL: f64 = 3.0;
/// Simulated interval of the run below the critical step, s.
pub const BELOW_RUN_S: f64 = 0.5;
/// Guyan (a)'s masters on the beam (§6.2.1).
pub const GUYAN_A: [usize; 3] = [1, 3, 5];
/// Guyan (b)'s masters on the beam (§6.2.1).
pub const GUYAN_B: [usize; 3] = [1, 2, 5];

/// Craig–Bampton on a boundary of [`TOO_FEW_BOUNDARIES`]: what it returned.
#[derive(Debug)]
pub struct BoundaryCase {
    /// The boundary nodes.
    pub nodes: &'static [usize],
    /// The basis, or the error it gave (expected: `ReductionError::SingularInterior`).
    pub outcome: Result<Basis>,
}

/// Craig–Bampton on the slab with each boundary of [`TOO_FEW_BOUNDARIES`].
pub fn too_few_boundary(model: &FeModel) -> Vec<BoundaryCase> {
    TOO_FEW_BOUNDARIES
        .iter()
        .map(|&nodes| BoundaryCase {
            nodes,
            outcome: reduce(
                model,
                &ReductionRequest::of(Method::CraigBampton)
                    .boundary(nodes)
                    .modes(ModeSelection::Count(KEPT_MODES)),
            ),
        })
        .collect()
}

/// Eitelberg's reduction of the beam on [`GUYAN_A`] without and with the $L = [I\ I]$
/// feedback.
#[derive(Debug)]
pub struct EitelbergFeedback {
    /// Without the feedback: the frequencies, or the error (expected:
    /// `ReductionError::UnstableSystem`).
    pub without: Result<Vec<f64>>,
    /// With it: the frequencies, Hz.
    pub with_hz: Vec<f64>,
}

/// See [`EitelbergFeedback`].
pub fn eitelberg_feedback(model: &FeModel) -> Result<EitelbergFeedback> {
    let without = eitelberg(
        model,
        &GUYAN_A,
        &EitelbergParameters {
            output_feedback: false,
        },
    )
    .map(|e| e.hz);
    let with_hz = eitelberg(model, &GUYAN_A, &EitelbergParameters::default())?.hz;
    Ok(EitelbergFeedback { without, with_hz })
}

/// Offline time of mode condensation (complete interior eigenproblem, Eq. 6.29) and of
/// Craig–Bampton (partial eigensolver) on the slabs of [`COST_MESHES`].
#[derive(Debug, Clone, PartialEq)]
pub struct CondensationCost {
    /// DOF of each mesh.
    pub dofs: Vec<usize>,
    /// Interior DOF of each mesh.
    pub interior: Vec<usize>,
    /// Mode condensation's offline time, s.
    pub mc_s: Vec<f64>,
    /// Craig–Bampton's offline time, s.
    pub cb_s: Vec<f64>,
    /// Largest principal angle between the two bases over the meshes, rad.
    pub max_angle: f64,
}

impl CondensationCost {
    /// The growth exponent of `times` between the two largest meshes.
    pub fn exponent(&self, times: &[f64]) -> f64 {
        let n = self.dofs.len();
        (times[n - 1] / times[n - 2]).ln()
            / (self.dofs[n - 1] as f64 / self.dofs[n - 2] as f64).ln()
    }
}

/// See [`CondensationCost`].
pub fn condensation_cost() -> Result<CondensationCost> {
    let mut cost = CondensationCost {
        dofs: Vec::new(),
        interior: Vec::new(),
        mc_s: Vec::new(),
        cb_s: Vec::new(),
        max_angle: 0.0,
    };
    for bricks in COST_MESHES {
        let model = slab(&SlabParameters::refined(bricks)?);
        let boundary = default_boundary(&model);
        let modes = ModeSelection::Count(KEPT_MODES);
        let start = Instant::now();
        let cb = reduce(
            &model,
            &ReductionRequest::of(Method::CraigBampton)
                .boundary(&boundary)
                .modes(modes)
                .solver(SolverPath::Sparse),
        )?;
        cost.cb_s.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let mc = reduce(
            &model,
            &ReductionRequest::of(Method::ModeCondensation)
                .boundary(&boundary)
                .modes(modes)
                .solver(SolverPath::Sparse)
                .route(ModeCondensationRoute::Complete),
        )?;
        cost.mc_s.push(start.elapsed().as_secs_f64());
        let angles = principal_angles(mc.psi.as_ref(), cb.psi.as_ref())?;
        cost.max_angle = angles.iter().copied().fold(cost.max_angle, f64::max);
        cost.dofs.push(model.dof_count());
        cost.interior.push(model.dof_count() - 3 * boundary.len());
    }
    Ok(cost)
}

/// The mass matrix of Guyan's masters used as a nodal mass matrix under mean axes.
#[derive(Debug, Clone, PartialEq)]
pub struct GuyanMeanAxes {
    /// §7.2's Guyan masters: the four corners and App. B's nodes 5 and 11.
    pub masters: Vec<usize>,
    /// Largest deviation of a 3×3 nodal block of the condensed M from a multiple of I.
    pub anisotropy_guyan: f64,
    /// The same for the full (lumped) M.
    pub anisotropy_lumped: f64,
    /// $\dot{\tilde\delta}^T M \dot\delta$ for two modes' velocities over its scale, condensed.
    pub identity_guyan: f64,
    /// The same on the full body.
    pub identity_full: f64,
    /// Relative error of the deformation term $\tilde\delta^T M \dot\delta$ of the angular
    /// mean-axis condition, condensed against the full body's.
    pub coupling_error: f64,
}

/// See [`GuyanMeanAxes`].
pub fn guyan_mean_axes(model: &FeModel) -> Result<GuyanMeanAxes> {
    let masters = reduction_nodes(model, Method::Guyan, &default_boundary(model));
    let g = reduce(
        model,
        &ReductionRequest::of(Method::Guyan).boundary(&masters),
    )?;
    // Columns node by node, x y z: the condensed model's nodes are the masters.
    for (c, col) in g.columns.iter().enumerate() {
        let expected = model.dofs_of_nodes(&[masters[c / 3]])?[c % 3];
        if col.dof != Some(expected) {
            return Err(Error::Reduction(ReductionError::ColumnNotAtDof {
                column: c,
                dof: expected,
            }));
        }
    }
    let m_g = g.reduced_mass(model);
    let m_full = model.m_dense();
    // Two elastic modes of the Guyan model, in master coordinates.
    let e = reduced_modes(model, &g)?;
    let elastic: Vec<usize> = (e.zero_energy..e.values.len()).take(2).collect();
    if elastic.len() < 2 {
        return Err(Error::Reduction(ReductionError::TooManyModes {
            requested: 2,
            available: elastic.len(),
        }));
    }
    let col = |j: usize| (0..e.vectors.nrows()).map(|i| e.vectors[(i, j)]).collect();
    let (a, b): (Vec<f64>, Vec<f64>) = (col(elastic[0]), col(elastic[1]));
    let v: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + y).collect();
    let expand = |z: &[f64]| -> Vec<f64> {
        (0..g.psi.nrows())
            .map(|i| (0..z.len()).map(|j| g.psi[(i, j)] * z[j]).sum())
            .collect()
    };
    // Eq. (4.17)'s dropped term: δ̇̃ᵀ M δ̇ (zero for a lumped or consistent M).
    let (h_g, scale_g) = skew_moment(&m_g, &v, &v);
    let (h_full, scale_full) = skew_moment(&m_full, &expand(&v), &expand(&v));
    // The deformation-dependent part of b̃ᵀMδ̇ (Eq. 4.15 with b = x + δ): δ̃ᵀ M δ̇ for
    // δ = mode 1, δ̇ = mode 2, condensed against the full body's.
    let (c_g, _) = skew_moment(&m_g, &a, &b);
    let (c_full, _) = skew_moment(&m_full, &expand(&a), &expand(&b));
    Ok(GuyanMeanAxes {
        masters,
        anisotropy_guyan: block_anisotropy(&m_g),
        anisotropy_lumped: block_anisotropy(&m_full),
        identity_guyan: norm3(h_g) / scale_g,
        identity_full: norm3(h_full) / scale_full,
        coupling_error: norm3([c_g[0] - c_full[0], c_g[1] - c_full[1], c_g[2] - c_full[2]])
            / norm3(c_full).max(f64::MIN_POSITIVE),
    })
}

/// Largest deviation of a nodal 3×3 block from a multiple of the identity, relative to the
/// largest block (Frobenius norms); 3 DOF per node, node by node.
fn block_anisotropy(m: &Mat<f64>) -> f64 {
    let nodes = m.nrows() / 3;
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for i in 0..nodes {
        for j in 0..nodes {
            let b = |r: usize, c: usize| m[(3 * i + r, 3 * j + c)];
            let mean = (b(0, 0) + b(1, 1) + b(2, 2)) / 3.0;
            let (mut dev, mut all) = (0.0, 0.0);
            for r in 0..3 {
                for c in 0..3 {
                    let iso = if r == c { mean } else { 0.0 };
                    dev += (b(r, c) - iso).powi(2);
                    all += b(r, c).powi(2);
                }
            }
            worst = worst.max(dev.sqrt());
            largest = largest.max(all.sqrt());
        }
    }
    if largest > 0.0 { worst / largest } else { 0.0 }
}

/// $\sum_i a_i \times (M b)_i$ over 3-DOF nodes, and its scale $\sum_i |a_i|\,|(Mb)_i|$.
fn skew_moment(m: &Mat<f64>, a: &[f64], b: &[f64]) -> ([f64; 3], f64) {
    let mb: Vec<f64> = (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)] * b[j]).sum())
        .collect();
    let (mut h, mut scale) = ([0.0; 3], 0.0);
    for n in 0..a.len() / 3 {
        let p = [a[3 * n], a[3 * n + 1], a[3 * n + 2]];
        let q = [mb[3 * n], mb[3 * n + 1], mb[3 * n + 2]];
        h[0] += p[1] * q[2] - p[2] * q[1];
        h[1] += p[2] * q[0] - p[0] * q[2];
        h[2] += p[0] * q[1] - p[1] * q[0];
        scale += norm3(p) * norm3(q);
    }
    (h, scale.max(f64::MIN_POSITIVE))
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// A reduced model's highest frequency and the explicit scheme's critical step it predicts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalStep {
    /// The method.
    pub method: Method,
    /// The body's coordinates.
    pub coordinates: usize,
    /// Highest retained frequency, Hz.
    pub highest_hz: f64,
    /// Predicted critical step, s.
    pub critical_s: f64,
}

/// slab-sim1 with Craig–Bampton ([`KEPT_MODES`] modes): fixed Dormand–Prince steps below and
/// above the predicted critical step.
#[derive(Debug)]
pub struct ExplicitStep {
    /// The critical steps of NR, GR, MT and CB.
    pub predicted: Vec<CriticalStep>,
    /// CB's critical step, s.
    pub critical: f64,
    /// The run at [`BELOW_CRITICAL`]: node 8's largest |ζ|, m, or its error.
    pub below: Result<f64>,
    /// The run at [`ABOVE_CRITICAL`]: its error (expected `DynamicsError::Diverged`), `None` when
    /// it
    /// did not diverge.
    pub above: Option<Error>,
    /// Node 8's |ζ| against time, m, below the critical step.
    pub below_history: Option<Vec<(f64, f64)>>,
    /// The same above it, stopped a few steps before the state leaves the bound.
    pub above_history: Option<Vec<(f64, f64)>>,
}

/// See [`ExplicitStep`]. Returns [`Error::Cancelled`] once `progress` is cancelled.
pub fn explicit_step(model: &FeModel, progress: &Progress) -> Result<ExplicitStep> {
    let axes = AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let boundary = default_boundary(model);
    let scenario = Scenario::HeldAtSix;
    let mut predicted = Vec::new();
    let mut cb_case = None;
    for (method, modes) in [
        (Method::NoReduction, 0),
        (Method::Guyan, 0),
        (Method::ModalTruncation, KEPT_MODES),
        (Method::CraigBampton, KEPT_MODES),
    ] {
        let body = slab_body(model, method, axes, &boundary, modes)?;
        let hz = reduced_modes(model, &body.basis)?.hz();
        let highest = hz.last().copied().unwrap_or(0.0);
        let critical = critical_step(2.0 * std::f64::consts::PI * highest);
        predicted.push(CriticalStep {
            method,
            coordinates: body.modes(),
            highest_hz: highest,
            critical_s: critical,
        });
        if method == Method::CraigBampton {
            cb_case = Some((body, critical));
        }
    }
    let (body, critical) = cb_case.expect("CB is in the list");
    let (system, state) = super::slab_system(&scenario, body)?;
    // Output at every step of the run above (no step is shortened to land on an output
    // time), so that it can be repeated up to just before its divergence.
    let fixed = |factor: f64, end: f64| {
        simulate(
            &system,
            &state,
            &IntegratorParameters {
                end_time: end,
                output_interval: if factor > 1.0 {
                    factor * critical
                } else {
                    end / 50.0
                },
                fixed_step: Some(factor * critical),
                ..Default::default()
            },
            progress,
        )
    };
    let cancelled = |r: &Result<Simulation>| matches!(r, Err(Error::Cancelled));
    let below = fixed(BELOW_CRITICAL, BELOW_RUN_S);
    let above = fixed(ABOVE_CRITICAL, scenario.end_time());
    if cancelled(&below) || cancelled(&above) {
        return Err(Error::Cancelled);
    }
    let below_history = below.as_ref().ok().map(|sim| zeta_history(&system, sim));
    // The diverging run again, stopped a few steps before the state leaves the bound, so its
    // growth can be drawn.
    let mut above_history = None;
    if let Err(Error::Dynamics(DynamicsError::Diverged { time, .. })) = &above {
        let h = ABOVE_CRITICAL * critical;
        let steps = ((time / h).floor() - 3.0).max(1.0);
        let run = simulate(
            &system,
            &state,
            &IntegratorParameters {
                end_time: steps * h,
                output_interval: h,
                fixed_step: Some(h),
                ..Default::default()
            },
            progress,
        );
        match run {
            Ok(sim) => above_history = Some(zeta_history(&system, &sim)),
            Err(Error::Cancelled) => return Err(Error::Cancelled),
            Err(_) => {}
        }
    }
    Ok(ExplicitStep {
        predicted,
        critical,
        below: below.map(|sim| {
            probe_history(&system, &sim, PROBE_NODE)[2]
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
        }),
        above: above.err(),
        below_history,
        above_history,
    })
}

/// $|\zeta|$ of node 8 against time, for a semi-log chart.
fn zeta_history(system: &System, sim: &Simulation) -> Vec<(f64, f64)> {
    let zeta = &probe_history(system, sim, PROBE_NODE)[2];
    sim.samples
        .iter()
        .zip(zeta)
        .map(|(s, z)| (s.t, z.abs()))
        .collect()
}

/// The beam's first elastic mode by one basis and its distance from mirror symmetry.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetryCase {
    /// `full`, `guyan_a` or `guyan_b`.
    pub id: &'static str,
    /// The mode on every DOF.
    pub mode: Vec<f64>,
    /// Its frequency, Hz.
    pub hz: f64,
    /// [`mirror_defect`] of the mode.
    pub defect: f64,
}

/// Guyan (a) and (b) against the full beam: symmetry of the first elastic mode.
pub fn guyan_symmetry(model: &FeModel) -> Result<Vec<SymmetryCase>> {
    [
        ("full", no_reduction(model)),
        (
            "guyan_a",
            reduce(
                model,
                &ReductionRequest::of(Method::Guyan).boundary(&GUYAN_A),
            )?,
        ),
        (
            "guyan_b",
            reduce(
                model,
                &ReductionRequest::of(Method::Guyan).boundary(&GUYAN_B),
            )?,
        ),
    ]
    .into_iter()
    .map(|(id, basis)| {
        let (mode, hz) = first_elastic_mode(model, &basis)?;
        Ok(SymmetryCase {
            id,
            defect: mirror_defect(&mode),
            mode,
            hz,
        })
    })
    .collect()
}

/// Distance of a beam displacement (2 DOF per node, x and y) from mirror symmetry about the
/// beam's middle: the smaller of its symmetric and antisymmetric defects, relative to its
/// largest entry.
pub fn mirror_defect(u: &[f64]) -> f64 {
    let nodes = u.len() / 2;
    let largest = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (mut sym, mut anti) = (0.0f64, 0.0f64);
    for i in 0..nodes {
        let j = nodes - 1 - i;
        // Mirror of (u_x, u_y) at x is (−u_x, u_y) at L − x.
        sym = sym
            .max((u[2 * i] + u[2 * j]).abs())
            .max((u[2 * i + 1] - u[2 * j + 1]).abs());
        anti = anti
            .max((u[2 * i] - u[2 * j]).abs())
            .max((u[2 * i + 1] + u[2 * j + 1]).abs());
    }
    sym.min(anti) / largest.max(f64::MIN_POSITIVE)
}

/// The first elastic mode of a basis on `model`, expanded to every DOF, and its frequency.
fn first_elastic_mode(model: &FeModel, basis: &Basis) -> Result<(Vec<f64>, f64)> {
    let e = reduced_modes(model, basis)?;
    let hz = e.hz();
    let j = (e.zero_energy < hz.len())
        .then_some(e.zero_energy)
        .ok_or(Error::Reduction(ReductionError::TooManyModes {
            requested: 1,
            available: 0,
        }))?;
    let u = (0..basis.psi.nrows())
        .map(|i| {
            (0..basis.size())
                .map(|c| basis.psi[(i, c)] * e.vectors[(c, j)])
                .sum()
        })
        .collect();
    Ok((u, hz[j]))
}

/// The slab held at its default boundary with node [`MOVED_NODE`] moved 1 m up (z): the exact
/// static response against modal truncation's and Craig–Bampton's best (Ritz) responses.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryMotion {
    /// The exact response, m.
    pub exact: Vec<f64>,
    /// Modal truncation's, m.
    pub mt: Vec<f64>,
    /// Craig–Bampton's, m.
    pub cb: Vec<f64>,
    /// Relative errors of MT and CB.
    pub mt_error: f64,
    /// See `mt_error`.
    pub cb_error: f64,
    /// MT's strain energy over the exact one (a Ritz response never has less).
    pub mt_energy_ratio: f64,
}

/// See [`BoundaryMotion`].
pub fn boundary_motion(model: &FeModel) -> Result<BoundaryMotion> {
    let boundary = default_boundary(model);
    let modes = ModeSelection::Count(KEPT_MODES);
    let moved = model.dofs_of_nodes(&[MOVED_NODE])?[2];
    let case = StaticLoadCase {
        held: model
            .dofs_of_nodes(&boundary)?
            .into_iter()
            .map(|d| (d, if d == moved { 1.0 } else { 0.0 }))
            .collect(),
        load: vec![0.0; model.dof_count()],
    };
    let exact = full_static_response(model, &case)?;
    let mt = ritz_static_response(
        model,
        &reduce(
            model,
            &ReductionRequest::of(Method::ModalTruncation)
                .boundary(&boundary)
                .modes(modes),
        )?,
        &case,
    )?;
    let cb = ritz_static_response(
        model,
        &reduce(
            model,
            &ReductionRequest::of(Method::CraigBampton)
                .boundary(&boundary)
                .modes(modes),
        )?,
        &case,
    )?;
    let k = model.k_dense();
    let energy = |u: &[f64]| -> f64 {
        (0..u.len())
            .map(|i| u[i] * (0..u.len()).map(|j| k[(i, j)] * u[j]).sum::<f64>())
            .sum::<f64>()
    };
    Ok(BoundaryMotion {
        mt_error: relative_error(&mt, &exact),
        cb_error: relative_error(&cb, &exact),
        mt_energy_ratio: energy(&mt) / energy(&exact),
        exact,
        mt,
        cb,
    })
}
