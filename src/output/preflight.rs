//! Checks made before a run writes anything or starts the simulation: the assets it reads
//! (the camera's mesh) and the resources it would take (telemetry rows, frame memory, saved
//! frames), each refused above a documented limit with the estimate and the key to change.

use crate::scenario::{Scenario, ScenarioError, ScenarioSource, SensorMode};
use crate::sensing::CameraConfig;
use crate::sensing::camera::load_target_mesh;
use crate::sim::Snapshot;

/// Most telemetry rows a run may log: the run keeps each row in memory for its summary and
/// plots (a [`Snapshot`], about 1.3 KB) and writes about 1 KB of CSV for it, so this is
/// about 2.6 GB of memory and 2 GB of CSV. The shipped scenarios log 14 000 to 42 000.
pub const MAX_TELEMETRY_ROWS: u64 = 2_000_000;
/// Most memory the camera's frame buffers may take, bytes (1 GiB): colour and depth at each
/// sample, the resolved frame and two read-back copies. 640x480 with 4 samples takes 13 MB.
pub const MAX_FRAME_MEMORY_BYTES: u64 = 1 << 30;
/// Most disk the saved frames may take, bytes (20 GiB), counted as uncompressed RGB (PNG
/// is smaller).
pub const MAX_SAVED_FRAMES_BYTES: u64 = 20 << 30;

/// Loads the scenario at `path` with its `--set` overrides and checks its resources and
/// assets, as `wingman run` does before anything else (the Python package too).
pub fn load(path: &std::path::Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
    let (scenario, source) = Scenario::load_with_source(path, overrides)?;
    check(&scenario, &source)?;
    Ok(scenario)
}

/// Checks the scenario's resources and assets; a failure names the key to change.
pub fn check(scenario: &Scenario, source: &ScenarioSource) -> Result<(), ScenarioError> {
    check_telemetry(scenario, source)?;
    if scenario.sensor.mode == SensorMode::Camera {
        check_frames(scenario, source)?;
        load_target_mesh(&CameraConfig::of(scenario))
            .map_err(|e| source.reject("camera.mesh", e.to_string()))?;
    }
    Ok(())
}

/// Bytes in a short human form (`13 TB`).
fn human_bytes(bytes: f64) -> String {
    let units = ["B", "KB", "MB", "GB", "TB", "PB"];
    let mut value = bytes;
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < units.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit + 1 == units.len() && value >= 1000.0 {
        return format!("{bytes:.1e} B");
    }
    format!("{value:.0} {}", units[unit])
}

/// The telemetry rows the run would log against [`MAX_TELEMETRY_ROWS`].
fn check_telemetry(scenario: &Scenario, source: &ScenarioSource) -> Result<(), ScenarioError> {
    let run = &scenario.run;
    let rows = (run.duration_s / run.dt_s) / f64::from(run.log_every) + 2.0;
    if rows <= MAX_TELEMETRY_ROWS as f64 {
        return Ok(());
    }
    let memory = rows * std::mem::size_of::<Snapshot>() as f64;
    Err(source.reject(
        "run.log_every",
        format!(
            "run.log_every = {}: the run would log {rows:.2e} telemetry rows (about {} in \
             memory), above the limit of {MAX_TELEMETRY_ROWS}: raise it or shorten \
             run.duration_s",
            run.log_every,
            human_bytes(memory)
        ),
    ))
}

/// The camera's frame memory and saved frames against their limits.
fn check_frames(scenario: &Scenario, source: &ScenarioSource) -> Result<(), ScenarioError> {
    let camera = &scenario.camera;
    let pixels = f64::from(camera.width_px) * f64::from(camera.height_px);
    // 4 bytes of colour and 4 of depth per sample, resolved frame, two read-back copies.
    let frame_bytes = pixels * (8.0 * f64::from(camera.msaa_samples) + 12.0);
    if frame_bytes > MAX_FRAME_MEMORY_BYTES as f64 {
        return Err(source.reject(
            "camera.width_px",
            format!(
                "camera.width_px x height_px = {} x {} with {} samples takes about {} of frame \
                 memory, above the limit of {}",
                camera.width_px,
                camera.height_px,
                camera.msaa_samples,
                human_bytes(frame_bytes),
                human_bytes(MAX_FRAME_MEMORY_BYTES as f64)
            ),
        ));
    }
    let every = scenario.output.frames_every;
    if every == 0 {
        return Ok(());
    }
    let saved = scenario.run.duration_s * camera.rate_hz / f64::from(every);
    let saved_bytes = saved * pixels * 3.0;
    if saved_bytes > MAX_SAVED_FRAMES_BYTES as f64 {
        return Err(source.reject(
            "output.frames_every",
            format!(
                "output.frames_every = {every}: {saved:.0} saved frames take up to {}, above \
                 the limit of {}: raise it",
                human_bytes(saved_bytes),
                human_bytes(MAX_SAVED_FRAMES_BYTES as f64)
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn source(overrides: &[&str]) -> (Scenario, ScenarioSource) {
        let source = ScenarioSource {
            path: PathBuf::from("s.toml"),
            text: "[run]\nseed = 1\n".to_string(),
            overrides: overrides.iter().map(|s| s.to_string()).collect(),
        };
        let scenario = Scenario::from_toml_str(&source.text, &source.path, &source.overrides)
            .expect("valid scenario");
        (scenario, source)
    }

    /// 10^10 rows are refused with the estimate and the key; the default run passes.
    #[test]
    fn telemetry_beyond_the_limit_is_refused() {
        let (scenario, s) = source(&[]);
        assert!(check(&scenario, &s).is_ok());
        let (scenario, s) = source(&["run.duration_s=1e5", "run.dt_s=1e-5", "run.log_every=1"]);
        let message = check(&scenario, &s).unwrap_err().to_string();
        assert!(message.contains("--set run.log_every=1"), "{message}");
        assert!(message.contains("1.00e10 telemetry rows"), "{message}");
        assert!(message.contains("2000000"), "{message}");
    }

    /// A huge multisampled frame is refused naming the camera's size.
    #[test]
    fn frame_memory_beyond_the_limit_is_refused() {
        let (scenario, s) = source(&[
            "sensor.mode=camera",
            "camera.rate_hz=25",
            "camera.width_px=8192",
            "camera.height_px=8192",
            "camera.msaa_samples=4",
        ]);
        let message = check(&scenario, &s).unwrap_err().to_string();
        assert!(message.contains("camera.width_px"), "{message}");
        assert!(message.contains("GB of frame memory"), "{message}");
    }
}
