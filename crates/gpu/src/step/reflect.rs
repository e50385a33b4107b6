//! Which of the balls' buffers each compute entry point uses, read from its
//! WGSL by naga (the validator wgpu itself runs): each pipeline binds only
//! those, so that no pass asks more of an adapter than it reads. WebGPU
//! promises only 8 storage buffers a shader stage.

/// One buffer an entry point uses: its binding in `common.wgsl`, and how.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Use {
    pub binding: u32,
    pub ty: wgpu::BufferBindingType,
}

impl Use {
    pub fn is_storage(&self) -> bool {
        matches!(self.ty, wgpu::BufferBindingType::Storage { .. })
    }
}

/// The buffers `entry` of the WGSL `source` uses, by binding; a source
/// naga cannot read, or an entry it lacks, is the engine's own fault and
/// named with naga's message.
pub fn uses(source: &str, entry: &str) -> Vec<Use> {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("the ball passes' WGSL: {}", e.emit_to_string(source)));
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("the ball passes' WGSL: {}", e.emit_to_string(source)));
    let index = module
        .entry_points
        .iter()
        .position(|e| e.name == entry)
        .unwrap_or_else(|| panic!("no entry point {entry} in the ball passes' WGSL"));
    let function = info.get_entry_point(index);
    let mut uses: Vec<Use> = module
        .global_variables
        .iter()
        .filter(|(handle, _)| !function[*handle].is_empty())
        .filter_map(|(_, global)| {
            let binding = global.binding.as_ref()?;
            let ty = match global.space {
                naga::AddressSpace::Uniform => wgpu::BufferBindingType::Uniform,
                naga::AddressSpace::Storage { access } => wgpu::BufferBindingType::Storage {
                    read_only: !access.contains(naga::StorageAccess::STORE),
                },
                _ => return None,
            };
            Some(Use {
                binding: binding.binding,
                ty,
            })
        })
        .collect();
    uses.sort_by_key(|u| u.binding);
    uses
}
