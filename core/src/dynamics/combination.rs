//! The coefficients of a linear combination of a driven body's operators.

use super::frame_stiffening::STIFFENING_CASES;

/// The coefficients of a combination $c_m M + c_k K + c_g G + c_h H + \sum_i c_{\sigma,i}
/// K_{\sigma,i}$, the last the body's geometric stiffnesses of unit frame loads
/// ([`FrameStiffening`](super::FrameStiffening); none on a body without stiffening).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Combination {
    /// Of the mass matrix.
    pub m: f64,
    /// Of the stiffness matrix.
    pub k: f64,
    /// Of the gyroscopic matrix $G = ME$.
    pub g: f64,
    /// Of the centrifugal matrix $H = ME^2$.
    pub h: f64,
    /// Of the geometric stiffnesses of the unit frame loads, in [`FrameStiffening`](super::FrameStiffening)'s order
    /// ($\dot\theta^2$, $\ddot\theta$, $g_x$, $g_y$, $g_z$).
    pub sigma: [f64; STIFFENING_CASES],
}
