//! The rolypoly renderer, on wgpu.
//!
//! One frame: the point light's shadow (six depth faces), the room, balls and
//! tumblers lit with Blinn-Phong in linear HDR with MSAA, the glowing bulb,
//! then tone mapping to the output. The same [`Renderer`] draws into a
//! window's surface or, through [`OffscreenTarget`], into an image.
//!
//! It draws a [`SceneView`], plain data read from the physics world.

#![warn(missing_docs)]

mod camera;
mod debug_view;
mod finish;
mod frame_view;
mod gpu;
mod instances;
mod irradiance;
mod lighting;
mod mesh;
mod offscreen;
mod paint;
mod quality;
mod renderer;
mod room;
mod scale;
pub mod shaders;
mod shadow;
mod snapshot;
mod temporal;
mod tumbler_mesh;
mod view;

pub use camera::Camera;
pub use debug_view::{
    DebugLayer, DebugMark, DebugViews, LegendEntry, MarkShape, REST_SPEED, mark_scale, mark_size,
    speed_color,
};
pub use finish::{BALL_FINISH, FLOOR_FINISH, Finish, TUMBLER_FINISH, WALL_FINISH};
pub use frame_view::{FrameFacts, FrameView, MOTION_FULL_PIXELS, SHADOW_CROSS, UnknownView};
pub use gpu::{Gpu, HDR_FORMAT, RenderError};
pub use lighting::{attenuated, power_of};
pub use mesh::{MeshData, Vertex};
pub use offscreen::{MAX_SIDE, OFFSCREEN_FORMAT, OffscreenTarget};
pub use paint::tumbler_paint;
pub use quality::{AUTO_TARGET_FPS, AutoQuality, Quality, QualityChoice};
pub use renderer::{
    FrameStats, PassTimes, RenderSettings, Renderer, StampSlots, shadow_cross_place,
};
pub use room::{Surface, surfaces as room_surfaces};
pub use scale::{DynamicScale, MAX_SCALE, MIN_SCALE};
pub use snapshot::Snapshot;
pub use temporal::{
    HISTORY_FRAMES, JITTER_PHASES, SAMPLE_SPREAD, halton, jitter, jittered, sample_offset,
};
pub use tumbler_mesh::{
    DEFAULT_TUMBLER_OBJ, OBJ_HEADER, coarse_tumbler_mesh, from_obj, mesh_for, to_obj, tumbler_mesh,
};
pub use view::{
    BallView, Bloom, CEILING_FALLOFF, GpuBallBuffer, Light, LightConfig, ParticleView, PointLight,
    SceneView, TumblerView, particle_color,
};
