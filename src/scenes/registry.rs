//! The list of scenes.

use crate::scenes::{SceneId, SceneOption, scene_info::SceneInfo};
use crate::scenes::{
    SceneOptions, SceneOutput, beam::beam_eitelberg, beam::beam_mean_axes, beam::beam_modes,
    beam::beam_profiles, body::body_modes, companion::cantilever_variants,
    companion::slab_mode_sets, failures::failure_catalogue, slab::plank_symmetry, slab::slab_modes,
    slab::slab_sims, spinning::spin_up, substructuring::amls,
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
    /// Runs the scene after refusing what it does not offer ([`Self::check`]).
    pub fn execute(&self, opts: &SceneOptions) -> Result<SceneOutput> {
        self.check(opts)?;
        (self.run)(opts)
    }

    /// Refuses every option the scene's table ([`SceneControls`](crate::scenes::SceneControls)) does
    /// not offer, naming the scenes that do, and an axis type it does not offer; values a
    /// scene's own run checks (a method, a node, an interval) are checked there.
    pub fn check(&self, opts: &SceneOptions) -> Result<()> {
        let controls = &self.info.controls;
        let scene = self.info.id.as_str();
        if let Some(a) = opts.axes
            && !controls.axes.contains(&a)
        {
            return Err(Error::UnknownAxes {
                id: a.id(),
                scene,
                available: controls.axes.iter().map(|a| a.id()).collect(),
            });
        }
        let refused = SceneOption::ALL
            .into_iter()
            .find(|&o| o != SceneOption::Axes && o.given(opts) && !o.offered_by(controls));
        if let Some(option) = refused {
            let takers: Vec<&str> = all()
                .iter()
                .filter(|s| option.offered_by(&s.info.controls))
                .map(|s| s.info.id.as_str())
                .collect();
            let mut reason = format!(
                "{option} does not apply to `{scene}`; it applies to {}",
                if takers.is_empty() {
                    "no scene".to_string()
                } else {
                    takers.join(", ")
                }
            );
            if let Some(because) = controls.fixed_because {
                reason.push_str(&format!(" ({because})"));
            }
            return Err(Error::InvalidOption {
                option: option.flag(),
                scene: Some(scene),
                reason,
            });
        }
        if let Some(b) = opts.band_hz
            && !(b.is_finite() && b > 0.0)
        {
            return Err(Error::InvalidOption {
                option: "--band",
                scene: Some(scene),
                reason: format!("--band must be a positive frequency in Hz, not {b}"),
            });
        }
        Ok(())
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
        SceneId::Failures => (failure_catalogue::INFO, failure_catalogue::run),
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

    #[test]
    fn every_option_is_taken_by_some_scene_and_refused_by_the_others_by_name() {
        let given = |option: SceneOption| {
            let mut o = SceneOptions::default();
            match option {
                SceneOption::Method => o.methods = Some(vec![]),
                SceneOption::Modes => o.modes = Some(3),
                SceneOption::Boundary => o.boundary = Some(vec![1]),
                SceneOption::Axes => o.axes = Some(crate::dynamics::AxisKind::Mean),
                SceneOption::EndTime => o.end_time = Some(1.0),
                SceneOption::Integrator => o.dt = Some(1e-3),
                SceneOption::DeformationScale => o.deformation_scale = Some(1.0),
                SceneOption::Refine => o.refine = Some([4, 2, 1]),
                SceneOption::Stiffening => o.stiffening = Some(true),
                SceneOption::Body => {
                    o.body = Some(crate::body_file::BodyHandle(std::sync::Arc::new(
                        crate::body_file::ImportedBody::load("builtin:l-bracket").unwrap(),
                    )))
                }
                SceneOption::Band => o.band_hz = Some(100.0),
                SceneOption::InterfaceModes => o.interface_modes = Some(2),
                SceneOption::Simulate => {
                    o.simulation = Some(crate::scenes::body_simulation::BodySimulation {
                        parameters: Default::default(),
                        full_body: false,
                    })
                }
            }
            assert!(option.given(&o), "{option}");
            o
        };
        for option in SceneOption::ALL {
            let options = given(option);
            let takers: Vec<Scene> = all()
                .into_iter()
                .filter(|s| option.offered_by(&s.info.controls))
                .collect();
            assert!(!takers.is_empty(), "no scene takes {option}");
            for scene in all() {
                let checked = scene.check(&options);
                let offered = option.offered_by(&scene.info.controls);
                match (option, checked) {
                    (_, Ok(())) => assert!(offered, "{} took {option}", scene.info.id),
                    (SceneOption::Axes, Err(Error::UnknownAxes { .. })) => {}
                    (
                        _,
                        Err(Error::InvalidOption {
                            option: flag,
                            reason,
                            ..
                        }),
                    ) => {
                        assert!(!offered, "{} refused {option}: {reason}", scene.info.id);
                        assert_eq!(flag, option.flag());
                        assert!(
                            reason.contains(takers[0].info.id.as_str()),
                            "the refusal names the takers: {reason}"
                        );
                    }
                    (_, Err(e)) => panic!("{}, {option}: {e}", scene.info.id),
                }
            }
        }
    }
}
