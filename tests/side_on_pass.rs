//! The size models on a synthetic side-on pass: the shipped target (8 ft span, 6 ft
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
//!   σ_b (the floor at 0) does not;
//! - with the `span` model the wing points at the camera, so no frame's length is the span and
//!   every frame counts for its bearing: b̂ stays near its 4 ft prior. With the length's
//!   bounds at any view (`estimator.span_length_min_fraction`, the mesh's 0.70, rounded down) the 6 ft
//!   fuselage still bounds the range, and b̂ ends between 6 ft and 6/0.70 ft.

use crate::common::repo_root;
use wingman::estimation::airframe::{AirframeShape, AirframeTable};
use wingman::estimation::{AirframeModel, KalmanTracker, TargetTracker};
use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::CameraIntrinsics;
use wingman::render::mesh::TargetMesh;
use wingman::scenario::{BearingPoint, EstimatorSection, Scenario, SizeModel};
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

/// The estimator with `size_model`, the airframe's shape floor `shape_sigma` and no length
/// bias.
fn section(size_model: SizeModel, shape_sigma: f64) -> EstimatorSection {
    EstimatorSection {
        size_model,
        airframe_length_bias_px: 0.0,
        airframe_shape_sigma: shape_sigma,
        jerk_psd: 1e-4,
        ..EstimatorSection::default()
    }
}

/// Flies the pass for 60 s at 30 frames/s with `section`, the bearing measured to `bearing_point`, every
/// measured length `length_factor(t)` times the exact one, and returns the final (b̂, σ_b).
fn fly(
    section: &EstimatorSection,
    bearing_point: BearingPoint,
    length_factor: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let mesh = mesh();
    let size_model = section.size_model;
    let camera = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let focal = camera.focal_px;
    let mut tracker = KalmanTracker::new(section, focal, 4.0, (1.0, 30.0));
    if size_model == SizeModel::Airframe {
        let table = AirframeTable::of_mesh(&mesh.vertices_ft, SIZE_FT).expect("table");
        let shape =
            AirframeShape::of_mesh(&mesh.vertices_ft, &mesh.triangles, SIZE_FT, bearing_point);
        tracker = tracker.with_airframe(AirframeModel::new(section, table, shape));
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
            b_i_px: truth.b_i_px * length_factor(t_s),
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
        let (b_hat, sigma) = fly(&section(SizeModel::Airframe, shape_sigma), point, |_| 1.0);
        assert!(
            (b_hat / SIZE_FT - 1.0).abs() < 0.02,
            "{point:?}: b̂ = {b_hat} ft"
        );
        assert!(
            (b_hat - SIZE_FT).abs() < 3.0 * sigma,
            "{point:?}: b̂ = {b_hat} ± {sigma} ft"
        );
    }
    let apparent_model = section(SizeModel::Apparent, shape_sigma);
    let (apparent, _) = fly(&apparent_model, BearingPoint::Centroid, |_| 1.0);
    assert!(apparent < 6.5, "apparent b̂ = {apparent} ft");
}

#[test]
fn shape_floor_covers_a_systematic_length_error() {
    let shape_sigma = EstimatorSection::default().airframe_shape_sigma;
    let airframe_model = section(SizeModel::Airframe, shape_sigma);
    let (b_hat, sigma) = fly(&airframe_model, BearingPoint::Centroid, |_| 1.04);
    assert!((b_hat / SIZE_FT - 1.04).abs() < 0.02, "b̂ = {b_hat} ft");
    let z = (b_hat - SIZE_FT) / sigma;
    assert!(z.abs() < 3.0, "b̂ = {b_hat} ± {sigma} ft");
    let white = section(SizeModel::Airframe, 0.0);
    let (b_white, sigma_white) = fly(&white, BearingPoint::Centroid, |_| 1.04);
    let z_white = (b_white - SIZE_FT) / sigma_white;
    assert!(z_white.abs() > 3.0, "b̂ = {b_white} ± {sigma_white} ft");
}

/// The bound's value: the seed mesh's narrowest view reads 0.709 of its span, and the bound
/// scenarios/platoon.toml sets lies under it (a bound above the mesh's narrowest view would
/// pull a true range away).
#[test]
fn the_seed_mesh_is_never_shorter_than_0_7_of_its_span() {
    let table = AirframeTable::of_mesh(&mesh().vertices_ft, SIZE_FT).expect("table");
    let narrowest = table.narrowest();
    assert!((0.70..0.72).contains(&narrowest), "n = {narrowest}");
    let platoon = Scenario::load(&repo_root().join("scenarios/platoon.toml"), &[]).expect("load");
    let bound = platoon.estimator.span_length_min_fraction;
    assert!(
        bound > 0.0 && bound <= narrowest,
        "platoon's bound {bound} against the mesh's {narrowest}"
    );
}

/// The span end-on, the first second's blob merged with something as long again: the
/// filter starts on twice the length, and no later frame's length is the span.
#[test]
fn the_length_bounds_the_range_when_the_span_is_end_on() {
    let merged_first_second = |t_s: f64| if t_s < 1.0 { 2.0 } else { 1.0 };
    let span = section(SizeModel::Span, 0.0);
    let (unbounded, _) = fly(&span, BearingPoint::LengthMidpoint, merged_first_second);
    assert!(unbounded > 10.0, "bearing only: b̂ = {unbounded} ft");
    let bounded_model = EstimatorSection {
        span_length_min_fraction: 0.70,
        ..span
    };
    let (bounded, _) = fly(
        &bounded_model,
        BearingPoint::LengthMidpoint,
        merged_first_second,
    );
    assert!(
        (5.9..=6.0 / 0.70 + 0.1).contains(&bounded),
        "bounded: b̂ = {bounded} ft"
    );
}
