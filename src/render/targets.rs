//! The textures frames are drawn into: the image's and the target windows' framebuffers (kept
//! by size), the sky texture, and the copy of a window into the image.

use crate::render::camera::CameraIntrinsics;
use crate::render::projection::PixelWindow;
use crate::render::window::WindowCopy;

/// The format of every colour texture (and of the frames read back).
pub(super) const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The format of every depth texture.
pub(super) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Colour (multisampled when there are several samples) and depth attachments of one size,
/// and the one-sample texture the colour resolves into (or is drawn into without
/// multisampling).
#[derive(Debug)]
pub(super) struct RenderTargets {
    msaa_view: Option<wgpu::TextureView>,
    /// The depth attachment.
    pub(super) depth_view: wgpu::TextureView,
    /// The one-sample colour the frame ends in.
    pub(super) resolve_texture: wgpu::Texture,
    /// A view of [`Self::resolve_texture`].
    pub(super) resolve_view: wgpu::TextureView,
}

impl RenderTargets {
    /// Targets of `size` with `samples` per pixel, labelled `label_prefix` + their role; the
    /// resolve texture is also used as `resolve_usage` says.
    pub(super) fn new(
        device: &wgpu::Device,
        label_prefix: &str,
        size: wgpu::Extent3d,
        samples: u32,
        resolve_usage: wgpu::TextureUsages,
    ) -> Self {
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let texture = |role: &str, sample_count, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&format!("{label_prefix}{role}")),
                size,
                mip_level_count: 1,
                sample_count,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let resolve_texture = texture("colour", 1, COLOR_FORMAT, attachment | resolve_usage);
        Self {
            msaa_view: (samples > 1).then(|| {
                texture("colour msaa", samples, COLOR_FORMAT, attachment)
                    .create_view(&Default::default())
            }),
            depth_view: texture("depth", samples, DEPTH_FORMAT, attachment)
                .create_view(&Default::default()),
            resolve_view: resolve_texture.create_view(&Default::default()),
            resolve_texture,
        }
    }

    /// The image's framebuffers for `cam` with `samples` per pixel; its resolve texture is
    /// the image read back, and receives the sky and the windows copied into it.
    pub(super) fn image(device: &wgpu::Device, cam: &CameraIntrinsics, samples: u32) -> Self {
        Self::new(
            device,
            "",
            extent_px(cam.width_px, cam.height_px),
            samples,
            wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST,
        )
    }

    /// The colour view to draw into and the view it resolves into (none without
    /// multisampling).
    pub(super) fn colour_attachment(&self) -> (&wgpu::TextureView, Option<&wgpu::TextureView>) {
        match &self.msaa_view {
            Some(msaa) => (msaa, Some(&self.resolve_view)),
            None => (&self.resolve_view, None),
        }
    }
}

/// The sky alone over the whole image of `cam`, drawn once: a frame drawn in a region of the
/// image copies its sky from here (the sky depends on the pixel only, never on the pose).
pub(super) fn sky_texture(device: &wgpu::Device, cam: &CameraIntrinsics) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sky"),
        size: extent_px(cam.width_px, cam.height_px),
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: COLOR_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// Window framebuffers by size, made when first needed; the least recently used goes when
/// more than [`WindowTargetsCache::CAPACITY`] sizes are kept.
#[derive(Debug, Default)]
pub(super) struct WindowTargetsCache {
    /// (width, height, frame last used, framebuffers).
    entries: Vec<(u32, u32, u64, RenderTargets)>,
    /// Frames drawn with a window.
    uses: u64,
}

impl WindowTargetsCache {
    /// Sizes kept: a target's window changes size with its range and attitude, a few sizes
    /// at a time.
    const CAPACITY: usize = 12;

    /// The slot of the framebuffers of `window`'s size with `samples` per pixel, made when
    /// missing.
    pub(super) fn slot_for(
        &mut self,
        device: &wgpu::Device,
        window: &PixelWindow,
        samples: u32,
    ) -> usize {
        self.uses += 1;
        let size = (window.width_px, window.height_px);
        let found = self.entries.iter().position(|e| (e.0, e.1) == size);
        let index = found.unwrap_or_else(|| {
            if self.entries.len() >= Self::CAPACITY
                && let Some(oldest) = (0..self.entries.len()).min_by_key(|&i| self.entries[i].2)
            {
                self.entries.swap_remove(oldest);
            }
            let targets = RenderTargets::new(
                device,
                "window ",
                extent_px(size.0, size.1),
                samples,
                wgpu::TextureUsages::COPY_SRC,
            );
            self.entries.push((size.0, size.1, 0, targets));
            self.entries.len() - 1
        });
        self.entries[index].2 = self.uses;
        index
    }

    /// The framebuffers in `slot` (from [`Self::slot_for`]).
    pub(super) fn targets(&self, slot: usize) -> &RenderTargets {
        &self.entries[slot].3
    }
}

/// A 2-D extent of `width_px` x `height_px`.
pub(super) fn extent_px(width_px: u32, height_px: u32) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width: width_px,
        height: height_px,
        depth_or_array_layers: 1,
    }
}

/// Copies the part of a window inside the image into the image.
pub(super) fn copy_window(
    encoder: &mut wgpu::CommandEncoder,
    window: &wgpu::Texture,
    image: &wgpu::Texture,
    copy: &WindowCopy,
) {
    let at = |texture, [x, y]: [u32; 2]| wgpu::TexelCopyTextureInfo {
        texture,
        mip_level: 0,
        origin: wgpu::Origin3d { x, y, z: 0 },
        aspect: wgpu::TextureAspect::All,
    };
    encoder.copy_texture_to_texture(
        at(window, copy.from_px),
        at(image, copy.to_px),
        extent_px(copy.size_px[0], copy.size_px[1]),
    );
}
