//! Reading a mapped buffer back, waiting for the GPU.

use crate::GpuError;

/// The first `size` bytes of `buffer` (MAP_READ), once the GPU is done
/// with what was submitted before.
pub fn read_buffer(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    size: usize,
) -> Result<Vec<u8>, GpuError> {
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let bytes = {
        let data = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        data[..size.min(data.len())].to_vec()
    };
    buffer.unmap();
    Ok(bytes)
}
