//! `flexmodes export`: a reduced model written for another code. The folder holds
//!
//! - `psi.npy`: Ψ (n × r, `float64`, column-major), the full DOF in the body file's
//!   node-major order, for `numpy.load` (or `psi.mtx`, `array real general`, with
//!   [`PsiFormat::MatrixMarket`]); `k_r.mtx` and `m_r.mtx`: $\Psi^TK\Psi$ and $\Psi^TM\Psi$
//!   (`array real symmetric`), readable by `scipy.io.mmread`, Julia's `MatrixMarket.mmread`
//!   and MATLAB's `mmread`;
//! - `model.json`: the body, method, interface and kept modes, one label per column, the
//!   reduced model's frequencies, and for floating-frame use the inertia invariants of the
//!   reduced body about the body frame's origin: the rigid-body mass matrix $R^TMR$ (6 × 6:
//!   translations, then rotations; 3 × 3 for a planar body) and the couplings $R^TM\Psi$
//!   (translations and rotations against each column).
//!
//! Everything is written to a temporary folder beside the destination and renamed into place,
//! so an interrupted export leaves the previous folder (or none) as it was.

mod exudyn_body;
mod model_document;
mod reduced_export;

pub use exudyn_body::{EXUDYN_FORMAT, ExudynBody, exudyn_body};
pub use reduced_export::{
    ExportParameters, ExportSummary, PsiFormat, ReducedExport, Written, export, reduce_for_export,
};
