//! Reading a mapped buffer back, waiting for the GPU within a bound.

use crate::GpuError;
use crate::wait::{WaitBound, WaitError};

/// The first `size` bytes of `buffer` (MAP_READ), once the GPU is done
/// with what was submitted before; `what` names it if the wait runs out.
pub fn read_buffer(
    device: &wgpu::Device,
    bound: &WaitBound,
    buffer: &wgpu::Buffer,
    size: usize,
    what: impl FnOnce() -> String,
) -> Result<Vec<u8>, GpuError> {
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    bound.wait(device, None, what)?;
    // The wait ran the map's callback.
    receiver
        .try_recv()
        .map_err(|_| WaitError::Failed {
            what: "a buffer's mapping".into(),
            message: "the GPU finished but the buffer was not mapped".into(),
        })?
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
