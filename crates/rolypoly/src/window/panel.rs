//! The sandbox panel (Tab): the scene list, the scene's constants applied
//! as they change, pause, single steps and the time scale, the throw
//! speed, and saving the settings as a scene file. It only draws the
//! sandbox and hands it what the player did; the window carries out the
//! actions that need more than the sandbox (loading a scene rebuilds the
//! renderer's tumbler mesh).

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use rolypoly_render::{DebugLayer, DebugViews, FrameView};

use super::plots::Plots;
use crate::sandbox::{SHIPPED_SCENES, Sandbox, THROW_SPEEDS, TIME_SCALES};
use crate::scene::Scene;
use crate::scene::keys::{Control, KEYS, Slot, Takes};

/// Widest the panel gets (points), and the share of a narrow window it may
/// take; a window too small for even [`MIN_PANEL`] shows no panel, and
/// the HUD says so.
const PANEL_WIDTH: f32 = 300.0;
const PANEL_SHARE: f32 = 0.45;
pub const MIN_PANEL: [f32; 2] = [180.0, 160.0];

/// A scene the list offers.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneSource {
    /// One of [`SHIPPED_SCENES`].
    Shipped(usize),
    /// The file given with `--scene`, read again when chosen.
    File(PathBuf),
}

impl SceneSource {
    pub fn label(&self) -> String {
        match self {
            SceneSource::Shipped(i) => SHIPPED_SCENES[*i].name.to_owned(),
            SceneSource::File(path) => path.display().to_string(),
        }
    }
}

/// What the panel asks of the window.
#[derive(Clone, Debug, PartialEq)]
pub enum PanelAction {
    Load(SceneSource),
    Restart,
    Save(PathBuf),
    /// The timeline moved to this tick.
    Rewind(u64),
    /// The plots tab's "export CSV", into this file.
    ExportPlots(PathBuf),
}

/// The panel's tabs: the sandbox's settings, or the plots (as their
/// window, key F4, shows them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tab {
    #[default]
    Sandbox,
    Plots,
}

pub struct Panel {
    pub open: bool,
    /// The list: the shipped scenes, and the file given, if any.
    pub scenes: Vec<SceneSource>,
    save_path: String,
    /// What the last action or refused change said.
    pub message: Option<String>,
    /// The debug views shown (keys 1 to 6).
    pub debug: DebugViews,
    /// The view of the frame shown (V and Shift+V).
    pub view: FrameView,
    pub tab: Tab,
}

impl Panel {
    pub fn new(scene_file: Option<PathBuf>) -> Panel {
        let mut scenes: Vec<SceneSource> = (0..SHIPPED_SCENES.len())
            .map(SceneSource::Shipped)
            .collect();
        scenes.extend(scene_file.map(SceneSource::File));
        Panel {
            open: false,
            scenes,
            save_path: "my-scene.toml".into(),
            message: None,
            debug: DebugViews::default(),
            view: FrameView::Final,
            tab: Tab::default(),
        }
    }

    /// Draws the panel, if open and the window can hold it, and applies
    /// the player's changes of settings and playback to `sandbox`.
    /// `plots` draw in the plots tab, their export into `folder`.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        sandbox: &mut Sandbox,
        plots: &mut Plots,
        folder: &Path,
    ) -> Option<PanelAction> {
        let screen = ui.ctx().content_rect();
        plots.docked = false;
        if !self.open || !fits(screen.size()) {
            return None;
        }
        let width = PANEL_WIDTH.min(PANEL_SHARE * screen.width());
        let mut action = None;
        egui::Panel::right("sandbox")
            .exact_size(width)
            .resizable(false)
            .show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.selectable_value(&mut self.tab, Tab::Sandbox, "Sandbox");
                    ui.selectable_value(&mut self.tab, Tab::Plots, "Plots");
                });
                egui::ScrollArea::vertical().show(ui, |ui| match self.tab {
                    Tab::Sandbox => action = self.contents(ui, sandbox),
                    Tab::Plots => {
                        plots.docked = true;
                        if plots.open {
                            ui.label("The plots show in their own window (F4 closes it).");
                        } else {
                            action = plots.contents(ui, folder).map(PanelAction::ExportPlots);
                        }
                    }
                });
            });
        action
    }

    fn contents(&mut self, ui: &mut egui::Ui, sandbox: &mut Sandbox) -> Option<PanelAction> {
        let mut action = None;
        ui.small("Tab hides this panel");
        if let Some(message) = &self.message {
            ui.colored_label(egui::Color32::from_rgb(255, 200, 80), message);
        }

        ui.separator();
        ui.strong("Scene");
        let current = sandbox.scene_name().to_owned();
        for source in &self.scenes {
            let label = source.label();
            let tip = match source {
                SceneSource::Shipped(i) => SHIPPED_SCENES[*i].summary(),
                SceneSource::File(_) => "the file given with --scene",
            };
            if ui
                .selectable_label(label == current, &label)
                .on_hover_text(tip)
                .clicked()
            {
                action = Some(PanelAction::Load(source.clone()));
            }
        }

        ui.separator();
        ui.strong("Time");
        ui.horizontal(|ui| {
            let mut paused = sandbox.playback.paused();
            if ui.checkbox(&mut paused, "pause (P)").changed() {
                sandbox.playback.set_paused(paused);
            }
            if ui.button("step (.)").clicked() {
                sandbox.playback.set_paused(true);
                sandbox.playback.step_once();
            }
        });
        ui.horizontal_wrapped(|ui| {
            ui.label("speed");
            for scale in TIME_SCALES {
                let label = scale_label(scale);
                if ui
                    .selectable_label(sandbox.playback.scale() == scale, label)
                    .clicked()
                {
                    sandbox.playback.set_scale(scale);
                }
            }
        });

        let (oldest, furthest) = sandbox.timeline();
        if furthest > oldest {
            let dt = sandbox.world().config().solver.dt;
            let mut tick = sandbox.ticks();
            let slider = egui::Slider::new(&mut tick, oldest..=furthest)
                .text("rewind (, a step, Backspace a second)")
                .custom_formatter(move |t, _| format!("{:.2} s", t * dt));
            if ui.add(slider).changed() {
                action = Some(PanelAction::Rewind(tick));
            }
        }

        let mut scene = sandbox.scene().clone();
        ui.separator();
        ui.strong("Physics, from the next step");
        settings(ui, &mut scene, Takes::NextStep);
        ui.separator();
        ui.strong("On restart (I)");
        settings(ui, &mut scene, Takes::Restart);
        if sandbox.restart_pending() {
            ui.colored_label(
                egui::Color32::from_rgb(255, 200, 80),
                "changes wait for a restart",
            );
        }
        if ui.button("restart (I)").clicked() {
            action = Some(PanelAction::Restart);
        }
        ui.separator();
        ui.strong("Light");
        settings(ui, &mut scene, Takes::NextFrame);
        if scene != *sandbox.scene() {
            self.message = sandbox.set_scene(scene).err().map(|e| e.to_string());
        }

        ui.separator();
        ui.strong("Inside the step");
        for (k, layer) in DebugLayer::ALL.into_iter().enumerate() {
            let mut on = self.debug.shows(layer);
            if ui
                .checkbox(&mut on, format!("{} ({})", layer.name(), k + 1))
                .changed()
            {
                self.debug.set(layer, on);
            }
        }
        ui.add(
            egui::Slider::new(&mut self.debug.impulse_scale, 0.05..=20.0)
                .logarithmic(true)
                .text("impulse scale (1: a ball's weight is its radius)"),
        );

        ui.separator();
        ui.strong("Inside the frame (V, Shift+V)");
        ui.horizontal_wrapped(|ui| {
            for view in FrameView::ALL {
                ui.selectable_value(&mut self.view, view, view.name())
                    .on_hover_text(view.about());
            }
        });

        ui.separator();
        ui.strong("Throwing (B)");
        number(
            ui,
            "speed, m/s",
            &mut sandbox.throw_speed,
            THROW_SPEEDS.0..=THROW_SPEEDS.1,
        );
        ui.label(format!(
            "{} thrown of {}",
            sandbox.thrown(),
            crate::sandbox::MAX_THROWN
        ));

        ui.separator();
        ui.strong("Save as");
        ui.horizontal(|ui| {
            let label = ui.label("file");
            ui.text_edit_singleline(&mut self.save_path)
                .labelled_by(label.id);
        });
        if ui.button("save the settings").clicked() {
            action = Some(PanelAction::Save(PathBuf::from(self.save_path.trim())));
        }
        action
    }
}

/// Whether a window of `size` points can hold the panel.
pub fn fits(size: egui::Vec2) -> bool {
    size.x * PANEL_SHARE >= MIN_PANEL[0] && size.y >= MIN_PANEL[1]
}

/// What a window too small for the panel says.
pub fn too_small() -> String {
    let [w, h] = MIN_PANEL;
    format!(
        "the window is too small for the panel: it needs {:.0} x {h:.0} points or more",
        w / PANEL_SHARE
    )
}

fn scale_label(scale: f64) -> String {
    if scale < 1.0 {
        format!("1/{}", (1.0 / scale).round())
    } else {
        format!("{scale}x")
    }
}

fn number(ui: &mut egui::Ui, label: &str, value: &mut f64, range: RangeInclusive<f64>) {
    ui.add(egui::Slider::new(value, range).text(label));
}

/// The controls of the keys the panel shows that take effect `when`, in
/// the order of the table of keys.
fn settings(ui: &mut egui::Ui, scene: &mut Scene, when: Takes) {
    for key in KEYS.iter().filter(|k| k.takes == when) {
        match (key.control, &key.slot) {
            (Control::Hidden, _) => {}
            (Control::Checkbox(label), Slot::Switch(place)) => {
                ui.checkbox((place.write)(scene), label);
            }
            (Control::Choice(label), Slot::Word(place)) => {
                let now = (place.read)(scene);
                egui::ComboBox::from_label(label)
                    .selected_text(now)
                    .show_ui(ui, |ui| {
                        for name in place.names {
                            if ui.selectable_label(*name == now, *name).clicked() {
                                (place.write)(scene, name);
                            }
                        }
                    });
            }
            (Control::Slider(label, lo, hi), Slot::Real(place)) => {
                number(ui, label, (place.write)(scene), lo..=hi);
            }
            (Control::Slider(label, lo, hi), Slot::Single(place)) => {
                let range = lo as f32..=hi as f32;
                ui.add(egui::Slider::new((place.write)(scene), range).text(label));
            }
            (Control::Slider(label, lo, hi), Slot::Count(place)) => {
                let range = lo as usize..=hi as usize;
                ui.add(egui::Slider::new((place.write)(scene), range).text(label));
            }
            // The table's own test rules out other pairs.
            (control, _) => unreachable!("{}: no {control:?} for its type", key.name),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui_kittest::kittest::Queryable as _;

    /// One frame of the panel in a headless egui context of `size` points.
    fn frame(panel: &mut Panel, sandbox: &mut Sandbox, size: [f32; 2]) -> egui::FullOutput {
        let ctx = egui::Context::default();
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size.into())),
            ..Default::default()
        };
        let mut output = ctx.run_ui(input, |ui| {
            panel.show(ui, sandbox, &mut Plots::default(), Path::new("."));
        });
        // Nothing draws them here.
        output.textures_delta.clear();
        output
    }

    #[test]
    fn the_panel_draws_every_scene_and_leaves_the_sandbox_as_it_was() {
        let mut sandbox = Sandbox::new(Scene::default(), "default.toml", 1).unwrap();
        let mut panel = Panel::new(Some("mine.toml".into()));
        assert_eq!(panel.scenes.len(), SHIPPED_SCENES.len() + 1);
        panel.open = true;
        let output = frame(&mut panel, &mut sandbox, [1280.0, 720.0]);
        assert!(!output.shapes.is_empty());
        // Drawing alone changes no setting (sliders clamp nothing the
        // default scene holds).
        assert_eq!(sandbox.scene(), &Scene::default());
        assert_eq!(panel.message, None);
    }

    #[test]
    fn a_window_too_small_shows_no_panel() {
        assert!(fits(egui::vec2(1280.0, 720.0)));
        assert!(fits(egui::vec2(400.0, 200.0)));
        assert!(!fits(egui::vec2(300.0, 720.0)));
        assert!(!fits(egui::vec2(1280.0, 100.0)));
        let mut sandbox = Sandbox::new(Scene::default(), "default.toml", 1).unwrap();
        let mut panel = Panel::new(None);
        panel.open = true;
        let output = frame(&mut panel, &mut sandbox, [200.0, 100.0]);
        assert!(output.shapes.is_empty());
    }

    /// The panel and what it drives, as the window holds them.
    struct Toy {
        panel: Panel,
        sandbox: Sandbox,
        plots: Plots,
        actions: Vec<PanelAction>,
    }

    /// The open panel in a test harness tall enough to show it whole.
    fn harness(seed: u64) -> egui_kittest::Harness<'static, Toy> {
        let mut panel = Panel::new(None);
        panel.open = true;
        let toy = Toy {
            panel,
            sandbox: Sandbox::new(Scene::default(), "default.toml", seed).unwrap(),
            plots: Plots::default(),
            actions: Vec::new(),
        };
        egui_kittest::Harness::builder()
            .with_size([1280.0, 2400.0])
            .build_ui_state(
                |ui, toy: &mut Toy| {
                    let (panel, sandbox, plots) =
                        (&mut toy.panel, &mut toy.sandbox, &mut toy.plots);
                    if let Some(action) = panel.show(ui, sandbox, plots, Path::new("shots")) {
                        toy.actions.push(action);
                    }
                },
                toy,
            )
    }

    /// The slider of the setting labelled `label`.
    fn slider<'h>(
        h: &'h egui_kittest::Harness<'static, Toy>,
        label: &'h str,
    ) -> egui_kittest::Node<'h> {
        h.get(
            egui_kittest::kittest::By::new()
                .label(label)
                .role(egui::accesskit::Role::Slider),
        )
    }

    #[test]
    fn the_gravity_slider_sets_the_next_steps_acceleration() {
        for (seed, gravity) in [(1, 3.0), (2, 20.0)] {
            let mut h = harness(seed);
            slider(&h, "gravity, m/s²").set_value_accesskit(gravity);
            h.run();
            let s = &mut h.state_mut().sandbox;
            assert_eq!(s.scene().world.gravity, gravity);
            assert!(!s.restart_pending());
            // A ball at rest in mid-air falls at the new g from the next step.
            let k = s
                .throw(glam::DVec3::new(0.0, 2.5, 0.0), glam::DVec3::X)
                .unwrap();
            s.sim
                .world
                .balls_mut()
                .set(k, glam::DVec3::new(0.0, 2.5, 0.0), glam::DVec3::ZERO);
            s.tick();
            let dt = s.world().config().solver.dt;
            let v = s.world().balls().velocities()[k].y;
            assert!((v + gravity * dt).abs() < 1e-12, "{v}");
        }
    }

    #[test]
    fn the_plots_tab_shows_the_plots_samples_them_and_exports_them() {
        let mut h = harness(3);
        assert!(!h.state().plots.docked);
        h.get_by_label("Plots").click();
        h.run();
        assert!(h.state().plots.docked && h.state().plots.wanted());
        {
            let toy = h.state_mut();
            for _ in 0..5 {
                toy.sandbox.sim.tick();
                toy.plots.record(&toy.sandbox.sim.world, &[]);
            }
        }
        h.run();
        h.get_by_label("export CSV").click();
        h.run();
        let expected = PanelAction::ExportPlots(PathBuf::from("shots/rolypoly-series-5.csv"));
        assert_eq!(h.state().actions, [expected]);
        // Back to the settings: the plots are no longer wanted.
        h.get_by_label("Sandbox").click();
        h.run();
        assert!(!h.state().plots.docked);
        h.get_by_label("pause (P)");
    }

    #[test]
    fn pause_step_and_speed_are_the_playbacks() {
        let mut h = harness(3);
        h.get_by_label("pause (P)").click();
        h.run();
        assert!(h.state().sandbox.playback.paused());
        let before = h.state().sandbox.world().step_count();
        h.get_by_label("step (.)").click();
        h.run();
        let s = &mut h.state_mut().sandbox;
        assert_eq!(s.frame(1.0 / 60.0, Default::default), 1);
        assert_eq!(s.world().step_count(), before + 1);
        h.get_by_label("1/4").click();
        h.run();
        assert_eq!(h.state().sandbox.playback.scale(), 0.25);
    }

    #[test]
    fn sizes_wait_for_the_restart_and_scenes_are_chosen_from_the_list() {
        let mut h = harness(4);
        slider(&h, "balls").set_value_accesskit(12.0);
        h.run();
        assert_eq!(h.state().sandbox.scene().world.balls.count, 12);
        assert!(h.state().sandbox.restart_pending());
        h.get_by_label("changes wait for a restart");
        h.get_by_label("restart (I)").click();
        h.run();
        h.get_by_label("newtons-cradle.toml").click();
        h.run();
        assert_eq!(
            h.state().actions,
            [
                PanelAction::Restart,
                PanelAction::Load(SceneSource::Shipped(1))
            ]
        );
    }

    #[test]
    fn time_scales_read_as_fractions_and_multiples() {
        let labels: Vec<String> = TIME_SCALES.into_iter().map(scale_label).collect();
        assert_eq!(labels, ["1/16", "1/8", "1/4", "1/2", "1x", "2x", "4x"]);
    }
}
