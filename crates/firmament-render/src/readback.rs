//! Copying a texture back to memory, minding wgpu's 256-byte row alignment.

use crate::context::GpuContext;
use crate::error::RenderError;

/// Bytes per row of a copy, rounded up to [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`].
pub fn padded_bytes_per_row(width: u32, bytes_per_pixel: u32) -> u32 {
    let unpadded = width * bytes_per_pixel;
    unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// The staging-buffer size, bytes, to read back a `width` × `height` image of `format`, or an
/// error naming the limit when the device cannot hold it (checked before rendering, so an absurd
/// size fails at once instead of after a long render).
pub fn check_readback(
    ctx: &GpuContext,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
) -> Result<u64, RenderError> {
    let bytes_per_pixel = format
        .block_copy_size(None)
        .ok_or_else(|| RenderError::Readback(format!("cannot copy {format:?} textures")))?;
    let size = u64::from(padded_bytes_per_row(width, bytes_per_pixel)) * u64::from(height);
    let max = ctx.device.limits().max_buffer_size;
    if size > max {
        return Err(RenderError::Readback(format!(
            "a {width}x{height} {format:?} image needs a {size}-byte buffer to read back; this GPU allows {max} bytes \
             (render a smaller image, or PNG instead of EXR)"
        )));
    }
    Ok(size)
}

/// Reads mip 0 of a 2D colour texture (with `COPY_SRC`) into tightly packed rows, top row first.
pub fn read_texture(ctx: &GpuContext, texture: &wgpu::Texture) -> Result<Vec<u8>, RenderError> {
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("firmament readback encoder"),
    });
    let copy = TextureCopy::record(ctx, &mut encoder, texture)?;
    let submission = ctx.queue.submit([encoder.finish()]);
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(RenderError::Readback(error.to_string()));
    }
    copy.map(submission).wait(ctx)
}

/// A copy of a texture into a staging buffer, recorded by [`TextureCopy::record`] into the
/// caller's encoder; after that encoder's submit, [`TextureCopy::map`] starts bringing it back.
#[derive(Debug)]
#[must_use = "a recorded copy is read back only through map and wait"]
pub struct TextureCopy {
    buffer: wgpu::Buffer,
    /// Bytes of one row as the caller gets it, and as the buffer holds it (256-byte aligned).
    row_bytes: usize,
    padded_row_bytes: usize,
}

impl TextureCopy {
    /// Records into `encoder` a copy of mip 0 of `texture` (a 2D colour texture with
    /// `COPY_SRC`) into a new staging buffer.
    pub fn record(
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
    ) -> Result<Self, RenderError> {
        let (width, height) = (texture.width(), texture.height());
        let bytes_per_pixel = texture
            .format()
            .block_copy_size(None)
            .ok_or_else(|| RenderError::Readback(format!("cannot copy {:?} textures", texture.format())))?;
        let padded = padded_bytes_per_row(width, bytes_per_pixel);
        let size = check_readback(ctx, width, height, texture.format())?;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament readback staging buffer"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        Ok(Self {
            buffer,
            row_bytes: (width * bytes_per_pixel) as usize,
            padded_row_bytes: padded as usize,
        })
    }

    /// Starts mapping the staging buffer, without waiting: call once the encoder holding the
    /// copy is submitted, with the index that submit returned.
    pub fn map(self, submission: wgpu::SubmissionIndex) -> PendingRead {
        let (sender, receiver) = std::sync::mpsc::channel();
        self.buffer.slice(..).map_async(wgpu::MapMode::Read, move |result| {
            // The receiver lives in the PendingRead; a failed send only means it was dropped.
            let _ = sender.send(result);
        });
        PendingRead {
            copy: self,
            submission,
            mapped: receiver,
        }
    }
}

/// A [`TextureCopy`] on its way to the CPU; [`PendingRead::wait`] returns its rows.
#[derive(Debug)]
#[must_use = "dropping a pending read discards the texels"]
pub struct PendingRead {
    copy: TextureCopy,
    submission: wgpu::SubmissionIndex,
    mapped: std::sync::mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>,
}

impl PendingRead {
    /// Waits until the GPU has finished the copy's submission (later submissions may still run)
    /// and returns the texels as tightly packed rows, top row first, as `T`s in the texture's
    /// byte order (`u8` for bytes; `u16` holds a half-float texture's channels on a
    /// little-endian machine).
    pub fn wait<T: bytemuck::Pod>(self, ctx: &GpuContext) -> Result<Vec<T>, RenderError> {
        // GL cuts every wait to 2^31 ns: a longer frame (8K on a software rasterizer) times out
        // and is waited for again, saying so, so that a stalled GPU shows as more than silence.
        let started = std::time::Instant::now();
        loop {
            match ctx.device.poll(wgpu::PollType::Wait {
                submission_index: Some(self.submission.clone()),
                timeout: None,
            }) {
                Err(wgpu::PollError::Timeout) => tracing::warn!(
                    "the GPU has not finished a frame after {:.0} s; still waiting",
                    started.elapsed().as_secs_f64()
                ),
                result => {
                    result.map_err(|e| RenderError::Readback(e.to_string()))?;
                    break;
                }
            }
        }
        self.mapped
            .recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let TextureCopy {
            buffer,
            row_bytes,
            padded_row_bytes,
        } = self.copy;
        let slice = buffer.slice(..);
        let mapped = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let rows = mapped.len() / padded_row_bytes;
        let size = std::mem::size_of::<T>();
        if size == 0 || row_bytes % size != 0 {
            return Err(RenderError::Readback(format!(
                "rows of {row_bytes} bytes do not hold whole {size}-byte values"
            )));
        }
        let mut out = vec![T::zeroed(); rows * row_bytes / size];
        // Row by row: only the unpadded bytes (one memcpy when the rows need no padding).
        let bytes: &mut [u8] = bytemuck::cast_slice_mut(&mut out);
        if row_bytes == padded_row_bytes {
            bytes.copy_from_slice(&mapped[..bytes.len()]);
        } else {
            for (row, padded_row) in bytes.chunks_exact_mut(row_bytes).zip(mapped.chunks(padded_row_bytes)) {
                row.copy_from_slice(&padded_row[..row_bytes]);
            }
        }
        drop(mapped);
        buffer.unmap();
        Ok(out)
    }
}

/// RGBA half-float texels (as [`read_texture`] returns an Rgba16Float texture) widened to `f32`.
pub fn decode_f16(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(2)
        .map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32())
        .collect()
}

/// Maps `slice` for reading and waits until the GPU has finished with it.
fn map_and_wait(ctx: &GpuContext, slice: &wgpu::BufferSlice<'_>) -> Result<(), RenderError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        // The receiver outlives the poll below; a failed send only means we already gave up.
        let _ = sender.send(result);
    });
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    Ok(())
}

/// Copies the first `size` bytes of `buffer` (which needs `COPY_SRC`) to the CPU: for tests and
/// tools that inspect GPU-side results; no rendering path calls it.
pub fn read_buffer(ctx: &GpuContext, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, RenderError> {
    let size = size.min(buffer.size()).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("firmament buffer readback staging buffer"),
        size: size.max(wgpu::COPY_BUFFER_ALIGNMENT),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("firmament buffer readback encoder"),
    });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let slice = staging.slice(..size);
    map_and_wait(ctx, &slice)?;
    let bytes = slice
        .get_mapped_range()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_pad_to_256_bytes() {
        assert_eq!(padded_bytes_per_row(64, 4), 256);
        assert_eq!(padded_bytes_per_row(65, 4), 512);
        assert_eq!(padded_bytes_per_row(333, 8), 2816);
        assert_eq!(padded_bytes_per_row(1, 4), 256);
    }
}
