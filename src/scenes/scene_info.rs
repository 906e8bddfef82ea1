//! What a scene is and which options it offers, as `flexmodes list` and the explorer's panel
//! show them.

use crate::scenes::SceneOption;
use crate::{dynamics::AxisKind, reduction::Method};

/// Static description of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneInfo {
    /// The scene's name (`beam-modes`): it names recordings and tables, and the command line
    /// and the registry's [`SceneId`](crate::scenes::SceneId) read it.
    pub name: &'static str,
    /// What recording the scene costs, in tenths of a second of one core (release build,
    /// `record --all --timings` on the 2-core reference machine, docs/benchmarks.md): `record`
    /// starts the costliest first, so that no core is left with a long scene at the end while
    /// the other idles. Only the order matters.
    pub recording_cost: u8,
    /// One line for `flexmodes list`.
    pub summary: &'static str,
    /// Thesis sections it reproduces.
    pub sections: &'static str,
    /// What the scene's options can be set to (for the desktop panel).
    pub controls: SceneControls,
}

/// The options a scene offers and their defaults: the table
/// [`SceneOption::offered_by`](crate::scenes::SceneOption::offered_by) reads, and the registry refuses
/// every option a scene does not offer before it runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneControls {
    /// Methods that can be shown.
    pub methods: &'static [Method],
    /// Default boundary/master nodes (empty: the scene has no boundary choice).
    pub boundary: &'static [usize],
    /// Default kept normal modes (`None`: the scene keeps none).
    pub modes: Option<usize>,
    /// Axis types offered (empty: no floating frame).
    pub axes: &'static [AxisKind],
    /// Default simulated interval, s (`None`: not a simulation).
    pub end_time: Option<f64>,
    /// Default mesh as bricks along x, y, z (`None`: the scene's body cannot be refined).
    pub refine: Option<[usize; 3]>,
    /// Whether `--stiffening on|off` switches the floating frame's dynamic stiffening.
    pub stiffening: bool,
    /// Whether the scene takes a body from a body file (`--body`, its node sets as
    /// `--boundary`, `--band`, `--interface-modes`, `simulate`).
    pub body: bool,
    /// Why the scene takes no more than it does, told with a refused option (the companion
    /// papers' fixed experiments).
    pub fixed_because: Option<&'static str>,
}

impl SceneControls {
    /// A scene that offers nothing: the base the scenes' tables start from.
    pub const NONE: SceneControls = SceneControls {
        methods: &[],
        boundary: &[],
        modes: None,
        axes: &[],
        end_time: None,
        refine: None,
        stiffening: false,
        body: false,
        fixed_because: None,
    };

    /// The options a scene with these controls takes ([`SceneOption::ALL`]'s order).
    pub fn takes(&self) -> Vec<SceneOption> {
        SceneOption::ALL
            .into_iter()
            .filter(|o| o.offered_by(self))
            .collect()
    }

    /// The options taken, each with its default where the scene has one (`flexmodes list
    /// --options`): `--method nr,mt (all)  --modes 6  …`, or `no options`.
    pub fn described(&self) -> String {
        let ids = |ids: Vec<&str>| ids.join(",");
        let said: Vec<String> = self
            .takes()
            .into_iter()
            .map(|o| {
                let default = match o {
                    SceneOption::Method => Some(ids(self.methods.iter().map(|m| m.id()).collect())),
                    SceneOption::Modes => self.modes.map(|k| k.to_string()),
                    SceneOption::Boundary if !self.boundary.is_empty() => Some(
                        self.boundary
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(","),
                    ),
                    SceneOption::Axes => Some(ids(self.axes.iter().map(|a| a.id()).collect())),
                    SceneOption::EndTime => self.end_time.map(|t| format!("{t} s")),
                    SceneOption::Refine => self.refine.map(|[x, y, z]| format!("{x},{y},{z}")),
                    _ => None,
                };
                match default {
                    Some(d) => format!("{o} {d}"),
                    None => o.flag().to_string(),
                }
            })
            .collect();
        if said.is_empty() {
            "no options".into()
        } else {
            said.join("  ")
        }
    }

    /// A scene whose only choice is which of `methods` to show (no boundary, kept modes, axes,
    /// interval or mesh), for the reason `because`: the companion papers' fixed experiments,
    /// the failures catalogue.
    pub const fn methods_only(methods: &'static [Method], because: &'static str) -> Self {
        Self {
            methods,
            fixed_because: Some(because),
            ..Self::NONE
        }
    }
}
