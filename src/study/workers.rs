//! What each worker thread of a sweep keeps across its cases: its GPU device, opened at its
//! first camera case, and the apparent-size camera while its cases share a scenario. The
//! sweep owns them and drops them before it returns, on its own thread, once its worker
//! threads have exited: devices left in the worker threads' thread-local storage were
//! destroyed while the process exited, which crashed lavapipe (a segmentation fault in 8 of
//! 40 sweeps run four at a time), and workers that exited after the last device was dropped
//! crashed NVIDIA's driver (`study::run`).

use super::apparent_size::ViewCamera;
use super::plan::Case;
use super::results::Column;
use crate::render::GpuContext;
use crate::scenario::Scenario;
use std::path::Path;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// One worker's state. The camera is declared first so that it is dropped before the
/// device it renders on.
#[derive(Default)]
struct Slot {
    view: Option<ViewCamera>,
    gpu: Option<Result<GpuContext, String>>,
}

/// The state of every worker of a rayon pool, by thread index.
pub struct Workers {
    slots: Vec<Mutex<Slot>>,
}

impl Workers {
    /// Empty state for a pool of `count` threads.
    pub fn new(count: usize) -> Self {
        Self {
            slots: (0..count.max(1)).map(|_| Mutex::default()).collect(),
        }
    }

    /// The calling worker's slot (the first one outside a pool).
    fn slot(&self) -> MutexGuard<'_, Slot> {
        let index = rayon::current_thread_index().unwrap_or(0) % self.slots.len();
        self.slots[index]
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Runs `f` with the calling worker's GPU device (or why it could not be opened).
    pub fn with_gpu<T>(&self, f: impl FnOnce(Result<&GpuContext, &str>) -> T) -> T {
        f(opened(&mut self.slot().gpu))
    }

    /// An apparent-size case on the calling worker's camera, set up anew when the scenario
    /// overrides change.
    pub fn measure_view(
        &self,
        overrides: Vec<String>,
        scenario: Scenario,
        case: &Case,
        dir: &Path,
    ) -> Result<Vec<Column>, String> {
        let mut slot = self.slot();
        let Slot { view, gpu } = &mut *slot;
        let camera = match view {
            Some(camera) if camera.is_for(&overrides) => camera,
            _ => {
                *view = None;
                let gpu = opened(gpu).map_err(str::to_string)?;
                view.insert(ViewCamera::new(overrides, scenario, gpu)?)
            }
        };
        camera.measure(case, dir)
    }
}

/// The device in `gpu`, opened first if it is not yet (or why it could not be).
fn opened(gpu: &mut Option<Result<GpuContext, String>>) -> Result<&GpuContext, &str> {
    gpu.get_or_insert_with(|| GpuContext::new().map_err(|e| e.to_string()))
        .as_ref()
        .map_err(String::as_str)
}
