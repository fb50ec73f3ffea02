//! The airframe size model on a synthetic side-on pass: the shipped target (8 ft span, 6 ft
//! fuselage) flies north at 50 ft/s, level; the follower flies 40 ft west of it, its camera
//! looking east, weaving along the track (±6 ft/s, 6 s period) so that the range scale is
//! observable. Each frame's (yI, zI, bI) is the projected mesh's exact image: (yI, zI) the
//! silhouette's true centroid (or the maximal length's midpoint), bI its maximal length (no
//! vision error; the length model's bias is set to 0). Seen side-on the silhouette's maximal
//! length is the fuselage, 6/8 of the size, and its centroid lies about a tenth of the size
//! aft of and above the reference point:
//! - with `size_model = "airframe"` the filter reads the view from its estimate, and the
//!   length and the bearing point's offset from it, and b̂ ends within 2% of 8 ft, the truth
//!   inside ±3σ_b, with either bearing point (this straight, level pass hardly turns the
//!   view, so the offset barely moves here and the pass would hold without it; the closed
//!   loop that needs it is tests/seed_ch7_velocity_camera.rs's airframe test);
//! - with the seed's `apparent` model b̂ ends near the fuselage's 6 ft (below 6.5 ft);
//! - when every length reads 4% long (a systematic error no averaging removes, as the
//!   vision's short reading changing with the aspect), b̂ ends about 4% high, and the floor
//!   `estimator.airframe_shape_sigma` keeps the truth inside ±3σ_b, which the filter's own
//!   σ_b (the floor at 0) does not.

use wingman::estimation::airframe::{AirframeShape, AirframeTable};
use wingman::estimation::{AirframeModel, KalmanTracker, TargetTracker};
use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::CameraIntrinsics;
use wingman::render::mesh::TargetMesh;
use wingman::scenario::{BearingPoint, EstimatorSection, SizeModel};
use wingman::sensing::transform::scaled_relative_position;
use wingman::sensing::{CaptureGeometry, FollowerPose, FrameRecord};
use wingman::vision::silhouette::SilhouetteCentroid;
use wingman::vision::{BlobStatus, ImageMeasurement, TruthProjector};

const SIZE_FT: f64 = 8.0;
const SPEED_FPS: f64 = 50.0;

fn mesh() -> TargetMesh {
    let unscaled = TargetMesh::target_aircraft(1.0).expect("shipped mesh");
    let factor = SIZE_FT / unscaled.max_dimension_ft();
    unscaled.scaled(factor)
}

/// Flies the pass for 60 s at 30 frames/s, the bearing measured to `bearing_point`, every
/// measured length `length_factor` times the exact one, and returns the final (b̂, σ_b).
fn fly(
    size_model: SizeModel,
    bearing_point: BearingPoint,
    length_factor: f64,
    shape_sigma: f64,
) -> (f64, f64) {
    let mesh = mesh();
    let section = EstimatorSection {
        size_model,
        airframe_length_bias_px: 0.0,
        airframe_shape_sigma: shape_sigma,
        jerk_psd: 1e-4,
        ..EstimatorSection::default()
    };
    let camera = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let focal = camera.focal_px;
    let mut tracker = KalmanTracker::new(&section, focal, 4.0, (1.0, 30.0));
    if size_model == SizeModel::Airframe {
        let table = AirframeTable::of_mesh(&mesh.vertices_ft, SIZE_FT).expect("table");
        let shape =
            AirframeShape::of_mesh(&mesh.vertices_ft, &mesh.triangles, SIZE_FT, bearing_point);
        tracker = tracker.with_airframe(AirframeModel::new(&section, table, shape));
    }
    let follower_attitude = EulerAngles::new(0.0, 0.0, 90f64.to_radians());
    let ned_from_camera = follower_attitude.body_from_ned().transpose();
    let weave = |t: f64| 6.0 * (2.0 * std::f64::consts::PI * t / 6.0).sin();
    let weave_position = |t: f64| {
        -36.0 / (2.0 * std::f64::consts::PI) * (2.0 * std::f64::consts::PI * t / 6.0).cos()
    };
    let mut projector = TruthProjector::new();
    let mut silhouette = SilhouetteCentroid::default();
    for index in 0..1800u64 {
        let t_s = index as f64 / 30.0;
        let target = Vec3::new(SPEED_FPS * t_s, 0.0, 0.0);
        let follower = Vec3::new(SPEED_FPS * t_s + weave_position(t_s), -40.0, 0.0);
        let relative = target - follower;
        let geometry = CaptureGeometry::exact(
            relative,
            EulerAngles::new(0.0, 0.0, 0.0),
            FollowerPose::at_origin(follower_attitude),
        );
        let pose = geometry.pose();
        let image = projector
            .image_truth(&mesh.vertices_ft, &pose, &camera)
            .expect("in front of the camera");
        let (y_i_px, z_i_px) = match bearing_point {
            BearingPoint::Centroid => silhouette
                .centroid(&mesh.vertices_ft, &mesh.triangles, &pose, &camera)
                .expect("an area"),
            BearingPoint::LengthMidpoint => {
                let (u_px, v_px) = image.feret.midpoint_px();
                camera.image_from_pixel(u_px, v_px)
            }
        };
        let truth = image.image_measurement();
        let measured = ImageMeasurement {
            y_i_px,
            z_i_px,
            b_i_px: truth.b_i_px * length_factor,
        };
        let record = FrameRecord {
            index,
            t_s,
            status: BlobStatus::Ok,
            measured: Some(measured),
            truth: Some(truth),
            r_measured: Some(scaled_relative_position(
                &measured,
                focal,
                &ned_from_camera.transpose(),
            )),
            follower_position_ned_ft: follower,
            ned_from_camera,
            range_ft: relative.norm(),
            length_direction: None,
            centroid_vs_silhouette_px: None,
            background: None,
        };
        let velocity = Vec3::new(SPEED_FPS + weave(t_s), 0.0, 0.0);
        tracker.fuse_frame(&record, &velocity);
    }
    let estimate = tracker.posterior().expect("fused");
    (estimate.b_hat_ft, estimate.b_sigma_ft)
}

#[test]
fn airframe_model_reads_the_size_side_on() {
    let shape_sigma = EstimatorSection::default().airframe_shape_sigma;
    for point in [BearingPoint::Centroid, BearingPoint::LengthMidpoint] {
        let (b_hat, sigma) = fly(SizeModel::Airframe, point, 1.0, shape_sigma);
        assert!(
            (b_hat / SIZE_FT - 1.0).abs() < 0.02,
            "{point:?}: b̂ = {b_hat} ft"
        );
        assert!(
            (b_hat - SIZE_FT).abs() < 3.0 * sigma,
            "{point:?}: b̂ = {b_hat} ± {sigma} ft"
        );
    }
    let (apparent, _) = fly(
        SizeModel::Apparent,
        BearingPoint::Centroid,
        1.0,
        shape_sigma,
    );
    assert!(apparent < 6.5, "apparent b̂ = {apparent} ft");
}

#[test]
fn shape_floor_covers_a_systematic_length_error() {
    let shape_sigma = EstimatorSection::default().airframe_shape_sigma;
    let (b_hat, sigma) = fly(
        SizeModel::Airframe,
        BearingPoint::Centroid,
        1.04,
        shape_sigma,
    );
    assert!((b_hat / SIZE_FT - 1.04).abs() < 0.02, "b̂ = {b_hat} ft");
    let z = (b_hat - SIZE_FT) / sigma;
    assert!(z.abs() < 3.0, "b̂ = {b_hat} ± {sigma} ft");
    let (b_white, sigma_white) = fly(SizeModel::Airframe, BearingPoint::Centroid, 1.04, 0.0);
    let z_white = (b_white - SIZE_FT) / sigma_white;
    assert!(z_white.abs() > 3.0, "b̂ = {b_white} ± {sigma_white} ft");
}
