//! Models: the physical set-ups of the scenes and their measures, computed and returned as
//! typed results. Scenes wire them to visuals and tables; tests and benches use them for
//! numbers. A model never imports a scene or the recorder.

mod body_advice;
mod body_campbell;
mod body_comparison;
mod body_import;
mod body_interfaces;
mod body_modes_study;
mod body_reduction;
mod cantilever_study;
mod driven_body;
mod driven_measure;
mod driven_setup;
mod driven_stability;
mod driven_study;
mod dual_spin_study;
mod failure_studies;
mod inertia_load_study;
mod interface_reduction_sweep;
mod interface_response;
mod plank_simulation;
mod slab_simulation;
mod spinning_beam_study;
mod spinning_model_label;
mod spinning_pairs;
mod statically_determinate_support;
mod substructuring_ladder;

pub(crate) use body_advice::advise;
pub use body_advice::{AdvisedModel, BodyAdvice};
pub use body_campbell::{
    BodyCampbell, BodyCampbellCurve, BodyCampbellParameters, body_campbell, spinning_frequencies,
};
pub use body_comparison::{
    BODY_COMPARED_MODES, BODY_MODE_SWEEP, BodyComparison, BodyComparisonParameters,
    BodyComparisonPoint, ROUND_OFF_ERROR, compare_body_methods,
};
pub use body_import::{
    FULL_MODES, amls_json, geometry_disagreement, import_summary, import_summary_by, missed_note,
    refuse_mechanism,
};
pub use body_interfaces::BodyInterfaces;
pub use body_modes_study::{
    BODY_MODES_COMPARED, BodyModesParameters, BodyModesStudy, HeldModes, MethodMeasure,
    body_modes_study,
};
pub use body_reduction::{
    BALANCED_MODES_PER_VECTOR, BALANCED_ZETA, BODY_METHODS, BodyReducer, ReducedBody,
};
pub use cantilever_study::{
    BAND_HZ, BT_ALPHA, CANTILEVER_METHODS, CantileverIo, CantileverStudy,
    INTEREST_HZ as WITTEVEEN_INTEREST_HZ, POINT_MASS_T, PRINTED_HZ, Printed, StaticCase,
    VariantModes, bottom_line_error, cantilever_study, witteveen_bases,
};
pub use driven_body::{DRIVEN_METHODS, DrivenBodyParameters, driven_body_study};
pub use driven_measure::{FieldMap, history_error};
pub use driven_stability::ExplicitCheck;
pub use driven_study::{DrivenRun, DrivenStudy};
pub use dual_spin_study::{
    ARTICULATION_DEG, AssembledSet, CbSets, DUAL_SPIN_METHODS, DualSpinSets, DualSpinStudy,
    INFLUENCE_FRACTION, INTEREST_HZ as SPANOS_INTEREST_HZ, RotorRanking, RotorSelection,
    TRUNCATION_HZ, ZETA, assemble, benfield_hruda_bases, dual_spin_study, full_synthesis, io_model,
    mode_set_bases, rank_rotor,
};
pub use failure_studies::{
    ABOVE_CRITICAL, BELOW_CRITICAL, BELOW_RUN_S, BoundaryCase, BoundaryMotion, COST_MESHES,
    CondensationCost, CriticalStep, EitelbergFeedback, ExplicitStep, GUYAN_A, GUYAN_B,
    GuyanMeanAxes, KEPT_MODES, MOVED_NODE, SymmetryCase, TOO_FEW_BOUNDARIES, boundary_motion,
    condensation_cost, eitelberg_feedback, explicit_step, guyan_mean_axes, guyan_symmetry,
    mirror_defect, too_few_boundary,
};
pub use inertia_load_study::{
    INERTIA_LOAD_BODY, INERTIA_LOAD_MODES, InertiaLoadStudy, inertia_load_study,
};
pub use interface_reduction_sweep::{
    INTERFACE_MODE_SWEEP, InterfaceReductionPoint, interface_reduction_sweep,
};
pub use interface_response::{
    InterfaceResponse, InterfaceStatics, MOST_BAND_MODES, RESPONSE_POINTS, modes_up_to,
};
pub use plank_simulation::{
    MID_X as PLANK_MID_X, PLANK_BOUNDARY, PlankSetup, Variant as PlankVariant, plank_body,
    plank_nodal_fixed, plank_setup, plank_system, symmetry_history,
};
pub use slab_simulation::{
    BOUNDARY as SLAB_BOUNDARY, DRIVEN_NODES, DrivenTables, PROBE_NODE, SIM1_END, SIM2_END,
    SIM3_END, Scenario, default_boundary, fixed, held_at_six, probe_history, record_driving_tables,
    reduction_nodes, sim3_rotation, slab_body, slab_node, slab_system,
};
pub use spinning_beam_study::{
    CAMPBELL_SPEEDS, CampbellCurve, CampbellParameters, CampbellStudy, Divergence,
    PUBLISHED_TOLERANCE, SPIN_UP_TOLERANCE, SpinUpModels, SpinUpParameters, SpinUpRun, SpinUpStudy,
    campbell_study, published_flapwise, spin_up_reference, spin_up_study, spinning_beam_body,
};
pub use spinning_model_label::{model_label, model_name};
pub use spinning_pairs::{CAMPBELL_DENSE_LIMIT, SpinningPairs, spinning_pairs, track_by_mac};
pub use statically_determinate_support::{macneal_rubin_on_body, three_two_one_support};
pub use substructuring_ladder::{
    LadderPoint, RefinedComparison, SubstructuringParameters, SubstructuringStudy, TreePart,
    substructuring_study,
};
