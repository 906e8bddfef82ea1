//! Where each method fails, case by case.

pub(super) mod failure_cases;
pub(super) mod failure_catalogue;
pub(super) mod failure_inertia_case;
pub(super) mod failure_motion_cases;
