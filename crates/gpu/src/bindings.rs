//! The buffers every ball pass binds, in the order of their bindings in
//! `step/common.wgsl`, and the one bind group that holds them.

use crate::layout::{Body, Catch, EVENT_CAPACITY, IMPACT_ROUNDS, SLOTS};

/// Bindings in the group: the uniform and the storage buffers.
pub const BINDINGS: u32 = 32;

/// A storage buffer a compute pass reads and writes.
pub const READ_WRITE: wgpu::BufferBindingType =
    wgpu::BufferBindingType::Storage { read_only: false };

/// A compute pass's buffer at `binding`, bound whole.
pub fn compute_buffer(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Each buffer, named by what it holds (see `common.wgsl`).
pub struct Buffers {
    pub params: wgpu::Buffer,
    pub pos: wgpu::Buffer,
    pub vel: wgpu::Buffer,
    pub spin: wgpu::Buffer,
    pub vel_start: wgpu::Buffer,
    pub delta: wgpu::Buffer,
    pub delta_spin: wgpu::Buffer,
    pub state: wgpu::Buffer,
    pub cell_of: wgpu::Buffer,
    pub cell_start: wgpu::Buffer,
    pub cell_fill: wgpu::Buffer,
    pub cell_balls: wgpu::Buffer,
    pub slot_other: wgpu::Buffer,
    pub slot_impulse: wgpu::Buffer,
    pub wall_impulse: wgpu::Buffer,
    pub body_of: wgpu::Buffer,
    pub body_impulse: wgpu::Buffer,
    pub bodies: wgpu::Buffer,
    pub palette: wgpu::Buffer,
    pub instances: wgpu::Buffer,
    pub tumbler_push: wgpu::Buffer,
    pub events: wgpu::Buffer,
    pub event_count: wgpu::Buffer,
    pub first_contact: wgpu::Buffer,
    pub body_impact: wgpu::Buffer,
    pub cell_speed: wgpu::Buffer,
    pub near_speed: wgpu::Buffer,
    pub slot_mirror: wgpu::Buffer,
    pub impact_count: wgpu::Buffer,
    pub ball_rank: wgpu::Buffer,
    pub slot_impulse_more: wgpu::Buffer,
    pub shift: wgpu::Buffer,
}

/// How many of each the buffers hold.
pub struct Sizes {
    /// Balls, thrown ones to come included.
    pub balls: u64,
    /// Grid cells.
    pub cells: u64,
    /// Tumbler spheres and the fireball.
    pub bodies: u64,
    /// Tumblers.
    pub tumblers: u64,
    /// Palette colours.
    pub colors: u64,
}

/// Contact slots a ball keeps in each of the impulses' two buffers (see
/// `impulse_at` in `step/common.wgsl`).
const HALF_SLOTS: u64 = SLOTS / 2;
const _: () = assert!(SLOTS.is_multiple_of(2));

impl Sizes {
    /// The largest buffer's size in bytes: each half of the balls'
    /// contacts' impulses.
    pub fn largest_buffer(&self) -> u64 {
        16 * HALF_SLOTS * self.balls
    }
}

impl Buffers {
    pub fn new(device: &wgpu::Device, sizes: &Sizes) -> Buffers {
        use wgpu::BufferUsages as U;
        // Every storage buffer can be copied whole, both ways, so that a
        // snapshot keeps every bit the next step reads.
        let make = |label: &str, size: u64, usage: U| {
            let copies = if usage.contains(U::STORAGE) {
                U::COPY_SRC | U::COPY_DST
            } else {
                U::empty()
            };
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: usage | copies,
                mapped_at_creation: false,
            })
        };
        let kept = U::STORAGE | U::COPY_DST | U::COPY_SRC;
        let n = sizes.balls;
        Buffers {
            params: make(
                "params",
                std::mem::size_of::<crate::layout::Params>() as u64,
                U::UNIFORM | U::COPY_DST,
            ),
            pos: make("positions", 16 * n, kept),
            vel: make("velocities", 16 * n, kept),
            spin: make("spins", 16 * n, kept),
            vel_start: make("velocities at the step's start", 16 * n, U::STORAGE),
            delta: make("second copy of the velocities", 16 * n, U::STORAGE),
            delta_spin: make("second copy of the spins", 16 * n, U::STORAGE),
            state: make("states", 4 * n, kept),
            cell_of: make("cell of each ball", 4 * n, U::STORAGE),
            cell_start: make(
                "cell starts",
                4 * (sizes.cells + 1),
                U::STORAGE | U::COPY_DST,
            ),
            cell_fill: make("cell fill", 4 * (sizes.cells + 1), U::STORAGE | U::COPY_SRC),
            cell_balls: make("balls by cell", 4 * n, U::STORAGE),
            slot_other: make("contact partners", 4 * SLOTS * n, U::STORAGE),
            slot_impulse: make("contact impulses", 16 * HALF_SLOTS * n, U::STORAGE),
            wall_impulse: make("wall impulses", 16 * 3 * n, U::STORAGE),
            body_of: make("body of each ball", 4 * n, U::STORAGE),
            body_impulse: make("body impulses", 16 * n, U::STORAGE),
            bodies: make(
                "bodies",
                std::mem::size_of::<Body>() as u64 * sizes.bodies.max(1),
                U::STORAGE | U::COPY_DST,
            ),
            palette: make("palette", 16 * sizes.colors, U::STORAGE | U::COPY_DST),
            instances: make(
                "ball instances",
                32 * n,
                U::STORAGE | U::VERTEX | U::COPY_SRC,
            ),
            tumbler_push: make(
                "tumbler pushes",
                32 * sizes.tumblers.max(1),
                U::STORAGE | U::COPY_SRC,
            ),
            events: make(
                "catches",
                std::mem::size_of::<Catch>() as u64 * EVENT_CAPACITY,
                U::STORAGE | U::COPY_SRC,
            ),
            event_count: make("catch count", 16, U::STORAGE | U::COPY_SRC | U::COPY_DST),
            first_contact: make("what each ball meets first, two copies", 8 * n, U::STORAGE),
            body_impact: make("impacts' pushes on bodies", 4 * n, U::STORAGE),
            cell_speed: make("fastest in each cell", 4 * (sizes.cells + 1), U::STORAGE),
            near_speed: make("fastest near each ball", 4 * n, U::STORAGE),
            slot_mirror: make("contact mirrors", 4 * SLOTS * n, U::STORAGE),
            shift: make("shifts out of overlaps, two copies", 32 * n, U::STORAGE),
            impact_count: make(
                "balls that meet a contact in each round",
                4 * u64::from(IMPACT_ROUNDS),
                U::STORAGE | U::COPY_DST,
            ),
            ball_rank: make("place of each ball by cell", 4 * n, U::STORAGE),
            slot_impulse_more: make(
                "contact impulses, second half",
                16 * HALF_SLOTS * n,
                U::STORAGE,
            ),
        }
    }

    /// In binding order.
    fn in_order(&self) -> [&wgpu::Buffer; BINDINGS as usize] {
        [
            &self.params,
            &self.pos,
            &self.vel,
            &self.spin,
            &self.vel_start,
            &self.delta,
            &self.delta_spin,
            &self.state,
            &self.cell_of,
            &self.cell_start,
            &self.cell_fill,
            &self.cell_balls,
            &self.slot_other,
            &self.slot_impulse,
            &self.wall_impulse,
            &self.body_of,
            &self.body_impulse,
            &self.bodies,
            &self.palette,
            &self.instances,
            &self.tumbler_push,
            &self.events,
            &self.event_count,
            &self.first_contact,
            &self.body_impact,
            &self.cell_speed,
            &self.near_speed,
            &self.slot_mirror,
            &self.shift,
            &self.impact_count,
            &self.ball_rank,
            &self.slot_impulse_more,
        ]
    }

    /// Every buffer but the step's constants (which the CPU writes before
    /// each step): what a snapshot copies.
    pub fn stored(&self) -> impl Iterator<Item = &wgpu::Buffer> {
        self.in_order().into_iter().skip(1)
    }

    /// The layout: binding 0 the uniform, 17 and 18 read-only, the rest
    /// read and written.
    pub fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..BINDINGS)
            .map(|binding| {
                compute_buffer(
                    binding,
                    match binding {
                        0 => wgpu::BufferBindingType::Uniform,
                        17 | 18 => wgpu::BufferBindingType::Storage { read_only: true },
                        _ => READ_WRITE,
                    },
                )
            })
            .collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("balls"),
            entries: &entries,
        })
    }

    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = self
            .in_order()
            .iter()
            .enumerate()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("balls"),
            layout,
            entries: &entries,
        })
    }
}
