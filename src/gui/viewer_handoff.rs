//! Hands the explorer's recordings to the embedded viewer so that a switch is atomic.
//!
//! The viewer takes in a recording's messages in 10 ms slices, one slice per frame, and
//! shows a new recording from its first message on: left to itself, a switch shows meshes
//! whose transforms have not arrived yet (stacked at the origin) and views reading "(empty)"
//! for a second or more. Here the previous recording stays on screen, with its own layout,
//! until every message of the new one is in; then, between two frames, the new recording
//! becomes the one shown, its layout replaces the active one (so a removed method leaves no
//! view behind), and the previous recording and its layout are closed (their memory freed).
//! When the new recording has the views shown and each view's contents lie inside what it
//! frames, filling at least half of it ([`BlueprintKey::frames`]: a method unticked, often a
//! mode fewer), the active layout is kept instead, with whatever the user made
//! of it (views resized, moved or hidden, a tab picked, a 3D camera turned). Contents beyond
//! the framing (a mode more in a new row, a ticked method's larger swing) or far smaller bring
//! the new layout: a kept camera never points where the body is not.
//!
//! Even with every message in, the viewer fills a newly shown layout's views over its first
//! frames (a few views per frame, measured on slab-sim1: 3–5 frames until every plot has its
//! lines). So the switch is made under a cover: a screenshot of the previous picture, drawn
//! over the viewer for [`COVER_FRAMES`] frames while the viewer lays out the new one beneath.

use re_viewer_context::{CommandSender, RecordingOrTable, SystemCommand, SystemCommandSender as _};

use crate::record::BlueprintKey;
use rerun::external::{
    egui,
    re_log_channel::{LogSender, LogSource},
    re_log_types::{LogMsg, StoreId},
    re_viewer::external::re_viewer_context::{self, Route},
};

/// The stores of one recording as the viewer holds them.
#[derive(Debug, Clone)]
struct Stores {
    recording: Option<StoreId>,
    /// Its layout, sent as the application's default blueprint.
    blueprint: Option<StoreId>,
    /// What the active layout frames while this recording is shown: its own blueprint's
    /// key, or the one it kept.
    blueprint_key: BlueprintKey,
}

impl Stores {
    fn of(offer: &Offer) -> Self {
        let mut s = Self {
            recording: None,
            blueprint: None,
            blueprint_key: offer.blueprint.clone(),
        };
        for m in &offer.messages {
            if let LogMsg::SetStoreInfo(info) = m {
                let id = &info.info.store_id;
                if id.is_recording() && s.recording.is_none() {
                    s.recording = Some(id.clone());
                } else if id.is_blueprint() && s.blueprint.is_none() {
                    s.blueprint = Some(id.clone());
                }
            }
        }
        s
    }
}

/// Frames the previous picture covers the viewer after a switch (see the module).
pub const COVER_FRAMES: u32 = 8;

/// What the viewer is doing with the explorer's recordings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HandoffState {
    /// Showing a complete recording (or nothing yet).
    Idle,
    /// Taking in a new recording while the previous one stays on screen: messages still
    /// queued.
    Loading {
        /// Messages not yet taken in.
        queued: usize,
    },
    /// Every message is in; the previous picture is being captured to cover the switch.
    Capturing,
    /// Switched: the previous picture covers the viewer while it lays out the new recording.
    Covering {
        /// Frames left.
        frames_left: u32,
    },
}

/// A recording offered to the viewer: its messages (the recording and its layout as a
/// default blueprint) and what that blueprint holds.
#[derive(Debug, Clone)]
pub struct Offer {
    /// The recording's messages.
    pub messages: Vec<LogMsg>,
    /// What its blueprint holds: a recording whose blueprint would be the one shown keeps
    /// the active layout.
    pub blueprint: BlueprintKey,
}

/// Where a handoff is.
enum Phase {
    /// Nothing on its way.
    Idle,
    /// A screenshot of the picture shown is on its way; then this recording is sent under
    /// it (the viewer shows a new recording for one frame at its first message).
    ShotBeforeSend(Offer),
    /// The viewer takes the messages in while the previous recording stays on screen.
    Loading,
    /// Every message is in; a screenshot of the picture shown is on its way to cover the
    /// switch.
    ShotBeforeSwitch,
}

/// Sends recordings to the viewer and switches between them in one step (see the module).
pub struct ViewerHandoff {
    tx: LogSender,
    commands: CommandSender,
    shown: Option<Stores>,
    incoming: Option<Stores>,
    phase: Phase,
    /// A newer recording that came while one was being taken in: sent once that one is in
    /// (and dropped unseen).
    waiting: Option<Offer>,
    atomic: bool,
    /// Whether a switch to the same views keeps the active layout (see the module).
    keep_layouts: bool,
    /// The previous picture over the viewer, and the frames it stays.
    cover: Option<(egui::TextureHandle, u32)>,
}

/// Marks the screenshots that cover a switch apart from others.
#[derive(Debug, Clone, Copy)]
struct CoverShot;

/// Frames the cover stays after the messages are sent: the frame the viewer takes the first
/// one in (and shows the new recording), and one more.
const SEND_COVER_FRAMES: u32 = 2;

impl ViewerHandoff {
    /// Hands recordings over through `tx`, switching with `commands`. `atomic: false` shows
    /// each recording as it arrives and replaces the layout at every switch (the old
    /// explorer's switch, kept for the check that the screenshots catch half-drawn frames).
    pub fn new(tx: LogSender, commands: CommandSender, atomic: bool) -> Self {
        Self {
            tx,
            commands,
            shown: None,
            incoming: None,
            phase: Phase::Idle,
            waiting: None,
            atomic,
            keep_layouts: atomic,
            cover: None,
        }
    }

    /// Whether a switch to a recording with the views shown keeps the active layout (the
    /// user's arrangement); by default, when the switch is atomic.
    pub fn keeping_layouts(mut self, keep: bool) -> Self {
        self.keep_layouts = keep;
        self
    }

    /// Offers a new recording (its messages and its layout as a default blueprint).
    pub fn offer(&mut self, ctx: &egui::Context, offer: Offer) {
        match &mut self.phase {
            Phase::Idle => self.start(ctx, offer),
            Phase::ShotBeforeSend(queued) => *queued = offer,
            Phase::Loading | Phase::ShotBeforeSwitch => self.waiting = Some(offer),
        }
    }

    /// A recording loaded from a file: shown as it arrives, never closed by a switch.
    pub fn show_file(&mut self, messages: Vec<LogMsg>) {
        for msg in messages {
            let _ = self.tx.send(msg.into());
        }
    }

    /// Sends `offer`, under a cover when a recording is on screen.
    fn start(&mut self, ctx: &egui::Context, offer: Offer) {
        if self.atomic && self.shown.is_some() {
            request_shot(ctx);
            self.phase = Phase::ShotBeforeSend(offer);
        } else {
            self.send(offer);
        }
    }

    fn send(&mut self, offer: Offer) {
        let stores = Stores::of(&offer);
        for msg in offer.messages {
            let _ = self.tx.send(msg.into());
        }
        self.incoming = Some(stores);
        self.phase = Phase::Loading;
        self.pin();
    }

    /// Keeps the viewer on the recording shown (or on its loading screen before the first):
    /// undoes the viewer's own switch to a new recording at its first message. Runs after
    /// the viewer took in this frame's messages and before it draws.
    fn pin(&self) {
        if !self.atomic {
            return;
        }
        let route = match self.shown.as_ref().and_then(|s| s.recording.clone()) {
            Some(recording_id) => Route::LocalRecording { recording_id },
            None => Route::Loading(Box::new(LogSource::Sdk)),
        };
        self.commands.send_system(SystemCommand::SetRoute(route));
    }

    fn close(&self, stores: &Stores) {
        for id in [&stores.recording, &stores.blueprint].into_iter().flatten() {
            self.commands
                .send_system(SystemCommand::CloseRecordingOrTable(
                    RecordingOrTable::Recording {
                        store_id: id.clone(),
                    },
                ));
        }
    }

    /// Called once per frame before the viewer's own logic; returns true when a new
    /// recording has just become the one shown.
    pub fn step(&mut self, ctx: &egui::Context) -> bool {
        if let Some((_, frames)) = &mut self.cover {
            *frames = frames.saturating_sub(1);
            if *frames == 0 {
                self.cover = None;
            }
        }
        let shot = cover_shot(ctx);
        match std::mem::replace(&mut self.phase, Phase::Idle) {
            Phase::Idle => false,
            Phase::ShotBeforeSend(offer) => {
                match shot {
                    Some(image) => {
                        self.cover = Some((texture(ctx, &image), SEND_COVER_FRAMES));
                        self.send(offer);
                    }
                    None => self.phase = Phase::ShotBeforeSend(offer),
                }
                false
            }
            Phase::Loading if !self.tx.is_empty() => {
                self.phase = Phase::Loading;
                self.pin();
                false
            }
            Phase::Loading => {
                // Every message is in (the viewer takes one in completely before the next).
                if let Some(next) = self.waiting.take() {
                    // Superseded before it was shown.
                    if let Some(incoming) = self.incoming.take() {
                        self.close(&incoming);
                    }
                    self.pin();
                    self.start(ctx, next);
                    false
                } else if self.atomic && self.shown.is_some() {
                    request_shot(ctx);
                    self.phase = Phase::ShotBeforeSwitch;
                    self.pin();
                    false
                } else {
                    self.switch()
                }
            }
            Phase::ShotBeforeSwitch => match shot {
                Some(image) => {
                    self.cover = Some((texture(ctx, &image), COVER_FRAMES));
                    self.switch()
                }
                None => {
                    self.phase = Phase::ShotBeforeSwitch;
                    self.pin();
                    false
                }
            },
        }
    }

    /// Shows the incoming recording with its layout (or the active one, when that frames
    /// it) and closes the previous one.
    fn switch(&mut self) -> bool {
        let Some(mut incoming) = self.incoming.take() else {
            return false;
        };
        if let Some(recording_id) = incoming.recording.clone() {
            self.commands
                .send_system(SystemCommand::SetRoute(Route::LocalRecording {
                    recording_id,
                }));
        }
        let kept = self.shown.as_ref().filter(|shown| {
            self.keep_layouts && shown.blueprint_key.frames(&incoming.blueprint_key)
        });
        if let Some(shown) = kept {
            // The active layout stays, framing what it framed: later switches are judged
            // against that, not against the layout this recording brought (the active
            // blueprint belongs to the scene's application, not to the recording closed).
            incoming.blueprint_key = shown.blueprint_key.clone();
        } else {
            // The route's application now; its default blueprint (the new layout) is
            // cloned into the active one before the frame is drawn.
            self.commands
                .send_system(SystemCommand::ClearActiveBlueprint);
        }
        if let Some(old) = self.shown.take() {
            self.close(&old);
        }
        self.shown = Some(incoming);
        true
    }

    /// Draws the previous picture over `viewer` (the viewer's part of the window, points)
    /// while the switch is covered.
    pub fn paint_cover(&self, ctx: &egui::Context, viewer: egui::Rect) {
        let Some((texture, _)) = &self.cover else {
            return;
        };
        let screen = ctx.content_rect();
        let uv = egui::Rect::from_min_max(
            egui::pos2(
                (viewer.min.x - screen.min.x) / screen.width(),
                (viewer.min.y - screen.min.y) / screen.height(),
            ),
            egui::pos2(
                (viewer.max.x - screen.min.x) / screen.width(),
                (viewer.max.y - screen.min.y) / screen.height(),
            ),
        );
        let painter = ctx.layer_painter(egui::LayerId::new(
            egui::Order::Foreground,
            egui::Id::new("flexmodes-cover"),
        ));
        painter.image(texture.id(), viewer, uv, egui::Color32::WHITE);
        ctx.request_repaint();
    }

    /// Whether a recording is being taken in, and how many of its messages are queued.
    pub fn state(&self) -> HandoffState {
        match self.phase {
            Phase::ShotBeforeSend(_) | Phase::ShotBeforeSwitch => HandoffState::Capturing,
            Phase::Loading => HandoffState::Loading {
                queued: self.tx.len(),
            },
            Phase::Idle => match &self.cover {
                Some((_, frames_left)) => HandoffState::Covering {
                    frames_left: *frames_left,
                },
                None => HandoffState::Idle,
            },
        }
    }
}

/// Asks for a screenshot of the next frame drawn.
fn request_shot(ctx: &egui::Context) {
    ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::new(
        CoverShot,
    )));
}

/// The screenshot asked for by [`request_shot`], if it arrived this frame.
fn cover_shot(ctx: &egui::Context) -> Option<std::sync::Arc<egui::ColorImage>> {
    ctx.input(|i| {
        i.raw.events.iter().find_map(|e| match e {
            egui::Event::Screenshot {
                image, user_data, ..
            } if user_data
                .data
                .as_ref()
                .is_some_and(|d| d.downcast_ref::<CoverShot>().is_some()) =>
            {
                Some(image.clone())
            }
            _ => None,
        })
    })
}

fn texture(ctx: &egui::Context, image: &egui::ColorImage) -> egui::TextureHandle {
    ctx.load_texture(
        "flexmodes-cover",
        image.clone(),
        egui::TextureOptions::LINEAR,
    )
}
