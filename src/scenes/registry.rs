//! The list of scenes: one line per scene names its id and the module that declares it.
//! Adding a scene is its own file (its `INFO` and `run`), its folder's `mod` line, and one line
//! here.

use crate::scenes::scene_id::declare_scenes;
use crate::scenes::{
    SceneInfo, SceneOption, SceneOptions, SceneOutput, beam, body, companion, failures, slab,
    spinning, substructuring,
};
use crate::{Error, Result};

declare_scenes! {
    BeamModes => beam::beam_modes { INFO, run },
    SlabModes => slab::slab_modes { INFO, run },
    BeamProfiles => beam::beam_profiles { INFO, run },
    BeamEitelberg => beam::beam_eitelberg { INFO, run },
    SlabSim1 => slab::slab_sims { INFO_1, run_sim1 },
    SlabSim2 => slab::slab_sims { INFO_2, run_sim2 },
    SlabSim3 => slab::slab_sims { INFO_3, run_sim3 },
    PlankSymmetry => slab::plank_symmetry { INFO, run },
    BeamMeanAxes => beam::beam_mean_axes { INFO, run },
    SlabModeSets => companion::slab_mode_sets { INFO, run },
    CantileverVariants => companion::cantilever_variants { INFO, run },
    Failures => failures::failure_catalogue { INFO, run },
    Modes => body::body_modes { INFO, run },
    SpinUp => spinning::spin_up { INFO, run },
    Amls => substructuring::amls { INFO, run },
}

/// A scene: computes its results and visuals for given options.
pub struct Scene {
    /// Which scene.
    pub id: SceneId,
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
        let scene = self.id.as_str();
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
                .map(|s| s.id.as_str())
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_id_leads_to_the_scene_that_says_it_is_that_one() {
        for id in SceneId::ALL {
            assert_eq!(get(id).id, id);
            assert_eq!(get(id).info.name, id.as_str());
            assert_eq!(find(id.as_str()).unwrap().id, id);
        }
    }

    #[test]
    fn every_id_reads_back_and_unknown_ones_name_the_known() {
        for id in SceneId::ALL {
            assert_eq!(id.as_str().parse::<SceneId>().unwrap(), id);
            assert_eq!(String::from(id).parse::<SceneId>().unwrap(), id);
        }
        let mut texts: Vec<_> = SceneId::ALL.map(SceneId::as_str).to_vec();
        texts.sort_unstable();
        texts.dedup();
        assert_eq!(
            texts.len(),
            SceneId::ALL.len(),
            "two scenes share a text form"
        );
        match "slab-sim4".parse::<SceneId>() {
            Err(Error::UnknownScene { id, known }) => {
                assert_eq!(id, "slab-sim4");
                assert_eq!(known, SceneId::ALL.map(SceneId::as_str));
            }
            other => panic!("expected UnknownScene, got {other:?}"),
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
                    (_, Ok(())) => assert!(offered, "{} took {option}", scene.id),
                    (SceneOption::Axes, Err(Error::UnknownAxes { .. })) => {}
                    (
                        _,
                        Err(Error::InvalidOption {
                            option: flag,
                            reason,
                            ..
                        }),
                    ) => {
                        assert!(!offered, "{} refused {option}: {reason}", scene.id);
                        assert_eq!(flag, option.flag());
                        assert!(
                            reason.contains(takers[0].id.as_str()),
                            "the refusal names the takers: {reason}"
                        );
                    }
                    (_, Err(e)) => panic!("{}, {option}: {e}", scene.id),
                }
            }
        }
    }
}
