//! The measurement audit: every measured frame beside its ground truth, the projection of the
//! true mesh in the true geometry, and the errors accumulated over the run. The audit only
//! reports; nothing in the loop reads it.

use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use crate::render::mesh::TargetMesh;
use crate::vision::silhouette::SilhouetteCentroid;
use crate::vision::{BlobMeasurement, ImageMeasurement, ImageTruth, TruthProjector};

/// Accumulated measurement-error statistics over `Ok` frames.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MeasurementErrors {
    /// Frames with both a measurement and its truth.
    pub count: u64,
    /// Σ of squared centroid distance, px².
    pub centroid_sq_px2: f64,
    /// Σ of squared maximal-length error, px².
    pub length_sq_px2: f64,
    /// Frames with both a measured centroid and the silhouette's true one.
    pub silhouette_count: u64,
    /// Σ of squared distance between the measured and the silhouette's true centroid, px².
    pub silhouette_centroid_sq_px2: f64,
}

impl MeasurementErrors {
    /// RMS centroid error, px (None before any frame).
    pub fn centroid_rms_px(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.centroid_sq_px2 / self.count as f64).sqrt())
    }

    /// RMS distance between the measured centroid and the silhouette's true centroid, px
    /// (None before any frame).
    pub fn silhouette_centroid_rms_px(&self) -> Option<f64> {
        (self.silhouette_count > 0)
            .then(|| (self.silhouette_centroid_sq_px2 / self.silhouette_count as f64).sqrt())
    }

    /// RMS maximal-length error, px (None before any frame).
    pub fn length_rms_px(&self) -> Option<f64> {
        (self.count > 0).then(|| (self.length_sq_px2 / self.count as f64).sqrt())
    }
}

/// A frame's measurement as the audit is given it.
pub(super) struct AuditedFrame<'a> {
    /// The target's true pose in the true camera axes.
    pub pose: &'a TargetPoseInCamera,
    /// The blob measured.
    pub blob: &'a BlobMeasurement,
    /// Its image measurement, px (None when nothing was found).
    pub measured: Option<ImageMeasurement>,
    /// Whether the measurement stands (status `Ok`).
    pub ok: bool,
}

/// The truth projectors and the errors so far.
#[derive(Debug, Default)]
pub(super) struct MeasurementAudit {
    truth: TruthProjector,
    silhouette: SilhouetteCentroid,
    errors: MeasurementErrors,
    last_truth: Option<ImageTruth>,
    /// The last frame's squared distance from the silhouette's true centroid, px² (None when
    /// it was not measured or the silhouette is not known).
    last_silhouette_sq_px2: Option<f64>,
}

impl MeasurementAudit {
    /// The truth of a measured frame of `mesh` through `intrinsics`, its errors added to the
    /// run's: the true (yI, zI, bI), px (None when part of the target is behind the camera).
    pub fn audit(
        &mut self,
        frame: &AuditedFrame,
        mesh: &TargetMesh,
        intrinsics: &CameraIntrinsics,
    ) -> Option<ImageMeasurement> {
        self.last_truth = self
            .truth
            .image_truth(&mesh.vertices_ft, frame.pose, intrinsics);
        let truth = self.last_truth.map(|t: ImageTruth| t.image_measurement());
        if let (true, Some(m), Some(t)) = (frame.ok, frame.measured, truth) {
            self.errors.count += 1;
            self.errors.centroid_sq_px2 +=
                (m.y_i_px - t.y_i_px).powi(2) + (m.z_i_px - t.z_i_px).powi(2);
            self.errors.length_sq_px2 += (m.b_i_px - t.b_i_px).powi(2);
        }
        self.last_silhouette_sq_px2 = None;
        if frame.ok {
            self.add_silhouette_error(frame, mesh, intrinsics);
        }
        truth
    }

    /// Adds a measured frame's distance from the silhouette's true centroid to the errors.
    fn add_silhouette_error(
        &mut self,
        frame: &AuditedFrame,
        mesh: &TargetMesh,
        intrinsics: &CameraIntrinsics,
    ) {
        let truth =
            self.silhouette
                .centroid(&mesh.vertices_ft, &mesh.triangles, frame.pose, intrinsics);
        if let Some((y_true, z_true)) = truth {
            let blob = frame.blob;
            let (y, z) = intrinsics.image_from_pixel(blob.centroid_u_px, blob.centroid_v_px);
            let sq_px2 = (y - y_true).powi(2) + (z - z_true).powi(2);
            self.errors.silhouette_count += 1;
            self.errors.silhouette_centroid_sq_px2 += sq_px2;
            self.last_silhouette_sq_px2 = Some(sq_px2);
        }
    }

    /// The ground truth of the last frame (None when part of the target was behind the
    /// camera).
    pub fn last_truth(&self) -> Option<ImageTruth> {
        self.last_truth
    }

    /// The last frame's squared distance from the silhouette's true centroid, px² (None when
    /// it was not measured or the silhouette is not known).
    pub fn last_silhouette_sq_px2(&self) -> Option<f64> {
        self.last_silhouette_sq_px2
    }

    /// Measurement errors against truth.
    pub fn errors(&self) -> MeasurementErrors {
        self.errors
    }
}
