//! The interfaces a body is reduced on: plain boundary nodes, rigid (RBE2) and averaging
//! (RBE3) rings, as a body file and the user name them.

use crate::{
    Result,
    body_file::{ImportedBody, InterfaceKind},
    reduction::{AveragingInterface, RigidInterface},
};

/// The interfaces of a body's reduction.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyInterfaces {
    /// Boundary nodes, 1-based: plain ones and every rigid interface's.
    pub boundary: Vec<usize>,
    /// Node sets tied to a 6-DOF master (RBE2).
    pub rigid: Vec<RigidInterface>,
    /// Node sets averaged into a 6-DOF master (RBE3): loads and outputs, no restraint; their
    /// nodes are not in `boundary`.
    pub averaging: Vec<AveragingInterface>,
    /// Characteristic constraint modes kept in place of the constraint modes (`None`: all).
    pub interface_modes: Option<usize>,
}

impl BodyInterfaces {
    /// The interfaces `items` name on `body` ([`Self::of`]), or, with none named, the body's
    /// default interface as plain boundary nodes ([`ImportedBody::default_interface_nodes`]).
    pub fn named_or_default(
        body: &ImportedBody,
        items: Option<&[String]>,
        interface_modes: Option<usize>,
    ) -> Result<Self> {
        match items {
            Some(items) => Self::of(body, items, interface_modes),
            None => Ok(Self {
                boundary: body.default_interface_nodes()?.to_vec(),
                rigid: Vec::new(),
                averaging: Vec::new(),
                interface_modes,
            }),
        }
    }

    /// The interfaces `items` name on `body` (set names, node numbers, `rbe2:SET`, `rbe3:SET`,
    /// interfaces the body file declares), each master at its set's centroid unless the file
    /// gives it.
    pub fn of(
        body: &ImportedBody,
        items: &[String],
        interface_modes: Option<usize>,
    ) -> Result<Self> {
        let (boundary, sets) = body.boundary_with_interfaces(items)?;
        let mut rigid = Vec::new();
        let mut averaging = Vec::new();
        for set in sets {
            match set.kind {
                InterfaceKind::Rbe2 => {
                    let mut i = RigidInterface::at_centroid(&body.model, &set.name, &set.nodes)?;
                    if let Some(master) = set.master {
                        i.master = master;
                    }
                    rigid.push(i);
                }
                InterfaceKind::Rbe3 => {
                    let mut i = AveragingInterface::at_centroid(
                        &body.model,
                        &set.name,
                        &set.nodes,
                        set.weights,
                    )?;
                    if let Some(master) = set.master {
                        i.master = master;
                    }
                    averaging.push(i);
                }
            }
        }
        Ok(Self {
            boundary,
            rigid,
            averaging,
            interface_modes,
        })
    }

    /// The boundary nodes that belong to no rigid interface.
    pub fn plain_nodes(&self) -> Vec<usize> {
        self.boundary
            .iter()
            .copied()
            .filter(|n| !self.rigid.iter().any(|i| i.nodes.contains(n)))
            .collect()
    }
}
