//! The panel's `simulate` section for the `modes` scene: the body driven through one of its
//! node sets, as `flexmodes simulate --drive rbe2:SET` drives it.

use rerun::external::egui;

use super::{
    Change, Command, Explorer,
    simulation_controls::{DriveMotion, ENDS, FREQUENCIES, RAMPS, RATES, SimulationControls},
};

impl Explorer {
    /// The switch between a body's modes and its driven simulation, and the drive's choices.
    pub(super) fn drive_ui(&mut self, ui: &mut egui::Ui, out: &mut Vec<Command>) {
        let sets = self.node_sets();
        if !self.controls.takes_body() || sets.is_empty() {
            return;
        }
        ui.separator();
        let current = self.controls.simulation.clone();
        let mut on = current.is_some();
        if ui
            .checkbox(&mut on, "simulate: drive an interface")
            .on_hover_text(
                "the body driven through a node set tied rigidly to its master (RBE2), \
                 integrated by generalized-α: the full body against each method, as \
                 `flexmodes simulate` runs it",
            )
            .changed()
        {
            let drive = self
                .default_interface_set()
                .or_else(|| sets.first().map(|(name, _)| name.clone()))
                .unwrap_or_default();
            out.push(Command::Set(Change::Simulation(
                on.then(|| SimulationControls::for_drive(&drive)),
            )));
        }
        let Some(s) = current else {
            return;
        };
        let mut changed = s.clone();
        interface_ui(ui, &sets, &mut changed);
        motion_ui(ui, &mut changed);
        choices(ui, "interval:", &ENDS, &mut changed.end, |p| {
            format!("{:.0} ms", p * 1e3)
        });
        ui.checkbox(
            &mut changed.full_body,
            "the full body too (NR, the reference)",
        )
        .on_hover_text(
            "integrates every DOF of the body: the reference the reduced models' history \
                 and reaction errors are measured against, and the slowest run",
        );
        if self.body_has_preload() {
            ui.checkbox(&mut changed.stiffening, "dynamic stiffening")
                .on_hover_text(
                    "the stress stiffening of the spin, from the stiffness the body file's \
                     [preload] gives at its rate, scaled with the rate²",
                );
        }
        ui.checkbox(
            &mut changed.residual_vectors,
            "residual vectors (inertia loads)",
        )
        .on_hover_text(
            "adds to each reduced basis the static responses to the frame's own inertia \
                 loads (its linear and angular accelerations and ω_iω_j), the body held at its \
                 interfaces: what a spun part's arms do under their own centrifugal load, which \
                 no low fixed-interface mode holds",
        );
        if changed != s {
            out.push(Command::Set(Change::Simulation(Some(changed))));
        }
    }
}

/// The drive's node set and the sets the reduced models also keep as interfaces.
fn interface_ui(ui: &mut egui::Ui, sets: &[(String, usize)], changed: &mut SimulationControls) {
    ui.horizontal_wrapped(|ui| {
        ui.label("drive:");
        for (name, count) in sets {
            ui.selectable_value(&mut changed.drive, name.clone(), format!("rbe2:{name}"))
                .on_hover_text(format!("{count} nodes tied to one 6-DOF master, driven"));
        }
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("also kept:");
        for (name, count) in sets.iter().filter(|(name, _)| *name != changed.drive) {
            let mut on = changed.kept.contains(name);
            if ui
                .checkbox(&mut on, format!("rbe2:{name}"))
                .on_hover_text(format!(
                    "{count} nodes tied to a master the reduced models keep as an \
                     interface (free in the simulation; Guyan needs one)"
                ))
                .changed()
            {
                changed.kept.retain(|k| k != name);
                if on {
                    changed.kept.push(name.clone());
                }
            }
        }
    });
}

/// Spin up (rate and ramp) or shake (frequency), as presets.
fn motion_ui(ui: &mut egui::Ui, changed: &mut SimulationControls) {
    ui.horizontal(|ui| {
        ui.label("motion:");
        ui.selectable_value(&mut changed.motion, DriveMotion::SpinUp, "spin up")
            .on_hover_text("about the body's z axis through the drive's master");
        ui.selectable_value(&mut changed.motion, DriveMotion::Shake, "shake")
            .on_hover_text("along the ground's x axis, not turning");
    });
    match changed.motion {
        DriveMotion::SpinUp => {
            choices(ui, "rate:", &RATES, &mut changed.rate, |p| {
                format!("{p} rad/s")
            });
            choices(ui, "ramp:", &RAMPS, &mut changed.ramp, |p| {
                format!("{p} s ramp")
            });
        }
        DriveMotion::Shake => {
            choices(
                ui,
                "frequency:",
                &FREQUENCIES,
                &mut changed.frequency,
                |p| format!("{p} Hz"),
            );
            ui.label(format!("amplitude: {} m", changed.amplitude));
        }
    }
}

/// One row of preset values, each shown by `text`; the current value stays listed when it is
/// none of them.
fn choices(
    ui: &mut egui::Ui,
    label: &str,
    presets: &[f64],
    value: &mut f64,
    text: impl Fn(f64) -> String,
) {
    ui.horizontal_wrapped(|ui| {
        ui.label(label);
        let mut listed = presets.to_vec();
        if !presets.contains(value) {
            listed.push(*value);
        }
        for p in listed {
            ui.selectable_value(value, p, text(p));
        }
    });
}
