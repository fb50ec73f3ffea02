//! Reading a frame back from the GPU: the region of the image's texture is copied into a
//! persistent staging buffer whose rows are padded to [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`],
//! the buffer is mapped once the frame's submission is done, and its rows are unpadded into a
//! reusable [`CameraImage`]. Another thread's poll may run the map callback, so the callback
//! reports on a channel.

use std::sync::mpsc;

use crate::render::camera::CameraIntrinsics;
use crate::render::image::CameraImage;
use crate::render::region::ImageRegion;
use crate::render::targets::extent_px;

/// The step of a frame's readback that failed, with wgpu's error.
#[derive(Debug, thiserror::Error)]
pub enum ReadbackError {
    /// Waiting for the frame's submission failed.
    #[error("waiting for the GPU: {0}")]
    Wait(#[from] wgpu::PollError),
    /// The staging buffer's map callback was dropped without reporting.
    #[error("map callback was dropped")]
    CallbackDropped(#[from] mpsc::RecvError),
    /// The staging buffer could not be mapped.
    #[error("mapping the staging buffer: {0}")]
    Map(#[from] wgpu::BufferAsyncError),
    /// The mapped staging buffer could not be viewed.
    #[error("{0}")]
    View(#[from] wgpu::MapRangeError),
}

/// Reports the staging buffer's mapping.
pub(super) type MapReport = mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>;

/// The staging buffer frames are read back through; it holds a whole image.
#[derive(Debug)]
pub(super) struct Staging {
    buffer: wgpu::Buffer,
}

impl Staging {
    /// A staging buffer for the whole image of `cam`.
    pub(super) fn new(device: &wgpu::Device, cam: &CameraIntrinsics) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: staging_bytes(&ImageRegion::whole(cam)),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { buffer }
    }

    /// Copies `region` of `texture`, an image-sized texture, into the staging buffer (rows
    /// padded).
    pub(super) fn copy_region(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
        region: &ImageRegion,
    ) {
        self.copy_from(encoder, texture, [region.u0_px, region.v0_px], region);
    }

    /// Copies the pixels of `texture` from column and row `origin_px`, as many as `region`
    /// holds, into the staging buffer as `region`'s (rows padded).
    pub(super) fn copy_from(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
        [x, y]: [u32; 2],
        region: &ImageRegion,
    ) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x, y, z: 0 },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_bytes_per_row(region.width_px)),
                    rows_per_image: Some(region.height_px),
                },
            },
            extent_px(region.width_px, region.height_px),
        );
    }

    /// Starts mapping the part of the buffer that holds `region` once the submission that
    /// copies it is done; the mapping reports on the channel returned.
    pub(super) fn map(&self, region: &ImageRegion) -> MapReport {
        let (sender, receiver) = mpsc::channel();
        self.buffer
            .slice(..staging_bytes(region))
            .map_async(wgpu::MapMode::Read, move |result| {
                // The receiver lives until the frame is read back; a send error cannot matter.
                let _ = sender.send(result);
            });
        receiver
    }

    /// Waits for `submission` and for `mapped`, and unpads the buffer's rows of `region` into
    /// `frame` (resized to the region).
    pub(super) fn read(
        &self,
        device: &wgpu::Device,
        submission: wgpu::SubmissionIndex,
        mapped: &MapReport,
        region: &ImageRegion,
        frame: &mut CameraImage,
    ) -> Result<(), ReadbackError> {
        device.poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: None,
        })?;
        mapped.recv()??;
        frame.width_px = region.width_px;
        frame.height_px = region.height_px;
        frame.rgba.resize(4 * region.pixel_count(), 0);
        let row_bytes = 4 * region.width_px as usize;
        {
            let mapped = self
                .buffer
                .slice(..staging_bytes(region))
                .get_mapped_range()?;
            for (dst, src) in frame
                .rgba
                .chunks_exact_mut(row_bytes)
                .zip(mapped.chunks_exact(padded_bytes_per_row(region.width_px) as usize))
            {
                dst.copy_from_slice(&src[..row_bytes]);
            }
        }
        self.buffer.unmap();
        Ok(())
    }
}

/// Bytes per staging-buffer row: 4 bytes a pixel, rounded up to 256 (a wgpu copy rule).
fn padded_bytes_per_row(width_px: u32) -> u32 {
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    (4 * width_px).div_ceil(align) * align
}

/// Bytes of the staging buffer that hold `region`, its rows padded.
fn staging_bytes(region: &ImageRegion) -> u64 {
    u64::from(padded_bytes_per_row(region.width_px)) * u64::from(region.height_px)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_bytes_per_row(64), 256);
        assert_eq!(padded_bytes_per_row(65), 512);
        assert_eq!(padded_bytes_per_row(160), 768);
        assert_eq!(padded_bytes_per_row(1920), 7680);
    }
}
