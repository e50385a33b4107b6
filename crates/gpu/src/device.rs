//! Opening a device for the ball engine without a window, and the limits
//! it needs of any device it runs on (the renderer's included).

use crate::GpuError;

/// The most storage buffers any of the ball passes binds: WebGPU's
/// default, which every WebGPU adapter has (see `bindings.rs`; the
/// limits test holds every pipeline to it).
pub const STORAGE_BUFFERS: u32 = 8;

/// An open device, its queue and the adapter's name.
pub struct Compute {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// "name (backend)".
    pub adapter: String,
}

/// The limits to ask of `adapter` for the ball engine: what the engine
/// needs (no more than the adapter has: the engine checks the rest and
/// says what is missing), the adapter's own for the sizes a scene decides,
/// the portable defaults (at the adapter's texture sizes) for the rest, so
/// that a renderer opening the device may draw too. A device asked for no
/// more than the engine needs refuses any pass that would bind more.
pub fn limits(adapter: &wgpu::Adapter) -> wgpu::Limits {
    let has = adapter.limits();
    let mut limits = wgpu::Limits::downlevel_defaults().using_resolution(has.clone());
    limits.max_storage_buffers_per_shader_stage =
        STORAGE_BUFFERS.min(has.max_storage_buffers_per_shader_stage);
    limits.max_buffers_and_acceleration_structures_per_shader_stage =
        (STORAGE_BUFFERS + 1).min(has.max_buffers_and_acceleration_structures_per_shader_stage);
    limits.max_storage_buffer_binding_size = has.max_storage_buffer_binding_size;
    limits.max_buffer_size = has.max_buffer_size;
    limits.max_compute_workgroup_storage_size = has.max_compute_workgroup_storage_size;
    limits.max_compute_invocations_per_workgroup = has.max_compute_invocations_per_workgroup;
    limits.max_compute_workgroup_size_x = has.max_compute_workgroup_size_x;
    limits.max_compute_workgroups_per_dimension = has.max_compute_workgroups_per_dimension;
    limits.max_bindings_per_bind_group = has.max_bindings_per_bind_group;
    limits
}

/// "name (backend)".
pub fn describe(adapter: &wgpu::Adapter) -> String {
    let info = adapter.get_info();
    format!("{} ({:?})", info.name, info.backend)
}

impl Compute {
    /// Opens the best adapter there is: the backends `WGPU_BACKEND` names,
    /// else Vulkan, Metal or DX12, else OpenGL.
    pub fn headless() -> Result<Compute, GpuError> {
        let attempts = match wgpu::Backends::from_env() {
            Some(chosen) => vec![chosen],
            None => vec![wgpu::Backends::PRIMARY, wgpu::Backends::GL],
        };
        match best_adapter(&attempts) {
            Some(adapter) => Compute::open(&adapter),
            None => Err(GpuError::NoAdapter {
                backends: attempts
                    .iter()
                    .map(|b| format!("{b:?}"))
                    .collect::<Vec<_>>()
                    .join(", then "),
            }),
        }
    }

    /// Opens a device on `adapter` with the limits the engine needs.
    pub fn open(adapter: &wgpu::Adapter) -> Result<Compute, GpuError> {
        let name = describe(adapter);
        check_compute(adapter)?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rolypoly gpu engine"),
            required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
            required_limits: limits(adapter),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| GpuError::NoDevice {
            adapter: name.clone(),
            message: e.to_string(),
        })?;
        Ok(Compute {
            device,
            queue,
            adapter: name,
        })
    }
}

/// The best adapter of the first of `attempts` that has one, without a
/// window: the one `WGPU_POWER_PREF` asks for, else the fastest.
pub fn best_adapter(attempts: &[wgpu::Backends]) -> Option<wgpu::Adapter> {
    attempts.iter().find_map(|backends| {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        desc.backends = *backends;
        let instance = wgpu::Instance::new(desc);
        pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference:
                wgpu::PowerPreference::from_env().unwrap_or(wgpu::PowerPreference::HighPerformance),
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .ok()
    })
}

/// Whether `adapter` runs compute shaders at all.
pub fn check_compute(adapter: &wgpu::Adapter) -> Result<(), GpuError> {
    let flags = adapter.get_downlevel_capabilities().flags;
    if flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS) {
        Ok(())
    } else {
        Err(GpuError::NoCompute {
            adapter: describe(adapter),
        })
    }
}
