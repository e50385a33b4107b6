//! What each drawn object is to the GPU: its per-instance data, the
//! buffers that carry it, and how a scene view fills them each frame.

use crate::finish::{BALL_FINISH, FLOOR_FINISH, Finish, TUMBLER_FINISH, WALL_FINISH};
use crate::gpu::Gpu;
use crate::room;
use crate::view::SceneView;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

/// Material kinds, as the shader knows them.
#[derive(Clone, Copy)]
pub enum Kind {
    Plain = 0,
    Wood = 1,
    Painted = 2,
    Glossy = 3,
}

/// Per-object data: model matrix, colour, material.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct Instance {
    model: [[f32; 4]; 4],
    color: [f32; 4],
    /// kind, specular strength, shininess, emission.
    material: [f32; 4],
}

impl Instance {
    /// What places its shadow: its model matrix, as numbers.
    pub fn shadow_place(&self) -> [[f32; 4]; 4] {
        self.model
    }

    const ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
        3 => Float32x4, 4 => Float32x4, 5 => Float32x4, 6 => Float32x4, 7 => Float32x4, 8 => Float32x4
    ];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Instance>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }

    fn new(
        model: Mat4,
        color: Vec3,
        kind: Kind,
        specular: f32,
        shininess: f32,
        emission: f32,
    ) -> Instance {
        Instance {
            model: model.to_cols_array_2d(),
            color: color.extend(1.0).to_array(),
            material: [kind as u32 as f32, specular, shininess, emission],
        }
    }

    /// Something that glows: `shape` 0 is a cube, 1 a shell.
    fn glow(model: Mat4, color: Vec3, alpha: f32, shape: f32) -> Instance {
        Instance {
            model: model.to_cols_array_2d(),
            color: color.extend(alpha).to_array(),
            material: [shape, 0.0, 0.0, 0.0],
        }
    }
}

/// A ball: its sphere and colour, all a traced ball needs (see `BallIn` in
/// scene.wgsl). A third of an [`Instance`], which for 100 000 balls is
/// 6.4 MB less to fill and upload every frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct BallInstance {
    /// Centre, then radius.
    sphere: [f32; 4],
    color: [f32; 3],
    /// Keeps instances 32 bytes apart.
    _pad: f32,
}

// What the shader's layout and the figures above assume.
const _: () = assert!(std::mem::size_of::<BallInstance>() == 32);
const _: () = assert!(std::mem::size_of::<Instance>() == 96);

impl BallInstance {
    /// Its centre and radius.
    pub fn sphere(&self) -> (Vec3, f32) {
        let [x, y, z, r] = self.sphere;
        (Vec3::new(x, y, z), r)
    }

    /// What places its shadow: its centre and radius, as numbers.
    pub fn shadow_place(&self) -> [f32; 4] {
        self.sphere
    }

    const ATTRIBUTES: [wgpu::VertexAttribute; 2] =
        wgpu::vertex_attr_array![3 => Float32x4, 4 => Float32x3];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<BallInstance>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

impl BallInstance {
    /// A ball's sphere the frame before, read from the same layout (see
    /// `BallBefore` in scene.wgsl): the last frame's instances, or the GPU
    /// engine's buffer copied at the end of the last frame.
    const BEFORE: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![5 => Float32x4];

    pub fn before_layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<BallInstance>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::BEFORE,
        }
    }
}

/// An object's model matrix the frame before (see `PreviousIn` in
/// scene.wgsl), one for each [`Instance`] of the frame, for its motion.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct PreviousModel([[f32; 4]; 4]);

impl PreviousModel {
    const ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        9 => Float32x4, 10 => Float32x4, 11 => Float32x4, 12 => Float32x4
    ];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<PreviousModel>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// Fills `list` with where each of this frame's `current` instances (laid
/// out as `ranges`) was the frame before, from that frame's `last` laid
/// out as `last_ranges`. The room, the tumblers and the lamps keep their
/// places in the list from frame to frame; one new this frame (a fireball's
/// heart) has not moved. The see-through particles write no motion (what
/// shows through them moves as itself), and keep their own.
pub fn fill_previous(
    list: &mut Vec<PreviousModel>,
    current: &[Instance],
    ranges: &Ranges,
    last: &[Instance],
    last_ranges: &Ranges,
) {
    list.clear();
    list.extend(current.iter().map(|i| PreviousModel(i.model)));
    for (now, before) in [
        (&ranges.room, &last_ranges.room),
        (&ranges.tumblers, &last_ranges.tumblers),
        (&ranges.lamps, &last_ranges.lamps),
    ] {
        let now = now.start as usize..now.end as usize;
        let before = before.start as usize..before.end as usize;
        for (slot, was) in list[now].iter_mut().zip(&last[before]) {
            slot.0 = was.model;
        }
    }
}

/// The one material of every ball: glossy and sharp-highlighted.
pub const BALL_MATERIAL: (Kind, Finish) = (Kind::Glossy, BALL_FINISH);

/// Instances of one layout, filled each frame and uploaded into a buffer
/// that grows to the largest frame seen.
pub struct InstanceBuffer<T> {
    pub items: Vec<T>,
    pub buffer: wgpu::Buffer,
    capacity: usize,
    label: &'static str,
}

impl<T: Pod> InstanceBuffer<T> {
    pub fn new(device: &wgpu::Device, label: &'static str) -> InstanceBuffer<T> {
        let capacity = 256;
        InstanceBuffer {
            items: Vec::new(),
            buffer: instance_buffer::<T>(device, label, capacity),
            capacity,
            label,
        }
    }

    pub fn upload(&mut self, gpu: &Gpu) {
        if self.items.len() > self.capacity {
            self.capacity = self.items.len().next_power_of_two();
            self.buffer = instance_buffer::<T>(&gpu.device, self.label, self.capacity);
        }
        if !self.items.is_empty() {
            gpu.queue
                .write_buffer(&self.buffer, 0, bytemuck::cast_slice(&self.items));
        }
    }

    /// All instances, for a draw call.
    pub fn range(&self) -> std::ops::Range<u32> {
        0..self.items.len() as u32
    }
}

/// Where each kind of object sits in the instance buffer this frame (the
/// balls have a buffer of their own).
#[derive(Clone, Debug, Default)]
pub struct Ranges {
    pub room: std::ops::Range<u32>,
    pub tumblers: std::ops::Range<u32>,
    /// What glows and is not lit: the bulb and the fireball's heart.
    pub lamps: std::ops::Range<u32>,
    /// Particles and the fireball's cores: glowing cubes.
    pub cubes: std::ops::Range<u32>,
    /// The fireball's shells.
    pub shells: std::ops::Range<u32>,
}

/// Fills `list` with the room, tumblers, bulb, particles and the
/// fireball, and says where each lies in it.
pub fn fill_scene(list: &mut Vec<Instance>, view: &SceneView) -> Ranges {
    list.clear();
    let mut ranges = Ranges::default();
    let start = list.len() as u32;
    for (i, surface) in room::surfaces(view.room_size).iter().enumerate() {
        // The unit quad's x and y run along the surface's two edges.
        let model = Mat4::from_cols(
            surface.u.extend(0.0),
            surface.v.extend(0.0),
            surface.normal().extend(0.0),
            surface.corner.extend(1.0),
        );
        let (kind, finish) = if i == 0 {
            (Kind::Wood, FLOOR_FINISH)
        } else {
            (Kind::Plain, WALL_FINISH)
        };
        list.push(Instance::new(
            model,
            view.room_colors[i],
            kind,
            finish.specular,
            finish.shininess,
            0.0,
        ));
    }
    ranges.room = start..list.len() as u32;

    let start = list.len() as u32;
    for t in &view.tumblers {
        list.push(Instance::new(
            t.model(),
            t.color,
            Kind::Painted,
            TUMBLER_FINISH.specular,
            TUMBLER_FINISH.shininess,
            0.0,
        ));
    }
    ranges.tumblers = start..list.len() as u32;

    let start = list.len() as u32;
    let light = view.light;
    let model = Mat4::from_scale_rotation_translation(
        Vec3::splat(light.bulb_radius),
        glam::Quat::IDENTITY,
        light.position,
    );
    let glow = light.color / light.color.max_element().max(1e-6);
    list.push(Instance::new(model, glow, Kind::Plain, 0.0, 1.0, 12.0));
    if let Some(look) = &view.fireball {
        let model = Mat4::from_scale_rotation_translation(
            Vec3::splat(look.heart_radius),
            glam::Quat::IDENTITY,
            look.centre,
        );
        list.push(Instance::new(
            model,
            rolypoly_fx::HEART_COLOR,
            Kind::Plain,
            0.0,
            1.0,
            1.0,
        ));
    }
    ranges.lamps = start..list.len() as u32;

    let start = list.len() as u32;
    for p in &view.particles {
        let model =
            Mat4::from_scale_rotation_translation(Vec3::splat(p.size), p.rotation, p.position);
        list.push(Instance::glow(model, p.color, p.alpha, 0.0));
    }
    if let Some(look) = &view.fireball {
        for core in &look.cores {
            let model = Mat4::from_scale_rotation_translation(
                Vec3::splat(core.size),
                core.rotation,
                core.position,
            );
            list.push(Instance::glow(model, rolypoly_fx::CORE_COLOR, 1.0, 0.0));
        }
    }
    ranges.cubes = start..list.len() as u32;

    let start = list.len() as u32;
    if let Some(look) = &view.fireball {
        for (shell, color) in look.shells.iter().zip(rolypoly_fx::SHELL_COLORS) {
            let model = Mat4::from_scale_rotation_translation(
                Vec3::splat(shell.radius),
                glam::Quat::IDENTITY,
                look.centre,
            );
            list.push(Instance::glow(model, color, shell.alpha, 1.0));
        }
    }
    ranges.shells = start..list.len() as u32;
    ranges
}

/// Fills `list` with the balls.
pub fn fill_balls(list: &mut Vec<BallInstance>, view: &SceneView) {
    list.clear();
    list.extend(view.balls.iter().map(|b| BallInstance {
        sphere: b.position.extend(b.radius).to_array(),
        color: b.color.to_array(),
        _pad: 0.0,
    }));
}

fn instance_buffer<T>(device: &wgpu::Device, label: &str, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (capacity * std::mem::size_of::<T>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}
