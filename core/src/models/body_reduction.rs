//! Every reduction method on a body of the user's own, on the interfaces the user names: the
//! pieces the methods share (the interior factor of $K_{ii}$, the fixed-interface modes, the
//! body's free-free modes) computed once, each model's reduced modes checked by their
//! residuals and its zero-energy modes told apart by the body's own scale.

use crate::reduction::ReductionRequest;
use std::time::Instant;

use faer::Mat;

use crate::{
    Result,
    analysis::{ZeroEnergyCount, reduced_modes},
    fem::{FeModel, InertiaLoads},
    linalg::GeneralizedEigen,
    progress::Progress,
    reduction::{
        Basis, ColumnKind, InterfaceLoads, InteriorProblem, Method, ModalBalancedParameters,
        ModalInfluence, ModalModel, ModeSelection, MomentMatchingParameters, ReductionError,
        ResidualVectorsAdded, SolverPath, lowest_free_modes, modal_balanced_basis, modal_influence,
        moment_matching, reduce_interface, reduce_interior, static_share_outside,
        with_inertia_residual_vectors,
    },
};

use super::{BodyInterfaces, macneal_rubin_on_body};

/// Every method a body can be reduced by, in the order tables list them.
pub const BODY_METHODS: [Method; 8] = [
    Method::Guyan,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
    Method::MacNealRubin,
    Method::BenfieldHruda,
    Method::MomentMatching,
    Method::BalancedTruncation,
];

/// Damping ratio at the lowest elastic mode of the stiffness-proportional damping with which
/// balanced truncation builds its vectors on a body ($\alpha = 2\zeta/\omega_1$): Witteveen's
/// $\alpha = 10^{-4}$ s suits his cantilever's 10–100 Hz, not a part whose first mode is at
/// kHz, so the damping is set by the body's own first frequency.
pub const BALANCED_ZETA: f64 = 0.01;

/// Free-free elastic modes whose gramian balanced truncation balances, per kept vector.
pub const BALANCED_MODES_PER_VECTOR: usize = 3;

/// One reduced model of the body.
#[derive(Debug, Clone)]
pub struct ReducedBody {
    /// The method.
    pub method: Method,
    /// Its basis, rigid interfaces tied and interface shapes reduced where asked.
    pub basis: Basis,
    /// $\mathrm{eig}(\Psi^TK\Psi, \Psi^TM\Psi)$, every pair's residual checked.
    pub modes: GeneralizedEigen,
    /// Leading pairs below the body's zero-energy threshold.
    pub zero_modes: usize,
    /// Offline wall time, s: the method's own work plus the shared interior factorisation
    /// for the methods that use it.
    pub offline_s: f64,
    /// What the method took in place of what a single body lacks, said beside its numbers.
    pub note: Option<String>,
    /// The inertia-load residual vectors appended to the basis (`None`: not asked for, or
    /// not a fixed-interface method).
    pub residual_vectors: Option<ResidualVectorsAdded>,
}

impl ReducedBody {
    /// Elastic frequencies, Hz, ascending.
    pub fn elastic_hz(&self) -> Vec<f64> {
        self.modes.hz().split_off(self.zero_modes)
    }

    /// Relative residuals of the elastic pairs.
    pub fn elastic_residuals(&self) -> Vec<f64> {
        self.modes.residuals[self.zero_modes..].to_vec()
    }

    /// The highest frequency given to a zero-energy mode, Hz (0 when there is none).
    pub fn rigid_hz_max(&self) -> f64 {
        self.modes.hz()[..self.zero_modes]
            .iter()
            .fold(0.0, |a: f64, &f| a.max(f))
    }

    /// Relative errors of the elastic frequencies against `full_hz`, paired by order, as many
    /// as both have.
    pub fn relative_errors(&self, full_hz: &[f64]) -> Vec<f64> {
        full_hz
            .iter()
            .zip(self.elastic_hz())
            .map(|(f, r)| (r - f) / f)
            .collect()
    }
}

/// Reduces one body by any method, sharing what methods have in common.
pub struct BodyReducer<'a> {
    model: &'a FeModel,
    interfaces: BodyInterfaces,
    full: &'a ZeroEnergyCount,
    full_s: f64,
    problem: Option<InteriorProblem<'a>>,
    free_modes: Option<GeneralizedEigen>,
    free_modes_s: f64,
    progress: Progress,
    residual_vectors: bool,
    inertia_loads: Option<InertiaLoads>,
}

impl<'a> BodyReducer<'a> {
    /// The reducer of `model` on `interfaces`; `full` is the body's lowest modes (zero-energy
    /// ones first), against which zero energy is judged, solved in `full_s` seconds (charged
    /// to the methods built from them).
    pub fn new(
        model: &'a FeModel,
        interfaces: BodyInterfaces,
        full: &'a ZeroEnergyCount,
        full_s: f64,
        progress: Progress,
    ) -> Result<Self> {
        // Rings tied by node coordinates that are not the ones K was made from.
        let tied = interfaces.rigid.iter().map(|i| i.name.clone());
        let tied: Vec<String> = tied
            .chain(interfaces.averaging.iter().map(|i| i.name.clone()))
            .collect();
        if !tied.is_empty()
            && model.rigid_motions == crate::fem::RigidMotions::Unknown
            && full.zero_modes == model.dofs.rigid_body_count()
        {
            let defect = model.rigid_motion_defect();
            if defect > 1e-9 {
                return Err(ReductionError::GeometryDisagrees {
                    interfaces: tied.join(", "),
                    defect,
                    nodes: model
                        .rigid_motion_residual_nodes(8)
                        .into_iter()
                        .map(|(n, _)| n)
                        .collect(),
                }
                .into());
            }
        }
        // Split at once when there is a boundary, so a bad one is an error here.
        let problem = if interfaces.boundary.is_empty() {
            None
        } else {
            Some(
                InteriorProblem::new(model, &interfaces.boundary, SolverPath::Auto)?
                    .with_rigid_interfaces(&interfaces.rigid)?
                    .with_progress(progress.clone()),
            )
        };
        Ok(Self {
            model,
            interfaces,
            full,
            full_s,
            problem,
            free_modes: None,
            free_modes_s: 0.0,
            progress,
            residual_vectors: false,
            inertia_loads: None,
        })
    }

    /// Appends the residual vectors of the frame's unit inertia loads to every
    /// fixed-interface basis (GR, MT, CB, MC) when `on` (see
    /// [`with_inertia_residual_vectors`]); off by default, as the thesis' models are.
    pub fn with_residual_vectors(mut self, on: bool) -> Self {
        self.residual_vectors = on;
        self
    }

    /// Whether fixed-interface bases get residual vectors.
    pub fn residual_vectors(&self) -> bool {
        self.residual_vectors
    }

    /// The share of the static response to each of `loads` (vectors on the body's DOF) that
    /// the interior columns of `basis` miss, in the energy norm of the body held at every
    /// interface ([`static_share_outside`]): the a-priori estimate of a basis for them.
    pub fn static_shares(&mut self, basis: &Basis, loads: &[Vec<f64>]) -> Result<Vec<f64>> {
        let problem = self.problem()?;
        loads
            .iter()
            .map(|f| static_share_outside(problem, basis, f))
            .collect()
    }

    /// The interior problem (its split, constraint and fixed-interface modes, for views):
    /// a [`ReductionError::MethodNeedsContext`] when the body has no boundary (only averaging
    /// interfaces, which hold nothing).
    pub fn problem(&mut self) -> Result<&mut InteriorProblem<'a>> {
        self.problem.as_mut().ok_or_else(|| {
            ReductionError::MethodNeedsContext {
                method: "a fixed-interface basis",
                needs: "a boundary that holds the body (node sets or rbe2 interfaces); rbe3 \
                        interfaces only average and load it",
            }
            .into()
        })
    }

    /// The interfaces.
    pub fn interfaces(&self) -> &BodyInterfaces {
        &self.interfaces
    }

    /// The body's zero-energy modes and its `elastic` lowest elastic free-free modes (the
    /// full body's own when it has enough, else solved once for the largest count asked).
    fn free_modes(&mut self, elastic: usize) -> Result<(GeneralizedEigen, f64)> {
        let z = self.full.zero_modes;
        // A small body has fewer modes than asked: all of them.
        let elastic = elastic.min(self.model.dof_count().saturating_sub(z));
        if self.full.modes.values.len() >= z + elastic {
            return Ok((self.full.modes.first(z + elastic), self.full_s));
        }
        let enough = self
            .free_modes
            .as_ref()
            .is_some_and(|f| f.values.len() >= z + elastic);
        if !enough {
            self.progress.phase("free-free modes")?;
            let started = Instant::now();
            self.free_modes = Some(lowest_free_modes(self.model, elastic)?);
            self.free_modes_s = started.elapsed().as_secs_f64();
        }
        let modes = self.free_modes.as_ref().expect("solved above");
        Ok((modes.first(z + elastic), self.free_modes_s))
    }

    /// The body's zero-energy modes, n × r, mass-normalised.
    fn zero_energy_modes(&self) -> Mat<f64> {
        self.full
            .modes
            .vectors
            .subcols(0, self.full.zero_modes)
            .to_owned()
    }

    /// The model of `method` keeping `kept` modes (for each method's meaning of "kept", see
    /// the variants below), its interface reduced to the interfaces' characteristic
    /// constraint modes when they say so.
    pub fn reduce(&mut self, method: Method, kept: usize) -> Result<ReducedBody> {
        self.reduce_with(method, kept, self.interfaces.interface_modes)
    }

    /// [`Self::reduce`] with every constraint mode kept (the start of an interface-reduction
    /// sweep).
    pub fn reduce_keeping_constraint_modes(
        &mut self,
        method: Method,
        kept: usize,
    ) -> Result<ReducedBody> {
        self.reduce_with(method, kept, None)
    }

    /// Moment matching about the lowest elastic ω of the interface loads made
    /// self-equilibrated, beside the zero-energy modes; and what the row says of it.
    fn moment_matching_basis(&mut self, kept: usize) -> Result<(Basis, String)> {
        let loads = self.loads()?;
        let lowest = self.lowest_elastic_omega()?;
        let blocks = kept.div_ceil(loads.count()).max(1);
        let note = format!(
            "Krylov blocks about s0 = {} rad/s (the lowest elastic ω) of the {} \
             interface loads made self-equilibrated, {blocks} block(s), beside the \
             zero-energy modes",
            crate::report::readable(lowest, 5),
            loads.count()
        );
        self.progress.phase("moment matching")?;
        let zero = self.zero_energy_modes();
        let labels = (1..=zero.ncols())
            .map(|k| format!("zero-energy {k}"))
            .collect();
        let basis = moment_matching(
            self.model,
            &MomentMatchingParameters {
                inputs: Vec::new(),
                held: Vec::new(),
                blocks,
                s0: lowest,
                loads: Some((loads.matrix, loads.labels)),
                leading: Some((zero, labels)),
                ..Default::default()
            },
        )?
        .basis;
        Ok((basis, note))
    }

    /// Balanced truncation of the lowest elastic free-free modes driven by the interface
    /// loads, beside the zero-energy modes; what the row says of it, and the shared free-mode
    /// solve's time, s.
    fn balanced_basis(&mut self, kept: usize) -> Result<(Basis, String, f64)> {
        let loads = self.loads()?;
        let count = (BALANCED_MODES_PER_VECTOR * kept).max(kept + 8);
        let (modes, solve_s) = self.free_modes(count)?;
        let z = self.full.zero_modes;
        // A small body has fewer modes than asked.
        let count = count.min(modes.values.len().saturating_sub(z));
        let lowest = self.lowest_elastic_omega()?;
        let elastic = GeneralizedEigen {
            values: modes.values[z..].to_vec(),
            vectors: modes.vectors.subcols(z, count).to_owned(),
            residuals: modes.residuals[z..].to_vec(),
            zero_energy: 0,
            sturm: None,
        };
        let note = format!(
            "position gramian of the {count} lowest elastic free-free modes driven by \
             the {} interface loads, damping ζ = {BALANCED_ZETA} at the lowest, beside \
             the zero-energy modes",
            loads.count()
        );
        self.progress.phase("balanced truncation")?;
        let basis = modal_balanced_basis(
            modes.vectors.subcols(0, z),
            &elastic,
            &loads,
            &ModalBalancedParameters {
                vectors: kept,
                alpha: 2.0 * BALANCED_ZETA / lowest,
            },
        )?;
        Ok((basis, note, solve_s))
    }

    /// The basis of `method` with `kept` modes, before its interface shapes are reduced and
    /// its residual vectors added; a note on how it was built where one is due, and the
    /// seconds of shared work (the free-free modes) it used.
    fn method_basis(
        &mut self,
        method: Method,
        kept: usize,
    ) -> Result<(Basis, Option<String>, f64)> {
        let model = self.model;
        let mut note = None;
        let mut shared_s = 0.0;
        let basis = match method {
            // Rigid interfaces are tied in the problem's boundary coordinates.
            Method::Guyan
            | Method::ModalTruncation
            | Method::CraigBampton
            | Method::ModeCondensation => reduce_interior(
                self.problem()?,
                &ReductionRequest::of(method).modes(ModeSelection::Count(kept)),
            )?,
            Method::MacNealRubin => {
                if !self.interfaces.rigid.is_empty() {
                    return Err(ReductionError::MethodNeedsContext {
                        method: "MacNeal-Rubin",
                        needs: "plain interface DOF: its free-interface and residual-flexibility \
                                columns are no unit boundary motions an rbe2 master could \
                                combine",
                    }
                    .into());
                }
                self.progress.phase("MacNeal-Rubin reduction")?;
                macneal_rubin_on_body(model, &self.interfaces.boundary, kept)?
            }
            Method::BenfieldHruda => {
                // Spanos–Tsuha Eq. (18) with the neighbours' loading (Eqs. 19–20): a body
                // alone has no neighbour, so its loaded-interface modes are its free ones.
                let (modes, solve_s) = self.free_modes(kept)?;
                shared_s = solve_s;
                note = Some(
                    "no neighbour's interface loading is known for a body alone: its \
                     loaded-interface modes are the free-interface ones (rigid and the lowest \
                     elastic)"
                        .to_string(),
                );
                loaded_modes_basis(modes)
            }
            Method::MomentMatching => {
                let (basis, says) = self.moment_matching_basis(kept)?;
                note = Some(says);
                basis
            }
            Method::BalancedTruncation => {
                let (basis, says, solve_s) = self.balanced_basis(kept)?;
                note = Some(says);
                shared_s = solve_s;
                basis
            }
            other => {
                return Err(ReductionError::MethodNeedsContext {
                    method: other.name(),
                    needs: "a set-up of its own (it is shown in its scenes, not on a body)",
                }
                .into());
            }
        };
        Ok((basis, note, shared_s))
    }

    fn reduce_with(
        &mut self,
        method: Method,
        kept: usize,
        interface_modes: Option<usize>,
    ) -> Result<ReducedBody> {
        let model = self.model;
        let started = Instant::now();
        let uses_interior = matches!(
            method,
            Method::Guyan
                | Method::ModalTruncation
                | Method::CraigBampton
                | Method::ModeCondensation
        );
        if (uses_interior || method == Method::MacNealRubin)
            && !self.interfaces.averaging.is_empty()
        {
            return Err(ReductionError::MethodNeedsContext {
                method: method.name(),
                needs: "interfaces that are boundary DOF: an rbe3 master is a dependent node \
                        (the weighted average of its ring, which stays free), so it has no \
                        constraint mode of its own; use rbe2 for a joint, or bh, mm, bt, which \
                        load the master",
            }
            .into());
        }
        let before = match &self.problem {
            Some(p) => p.statistics.factorization_s,
            None => 0.0,
        };
        let (basis, mut note, shared_s) = self.method_basis(method, kept)?;
        let constraint_columns = basis.columns_of(|k| *k == ColumnKind::Constraint).len();
        let basis = match interface_modes {
            Some(n) if constraint_columns > 0 => reduce_interface(model, basis, n)?,
            _ => basis,
        };
        // Static responses need a boundary that holds the body; modal truncation can do
        // without one, and then has none.
        let holds = uses_interior && self.problem()?.check_restraint().is_ok();
        if self.residual_vectors && uses_interior && !holds {
            note = Some(
                "no residual vectors: the boundary does not hold the body (K_ii is singular), \
                 so its inertia loads have no static response"
                    .to_string(),
            );
        }
        let (basis, residual_vectors) = if self.residual_vectors && holds {
            self.progress.phase("inertia-load residual vectors")?;
            let loads = self
                .inertia_loads
                .get_or_insert_with(|| InertiaLoads::of(model))
                .clone();
            let (basis, added) = with_inertia_residual_vectors(self.problem()?, basis, &loads)?;
            (basis, Some(added))
        } else {
            (basis, None)
        };
        let modes = reduced_modes(model, &basis)?;
        let zero_modes = self.full.zero_energy_in(&modes);
        // The interior factor is shared: each model that uses it is charged with it once.
        let factor_s = self
            .problem
            .as_ref()
            .map_or(0.0, |p| p.statistics.factorization_s);
        let offline_s = started.elapsed().as_secs_f64()
            + shared_s
            + if uses_interior && factor_s == before {
                factor_s
            } else {
                0.0
            };
        Ok(ReducedBody {
            method,
            basis,
            modes,
            zero_modes,
            offline_s,
            note,
            residual_vectors,
        })
    }

    /// Gregory's influence coefficient (Spanos–Tsuha Eq. 44) of each of the body's `count`
    /// lowest elastic free-free modes from its interface loads to the work-conjugate
    /// displacements, with modal damping ζ = `zeta`: $\sigma_i = \|L^T\varphi_i\|^2 /
    /// (4\zeta\omega_i^2)$, how much mode i carries across the interface. Returns the modes'
    /// frequencies (Hz) and the coefficients, in mode order.
    pub fn interface_influence(
        &mut self,
        count: usize,
        zeta: f64,
    ) -> Result<(Vec<f64>, ModalInfluence)> {
        let loads = self.loads()?;
        let (modes, _) = self.free_modes(count)?;
        let z = self.full.zero_modes;
        // A small body has fewer modes than asked.
        let count = count.min(modes.values.len().saturating_sub(z));
        let omega: Vec<f64> = modes.values[z..]
            .iter()
            .map(|l| l.max(0.0).sqrt())
            .collect();
        let hz = modes.hz()[z..].to_vec();
        let model = ModalModel::from_loads(
            modes.vectors.subcols(z, count).to_owned(),
            omega,
            0,
            loads.matrix.as_ref(),
            zeta,
        );
        Ok((hz, modal_influence(&model)?))
    }

    /// The interface loads: a unit force on every plain boundary DOF, six per rigid or
    /// averaging interface's master.
    pub fn loads(&self) -> Result<InterfaceLoads> {
        let plain = self.model.dofs_of_nodes(&self.interfaces.plain_nodes())?;
        InterfaceLoads::of(
            self.model,
            &plain,
            &self.interfaces.rigid,
            &self.interfaces.averaging,
        )
    }

    /// ω of the body's lowest elastic mode, rad/s.
    fn lowest_elastic_omega(&self) -> Result<f64> {
        self.full
            .modes
            .values
            .get(self.full.zero_modes)
            .map(|l| l.max(0.0).sqrt())
            .filter(|w| *w > 0.0)
            .ok_or_else(|| {
                ReductionError::EmptyBand {
                    low_hz: 0.0,
                    high_hz: f64::INFINITY,
                    what: "body's elastic modes (none was computed)",
                }
                .into()
            })
    }
}

/// Benfield–Hruda's basis from loaded modes (here unloaded: the free-free ones).
fn loaded_modes_basis(modes: GeneralizedEigen) -> Basis {
    let columns = modes
        .hz()
        .iter()
        .enumerate()
        .map(|(k, &hz)| crate::reduction::Column {
            kind: ColumnKind::Loaded { hz },
            dof: None,
            label: format!("loaded {} ({hz:.4} Hz)", k + 1),
        })
        .collect();
    Basis {
        method: Method::BenfieldHruda,
        psi: modes.vectors,
        columns,
        statistics: Default::default(),
    }
}
