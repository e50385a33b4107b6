//! The keys and the mouse: walking, the mouse's three modes (look, grab,
//! free), and the keys that launch the fireball, throw balls, pause, step,
//! change the time scale, re-initialise the balls, open the panel, show
//! help and take screenshots.

use glam::{DVec3, Vec2, Vec3};
use serde_json::json;
use winit::dpi::PhysicalPosition;
use winit::event::{ElementState, KeyEvent, MouseButton};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::CursorGrabMode;

use super::{App, DragPlane};
use crate::sandbox::Input;
use crate::window::panel::{fits, too_small};
use rolypoly_render::{Camera, DebugLayer};

/// What the mouse does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum MouseMode {
    /// Captured and hidden; moving it turns the view.
    Look,
    /// The view is locked; our own white arrow is the cursor; the left
    /// button grabs tumblers.
    Grab,
    /// Released by Escape: the mouse is the desktop's again.
    Free,
}

#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Keys {
    pub forward: bool,
    pub back: bool,
    pub left: bool,
    pub right: bool,
    /// Either Shift is down: V then shows the previous view.
    pub shift: [bool; 2],
}

impl App {
    pub(super) fn set_mode(&mut self, mode: MouseMode) {
        let Some(r) = &self.running else { return };
        let window = &r.window;
        match mode {
            MouseMode::Look => {
                // Confining is a courtesy: without it (no window manager) the
                // pointer is re-centred every move anyway.
                let _ = window.set_cursor_grab(CursorGrabMode::Confined);
                window.set_cursor_visible(false);
                self.look_settled = false;
                self.recentre();
            }
            MouseMode::Grab => {
                let _ = window.set_cursor_grab(CursorGrabMode::None);
                window.set_cursor_visible(false);
            }
            MouseMode::Free => {
                let _ = window.set_cursor_grab(CursorGrabMode::None);
                window.set_cursor_visible(true);
            }
        }
        if self.mode == MouseMode::Grab && mode != MouseMode::Grab {
            self.release_tumbler();
        }
        self.mode = mode;
    }

    pub(super) fn centre(&self) -> Vec2 {
        self.running.as_ref().map_or(Vec2::ZERO, |r| {
            Vec2::new(r.config.width as f32, r.config.height as f32) * 0.5
        })
    }

    pub(super) fn recentre(&self) {
        if let Some(r) = &self.running {
            let c = self.centre();
            let _ = r
                .window
                .set_cursor_position(PhysicalPosition::new(c.x as f64, c.y as f64));
        }
    }

    pub(super) fn viewport(&self) -> Vec2 {
        self.running.as_ref().map_or(Vec2::ONE, |r| {
            Vec2::new(r.config.width as f32, r.config.height as f32)
        })
    }

    pub(super) fn key(&mut self, event_loop: &ActiveEventLoop, event: &KeyEvent) {
        let PhysicalKey::Code(code) = event.physical_key else {
            return;
        };
        let down = event.state == ElementState::Pressed;
        match code {
            KeyCode::KeyW => self.keys.forward = down,
            KeyCode::KeyS => self.keys.back = down,
            KeyCode::KeyA => self.keys.left = down,
            KeyCode::KeyD => self.keys.right = down,
            KeyCode::ShiftRight => self.keys.shift[1] = down,
            KeyCode::ShiftLeft => {
                self.keys.shift[0] = down;
                let frozen = self.sandbox.playback.frozen();
                self.sandbox.playback.set_held(down);
                if self.sandbox.playback.frozen() != frozen {
                    self.log_pause();
                }
            }
            _ if !down
                || event.repeat
                    && !matches!(code, KeyCode::Period | KeyCode::Comma | KeyCode::Backspace) => {}
            KeyCode::KeyP => {
                let paused = self.sandbox.playback.paused();
                self.sandbox.playback.set_paused(!paused);
                self.log_pause();
            }
            KeyCode::Period => {
                self.sandbox.playback.set_paused(true);
                self.sandbox.playback.step_once();
            }
            // Back one step, or one second, paused there.
            KeyCode::Comma | KeyCode::Backspace => {
                let dt = self.sandbox.world().config().solver.dt;
                let back = if code == KeyCode::Comma {
                    1
                } else {
                    (1.0 / dt).round() as u64
                };
                let to = self.sandbox.ticks().saturating_sub(back);
                self.rewind_to(to);
            }
            KeyCode::BracketLeft | KeyCode::BracketRight => {
                self.sandbox
                    .playback
                    .shift_scale(code == KeyCode::BracketRight);
                self.log.say(
                    "time_scale",
                    json!({ "scale": self.sandbox.playback.scale() }),
                );
            }
            KeyCode::KeyB => self.throw_ball(),
            KeyCode::Tab => {
                self.panel.open = !self.panel.open;
                self.log.say("panel", json!({ "open": self.panel.open }));
                let scale = self
                    .running
                    .as_ref()
                    .map_or(1.0, |r| r.window.scale_factor());
                let points = self.viewport() / scale as f32;
                if self.panel.open && !fits(egui::vec2(points.x, points.y)) {
                    self.tell(too_small());
                }
            }
            KeyCode::KeyF => {
                let input = if self.sandbox.world().fireball().is_some() {
                    Input::FireballOff
                } else {
                    let forward = self.camera.forward();
                    let from = self.camera.position + forward * 0.6;
                    Input::Fireball {
                        from: from.as_dvec3().to_array(),
                        direction: forward.as_dvec3().to_array(),
                    }
                };
                let _ = self.sandbox.apply(input);
                self.log.say(
                    "fireball",
                    json!({ "on": self.sandbox.world().fireball().is_some() }),
                );
            }
            KeyCode::KeyR => self.toggle_recording(),
            KeyCode::KeyM => {
                let muted = self.sound.toggle_mute();
                self.log.say(
                    "sound",
                    json!({ "muted": muted, "device": self.sound.playing() }),
                );
            }
            KeyCode::KeyG => {
                let next = if self.mode == MouseMode::Grab {
                    MouseMode::Look
                } else {
                    MouseMode::Grab
                };
                self.set_mode(next);
                self.log.say("grab_mode", json!({ "on": next == MouseMode::Grab, "tumblers_on_screen": self.tumblers_on_screen() }));
            }
            KeyCode::KeyI => self.restart(),
            // The frame's views in turn; the frame shows the new one.
            KeyCode::KeyV => {
                let view = self.panel.view;
                self.panel.view = if self.keys.shift.contains(&true) {
                    view.previous()
                } else {
                    view.next()
                };
                self.tell_view();
            }
            KeyCode::KeyO => self.toggle_orbit(),
            KeyCode::F4 => {
                self.plots.open = !self.plots.open;
                self.log.say("plots", json!({ "open": self.plots.open }));
            }
            KeyCode::F3 => {
                self.profiler.open = !self.profiler.open;
                self.log
                    .say("profiler", json!({ "open": self.profiler.open }));
            }
            KeyCode::Digit1
            | KeyCode::Digit2
            | KeyCode::Digit3
            | KeyCode::Digit4
            | KeyCode::Digit5
            | KeyCode::Digit6 => {
                let digits = [
                    KeyCode::Digit1,
                    KeyCode::Digit2,
                    KeyCode::Digit3,
                    KeyCode::Digit4,
                    KeyCode::Digit5,
                    KeyCode::Digit6,
                ];
                let k = digits.iter().position(|&d| d == code).unwrap_or(0);
                let layer = DebugLayer::ALL[k];
                let on = !self.panel.debug.shows(layer);
                self.panel.debug.set(layer, on);
                self.log
                    .say("debug_view", json!({ "view": layer.name(), "on": on }));
            }
            KeyCode::KeyH | KeyCode::F1 => self.hud_state.help = !self.hud_state.help,
            KeyCode::F12 => {
                if let Err(e) = self.screenshot() {
                    // A screenshot that cannot be written is reported, and the program goes on.
                    eprintln!("error: {e:#}");
                    self.log
                        .say("screenshot_failed", json!({ "error": format!("{e:#}") }));
                }
            }
            KeyCode::Escape => {
                if self.mode == MouseMode::Free {
                    event_loop.exit();
                } else {
                    self.set_mode(MouseMode::Free);
                    self.log.say("mouse", json!({ "captured": false }));
                }
            }
            _ => {}
        }
    }

    pub(super) fn mouse_moved(&mut self, at: Vec2) {
        match self.mode {
            MouseMode::Look => {
                let delta = at - self.centre();
                // The first position after capturing says where the pointer
                // was, not how far it moved; so does a jump across a good part
                // of the window (the pointer left and came back).
                let jump = 0.25 * self.viewport().min_element();
                if !self.look_settled {
                    self.look_settled = true;
                } else if delta.length_squared() > 0.0 && delta.length() < jump {
                    match &mut self.orbit {
                        Some((orbit, _)) => orbit.turn(delta, self.options.look_speed),
                        None => self.camera.turn(delta, self.options.look_speed),
                    }
                }
                if delta.length_squared() > 0.0 {
                    self.recentre();
                }
            }
            MouseMode::Grab => {
                self.cursor = at;
                if let Some(plane) = self.drag_plane
                    && let Some(target) = self.cursor_on_plane(plane)
                {
                    let _ = self.sandbox.apply(Input::Drag {
                        to: target.to_array(),
                    });
                }
            }
            MouseMode::Free => {}
        }
    }

    /// Where the ray under our cursor meets the drag plane `plane`.
    pub(super) fn cursor_on_plane(&self, plane: DragPlane) -> Option<DVec3> {
        let (origin, dir) = self.camera.camera().ray(self.cursor, self.viewport());
        let (origin, dir) = (origin.as_dvec3(), dir.as_dvec3());
        let across = dir.dot(plane.normal);
        if across.abs() < 1e-4 {
            return None;
        }
        let t = (plane.point - origin).dot(plane.normal) / across;
        (t > 0.0).then(|| origin + dir * t)
    }

    pub(super) fn button(&mut self, button: MouseButton, state: ElementState) {
        if button != MouseButton::Left {
            return;
        }
        match (self.mode, state) {
            (MouseMode::Free, ElementState::Pressed) => {
                self.set_mode(MouseMode::Look);
                self.log.say("mouse", json!({ "captured": true }));
            }
            (MouseMode::Grab, ElementState::Pressed) => self.grab_under_cursor(),
            (MouseMode::Grab, ElementState::Released) => self.release_tumbler(),
            _ => {}
        }
    }

    /// Where each tumbler's belly appears in the window (pixels), for the log.
    pub(super) fn tumblers_on_screen(&self) -> Vec<[f32; 2]> {
        let size = self.viewport();
        let view_proj = self.camera.camera().view_projection(size.x / size.y);
        let shape = self.sandbox.sim.world.tumbler_shape();
        self.sandbox
            .sim
            .world
            .tumblers()
            .iter()
            .map(|t| {
                let belly = t
                    .sphere_center(shape, 2.min(shape.spheres.len() - 1))
                    .as_vec3();
                let clip = view_proj * belly.extend(1.0);
                if clip.w <= 0.0 {
                    // Behind the camera: nowhere on screen.
                    return [-1.0, -1.0];
                }
                let ndc = clip.truncate() / clip.w;
                [(ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y]
            })
            .collect()
    }

    /// The left button in grab mode: the hand takes the nearest tumbler or
    /// ball under the cursor.
    fn grab_under_cursor(&mut self) {
        let (origin, dir) = self.camera.camera().ray(self.cursor, self.viewport());
        let (origin, dir) = (origin.as_dvec3(), dir.as_dvec3());
        let world = &self.sandbox.sim.world;
        let tumbler = world.pick(origin, dir);
        let ball = world.pick_ball(origin, dir);
        match (tumbler, ball) {
            (Some(pick), b) if b.is_none_or(|b| pick.distance <= b.distance) => {
                let _ = self.sandbox.apply(Input::Grab {
                    tumbler: pick.tumbler,
                    point: pick.point.to_array(),
                });
                self.drag_plane = Some(DragPlane {
                    point: pick.point,
                    normal: DVec3::Y,
                });
                let at = self.sandbox.sim.world.tumblers()[pick.tumbler].bottom_center();
                self.log.say("grabbed", json!({ "tumbler": pick.tumbler, "at": [at.x, at.z], "point": pick.point.to_array() }));
            }
            (_, Some(pick)) => {
                let _ = self.sandbox.apply(Input::GrabBall { ball: pick.ball });
                let centre = self.sandbox.sim.world.balls().positions()[pick.ball];
                self.drag_plane = Some(DragPlane {
                    point: centre,
                    normal: self.camera.forward().as_dvec3(),
                });
                self.log.say(
                    "grabbed",
                    json!({ "ball": pick.ball, "point": pick.point.to_array(), "centre": centre.to_array() }),
                );
            }
            _ => {}
        }
    }

    pub(super) fn release_tumbler(&mut self) {
        let world = &self.sandbox.sim.world;
        let held = (world.grabbed(), world.held_ball());
        if held != (None, None) {
            let _ = self.sandbox.apply(Input::Release);
        }
        let world = &self.sandbox.sim.world;
        match held {
            (Some(index), _) => {
                let at = world.tumblers()[index].bottom_center();
                self.log
                    .say("released", json!({ "tumbler": index, "at": [at.x, at.z] }));
            }
            (_, Some(ball)) => {
                let v = world.balls().velocities()[ball];
                self.log.say(
                    "released",
                    json!({ "ball": ball, "velocity": v.to_array() }),
                );
            }
            _ => {}
        }
        self.drag_plane = None;
    }

    /// Moves the camera by the walking keys held, for `elapsed` seconds.
    pub(super) fn walk(&mut self, elapsed: f32) {
        let forward = self.keys.forward as i32 - self.keys.back as i32;
        let right = self.keys.right as i32 - self.keys.left as i32;
        // The orbit camera does not walk: it circles.
        if forward == 0 && right == 0 || self.orbit.is_some() {
            return;
        }
        let room = *self.sandbox.sim.world.room();
        let margin = Vec3::splat(0.15);
        // Inside the room, or back out to where the view starts, in front
        // of its open front wall.
        let start = Camera::overview(self.sandbox.sim.world.config().room.size.as_vec3()).eye;
        self.camera.walk(
            forward as f32,
            right as f32,
            self.options.move_speed,
            elapsed,
            room.min.as_vec3() + margin,
            (room.max.as_vec3() - margin).max(start),
        );
    }
}
