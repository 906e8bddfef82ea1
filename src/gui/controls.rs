//! The panel's persisted state and the commands its UI returns.

use serde::{Deserialize, Serialize};

use crate::{
    Error, Result,
    reduction::Method,
    scenes::{self, SceneOptions},
};

/// What the user chose; persisted between sessions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Controls {
    /// Scene id.
    pub scene: String,
    /// Method ids to show.
    pub methods: Vec<String>,
    /// Kept normal modes.
    pub modes: usize,
    /// Boundary nodes as typed, 1-based, comma separated.
    pub boundary: String,
    /// Axis type id (empty: the scene's default).
    pub axes: String,
    /// Simulated interval, s (simulations only).
    #[serde(default)]
    pub end_time: f64,
}

impl Controls {
    /// The defaults of a scene.
    pub fn for_scene(id: &str) -> Result<Self> {
        let info = scenes::find(id)?.info;
        let c = info.controls;
        Ok(Self {
            scene: id.into(),
            methods: c.methods.iter().map(|m| m.id().to_string()).collect(),
            modes: c.modes.unwrap_or(0),
            boundary: join(c.boundary),
            // Empty: the scene's own choice (plank-symmetry compares both frames).
            axes: String::new(),
            end_time: c.end_time.unwrap_or(0.0),
        })
    }

    /// The scene's default boundary, as text.
    pub fn default_boundary(&self) -> String {
        scenes::find(&self.scene)
            .map(|s| join(s.info.controls.boundary))
            .unwrap_or_default()
    }

    /// Scene options from the controls; a malformed boundary is an error that names it.
    pub fn options(&self) -> Result<SceneOptions> {
        let info = scenes::find(&self.scene)?.info;
        let c = info.controls;
        let boundary = if c.boundary.is_empty() {
            None
        } else {
            let nodes = self
                .boundary
                .split([',', ' '])
                .filter(|t| !t.trim().is_empty())
                .map(|t| {
                    t.trim().parse::<usize>().map_err(|_| Error::InvalidOption {
                        scene: self.scene.clone(),
                        reason: format!("boundary `{}`: `{t}` is not a node number", self.boundary),
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            Some(nodes)
        };
        let methods = self
            .methods
            .iter()
            .filter_map(|id| Method::from_id(id))
            .collect::<Vec<_>>();
        if methods.is_empty() {
            return Err(Error::InvalidOption {
                scene: self.scene.clone(),
                reason: "select at least one method".into(),
            });
        }
        Ok(SceneOptions {
            methods: Some(methods),
            modes: c.modes.map(|_| self.modes),
            boundary,
            axes: if self.axes.is_empty() {
                None
            } else {
                Some(self.axes.clone())
            },
            end_time: c.end_time.map(|_| self.end_time),
            ..Default::default()
        })
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
    SelectScene(String),
    /// The options changed: recompute.
    Recompute,
    /// Put the scene's default boundary back and recompute.
    ResetBoundary,
    /// Write the current recording to this file.
    Save(std::path::PathBuf),
}
