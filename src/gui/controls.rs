//! The panel's persisted state and the commands its UI returns.

use crate::dynamics::AxisKind;
use serde::{Deserialize, Serialize};

use super::{SimulationControls, simulation_controls::DRIVEN_DEFAULT};
use crate::{
    Result,
    body_file::BodyHandle,
    dynamics::IntegrationScheme,
    reduction::Method,
    scenes::{self, SceneId, SceneOption, SceneOptions},
};

/// What the user chose; persisted between sessions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Controls {
    /// Which scene (a saved state naming no scene is not restored).
    pub scene: SceneId,
    /// Methods to show.
    pub methods: Vec<Method>,
    /// Kept normal modes.
    pub modes: usize,
    /// Boundary nodes as typed, 1-based, comma separated.
    pub boundary: String,
    /// Axis type (`None`: the scene's default).
    pub axes: Option<AxisKind>,
    /// Simulated interval, s (simulations only).
    #[serde(default)]
    pub end_time: f64,
    /// Mesh as bricks along x, y, z (scenes whose body can be refined; empty otherwise).
    #[serde(default)]
    pub refine: Vec<usize>,
    /// Factor on the drawn deflections of the simulations (0: automatic).
    #[serde(default)]
    pub deformation_scale: f64,
    /// Body file of the `modes` scene (a path or `builtin:NAME`; `None`: its default body).
    #[serde(default, deserialize_with = "empty_as_none")]
    pub body: Option<String>,
    /// Integrator of the simulations (`None`: the scene's default, Dormand–Prince).
    #[serde(default, deserialize_with = "empty_as_none")]
    pub integrator: Option<IntegrationScheme>,
    /// The `modes` scene's body driven through an interface instead of its modes compared
    /// (`None`: its modes).
    #[serde(default)]
    pub simulation: Option<SimulationControls>,
    /// Dynamic stiffening of the slab simulations' floating frame (off: the thesis' model).
    #[serde(default)]
    pub stiffening: bool,
}

/// The largest preset a simulation scene offers, DOF (its full model is integrated too).
pub const SIMULATION_MESH_DOF_LIMIT: usize = 2_500;

/// Meshes the explorer offers for a refinable slab: App. B and the benchmark's sizes that a
/// desktop reduces in seconds.
pub const MESH_PRESETS: [[usize; 3]; 5] =
    [[4, 2, 1], [8, 4, 2], [16, 8, 4], [24, 12, 6], [40, 20, 10]];

impl Controls {
    /// The defaults of a scene.
    pub fn for_scene(id: SceneId) -> Self {
        let c = scenes::get(id).info.controls;
        Self {
            scene: id,
            methods: c.methods.to_vec(),
            modes: c.modes.unwrap_or(0),
            boundary: join(c.boundary),
            // Empty: the scene's own choice (plank-symmetry compares both frames).
            axes: None,
            end_time: c.end_time.unwrap_or(0.0),
            refine: c.refine.map(|r| r.to_vec()).unwrap_or_default(),
            body: None,
            deformation_scale: 0.0,
            integrator: None,
            simulation: None,
            stiffening: false,
        }
    }

    /// The defaults of the `modes` scene on the body file `body`.
    pub fn for_body(body: &str) -> Result<Self> {
        Ok(Self {
            body: body_file(body),
            ..Self::for_scene(SceneId::Modes)
        })
    }

    /// The file name `save .rrd` proposes: the scene's id, or `simulate` for a driven body
    /// (the name `flexmodes simulate --save` users give it).
    pub fn file_name(&self) -> String {
        match &self.simulation {
            Some(_) if self.takes_body() => "simulate.rrd".into(),
            _ => format!("{}.rrd", self.scene),
        }
    }

    /// Whether the scene takes a body file (and node-set names as boundary).
    pub fn takes_body(&self) -> bool {
        self.scene == SceneId::Modes
    }

    /// The scene's default boundary, as text.
    pub fn default_boundary(&self) -> String {
        join(scenes::get(self.scene).info.controls.boundary)
    }

    /// Scene options from the controls; a malformed boundary is an error that names it. For
    /// the `modes` scene, `body` is the loaded body file: the boundary may name its node sets.
    pub fn options_with(&self, body: Option<&BodyHandle>) -> Result<SceneOptions> {
        if self.takes_body() {
            let items: Vec<String> = self
                .boundary
                .split([',', ' '])
                .filter(|t| !t.trim().is_empty())
                .map(|t| t.trim().to_string())
                .collect();
            let (boundary, rigid, averaging) = match body {
                Some(b) if !items.is_empty() => {
                    let i = crate::models::BodyInterfaces::of(b, &items, None)?;
                    (Some(i.boundary), i.rigid, i.averaging)
                }
                _ => (None, Vec::new(), Vec::new()),
            };
            let mut options = self.options()?;
            options.simulation = self
                .simulation
                .as_ref()
                .map(|s| s.simulation())
                .transpose()?;
            options.boundary = boundary;
            options.rigid_interfaces = rigid;
            options.averaging_interfaces = averaging;
            options.body = body.cloned();
            return Ok(options);
        }
        self.options()
    }

    /// Scene options from the controls; a malformed boundary is an error that names it.
    pub fn options(&self) -> Result<SceneOptions> {
        let info = scenes::get(self.scene).info;
        let c = info.controls;
        let refine = match (c.refine, self.refine.as_slice()) {
            (Some(_), &[x, y, z]) => Some([x, y, z]),
            _ => None,
        };
        // The default boundary names App. B nodes; on another mesh the scene's own default
        // (the same four bottom corners) applies.
        let refined = refine.is_some() && refine != c.refine;
        let boundary = if c.boundary.is_empty() || (refined && self.boundary == join(c.boundary)) {
            None
        } else {
            let nodes = SceneOptions::boundary_from_text(self.scene.as_str(), &self.boundary)?;
            Some(nodes)
        };
        let methods = self.methods.clone();
        // A scene without method choices (the failures scene) runs with its own settings.
        SceneOptions::require_a_method(&info, &methods)?;
        // Only what the scene's table offers is set (the registry refuses the rest).
        let offers = |option: SceneOption| option.offered_by(&c);
        Ok(SceneOptions {
            methods: offers(SceneOption::Method).then_some(methods),
            modes: offers(SceneOption::Modes).then_some(self.modes),
            boundary,
            axes: self.axes,
            end_time: offers(SceneOption::EndTime).then_some(self.end_time),
            deformation_scale: (offers(SceneOption::DeformationScale)
                && self.deformation_scale > 0.0)
                .then_some(self.deformation_scale),
            refine,
            integrator: self.integrator.filter(|_| offers(SceneOption::Integrator)),
            stiffening: offers(SceneOption::Stiffening).then_some(self.stiffening),
            ..Default::default()
        })
    }
}

/// A body file as typed: blank is the scene's default body.
fn body_file(text: &str) -> Option<String> {
    let text = text.trim();
    (!text.is_empty()).then(|| text.into())
}

/// A persisted value read back: absent, `null` or empty (how earlier versions stored "the
/// default") is `None`; otherwise it must parse.
fn empty_as_none<'de, D, T>(deserializer: D) -> std::result::Result<Option<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: std::str::FromStr,
    T::Err: std::fmt::Display,
{
    match Option::<String>::deserialize(deserializer)? {
        Some(text) if !text.trim().is_empty() => text
            .trim()
            .parse()
            .map(Some)
            .map_err(serde::de::Error::custom),
        _ => Ok(None),
    }
}

fn join(nodes: &[usize]) -> String {
    nodes
        .iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// What the panel asks for; applied after the frame's UI is drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    /// Switch to another scene (with its defaults).
    SelectScene(SceneId),
    /// Put the scene's default boundary back and recompute.
    ResetBoundary,
    /// Write the current recording to this file.
    Save(std::path::PathBuf),
    /// Change one control and recompute.
    Set(Change),
}

/// One change of the controls, as the panel asks for it.
#[derive(Debug, Clone, PartialEq)]
pub enum Change {
    /// Show (`true`) or hide a method.
    Method(Method, bool),
    /// Keep this many normal modes.
    Modes(usize),
    /// Load this body file (a path or `builtin:NAME`); the boundary goes back to its default.
    Body(String),
    /// Take this boundary (node numbers or a node-set name, as typed).
    Boundary(String),
    /// Take these axes (`None`: the scene's default).
    Axes(Option<AxisKind>),
    /// Mesh the slab with these bricks along x, y, z.
    Refine(Vec<usize>),
    /// Integrate with this scheme.
    Integrator(IntegrationScheme),
    /// Draw deflections with this factor (0: automatic).
    DeformationScale(f64),
    /// Simulate this interval, s.
    EndTime(f64),
    /// Drive the body as these controls say (`None`: show its modes).
    Simulation(Option<SimulationControls>),
    /// Simulate the slab with (`true`) or without dynamic stiffening.
    Stiffening(bool),
}

impl Controls {
    /// Applies one change.
    pub fn change(&mut self, change: Change) {
        match change {
            Change::Method(m, on) => {
                self.methods.retain(|&shown| shown != m);
                if on {
                    self.methods.push(m);
                }
            }
            Change::Modes(n) => self.modes = n,
            Change::Body(body) => {
                self.body = body_file(&body);
                self.boundary.clear();
                // The new body need not have the driven set.
                self.simulation = None;
            }
            Change::Boundary(boundary) => self.boundary = boundary,
            Change::Axes(axes) => self.axes = axes,
            Change::Refine(bricks) => self.refine = bricks,
            Change::Integrator(scheme) => self.integrator = Some(scheme),
            Change::DeformationScale(f) => self.deformation_scale = f,
            Change::EndTime(t) => self.end_time = t,
            Change::Stiffening(on) => self.stiffening = on,
            Change::Simulation(simulation) => {
                if simulation.is_some() && self.simulation.is_none() {
                    // `simulate`'s models: CB and MC (Guyan needs an interface besides the
                    // drive, and the other methods do not hold the driven ring still).
                    self.methods = DRIVEN_DEFAULT.to_vec();
                }
                self.simulation = simulation;
            }
        }
    }
}
