//! The list of scenes.

use super::{SceneId, scene_info::SceneInfo};
use super::{
    SceneOptions, SceneOutput, beam_eitelberg, beam_mean_axes, beam_modes, beam_profiles,
    body_modes, cantilever_variants, failures, plank_symmetry, slab_mode_sets, slab_modes,
    slab_sims,
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

/// Every scene, in catalogue order.
pub fn all() -> Vec<Scene> {
    vec![
        Scene {
            info: beam_modes::INFO,
            run: beam_modes::run,
        },
        Scene {
            info: slab_modes::INFO,
            run: slab_modes::run,
        },
        Scene {
            info: beam_profiles::INFO,
            run: beam_profiles::run,
        },
        Scene {
            info: beam_eitelberg::INFO,
            run: beam_eitelberg::run,
        },
        Scene {
            info: slab_sims::INFO_1,
            run: slab_sims::run_sim1,
        },
        Scene {
            info: slab_sims::INFO_2,
            run: slab_sims::run_sim2,
        },
        Scene {
            info: slab_sims::INFO_3,
            run: slab_sims::run_sim3,
        },
        Scene {
            info: plank_symmetry::INFO,
            run: plank_symmetry::run,
        },
        Scene {
            info: beam_mean_axes::INFO,
            run: beam_mean_axes::run,
        },
        Scene {
            info: slab_mode_sets::INFO,
            run: slab_mode_sets::run,
        },
        Scene {
            info: cantilever_variants::INFO,
            run: cantilever_variants::run,
        },
        Scene {
            info: failures::INFO,
            run: failures::run,
        },
        Scene {
            info: body_modes::INFO,
            run: body_modes::run,
        },
    ]
}

/// Every scene's id, in the registry's order.
pub fn all_ids() -> Vec<SceneId> {
    all().iter().map(|s| s.info.id).collect()
}

/// Finds a scene by its text form (as a user typed it).
pub fn find(id: &str) -> Result<Scene> {
    Ok(get(id.parse()?))
}

/// The scene `id`.
pub fn get(id: SceneId) -> Scene {
    all()
        .into_iter()
        .find(|s| s.info.id == id)
        .expect("the registry holds every SceneId")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_holds_every_scene_id_once_in_catalogue_order() {
        assert_eq!(all_ids(), SceneId::ALL.to_vec());
        for id in SceneId::ALL {
            assert_eq!(get(id).info.id, id);
            assert_eq!(find(id.as_str()).unwrap().info.id, id);
        }
    }
}
