//! Typed errors, one small enum per layer (linear algebra, meshes, body files, reductions,
//! dynamics), each variant carrying its data (which node, DOF, file and line, residual),
//! wrapped by the crate's [`Error`]. They live at the ground floor so every layer can name
//! its own and the top-level one without importing upwards.

mod as_text;
mod attachment_problem;
mod body_file_error;
mod body_spec_problem;
mod divergence_cause;
mod dof_set_name;
mod dof_set_problem;
mod dynamics_error;
mod eigen_attempt;
mod excerpt;
mod export_problem;
mod flexmodes_error;
mod free_motion;
mod linalg_error;
mod mass_defect;
mod matrix_label;
mod matrix_line_problem;
mod mesh_error;
mod name;
mod r_set_name;
mod r_set_problem;
mod reduction_error;
mod report_diff_error;
mod size_expectation;
mod str_newtype;
mod table_problem;
mod unknown_id;

pub use attachment_problem::AttachmentProblem;
pub use body_file_error::BodyFileError;
pub use body_spec_problem::BodySpecProblem;
pub use divergence_cause::DivergenceCause;
pub use dof_set_name::DofSetName;
pub use dof_set_problem::DofSetProblem;
pub use dynamics_error::DynamicsError;
pub use eigen_attempt::{EigenAttempt, EigenRoute};
pub use excerpt::Excerpt;
pub use export_problem::ExportProblem;
pub use flexmodes_error::{Error, Result, cause_chain};
pub use free_motion::FreeMotion;
pub use linalg_error::LinalgError;
pub use mass_defect::MassDefect;
pub use matrix_label::{LabelContext, MatrixLabel, PencilPart};
pub use matrix_line_problem::MatrixLineProblem;
pub use mesh_error::MeshError;
pub use name::Name;
pub use r_set_name::RSetName;
pub use r_set_problem::RSetProblem;
pub use reduction_error::ReductionError;
pub use report_diff_error::ReportDiffError;
pub use size_expectation::SizeExpectation;
pub use table_problem::TableProblem;
pub use unknown_id::UnknownId;
