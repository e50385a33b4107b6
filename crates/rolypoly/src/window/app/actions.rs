//! What the panel and the keys ask of the sandbox beyond a setting: load a
//! scene, restart, throw a ball, save the settings, record the inputs.
//! Where the tumblers' shape changes, the renderer is made anew with their
//! mesh.

use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::json;

use anyhow::Context as _;

use super::App;
use crate::sandbox::Input;
use crate::scene;
use crate::window::fly_camera::FlyCamera;
use crate::window::panel::{PanelAction, SceneSource};

/// How long a message stays on the HUD.
const MESSAGE_SECONDS: Duration = Duration::from_secs(4);

impl App {
    pub(super) fn act(&mut self, action: PanelAction) {
        match action {
            PanelAction::Load(source) => self.load(&source),
            PanelAction::Restart => self.restart(),
            PanelAction::Save(path) => self.save(&path),
            PanelAction::Rewind(tick) => self.rewind_to(tick),
            PanelAction::ExportPlots(path) => self.export_plots(&path),
        }
    }

    /// Writes the plots' samples to `path` as `simulate --series` does, and
    /// says where (or why not: the program goes on).
    pub(super) fn export_plots(&mut self, path: &std::path::Path) {
        match self.plots.export(path) {
            Ok(()) => {
                self.log.say(
                    "series_exported",
                    json!({ "path": path.display().to_string() }),
                );
                self.tell(format!("series written to {}", path.display()));
            }
            Err(e) => self.tell(format!("{e}: {}", e.source)),
        }
    }

    /// Shows `message` on the HUD and in the panel for a few seconds.
    pub(super) fn tell(&mut self, message: String) {
        self.log.say("message", json!({ "text": message }));
        self.panel.message = Some(message.clone());
        self.hud_state.message = Some((message, Instant::now() + MESSAGE_SECONDS));
    }

    pub(super) fn log_pause(&self) {
        self.log.say(
            "pause",
            json!({ "paused": self.sandbox.playback.frozen(), "sim_time": self.sandbox.world().time() }),
        );
    }

    /// I: the balls anew, or the world anew where settings wait for it.
    pub(super) fn restart(&mut self) {
        self.release_tumbler();
        match self.sandbox.restart() {
            Ok(()) => {
                self.refresh_tumbler_look();
                self.log.say(
                    "reset",
                    json!({ "balls": self.sandbox.sim.ball_count(), "sim_time": self.sandbox.world().time() }),
                );
            }
            Err(e) => self.tell(format!("cannot restart: {e}")),
        }
    }

    /// B: a ball from just in front of the eye, along the view.
    pub(super) fn throw_ball(&mut self) {
        let forward = self.camera.forward();
        let from = (self.camera.position + forward * 0.4).as_dvec3();
        match self.sandbox.throw(from, forward.as_dvec3()) {
            Ok(ball) => self.log.say(
                "throw",
                json!({ "ball": ball, "balls": self.sandbox.sim.ball_count() }),
            ),
            Err(refused) => self.tell(refused.to_string()),
        }
    }

    fn load(&mut self, source: &SceneSource) {
        let name = source.label();
        let text = match source {
            SceneSource::Shipped(i) => Ok(crate::sandbox::SHIPPED_SCENES[*i].text.to_owned()),
            SceneSource::File(path) => std::fs::read_to_string(path)
                .with_context(|| format!("cannot read scene file `{}`", path.display())),
        };
        let loaded = text.and_then(|text| Ok(self.sandbox.load(&text, &name)?));
        match loaded {
            Ok(()) => {
                self.release_tumbler();
                self.refresh_tumbler_look();
                self.panel.message = None;
                self.log.say(
                    "scene",
                    json!({ "name": name, "balls": self.sandbox.sim.ball_count() }),
                );
            }
            Err(e) => self.tell(format!("cannot load {name}: {e:#}")),
        }
    }

    /// R: starts recording the inputs, or stops and writes them to a file
    /// beside the screenshots.
    pub(super) fn toggle_recording(&mut self) {
        if !self.sandbox.recording() {
            self.sandbox.start_recording();
            self.record_camera();
            self.log.say(
                "recording",
                json!({ "on": true, "tick": self.sandbox.ticks() }),
            );
            self.tell("recording the inputs: R again to stop".into());
            return;
        }
        let Some(log) = self.sandbox.stop_recording() else {
            return;
        };
        let stamp = super::seconds_since_1970();
        let path = self
            .options
            .screenshot_dir
            .join(format!("rolypoly-{stamp}-{}.replay", log.to_tick));
        match log.write(&path) {
            Ok(()) => {
                self.log.say(
                    "recorded",
                    json!({ "path": path.display().to_string(), "from_tick": log.from_tick, "to_tick": log.to_tick, "digest": log.end_digest }),
                );
                self.tell(format!(
                    "recorded {}: rolypoly replay {0} plays it",
                    path.display()
                ));
            }
            Err(e) => self.tell(format!("{e:#}")),
        }
    }

    /// In a replay: the recorded camera; at its end, the state checked
    /// against the recording's, and time paused there.
    pub(super) fn follow_replay(&mut self) {
        if let Some(pose) = self.sandbox.view_pose.take() {
            self.camera = FlyCamera::posed(&pose, &self.camera.camera());
        }
        if self.sandbox.replaying() {
            return;
        }
        let Some(expected) = self.options.replay_digest.take() else {
            return;
        };
        let digest = self.sandbox.digest();
        let identical = digest == expected;
        self.sandbox.end_replay();
        self.sandbox.playback.set_paused(true);
        self.log.say(
            "replay_end",
            json!({ "tick": self.sandbox.ticks(), "digest": digest, "identical": identical }),
        );
        self.tell(if identical {
            "the replay's end: the same state as recorded (P goes on)".into()
        } else {
            format!("the replay's end: another state than recorded ({digest}, not {expected})")
        });
    }

    /// While recording, the camera as an input, so that a replay sees
    /// what the player saw.
    pub(super) fn record_camera(&mut self) {
        if self.sandbox.recording() {
            let c = self.camera;
            let _ = self.sandbox.apply(Input::Camera {
                position: c.position.to_array(),
                yaw: c.yaw,
                pitch: c.pitch,
            });
        }
    }

    /// Writes the settings as a scene file, never over an existing file.
    fn save(&mut self, path: &Path) {
        let said = if path.as_os_str().is_empty() {
            "give the file a name to save the settings".to_owned()
        } else if path.exists() {
            format!("`{}` exists already: choose another name", path.display())
        } else {
            let header = format!(
                "Settings saved from the sandbox panel, starting from {} (seed {}).\n\nRun it with:\n\n    rolypoly --scene {}",
                self.sandbox.scene_name(),
                self.sandbox.seed(),
                path.display()
            );
            let text = scene::scene_file_text(self.sandbox.scene(), &header);
            match std::fs::write(path, text) {
                Ok(()) => format!("saved {}", path.display()),
                Err(e) => format!("cannot write `{}`: {e}", path.display()),
            }
        };
        self.tell(said);
    }

    /// After a world built anew: its tumblers' mesh, and a renderer for it
    /// if the shape changed.
    fn refresh_tumbler_look(&mut self) {
        let spheres = &self.sandbox.world().config().tumblers.spheres;
        if *spheres == self.tumbler_spheres {
            return;
        }
        match super::tumbler_look(spheres) {
            Ok((mesh, coarse, paint)) => {
                self.tumbler_spheres = spheres.clone();
                self.tumbler_mesh = mesh;
                self.coarse_tumbler = coarse;
                self.paint = paint;
                if let Some(r) = self.running.take() {
                    let renderer = self.renderer(&r.gpu, r.renderer.settings(), r.config.format);
                    self.running = Some(super::Running { renderer, ..r });
                }
            }
            Err(e) => self.tell(format!("cannot draw the new tumblers: {e:#}")),
        }
    }
}
