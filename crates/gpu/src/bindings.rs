//! The buffers the ball passes bind, in the order of their bindings in
//! `step/common.wgsl`; each pipeline binds those its entry point uses
//! (see `step/reflect.rs`).
//!
//! WebGPU promises a shader stage only 8 storage buffers, and the solver
//! reads some twenty arrays. So arrays of one element type live in one
//! buffer, section after section: the WGSL reads section `VEL` of
//! `motion` as `motion[VEL + i]`, each section's first element a constant
//! written above the WGSL from [`Packing`]. A ball's sections are each as
//! long as the buffers have room for balls, so that each keeps the order of
//! its own array (neighbouring threads read neighbouring elements).

use crate::layout::{Body, Catch, EVENT_CAPACITY, IMPACT_CAPACITY, IMPACT_ROUNDS, SLOTS};

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

/// How long a section is.
#[derive(Clone, Copy)]
enum Extent {
    /// So many elements a ball.
    Balls(u64),
    /// One element a grid cell and one past the last.
    Cells,
    /// So many elements.
    Fixed(u64),
}

/// Contact slots a ball keeps in each of the impulses' two buffers (see
/// `impulse_at` in `step/common.wgsl`).
const HALF_SLOTS: u64 = SLOTS / 2;
const _: () = assert!(SLOTS.is_multiple_of(2));

/// The packed buffers' sections, in order, by their names in the WGSL.
/// Velocities and spins have a second copy each (`DELTA`, `DELTA_SPIN`)
/// that the Jacobi sweeps alternate with; `FIRST_CONTACT` and `SHIFT`
/// hold two copies in one section.
const MOTION: &[(&str, Extent)] = &[
    ("POS", Extent::Balls(1)),
    ("VEL", Extent::Balls(1)),
    ("SPIN", Extent::Balls(1)),
    ("VEL_START", Extent::Balls(1)),
    ("DELTA", Extent::Balls(1)),
    ("DELTA_SPIN", Extent::Balls(1)),
];
const PUSHES: &[(&str, Extent)] = &[
    ("WALL_IMPULSE", Extent::Balls(3)),
    ("BODY_IMPULSE", Extent::Balls(1)),
    ("SHIFT", Extent::Balls(2)),
    ("IMPACTS", Extent::Fixed(3 * IMPACT_CAPACITY)),
];
const SLOT_IMPULSE: &[(&str, Extent)] = &[("SLOT_IMPULSE", Extent::Balls(HALF_SLOTS))];
const SLOT_IMPULSE_MORE: &[(&str, Extent)] = &[("SLOT_IMPULSE_MORE", Extent::Balls(HALF_SLOTS))];
const BALL_WORDS: &[(&str, Extent)] = &[
    ("STATE", Extent::Balls(1)),
    ("CELL_OF", Extent::Balls(1)),
    ("BODY_OF", Extent::Balls(1)),
    ("BALL_RANK", Extent::Balls(1)),
    ("CELL_BALLS", Extent::Balls(1)),
    ("FIRST_CONTACT", Extent::Balls(2)),
    ("BODY_IMPACT", Extent::Balls(1)),
    ("NEAR_SPEED", Extent::Balls(1)),
];
const SLOT_WORDS: &[(&str, Extent)] = &[
    ("SLOT_OTHER", Extent::Balls(SLOTS)),
    ("SLOT_MIRROR", Extent::Balls(SLOTS)),
];
// The scan reads the cells' counts from the start of `cell_words`, and
// they are copied there from the start of `counters`.
const CELL_WORDS: &[(&str, Extent)] =
    &[("CELL_START", Extent::Cells), ("CELL_SPEED", Extent::Cells)];
const COUNTERS: &[(&str, Extent)] = &[
    ("CELL_FILL", Extent::Cells),
    ("EVENT_COUNT", Extent::Fixed(1)),
    ("IMPACT_COUNT", Extent::Fixed(IMPACT_ROUNDS as u64)),
    ("IMPACT_EVENTS", Extent::Fixed(1)),
];

/// One packed buffer: its label, its element's size in bytes, and its
/// sections.
struct Packed {
    label: &'static str,
    element: u64,
    sections: &'static [(&'static str, Extent)],
}

/// The packed buffers, in binding order from binding 1.
const PACKED: [Packed; 8] = [
    Packed {
        label: "motion",
        element: 16,
        sections: MOTION,
    },
    Packed {
        label: "pushes",
        element: 16,
        sections: PUSHES,
    },
    Packed {
        label: "contact impulses",
        element: 16,
        sections: SLOT_IMPULSE,
    },
    Packed {
        label: "contact impulses, second half",
        element: 16,
        sections: SLOT_IMPULSE_MORE,
    },
    Packed {
        label: "ball words",
        element: 4,
        sections: BALL_WORDS,
    },
    Packed {
        label: "contact words",
        element: 4,
        sections: SLOT_WORDS,
    },
    Packed {
        label: "cell words",
        element: 4,
        sections: CELL_WORDS,
    },
    Packed {
        label: "counters",
        element: 4,
        sections: COUNTERS,
    },
];

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

impl Sizes {
    fn elements(&self, extent: Extent) -> u64 {
        match extent {
            Extent::Balls(k) => k * self.balls,
            Extent::Cells => self.cells + 1,
            Extent::Fixed(k) => k,
        }
    }

    /// Each section's first element in its buffer, and the buffer's
    /// length in elements.
    fn offsets(&self, packed: &Packed) -> (Vec<(&'static str, u64)>, u64) {
        let mut at = 0;
        let firsts = packed
            .sections
            .iter()
            .map(|&(name, extent)| {
                let first = at;
                at += self.elements(extent);
                (name, first)
            })
            .collect();
        (firsts, at)
    }

    /// The largest buffer's size in bytes: a ball's sections of vectors.
    pub fn largest_buffer(&self) -> u64 {
        PACKED
            .iter()
            .map(|p| p.element * self.offsets(p).1)
            .chain([32 * self.balls])
            .max()
            .unwrap_or(0)
    }
}

/// Each buffer, named by what it holds (see `common.wgsl`).
pub struct Buffers {
    pub params: wgpu::Buffer,
    /// The packed buffers, in binding order from binding 1.
    packed: Vec<wgpu::Buffer>,
    pub bodies: wgpu::Buffer,
    pub palette: wgpu::Buffer,
    pub instances: wgpu::Buffer,
    pub tumbler_push: wgpu::Buffer,
    pub events: wgpu::Buffer,
    /// Each section's buffer (its place in `packed`), first element and
    /// element size, by name.
    sections: Vec<(&'static str, usize, u64, u64)>,
    /// Balls a section has room for.
    capacity: u64,
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
        let mut sections = Vec::new();
        let packed = PACKED
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let (firsts, len) = sizes.offsets(p);
                sections.extend(
                    firsts
                        .into_iter()
                        .map(|(name, first)| (name, k, first, p.element)),
                );
                make(p.label, p.element * len, U::STORAGE)
            })
            .collect();
        Buffers {
            params: make(
                "params",
                std::mem::size_of::<crate::layout::Params>() as u64,
                U::UNIFORM | U::COPY_DST,
            ),
            packed,
            bodies: make(
                "bodies",
                std::mem::size_of::<Body>() as u64 * sizes.bodies.max(1),
                U::STORAGE,
            ),
            palette: make("palette", 16 * sizes.colors, U::STORAGE),
            instances: make("ball instances", 32 * sizes.balls, U::STORAGE | U::VERTEX),
            tumbler_push: make("tumbler pushes", 32 * sizes.tumblers.max(1), U::STORAGE),
            events: make(
                "catches",
                std::mem::size_of::<Catch>() as u64 * EVENT_CAPACITY,
                U::STORAGE,
            ),
            sections,
            capacity: sizes.balls,
        }
    }

    /// Section `name`'s buffer and its first byte.
    pub fn section(&self, name: &str) -> (&wgpu::Buffer, u64) {
        let &(_, k, first, element) = self
            .sections
            .iter()
            .find(|s| s.0 == name)
            .unwrap_or_else(|| panic!("no section {name}"));
        (&self.packed[k], first * element)
    }

    /// The sections' first elements as WGSL constants, and the balls they
    /// have room for (`CAPACITY`), to go above the passes' WGSL.
    pub fn wgsl_sections(&self) -> String {
        let mut constants = format!("const CAPACITY: u32 = {}u;\n", self.capacity);
        for (name, _, first, _) in &self.sections {
            constants += &format!("const {name}: u32 = {first}u;\n");
        }
        constants
    }

    /// In binding order.
    fn in_order(&self) -> Vec<&wgpu::Buffer> {
        let mut order = vec![&self.params];
        order.extend(&self.packed);
        order.extend([
            &self.bodies,
            &self.palette,
            &self.instances,
            &self.tumbler_push,
            &self.events,
        ]);
        order
    }

    /// Every buffer but the step's constants (which the CPU writes before
    /// each step): what a snapshot copies.
    pub fn stored(&self) -> impl Iterator<Item = &wgpu::Buffer> {
        self.in_order().into_iter().skip(1)
    }

    /// The buffer at `binding` in `common.wgsl`.
    pub fn at(&self, binding: u32) -> &wgpu::Buffer {
        self.in_order()[binding as usize]
    }
}
