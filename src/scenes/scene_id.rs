//! Which scene: the registry's typed id, parsed once where a user names it (the command line,
//! the explorer's saved state, the classroom's `show` command).

use serde::{Deserialize, Serialize};

use crate::{Error, Result};

/// A scene of the registry. Its text form (`slab-sim1`) names recordings, tables and the
/// command line's arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum SceneId {
    /// `beam-modes`: the App. A beam's mode sets.
    BeamModes,
    /// `slab-modes`: the App. B slab's free-free, constraint and fixed-interface modes.
    SlabModes,
    /// `beam-profiles`: §7.1 deformed profiles of the beam.
    BeamProfiles,
    /// `beam-eitelberg`: §6.6 Eitelberg's method on the beam.
    BeamEitelberg,
    /// `slab-sim1`: §7.2.2 the slab held under gravity.
    SlabSim1,
    /// `slab-sim2`: §7.2.3 the slab driven on the orbit of Eq. 7.10.
    SlabSim2,
    /// `slab-sim3`: §7.2.4 the slab driven by recorded accelerations.
    SlabSim3,
    /// `plank-symmetry`: §5.3.3 nodal-fixed against mean axes on the hung plank.
    PlankSymmetry,
    /// `beam-mean-axes`: §8.4–8.5 mode condensation with mean axes.
    BeamMeanAxes,
    /// `slab-mode-sets`: Spanos–Tsuha §4 mode sets on a dual-spin assembly.
    SlabModeSets,
    /// `cantilever-variants`: Witteveen §4, CB against Krylov and balanced truncation.
    CantileverVariants,
    /// `failures`: where each method fails.
    Failures,
    /// `modes`: a body file's modes under every method.
    Modes,
    /// `spin-up`: dynamic stiffening, the Campbell diagram and Kane's spin-up.
    SpinUp,
    /// `amls`: multi-level substructuring, the last rung of the component-mode ladder.
    Amls,
}

impl SceneId {
    /// Every scene, in the catalogue's order.
    pub const ALL: [SceneId; 15] = [
        SceneId::BeamModes,
        SceneId::SlabModes,
        SceneId::BeamProfiles,
        SceneId::BeamEitelberg,
        SceneId::SlabSim1,
        SceneId::SlabSim2,
        SceneId::SlabSim3,
        SceneId::PlankSymmetry,
        SceneId::BeamMeanAxes,
        SceneId::SlabModeSets,
        SceneId::CantileverVariants,
        SceneId::Failures,
        SceneId::Modes,
        SceneId::SpinUp,
        SceneId::Amls,
    ];

    /// What recording the scene costs, in tenths of a second of one core (release build,
    /// `record --all --timings` on the 2-core reference machine, docs/benchmarks.md): `record`
    /// starts the costliest first, so that no core is left with a long scene at the end
    /// while the other idles. Only the order matters; a new scene must be placed here.
    pub const fn recording_cost(self) -> u8 {
        match self {
            SceneId::PlankSymmetry => 9,
            SceneId::SlabSim2 | SceneId::SlabModeSets => 8,
            SceneId::SlabSim3 => 6,
            SceneId::SlabSim1 | SceneId::Modes => 5,
            SceneId::Amls => 4,
            SceneId::Failures | SceneId::CantileverVariants | SceneId::SpinUp => 2,
            SceneId::BeamModes
            | SceneId::SlabModes
            | SceneId::BeamProfiles
            | SceneId::BeamEitelberg
            | SceneId::BeamMeanAxes => 0,
        }
    }

    /// The text form (`beam-modes`).
    pub const fn as_str(self) -> &'static str {
        match self {
            SceneId::BeamModes => "beam-modes",
            SceneId::SlabModes => "slab-modes",
            SceneId::BeamProfiles => "beam-profiles",
            SceneId::BeamEitelberg => "beam-eitelberg",
            SceneId::SlabSim1 => "slab-sim1",
            SceneId::SlabSim2 => "slab-sim2",
            SceneId::SlabSim3 => "slab-sim3",
            SceneId::PlankSymmetry => "plank-symmetry",
            SceneId::BeamMeanAxes => "beam-mean-axes",
            SceneId::SlabModeSets => "slab-mode-sets",
            SceneId::CantileverVariants => "cantilever-variants",
            SceneId::Failures => "failures",
            SceneId::Modes => "modes",
            SceneId::SpinUp => "spin-up",
            SceneId::Amls => "amls",
        }
    }
}

impl std::fmt::Display for SceneId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for SceneId {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self> {
        let s = s.trim();
        SceneId::ALL
            .into_iter()
            .find(|id| id.as_str() == s)
            .ok_or_else(|| Error::UnknownScene {
                id: s.into(),
                known: SceneId::ALL.map(SceneId::as_str).to_vec(),
            })
    }
}

impl TryFrom<String> for SceneId {
    type Error = Error;

    fn try_from(id: String) -> Result<Self> {
        id.parse()
    }
}

impl From<SceneId> for String {
    fn from(id: SceneId) -> Self {
        id.as_str().into()
    }
}

impl PartialEq<str> for SceneId {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
