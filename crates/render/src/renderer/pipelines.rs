//! The render pipelines: how each kind of thing is drawn, into which
//! target, with which shader entry points, blending and depth.

use super::bindings::Layouts;
use super::taa::MOTION_FORMAT;
use super::{DEPTH_FORMAT, GEOMETRY_FORMAT, HDR_FORMAT, RenderSettings};
use crate::frame_view::ViewCodes;
use crate::instances::{BALL_MATERIAL, BallInstance, Instance, PreviousModel};
use crate::mesh::Vertex;
use crate::shaders::{self, ShaderFile, ShaderSet};
use crate::shadow;

/// Every pipeline of a frame but the cursor's.
pub(super) struct Pipelines {
    /// Lit and opaque meshes: the room and the tumblers.
    pub lit: wgpu::RenderPipeline,
    /// Balls, each a square that traces its sphere.
    pub ball: wgpu::RenderPipeline,
    /// What glows and is not lit: the bulb.
    pub emissive: wgpu::RenderPipeline,
    /// See-through particles, blended over what is behind.
    pub glow: wgpu::RenderPipeline,
    /// Meshes into a shadow face.
    pub shadow: wgpu::RenderPipeline,
    /// Balls into a shadow face.
    pub ball_shadow: wgpu::RenderPipeline,
    /// The HDR frame, tone-mapped into the output (or, lit at a lower
    /// resolution, into a target of its own size).
    pub tonemap: wgpu::RenderPipeline,
    /// The frame tone-mapped at a lower resolution, spread over the output.
    pub upscale: wgpu::RenderPipeline,
    /// The view the scene's and tone mapping's pipelines draw.
    pub view: ViewCodes,
}

impl Pipelines {
    /// The pipelines for `settings` (its multisample count and early ball
    /// depth as the adapter allows), tone mapping into `output_format`,
    /// drawing the view of the frame `view` codes.
    pub fn new(
        device: &wgpu::Device,
        shaders: &ShaderSet,
        layouts: &Layouts,
        settings: &RenderSettings,
        output_format: wgpu::TextureFormat,
        view: ViewCodes,
    ) -> Pipelines {
        let msaa = settings.msaa;
        let scene = shaders.source(&shaders::SCENE);
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(shaders::SCENE.name),
            source: wgpu::ShaderSource::Wgsl(scene_shader(scene, settings.early_ball_depth).into()),
        });
        let tonemap_shader = screen_shader(device, shaders, &shaders::TONEMAP);

        let scene_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("scene"),
                bind_group_layouts: &[Some(&layouts.scene)],
                immediate_size: 0,
            });
        let buffers = [Some(Vertex::layout()), Some(Instance::layout())];
        let scene_buffers = [
            Some(Vertex::layout()),
            Some(Instance::layout()),
            Some(PreviousModel::layout()),
        ];
        let temporal = settings.temporal;
        let shadow_taps = ("SHADOW_TAPS", f64::from(settings.shadow_taps));
        let frame_view = ("FRAME_VIEW", f64::from(view.scene));
        let scene_constants = [shadow_taps, frame_view];
        // Opaque passes write depth; see-through ones blend and only test it.
        let scene_pipeline_for = |entry: &str, label: &str, blend: Option<wgpu::BlendState>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&scene_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some("vs_scene"),
                    compilation_options: Default::default(),
                    buffers: &scene_buffers,
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode: Some(wgpu::Face::Back),
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(blend.is_none()),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: msaa,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants: &scene_constants,
                        ..Default::default()
                    },
                    targets: &scene_targets(blend, temporal),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let scene_pipeline = scene_pipeline_for("fs_lit", "lit", None);
        // Balls are squares that trace their sphere (see scene.wgsl): seen
        // from either side, and smooth at the outline through alpha to
        // coverage where there are samples to cover.
        let alpha_to_coverage = msaa > 1;
        let (kind, finish) = BALL_MATERIAL;
        let (specular, shininess) = (finish.specular, finish.shininess);
        let ball_constants = [
            ("ALPHA_TO_COVERAGE", f64::from(u8::from(alpha_to_coverage))),
            ("BALL_KIND", f64::from(kind as u32)),
            ("BALL_SPECULAR", f64::from(specular)),
            ("BALL_SHININESS", f64::from(shininess)),
            shadow_taps,
            frame_view,
        ];
        let ball_buffers = [Some(Vertex::layout()), Some(BallInstance::layout())];
        let ball_scene_buffers = [
            Some(Vertex::layout()),
            Some(BallInstance::layout()),
            Some(BallInstance::before_layout()),
        ];
        let ball_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("balls"),
            layout: Some(&scene_pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_ball"),
                compilation_options: Default::default(),
                buffers: &ball_scene_buffers,
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: msaa,
                alpha_to_coverage_enabled: alpha_to_coverage,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_ball"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &ball_constants,
                    ..Default::default()
                },
                targets: &scene_targets(None, temporal),
            }),
            multiview_mask: None,
            cache: None,
        });
        let emissive_pipeline = scene_pipeline_for("fs_emissive", "emissive", None);
        // Premultiplied alpha: a fragment adds its light and covers a share
        // of what is behind; with no cover it is purely additive (the shells,
        // the cubes' glowing frames), so only the cubes' dark insides depend
        // on drawing order, and small cubes need no sorting. Depth is tested
        // (walls hide particles) but not written (particles never hide each
        // other).
        let glow_pipeline = scene_pipeline_for(
            "fs_glow",
            "glow",
            Some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent::OVER,
            }),
        );

        let shadow_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("shadow"),
                bind_group_layouts: &[Some(&layouts.face)],
                immediate_size: 0,
            });
        // Slope-scaled bias keeps surfaces from shadowing themselves (acne).
        let shadow_bias = wgpu::DepthBiasState {
            constant: 2,
            slope_scale: 2.0,
            clamp: 0.0,
        };
        let shadow_pipeline_for = |vertex: &str,
                                   fragment: Option<&str>,
                                   buffers: &[Option<wgpu::VertexBufferLayout>],
                                   label: &str| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&shadow_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vertex),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: shadow::SHADOW_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: shadow_bias,
                }),
                multisample: Default::default(),
                fragment: fragment.map(|entry| wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &[],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let shadow_pipeline = shadow_pipeline_for("vs_shadow", None, &buffers, "shadow");
        let ball_shadow_pipeline = shadow_pipeline_for(
            "vs_ball_shadow",
            Some("fs_ball_shadow"),
            &ball_buffers,
            "ball shadow",
        );

        let tonemap_pipeline = screen_pipeline_into(
            device,
            "tonemap",
            &layouts.tonemap,
            &tonemap_shader,
            ("vs_screen", "fs_tonemap"),
            &[Some(output_format.into())],
            &[("SHOW", f64::from(view.show))],
        );

        let upscale_shader = screen_shader(device, shaders, &shaders::UPSCALE);
        let upscale_pipeline = screen_pipeline(
            device,
            "upscale",
            &layouts.upscale,
            &upscale_shader,
            ("vs_screen", "fs_upscale"),
            output_format.into(),
        );

        Pipelines {
            lit: scene_pipeline,
            ball: ball_pipeline,
            emissive: emissive_pipeline,
            glow: glow_pipeline,
            shadow: shadow_pipeline,
            ball_shadow: ball_shadow_pipeline,
            tonemap: tonemap_pipeline,
            upscale: upscale_pipeline,
            view,
        }
    }
}

/// The scene pass's targets: the HDR colour, the surface's normal and
/// distance for the occlusion and, on the `temporal` path, its motion.
/// Only opaque things (no `blend`) write the last two: see-through
/// particles leave the surface behind them there.
fn scene_targets(
    blend: Option<wgpu::BlendState>,
    temporal: bool,
) -> Vec<Option<wgpu::ColorTargetState>> {
    let surface = |format| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: if blend.is_some() {
                wgpu::ColorWrites::empty()
            } else {
                wgpu::ColorWrites::ALL
            },
        })
    };
    let mut targets = vec![
        Some(wgpu::ColorTargetState {
            format: HDR_FORMAT,
            blend,
            write_mask: wgpu::ColorWrites::ALL,
        }),
        surface(GEOMETRY_FORMAT),
    ];
    if temporal {
        targets.push(surface(MOTION_FORMAT));
    }
    targets
}

/// The shader of a pass over whole images: `file` of `shaders` after the
/// shared vertex shader that covers the target (screen.wgsl's `vs_screen`).
pub(super) fn screen_shader(
    device: &wgpu::Device,
    shaders: &ShaderSet,
    file: &ShaderFile,
) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(file.name),
        source: wgpu::ShaderSource::Wgsl(shaders.screen_pass(file).into()),
    })
}

/// A pipeline that draws in screen space into one `target`: no vertex
/// buffers, no depth, one bind group.
pub(super) fn screen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    shader: &wgpu::ShaderModule,
    (vertex, fragment): (&str, &str),
    target: wgpu::ColorTargetState,
) -> wgpu::RenderPipeline {
    screen_pipeline_into(
        device,
        label,
        layout,
        shader,
        (vertex, fragment),
        &[Some(target)],
        &[],
    )
}

/// As [`screen_pipeline`], drawing into several `targets` at once, the
/// fragment shader's overridable constants set to `constants`.
pub(super) fn screen_pipeline_into(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    shader: &wgpu::ShaderModule,
    (vertex, fragment): (&str, &str),
    targets: &[Option<wgpu::ColorTargetState>],
    constants: &[(&str, f64)],
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some(fragment),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The ball fragment shaders, whose written depth is never nearer than the
/// square they are drawn on (see `ball_depth` in scene.wgsl).
const BALL_FRAGMENT_ENTRIES: [&str; 2] = ["fs_ball(", "fs_ball_shadow("];

/// Their promise: the depth they write is never nearer than the fragment's.
const EARLY_DEPTH_TEST: &str = "@early_depth_test(greater_equal)";

/// scene.wgsl, with the ball fragment shaders promising the GPU that they
/// only ever push a fragment's depth back, when `early_ball_depth`: the GPU
/// may then drop a hidden fragment before tracing its sphere. The promise
/// is a native feature that not every adapter has, so it is added only
/// where asked for.
fn scene_shader(source: &str, early_ball_depth: bool) -> String {
    if !early_ball_depth {
        return source.to_string();
    }
    BALL_FRAGMENT_ENTRIES
        .iter()
        .fold(source.to_string(), |s, entry| {
            s.replace(
                &format!("@fragment\nfn {entry}"),
                &format!("@fragment {EARLY_DEPTH_TEST}\nfn {entry}"),
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn early_ball_depth_marks_both_ball_fragment_shaders_and_nothing_else() {
        let marked = format!("@fragment {EARLY_DEPTH_TEST}\nfn ");
        assert!(!scene_shader(shaders::SCENE.source, false).contains(&marked));
        let early = scene_shader(shaders::SCENE.source, true);
        for entry in BALL_FRAGMENT_ENTRIES {
            assert!(
                early.contains(&format!("{EARLY_DEPTH_TEST}\nfn {entry}")),
                "{entry} is not marked"
            );
        }
        assert_eq!(early.matches(&marked).count(), 2);
    }
}
