//! The list of scenes.

use super::{SceneId, scene_info::SceneInfo};
use super::{
    SceneOptions, SceneOutput, amls, beam_eitelberg, beam_mean_axes, beam_modes, beam_profiles,
    body_modes, cantilever_variants, failures, plank_symmetry, slab_mode_sets, slab_modes,
    slab_sims, spin_up,
};
use crate::{Error, Result};

/// A scene: computes its results and visuals for given options.
pub struct Scene {
    /// Description.
    pub info: SceneInfo,
    /// Runs the scene.
    pub run: fn(&SceneOptions) -> Result<SceneOutput>,
}

impl Scene {
    /// Runs the scene after checking the options it does not offer.
    pub fn execute(&self, opts: &SceneOptions) -> Result<SceneOutput> {
        if opts.refine.is_some() && self.info.controls.refine.is_none() {
            return Err(Error::InvalidOption {
                option: "--refine",
                scene: Some(self.info.id.as_str()),
                reason: "--refine applies to slab-modes only".into(),
            });
        }
        opts.check_integrator(&self.info)?;
        if opts.stiffening.is_some() && !self.info.id.takes_stiffening() {
            return Err(Error::InvalidOption {
                option: "--stiffening",
                scene: Some(self.info.id.as_str()),
                reason: "--stiffening applies to slab-sim1, slab-sim2 and slab-sim3 (spin-up \
                         shows the models with and without it; simulate --body takes its own)"
                    .into(),
            });
        }
        if opts.band_hz.is_some() && self.info.id != super::body_modes::INFO.id {
            return Err(Error::InvalidOption {
                option: "--band",
                scene: Some(self.info.id.as_str()),
                reason: format!(
                    "--band compares interface responses in the `{}` scene only",
                    super::body_modes::INFO.id
                ),
            });
        }
        if let Some(b) = opts.band_hz
            && !(b.is_finite() && b > 0.0)
        {
            return Err(Error::InvalidOption {
                option: "--band",
                scene: Some(self.info.id.as_str()),
                reason: format!("--band must be a positive frequency in Hz, not {b}"),
            });
        }
        if opts.simulation.is_some() && self.info.id != SceneId::Modes {
            return Err(Error::InvalidOption {
                option: "simulate",
                scene: Some(self.info.id.as_str()),
                reason: "a body is driven in the `modes` scene only".into(),
            });
        }
        if opts.body.is_some() && self.info.id != super::body_modes::INFO.id {
            return Err(Error::InvalidOption {
                option: "--body",
                scene: Some(self.info.id.as_str()),
                reason: format!(
                    "--body applies to the `{}` scene only (the other scenes are the thesis' \
                     bodies)",
                    super::body_modes::INFO.id
                ),
            });
        }
        (self.run)(opts)
    }
}

/// Every scene, in catalogue order ([`SceneId::ALL`]).
pub fn all() -> Vec<Scene> {
    SceneId::ALL.into_iter().map(get).collect()
}

/// Every scene's id, in catalogue order.
pub fn all_ids() -> Vec<SceneId> {
    SceneId::ALL.to_vec()
}

/// Finds a scene by its text form (as a user typed it).
pub fn find(id: &str) -> Result<Scene> {
    Ok(get(id.parse()?))
}

/// The scene `id` (every id has one: the match is exhaustive).
pub fn get(id: SceneId) -> Scene {
    let (info, run): (SceneInfo, fn(&SceneOptions) -> Result<SceneOutput>) = match id {
        SceneId::BeamModes => (beam_modes::INFO, beam_modes::run),
        SceneId::SlabModes => (slab_modes::INFO, slab_modes::run),
        SceneId::BeamProfiles => (beam_profiles::INFO, beam_profiles::run),
        SceneId::BeamEitelberg => (beam_eitelberg::INFO, beam_eitelberg::run),
        SceneId::SlabSim1 => (slab_sims::INFO_1, slab_sims::run_sim1),
        SceneId::SlabSim2 => (slab_sims::INFO_2, slab_sims::run_sim2),
        SceneId::SlabSim3 => (slab_sims::INFO_3, slab_sims::run_sim3),
        SceneId::PlankSymmetry => (plank_symmetry::INFO, plank_symmetry::run),
        SceneId::BeamMeanAxes => (beam_mean_axes::INFO, beam_mean_axes::run),
        SceneId::SlabModeSets => (slab_mode_sets::INFO, slab_mode_sets::run),
        SceneId::CantileverVariants => (cantilever_variants::INFO, cantilever_variants::run),
        SceneId::Failures => (failures::INFO, failures::run),
        SceneId::Modes => (body_modes::INFO, body_modes::run),
        SceneId::SpinUp => (spin_up::INFO, spin_up::run),
        SceneId::Amls => (amls::INFO, amls::run),
    };
    Scene { info, run }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_id_leads_to_the_scene_that_says_it_is_that_one() {
        for id in SceneId::ALL {
            assert_eq!(get(id).info.id, id);
            assert_eq!(find(id.as_str()).unwrap().info.id, id);
        }
    }
}
