//! Which scene: the registry's typed id, parsed once where a user names it (the command line,
//! the explorer's saved state, the classroom's `show` command).
//!
//! The id is declared with the list of scenes ([`declare_scenes!`]): the registry names each
//! scene once, by its variant and the module that defines its [`SceneInfo`] and `run`, and
//! the enum, its catalogue order, its text forms and the lookup all follow from that line.
//!
//! [`SceneInfo`]: crate::scenes::SceneInfo

/// Declares [`SceneId`](crate::scenes::SceneId) and the registry's `get` from one line per
/// scene, in the catalogue's order:
///
/// ```text
/// declare_scenes! {
///     BeamModes => beam::beam_modes { INFO, run },
///     SlabSim1 => slab::slab_sims { INFO_1, run_sim1 },
/// }
/// ```
///
/// The module's `INFO` ([`SceneInfo`](crate::scenes::SceneInfo)) gives the scene's name
/// (its text form) and recording cost; `run` computes it.
macro_rules! declare_scenes {
    ($($variant:ident => $($segment:ident)::+ { $info:ident, $run:ident }),+ $(,)?) => {
        /// A scene of the registry. Its text form (`slab-sim1`) names recordings, tables and
        /// the command line's arguments.
        #[derive(
            Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord,
            serde::Serialize, serde::Deserialize,
        )]
        #[serde(try_from = "String", into = "String")]
        pub enum SceneId {
            $(
                #[doc = concat!("The scene `scenes::", stringify!($($segment)::+), "` declares.")]
                $variant,
            )+
        }

        impl SceneId {
            /// Every scene, in the catalogue's order.
            pub const ALL: [SceneId; [$(stringify!($variant)),+].len()] = [$(SceneId::$variant),+];

            /// The text form (`beam-modes`): the scene's [`SceneInfo::name`](crate::scenes::SceneInfo::name).
            pub const fn as_str(self) -> &'static str {
                match self {
                    $(SceneId::$variant => $($segment)::+::$info.name,)+
                }
            }

            /// What recording the scene costs ([`SceneInfo::recording_cost`](crate::scenes::SceneInfo::recording_cost)):
            /// `record` starts the costliest first.
            pub const fn recording_cost(self) -> u8 {
                match self {
                    $(SceneId::$variant => $($segment)::+::$info.recording_cost,)+
                }
            }
        }

        impl std::fmt::Display for SceneId {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.as_str())
            }
        }

        impl std::str::FromStr for SceneId {
            type Err = crate::Error;

            fn from_str(s: &str) -> crate::Result<Self> {
                let s = s.trim();
                SceneId::ALL
                    .into_iter()
                    .find(|id| id.as_str() == s)
                    .ok_or_else(|| crate::Error::UnknownScene {
                        id: s.into(),
                        known: SceneId::ALL.map(SceneId::as_str).to_vec(),
                    })
            }
        }

        impl TryFrom<String> for SceneId {
            type Error = crate::Error;

            fn try_from(id: String) -> crate::Result<Self> {
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

        /// The scene `id` (every id has one: the match is exhaustive).
        pub fn get(id: SceneId) -> Scene {
            let (info, run): (SceneInfo, fn(&SceneOptions) -> Result<SceneOutput>) = match id {
                $(SceneId::$variant => ($($segment)::+::$info, $($segment)::+::$run),)+
            };
            Scene { id, info, run }
        }
    };
}

pub(super) use declare_scenes;
