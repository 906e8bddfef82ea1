//! The panel's model section: axes, the slab's mesh, the integrator and the dynamic
//! stiffening; a simulation's deflection factor and end time.

use rerun::external::egui;

use super::{Change, Command, Explorer};
use crate::{
    dynamics::{AxisKind, IntegrationScheme},
    fem::SlabParameters,
    scenes::SceneInfo,
};

impl Explorer {
    /// Axes, the slab's mesh and the integrator.
    pub(super) fn model_ui(&mut self, ui: &mut egui::Ui, info: &SceneInfo, out: &mut Vec<Command>) {
        if !info.controls.axes.is_empty() {
            ui.horizontal_wrapped(|ui| {
                ui.label("axes");
                let choices =
                    std::iter::once(None).chain(info.controls.axes.iter().copied().map(Some));
                for a in choices {
                    let text = a.map_or("default", AxisKind::id);
                    if ui.selectable_label(self.controls.axes == a, text).clicked()
                        && self.controls.axes != a
                    {
                        out.push(Command::Set(Change::Axes(a)));
                    }
                }
            });
        }
        if info.controls.refine.is_some() {
            let label = |b: &[usize]| match b {
                &[x, y, z] => match SlabParameters::refined([x, y, z]) {
                    Ok(p) => format!("{x}×{y}×{z} ({} DOF)", p.dof_count()),
                    Err(_) => format!("{x}×{y}×{z}"),
                },
                _ => "default".into(),
            };
            let mut mesh = self.controls.refine.clone();
            egui::ComboBox::from_label("mesh")
                .selected_text(label(&mesh))
                .show_ui(ui, |ui| {
                    // A simulation integrates the full model too: meshes up to a few
                    // thousand DOF only.
                    let simulation = info.controls.end_time.is_some();
                    for p in super::controls::MESH_PRESETS {
                        let dofs = SlabParameters::refined(p).map_or(0, |q| q.dof_count());
                        if !simulation || dofs <= super::controls::SIMULATION_MESH_DOF_LIMIT {
                            ui.selectable_value(&mut mesh, p.to_vec(), label(&p));
                        }
                    }
                });
            if mesh != self.controls.refine {
                out.push(Command::Set(Change::Refine(mesh)));
            }
        }
        if info.controls.end_time.is_some() {
            ui.horizontal(|ui| {
                ui.label("integrator");
                for id in IntegrationScheme::IDS {
                    let chosen = self.controls.integrator.map_or("dp5", |s| s.id()) == id;
                    if ui.selectable_label(chosen, id).clicked()
                        && !chosen
                        && let Some(scheme) = IntegrationScheme::from_id(id)
                    {
                        out.push(Command::Set(Change::Integrator(scheme)));
                    }
                }
            });
        }
        if info.controls.stiffening {
            let mut on = self.controls.stiffening;
            ui.checkbox(&mut on, "dynamic stiffening").on_hover_text(
                "the geometric stiffness of the frame's loads (spin, gravity, the frame's \
                     acceleration), which Lin's thesis leaves out: off reproduces the thesis",
            );
            if on != self.controls.stiffening {
                out.push(Command::Set(Change::Stiffening(on)));
            }
        }
    }

    /// A simulation's deflection factor and end time.
    pub(super) fn simulation_ui(
        &mut self,
        ui: &mut egui::Ui,
        info: &SceneInfo,
        out: &mut Vec<Command>,
    ) {
        if info.controls.end_time.is_some() {
            // The factor in use: the typed one, else the scene's automatic one.
            let shown = self
                .current
                .as_ref()
                .and_then(|c| c.report.results.get("deformation_scale"))
                .and_then(|v| v.as_f64());
            ui.horizontal(|ui| {
                ui.label(match (self.controls.deformation_scale, shown) {
                    (f, _) if f > 0.0 => format!("deflection ×{f}"),
                    (_, Some(f)) => format!("deflection ×{f} (auto)"),
                    _ => "deflection: auto".into(),
                });
                let base = if self.controls.deformation_scale > 0.0 {
                    self.controls.deformation_scale
                } else {
                    shown.unwrap_or(1.0)
                };
                if ui.button("×½").clicked() {
                    out.push(Command::Set(Change::DeformationScale(base / 2.0)));
                }
                if ui.button("×2").clicked() {
                    out.push(Command::Set(Change::DeformationScale(base * 2.0)));
                }
                if ui.button("auto").clicked() && self.controls.deformation_scale != 0.0 {
                    out.push(Command::Set(Change::DeformationScale(0.0)));
                }
            });
            ui.horizontal(|ui| {
                ui.label(format!("end time: {:.2} s", self.controls.end_time));
                if ui.button("shorter").clicked() && self.controls.end_time > 0.25 {
                    let t = (self.controls.end_time - 0.25).max(0.25);
                    out.push(Command::Set(Change::EndTime(t)));
                }
                if ui.button("longer").clicked() && self.controls.end_time < 60.0 {
                    out.push(Command::Set(Change::EndTime(self.controls.end_time + 0.25)));
                }
            });
        }
        ui.separator();
    }
}
