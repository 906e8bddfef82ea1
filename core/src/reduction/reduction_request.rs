//! The one way to reduce a body by a classical method: a [`ReductionRequest`] (the method,
//! its boundary, the kept modes, the linear algebra and what each method takes besides) into
//! [`reduce`], or into [`reduce_interior`] on an interior problem shared between methods.

use super::{
    Basis, EitelbergParameters, InteriorProblem, Method, ModeCondensationRoute, ModeSelection,
    ReductionError, SolverPath, craig_bampton, eitelberg::eitelberg, guyan, modal_truncation,
    mode_condensation, no_reduction,
};
use crate::{Result, fem::FeModel};

/// What to reduce and how, for [`reduce`].
///
/// Built from [`ReductionRequest::of`] and its setters, or as a literal over
/// [`Default`] (Craig–Bampton, six kept modes, the linear algebra chosen by size).
#[derive(Debug, Clone, PartialEq)]
pub struct ReductionRequest {
    /// The method.
    pub method: Method,
    /// Boundary (master, interface) nodes, 1-based as in the thesis.
    pub boundary_nodes: Vec<usize>,
    /// Kept fixed-interface normal modes (MT, CB, MC).
    pub modes: ModeSelection,
    /// Dense or sparse linear algebra.
    pub solver: SolverPath,
    /// Mode condensation's route to its condensed columns (`None`: by the interior's size,
    /// [`ModeCondensationRoute::for_interior`]).
    pub route: Option<ModeCondensationRoute>,
    /// Eitelberg's settings (§6.6).
    pub eitelberg: EitelbergParameters,
}

impl Default for ReductionRequest {
    fn default() -> Self {
        Self {
            method: Method::CraigBampton,
            boundary_nodes: Vec::new(),
            modes: ModeSelection::Count(6),
            solver: SolverPath::Auto,
            route: None,
            eitelberg: EitelbergParameters::default(),
        }
    }
}

impl ReductionRequest {
    /// `method` with the defaults (no boundary yet, six kept modes, the path by size).
    pub fn of(method: Method) -> Self {
        Self {
            method,
            ..Self::default()
        }
    }

    /// The same request for another method.
    pub fn with_method(&self, method: Method) -> Self {
        Self {
            method,
            ..self.clone()
        }
    }

    /// The boundary nodes, 1-based.
    pub fn boundary(mut self, nodes: &[usize]) -> Self {
        self.boundary_nodes = nodes.to_vec();
        self
    }

    /// The kept fixed-interface modes.
    pub fn modes(mut self, modes: ModeSelection) -> Self {
        self.modes = modes;
        self
    }

    /// The linear algebra.
    pub fn solver(mut self, solver: SolverPath) -> Self {
        self.solver = solver;
        self
    }

    /// Mode condensation's route.
    pub fn route(mut self, route: ModeCondensationRoute) -> Self {
        self.route = Some(route);
        self
    }
}

/// Builds the basis `request` asks of `model`. The methods that need more than a boundary
/// (MacNeal–Rubin's r-set, Benfield–Hruda's adjacent loading, moment matching's inputs,
/// balanced truncation's inputs, outputs and damping) are
/// [`ReductionError::MethodNeedsContext`], naming where they are built.
pub fn reduce(model: &FeModel, request: &ReductionRequest) -> Result<Basis> {
    let method = request.method;
    let needs = |needs: &'static str| {
        Err(ReductionError::MethodNeedsContext {
            method: method.name(),
            needs,
        }
        .into())
    };
    match method {
        Method::NoReduction => Ok(no_reduction(model)),
        Method::Guyan
        | Method::ModalTruncation
        | Method::CraigBampton
        | Method::ModeCondensation => reduce_interior(
            &mut InteriorProblem::new(model, &request.boundary_nodes, request.solver)?,
            request,
        ),
        Method::Eitelberg => {
            Ok(eitelberg(model, &request.boundary_nodes, &request.eitelberg)?.basis)
        }
        Method::MacNealRubin => needs("an r-set besides the interface (use `macneal_rubin`)"),
        Method::BenfieldHruda => {
            needs("the interface loading of the adjacent components (use `benfield_hruda`)")
        }
        Method::MomentMatching => needs("input DOF and a block count (use `moment_matching`)"),
        Method::BalancedTruncation => {
            needs("inputs, outputs and damping (use `balanced_truncation_basis`)")
        }
    }
}

/// Builds the basis of a fixed-interface method (Guyan, modal truncation, Craig–Bampton, mode
/// condensation) on an interior problem already split and perhaps factored for another of
/// them, its boundary perhaps tied to rigid interfaces' masters
/// ([`InteriorProblem::with_rigid_interfaces`]). The request's method, modes and route are
/// read; its boundary and solver are the problem's. Another method is
/// [`ReductionError::MethodNeedsContext`].
pub fn reduce_interior(
    problem: &mut InteriorProblem<'_>,
    request: &ReductionRequest,
) -> Result<Basis> {
    let modes = request.modes;
    match request.method {
        Method::Guyan => guyan::guyan_basis(problem),
        Method::ModalTruncation => modal_truncation::modal_truncation_basis(problem, modes),
        Method::CraigBampton => craig_bampton::craig_bampton_basis(problem, modes),
        Method::ModeCondensation => {
            let route = request
                .route
                .unwrap_or_else(|| ModeCondensationRoute::for_interior(problem.interior_dofs()));
            mode_condensation::mode_condensation_basis(problem, modes, route)
        }
        other => Err(ReductionError::MethodNeedsContext {
            method: other.name(),
            needs: "a fixed-interface basis is built by gr, mt, cb or mc",
        }
        .into()),
    }
}
