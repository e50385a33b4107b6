//! The debug views' legend: what each colour and mark means, for the views
//! shown. The window shows it while any view is on; `render --legend` and
//! `record --legend` draw it into the frame. The entries themselves come
//! from the renderer's own list (`DebugLayer::legend`), so the legend and
//! the marks cannot drift apart.

use egui::{Color32, Pos2, Stroke, Vec2};
use rolypoly_render::{DebugLayer, DebugViews, Gpu, LegendEntry, MarkShape, OFFSCREEN_FORMAT};

use crate::egui_paint::EguiPainter;

/// Shows the legend of the views `views` shows, at the bottom left of the
/// window (under the HUD); nothing when none is shown.
pub fn show(ctx: &egui::Context, views: &DebugViews) {
    show_at(ctx, views, egui::Align2::LEFT_BOTTOM, [8.0, -8.0]);
}

/// Shows the legend where `anchor` and `offset` put it.
fn show_at(ctx: &egui::Context, views: &DebugViews, anchor: egui::Align2, offset: [f32; 2]) {
    if !views.any() {
        return;
    }
    egui::Area::new(egui::Id::unique("debug views legend"))
        .anchor(anchor, offset)
        .interactable(false)
        // Whole from its first frame: an off-screen frame has no next one.
        .fade_in(false)
        .show(ctx, |ui| {
            // Its own colours, whatever the theme: light text on a dark
            // glass, as the marks are bright on a dark outline.
            egui::Frame::new()
                .fill(Color32::from_black_alpha(190))
                .corner_radius(4.0)
                .inner_margin(6.0)
                .show(ui, |ui| {
                    ui.spacing_mut().item_spacing.y = 1.0;
                    for layer in DebugLayer::ALL.into_iter().filter(|&l| views.shows(l)) {
                        ui.label(
                            egui::RichText::new(layer_title(layer))
                                .size(TEXT_SIZE)
                                .strong()
                                .color(Color32::WHITE),
                        );
                        for entry in layer.legend() {
                            ui.horizontal(|ui| {
                                swatch(ui, &entry);
                                ui.label(
                                    egui::RichText::new(&entry.text)
                                        .size(TEXT_SIZE)
                                        .color(Color32::from_gray(225)),
                                );
                            });
                        }
                    }
                });
        });
}

/// The legend's text size, in points.
const TEXT_SIZE: f32 = 11.0;

/// A view's title, with the key that toggles it.
fn layer_title(layer: DebugLayer) -> String {
    let key = DebugLayer::ALL
        .iter()
        .position(|&l| l == layer)
        .map_or(0, |k| k + 1);
    format!("{key}  {}", layer.name())
}

/// The entry's mark, drawn as the frame draws it: its colour with a dark
/// outline.
fn swatch(ui: &mut egui::Ui, entry: &LegendEntry) {
    let (rect, _) = ui.allocate_exact_size(Vec2::new(24.0, 12.0), egui::Sense::hover());
    let [r, g, b] = entry
        .color
        .map(|c| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0) as u8);
    let color = Color32::from_rgb(r, g, b);
    let outline = Stroke::new(5.0, Color32::from_rgb(5, 5, 8));
    let painter = ui.painter_at(rect);
    let (left, right, centre) = (rect.left_center(), rect.right_center(), rect.center());
    match entry.shape {
        MarkShape::Dot => {
            painter.circle(
                centre,
                5.0,
                color,
                Stroke::new(1.5, Color32::from_rgb(5, 5, 8)),
            );
        }
        MarkShape::Line | MarkShape::Spike => {
            painter.line_segment([left, right], outline);
            painter.line_segment([left, right], Stroke::new(3.0, color));
        }
        MarkShape::Arrow => {
            let tip = right - Vec2::new(2.0, 0.0);
            let head = [tip, tip + Vec2::new(-9.0, -5.0), tip + Vec2::new(-9.0, 5.0)];
            painter.line_segment([left, tip - Vec2::new(8.0, 0.0)], outline);
            painter.line_segment([left, tip - Vec2::new(8.0, 0.0)], Stroke::new(3.0, color));
            painter.add(egui::Shape::convex_polygon(
                head.to_vec(),
                color,
                Stroke::new(1.5, Color32::from_rgb(5, 5, 8)),
            ));
        }
    }
}

/// The legend drawn into off-screen frames.
pub struct OffscreenLegend {
    context: egui::Context,
    painter: EguiPainter,
}

impl OffscreenLegend {
    /// A legend for off-screen frames, drawn with `gpu`.
    pub fn new(gpu: &Gpu) -> OffscreenLegend {
        OffscreenLegend {
            context: egui::Context::default(),
            painter: EguiPainter::new(gpu, OFFSCREEN_FORMAT),
        }
    }
}

impl rolypoly_core::frames::Overlay for OffscreenLegend {
    /// Draws the legend of `views` over `target`, a frame of `size` pixels:
    /// a point a pixel up to 720 pixels high, larger in proportion above.
    fn draw(&mut self, gpu: &Gpu, target: &wgpu::TextureView, size: [u32; 2], views: &DebugViews) {
        let pixels_per_point = (size[1] as f32 / 720.0).max(1.0);
        let mut input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                Pos2::ZERO,
                Vec2::new(size[0] as f32, size[1] as f32) / pixels_per_point,
            )),
            ..Default::default()
        };
        input
            .viewports
            .entry(egui::ViewportId::ROOT)
            .or_default()
            .native_pixels_per_point = Some(pixels_per_point);
        // At the top left, where no size of its own moves it; egui sizes a
        // new area in a first pass it does not show: lay out twice, keep
        // the textures of both, paint the second.
        let top_left = |ctx: &egui::Context| {
            show_at(ctx, views, egui::Align2::LEFT_TOP, [6.0, 6.0]);
        };
        let mut first = self.context.run_pass(input.clone(), top_left);
        let mut output = self.context.run_pass(input, top_left);
        first.textures_delta.append(output.textures_delta);
        output.textures_delta = first.textures_delta;
        self.painter.paint(gpu, &self.context, output, target, size);
    }
}
