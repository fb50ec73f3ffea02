//! The apparent-size study (seed 8.2): one frame of the target per case, at the case's view
//! ([`View`]), with the camera of the base scenario. Per case: the measured maximal length,
//! the projected mesh's, the flat four-point model's (8.1)-(8.2), and the size each implies
//! (‖R‖ / aI, (3.7)) against the target's true size.

use super::plan::Case;
use super::results::Column;
use super::view::{FourPoints, View};
use crate::output::frame_images::{Overlay, write_frame};
use crate::render::GpuContext;
use crate::scenario::Scenario;
use crate::sensing::CameraConfig;
use crate::sensing::camera::{CameraSensor, load_target_mesh};
use crate::vision::{BlobStatus, ImageMeasurement};
use serde_json::Value;
use std::path::Path;

/// A camera set up for one scenario, kept by a worker across the cases that share it.
pub struct ViewCamera {
    overrides: Vec<String>,
    scenario: Scenario,
    sensor: CameraSensor,
    four_points: FourPoints,
}

impl ViewCamera {
    /// The camera and target of `scenario` (loaded with `overrides`) on `gpu`.
    pub fn new(
        overrides: Vec<String>,
        scenario: Scenario,
        gpu: &GpuContext,
    ) -> Result<Self, String> {
        let mesh = load_target_mesh(&CameraConfig::of(&scenario)).map_err(|e| e.to_string())?;
        let four_points = FourPoints::of_mesh(&mesh.vertices_ft)
            .ok_or_else(|| "camera.mesh: the mesh has no vertices".to_string())?;
        let sensor =
            CameraSensor::on_gpu(&CameraConfig::of(&scenario), gpu).map_err(|e| e.to_string())?;
        Ok(Self {
            overrides,
            scenario,
            sensor,
            four_points,
        })
    }

    /// Whether this camera was set up with these scenario overrides.
    pub fn is_for(&self, overrides: &[String]) -> bool {
        self.overrides == overrides
    }

    /// Renders and measures `case`'s view, saves the frame into `dir` when the scenario's
    /// `output.frames_every` is above 0, and returns the case's columns (or why it failed).
    pub fn measure(&mut self, case: &Case, dir: &Path) -> Result<Vec<Column>, String> {
        let view = View::from_settings(&case.settings)?;
        let geometry = view.geometry();
        let record = self
            .sensor
            .capture_now(0.0, &geometry)
            .map_err(|e| e.to_string())?;
        let camera = *self.sensor.intrinsics();
        let four_point_px = self.four_points.image_length_px(&geometry.pose(), &camera);
        if self.scenario.output.frames_every > 0
            && let Some((frame, _, blob)) = self.sensor.last_frame()
        {
            let overlay = Overlay {
                measurement: blob,
                captions: vec![],
            };
            write_frame(&dir.join("frame.png"), frame, Some(&overlay))
                .map_err(|e| e.to_string())?;
        }
        let size_true_ft = self.scenario.target.size_ft;
        // The size each length implies at the true range (3.7), the bearing of the measured
        // centroid for the measurement and of the reference point for the models.
        let implied = |m: Option<ImageMeasurement>| {
            m.map(|m| m.apparent_size_ft(camera.focal_px, view.range_ft))
        };
        let four_point = record
            .truth
            .zip(four_point_px)
            .map(|(t, b_i_px)| ImageMeasurement { b_i_px, ..t });
        let measured = record.measured.filter(|_| record.status == BlobStatus::Ok);
        let sizes = [
            ("measured", measured),
            ("mesh", record.truth),
            ("four_point", four_point),
        ];
        let mut columns = vec![column("meas_status", Value::from(record.status.label()))];
        for (name, m) in sizes {
            columns.push(column(
                &format!("b_i_{name}_px"),
                number(m.map(|m| m.b_i_px)),
            ));
        }
        for (name, m) in sizes {
            columns.push(column(&format!("size_{name}_ft"), number(implied(m))));
        }
        columns.push(column("size_true_ft", number(Some(size_true_ft))));
        for (name, m) in sizes {
            let ratio = implied(m).map(|s| s / size_true_ft);
            columns.push(column(&format!("ratio_{name}_true"), number(ratio)));
        }
        Ok(columns)
    }
}

fn column(name: &str, value: Value) -> Column {
    (name.to_string(), value)
}

/// A finite number, or null.
fn number(x: Option<f64>) -> Value {
    x.filter(|x| x.is_finite()).map_or(Value::Null, Value::from)
}
