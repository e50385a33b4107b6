//! Finding a graphics adapter and opening a device on it.

use thiserror::Error;

/// The scene is lit in linear HDR and tone-mapped at the end, so that
/// glowing things can be brighter than white.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Why rendering could not start or finish.
#[derive(Debug, Error)]
pub enum RenderError {
    #[error(
        "no usable graphics adapter was found (backends tried: {backends}). \
         Install a Vulkan driver and the Vulkan loader (on Debian or Ubuntu: `apt-get install \
         libvulkan1 mesa-vulkan-drivers`; Mesa's driver includes the lavapipe software \
         renderer, and a GPU's own driver needs the loader too), or try the OpenGL backend \
         with WGPU_BACKEND=gl"
    )]
    /// No adapter could be found.
    NoAdapter {
        /// The backends tried, in words.
        backends: String,
    },
    #[error("the graphics adapter {adapter} refused to open a device: {source}")]
    /// The adapter would not open a device.
    NoDevice {
        /// The adapter, in words.
        adapter: String,
        /// What it said.
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// A wait on the GPU ran out of time or failed.
    #[error(transparent)]
    Wait(#[from] rolypoly_gpu::WaitError),
    #[error("reading the rendered frame back failed: {0}")]
    /// The frame could not be read back.
    Readback(String),
    #[error("tumbler mesh `{origin}`: {message}")]
    /// A tumbler mesh file is not usable.
    Mesh {
        /// The file.
        origin: String,
        /// What is wrong with it.
        message: String,
    },
    #[error("frame size {width}x{height} is not allowed: {reason}")]
    /// A frame size that cannot be drawn.
    Size {
        /// Asked width in pixels.
        width: u32,
        /// Asked height in pixels.
        height: u32,
        /// Why not.
        reason: String,
    },
}

/// An open device and its queue.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter it was opened on.
    pub adapter: wgpu::Adapter,
    /// How long any wait on it may last (see [`rolypoly_gpu::WaitBound`]).
    pub wait: rolypoly_gpu::WaitBound,
}

impl Gpu {
    /// Opens the best adapter available without a window. `WGPU_BACKEND`
    /// (vulkan, gl, metal, dx12) chooses the backends; without it the
    /// primary ones (Vulkan, Metal, DX12) are tried first, then OpenGL.
    pub fn headless() -> Result<Gpu, RenderError> {
        match wgpu::Backends::from_env() {
            Some(chosen) => Gpu::headless_on(&[chosen]),
            None => Gpu::headless_on(&[wgpu::Backends::PRIMARY, wgpu::Backends::GL]),
        }
    }

    /// Opens the best adapter of the first of `attempts` that has one.
    pub fn headless_on(attempts: &[wgpu::Backends]) -> Result<Gpu, RenderError> {
        if let Some(adapter) = rolypoly_gpu::best_adapter(attempts) {
            return Gpu::open(adapter);
        }
        let backends = attempts
            .iter()
            .map(|&b| backend_names(b & wgpu::Instance::enabled_backend_features()))
            .filter(|names| !names.is_empty())
            .collect::<Vec<_>>()
            .join(", then ");
        let backends = if backends.is_empty() {
            "none: this build has none of the backends asked for".to_string()
        } else {
            backends
        };
        Err(RenderError::NoAdapter { backends })
    }

    /// Opens a device on `adapter` with the limits this renderer needs.
    pub fn open(adapter: wgpu::Adapter) -> Result<Gpu, RenderError> {
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rolypoly"),
            // Optional: lets ball fragments be depth-tested before they are
            // traced; and lets the profiler time the frame's passes.
            required_features: adapter.features()
                & (wgpu::Features::SHADER_EARLY_DEPTH_TEST | wgpu::Features::TIMESTAMP_QUERY),
            // What the GPU ball engine needs too, so that it may step on this device.
            required_limits: rolypoly_gpu::limits(&adapter),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|source| RenderError::NoDevice {
            adapter: format!("{} ({:?})", info.name, info.backend),
            source,
        })?;
        Ok(Gpu {
            device,
            queue,
            wait: rolypoly_gpu::WaitBound::new(format!("{} ({:?})", info.name, info.backend)),
            adapter,
        })
    }

    /// "name (backend)", for logs and benchmark reports.
    pub fn describe(&self) -> String {
        self.wait.adapter.clone()
    }

    /// Whether shaders may promise the GPU how they change a fragment's
    /// depth, so that it tests the depth before running them (Vulkan,
    /// OpenGL 4.2 or ES 3.1 and later).
    pub fn has_early_depth_test(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST)
    }

    /// Whether a multisampled target can also be read sample by sample in
    /// a shader (the msaa-edges view). Not on OpenGL, where wgpu draws such
    /// a readable target and its resolve stays empty.
    pub fn reads_multisampled_targets(&self) -> bool {
        self.adapter.get_info().backend != wgpu::Backend::Gl
    }

    /// The largest multisample count up to `wanted` that the adapter supports
    /// for the HDR target.
    pub fn msaa_samples(&self, wanted: u32) -> u32 {
        let flags = self.adapter.get_texture_format_features(HDR_FORMAT).flags;
        [wanted, 4, 2, 1]
            .into_iter()
            .filter(|&n| n <= wanted)
            .find(|&n| n == 1 || flags.sample_count_supported(n))
            .unwrap_or(1)
    }
}

/// The backends of `set` by their names, as a user knows them: "Vulkan,
/// Metal".
fn backend_names(set: wgpu::Backends) -> String {
    const NAMES: [(wgpu::Backends, &str); 5] = [
        (wgpu::Backends::VULKAN, "Vulkan"),
        (wgpu::Backends::METAL, "Metal"),
        (wgpu::Backends::DX12, "DX12"),
        (wgpu::Backends::GL, "OpenGL"),
        (wgpu::Backends::BROWSER_WEBGPU, "WebGPU"),
    ];
    NAMES
        .iter()
        .filter(|(backend, _)| set.contains(*backend))
        .map(|&(_, name)| name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backends_are_named_in_words() {
        assert_eq!(backend_names(wgpu::Backends::VULKAN), "Vulkan");
        assert_eq!(
            backend_names(wgpu::Backends::PRIMARY),
            "Vulkan, Metal, DX12, WebGPU"
        );
        assert_eq!(backend_names(wgpu::Backends::empty()), "");
    }
}
