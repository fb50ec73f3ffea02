//! The headless wgpu device, created once per simulator and shared by its renderers.
//!
//! No surface is created. On machines without a GPU the Vulkan backend finds Mesa's lavapipe
//! ("llvmpipe", [`wgpu::DeviceType::Cpu`]). Mesa may print a harmless
//! "XDG_RUNTIME_DIR is invalid" line on stderr; `NODEVICE_SELECT=1` in the environment silences
//! it (it is not set here: changing the environment of a running multi-threaded program is
//! unsound).

/// What to install when no adapter exists (Mesa's lavapipe; docs/design.md, The camera on a
/// CPU).
pub const INSTALL_HINT: &str = "apt-get install -y mesa-vulkan-drivers libvulkan1";

/// Why no GPU context could be created.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter (GPU or software rasteriser) is available.
    #[error(
        "no GPU adapter found ({}); install a software Vulkan driver: {hint}",
        one_line(.source)
    )]
    NoAdapter {
        /// wgpu's reason.
        #[source]
        source: wgpu::RequestAdapterError,
        /// The install command, [`INSTALL_HINT`].
        hint: &'static str,
    },
    /// The adapter refused to create a device.
    #[error(
        "GPU adapter {adapter} refused to create a device: {}",
        one_line(.source)
    )]
    NoDevice {
        /// The adapter's name.
        adapter: String,
        /// wgpu's reason.
        #[source]
        source: wgpu::RequestDeviceError,
    },
}

/// `error`'s message on one line, whatever line breaks it held.
fn one_line(error: &dyn std::error::Error) -> String {
    error
        .to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The folder to give `XDG_RUNTIME_DIR` before the first GPU context is made, when it
/// names none: Mesa's Vulkan layers print "XDG_RUNTIME_DIR is invalid or not set" otherwise
/// (twice a run; a user must not see it). A private folder (mode 0700) in the temporary
/// folder, made here; None when the variable already names a folder, or none can be made.
pub fn runtime_dir_to_set() -> Option<std::path::PathBuf> {
    use std::os::unix::fs::DirBuilderExt;
    let current = std::env::var_os("XDG_RUNTIME_DIR").map(std::path::PathBuf::from);
    if current.is_some_and(|dir| dir.is_absolute() && dir.is_dir()) {
        return None;
    }
    // SAFETY: getuid has no preconditions and cannot fail.
    let uid = unsafe { libc::getuid() };
    let dir = std::env::temp_dir().join(format!("wingman-runtime-{uid}"));
    if !dir.is_dir() {
        std::fs::DirBuilder::new().mode(0o700).create(&dir).ok()?;
    }
    Some(dir)
}

/// The value to give `LP_NUM_THREADS` (lavapipe's rasterizer threads) before the first GPU
/// context is made, when it is unset: "0", so lavapipe draws on its queue's own thread, unless
/// the frames shade the whole image every time (`shades_whole_frames`: a world scene). A
/// tracking window of a few thousand pixels gains nothing from the rasterizer's threads,
/// while every draw pays their barrier and wake-ups, and the simulation already keeps the
/// cores busy: formation.toml runs about 20% faster, the platoon about 7%, a sweep of two
/// jobs 23%, a world scene 13% slower (docs/findings.md, Speed). Frames are the same either
/// way.
pub fn lavapipe_threads_to_set(shades_whole_frames: bool) -> Option<&'static str> {
    let unset = std::env::var_os("LP_NUM_THREADS").is_none();
    (unset && !shades_whole_frames).then_some("0")
}

/// A wgpu device and queue without a surface, with the adapter's description. A clone shares
/// the device and queue.
#[derive(Debug, Clone)]
pub struct GpuContext {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    limits: wgpu::Limits,
}

impl GpuContext {
    /// Opens the best adapter the enabled backends offer (`WGPU_BACKEND` and other wgpu
    /// environment variables are honoured) with default limits. Blocks until done.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                apply_limit_buckets: false,
            })
            .await
            .map_err(|source| GpuError::NoAdapter {
                source,
                hint: INSTALL_HINT,
            })?;
        let info = adapter.get_info();
        let limits = wgpu::Limits::default();
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("wingman"),
                required_limits: limits.clone(),
                ..Default::default()
            })
            .await
            .map_err(|source| GpuError::NoDevice {
                adapter: info.name.clone(),
                source,
            })?;
        Ok(Self {
            device,
            queue,
            info,
            limits,
        })
    }

    /// The device (a cheap handle: clone it to keep it).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The device's queue (a cheap handle: clone it to keep it).
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// The limits the device was created with.
    pub fn limits(&self) -> &wgpu::Limits {
        &self.limits
    }

    /// Adapter kind; lavapipe is [`wgpu::DeviceType::Cpu`].
    pub fn device_type(&self) -> wgpu::DeviceType {
        self.info.device_type
    }

    /// Backend in use (Vulkan in this build).
    pub fn backend(&self) -> wgpu::Backend {
        self.info.backend
    }

    /// One line for logs and reports: name, device type, backend, driver.
    pub fn description(&self) -> String {
        format!(
            "{} ({:?}, {}, driver {} {})",
            self.info.name,
            self.info.device_type,
            self.info.backend,
            self.info.driver,
            self.info.driver_info
        )
    }
}

#[cfg(test)]
mod tests {
    use super::lavapipe_threads_to_set;

    /// A world scene keeps lavapipe's rasterizer threads whatever the environment; window
    /// frames turn them off unless the user set their number.
    #[test]
    fn rasterizer_threads_stay_for_world_scenes_and_user_settings() {
        assert_eq!(lavapipe_threads_to_set(true), None);
        let user_set = std::env::var_os("LP_NUM_THREADS").is_some();
        assert_eq!(lavapipe_threads_to_set(false).is_none(), user_set);
    }
}
