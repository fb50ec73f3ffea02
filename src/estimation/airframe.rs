//! The airframe size model (seed 8.2, beyond the seed's constant apparent size): with
//! `estimator.size_model = "airframe"` the target's shape is known up to scale (the mesh the
//! scenario names, `camera.mesh`) and b is its size (the mesh's largest dimension). The
//! maximal length a frame measures is b n(v), with n the normalised maximal length of that
//! shape seen along the line of sight v (target-body axes): n = 1 where the largest dimension
//! lies across the line of sight, the fuselage's 6/8 seen side-on from the wing axis.
//!
//! n is precomputed once per run over view directions, with the apparent-size study's
//! geometry ([`CaptureGeometry::on_axis`]: the target's attitude relative to the camera, here
//! roll 0) and the
//! truth's maximal length of the projected mesh ([`TruthProjector`]), far enough away that
//! the projection is orthographic; then interpolated bilinearly. A rotation about the line of
//! sight turns the image but not its lengths, so two angles describe a view: the line of
//! sight v = (cos ψ cos θ, -sin ψ, cos ψ sin θ) in target-body axes, ψ ∈ [-90°, 90°] the
//! yaw of the target relative to it (90°: side-on, nose to the right) and θ ∈ (-180°, 180°]
//! the pitch (0: seen from behind, 90°: from above, 180°: from the front).
//!
//! The image pipeline measures a point of the silhouette (its centroid, or the midpoint of
//! its maximal length's ends: `camera.bearing_point`), not the image of the target's
//! reference point that the filter estimates. The two lie apart by up to a tenth of the size
//! (from the side the fin and tail pull the centroid up and aft; from behind the wing tips'
//! midpoint lies at the wing, below and ahead of the reference point), and the offset moves
//! with the view, so a follower whose own motion changes the view would read it as the
//! target's motion and bias its range from own motion. [`AirframeShape`] predicts the
//! offset per frame by drawing the shape in perspective where the filter puts it, in units
//! of the size: the image of a target at R is that of the shape at unit size at R / b, so b
//! is not needed.

use crate::frames::EulerAngles;
use crate::frames::Mat3;
use crate::frames::Vec3;
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use crate::scenario::BearingPoint;
use crate::sensing::CaptureGeometry;
use crate::vision::TruthProjector;
use crate::vision::silhouette::SilhouetteCentroid;

/// The table's step in both angles, deg.
const STEP_DEG: f64 = 2.5;
/// The range the table's views are projected from, in target sizes (orthographic to 1e-8).
const FAR_RANGE_SIZES: f64 = 1e4;
/// The focal length of the table's camera, px (lengths of about 100 px at the far range).
const FAR_FOCAL_PX: f64 = 1e6;
/// cos² ψ below which a pitch error is not magnified further near the side-on pole.
const POLE_COS_SQ_MIN: f64 = 0.01;

/// A view direction: the line of sight in the target's body axes as two angles (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewAngles {
    /// ψ, the target's yaw relative to the line of sight, rad, in [-π/2, π/2].
    pub yaw_rad: f64,
    /// θ, the target's pitch relative to the line of sight, rad, in (-π, π].
    pub pitch_rad: f64,
}

impl ViewAngles {
    /// The angles of the line of sight `line_of_sight_body` (camera to target, target-body
    /// axes, any length); `None` for a zero vector.
    pub fn of_line_of_sight(line_of_sight_body: &Vec3) -> Option<Self> {
        let v = line_of_sight_body.try_normalize(1e-12)?;
        Some(Self {
            yaw_rad: (-v.y).clamp(-1.0, 1.0).asin(),
            pitch_rad: v.z.atan2(v.x),
        })
    }

    /// The target's attitude relative to the camera for this view (roll 0).
    pub fn attitude(&self) -> EulerAngles {
        EulerAngles::new(0.0, self.pitch_rad, self.yaw_rad)
    }
}

/// n at one view and its slopes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalisedLength {
    /// n, the maximal length over the target's size.
    pub length: f64,
    /// ∂n/∂ψ, 1/rad.
    pub per_yaw_rad: f64,
    /// ∂n/∂θ, 1/rad.
    pub per_pitch_rad: f64,
}

impl NormalisedLength {
    /// σ of n when the view direction is uncertain by `sigma_rad` (an angle on the sphere,
    /// each way): a pitch error of the line of sight is magnified by 1 / cos ψ in θ.
    pub fn sigma(&self, yaw_rad: f64, sigma_rad: f64) -> f64 {
        let cos_sq = yaw_rad.cos().powi(2).max(POLE_COS_SQ_MIN);
        sigma_rad * (self.per_yaw_rad.powi(2) + self.per_pitch_rad.powi(2) / cos_sq).sqrt()
    }
}

/// n over view directions for one shape.
#[derive(Debug, Clone, PartialEq)]
pub struct AirframeTable {
    /// n at ψ = -90° + i step, θ = -180° + j step, row-major in ψ.
    lengths: Vec<f64>,
    pitch_nodes: usize,
}

impl AirframeTable {
    /// The table of a mesh (`vertices_ft`, target-body axes) whose size (largest dimension)
    /// is `size_ft`; `None` when a view cannot be projected (no vertices, non-finite ones).
    pub fn of_mesh(vertices_ft: &[Vec3], size_ft: f64) -> Option<Self> {
        let yaw_nodes = (180.0 / STEP_DEG).round() as usize + 1;
        let pitch_nodes = (360.0 / STEP_DEG).round() as usize + 1;
        let camera = CameraIntrinsics {
            width_px: 1,
            height_px: 1,
            focal_px: FAR_FOCAL_PX,
        };
        let range_ft = FAR_RANGE_SIZES * size_ft;
        let mut projector = TruthProjector::new();
        let mut lengths = Vec::with_capacity(yaw_nodes * pitch_nodes);
        for i in 0..yaw_nodes {
            for j in 0..pitch_nodes {
                let angles = ViewAngles {
                    yaw_rad: (-90.0 + i as f64 * STEP_DEG).to_radians(),
                    pitch_rad: (-180.0 + j as f64 * STEP_DEG).to_radians(),
                };
                let pose = CaptureGeometry::on_axis(range_ft, angles.attitude()).pose();
                let truth = projector.image_truth(vertices_ft, &pose, &camera)?;
                lengths.push(truth.b_i_px * range_ft / (FAR_FOCAL_PX * size_ft));
            }
        }
        Some(Self {
            lengths,
            pitch_nodes,
        })
    }

    /// The shortest n over every view: the narrowest view's maximal length over the size
    /// (docs/equations.md, The length's bounds at any view).
    pub fn narrowest(&self) -> f64 {
        self.lengths.iter().copied().fold(f64::INFINITY, f64::min)
    }

    fn node(&self, i: usize, j: usize) -> f64 {
        self.lengths[i * self.pitch_nodes + j]
    }

    /// n and its slopes at `angles`, interpolated bilinearly.
    pub fn at(&self, angles: &ViewAngles) -> NormalisedLength {
        let step = STEP_DEG.to_radians();
        let yaw_nodes = self.lengths.len() / self.pitch_nodes;
        let cell = |x: f64, nodes: usize| {
            let i = (x.floor().max(0.0) as usize).min(nodes - 2);
            (i, (x - i as f64).clamp(0.0, 1.0))
        };
        let (i, fy) = cell(
            (angles.yaw_rad + 0.5 * std::f64::consts::PI) / step,
            yaw_nodes,
        );
        let (j, fp) = cell(
            (angles.pitch_rad + std::f64::consts::PI) / step,
            self.pitch_nodes,
        );
        let (n00, n10) = (self.node(i, j), self.node(i + 1, j));
        let (n01, n11) = (self.node(i, j + 1), self.node(i + 1, j + 1));
        let low = n00 + fp * (n01 - n00);
        let high = n10 + fp * (n11 - n10);
        NormalisedLength {
            length: low + fy * (high - low),
            per_yaw_rad: (high - low) / step,
            per_pitch_rad: ((1.0 - fy) * (n01 - n00) + fy * (n11 - n10)) / step,
        }
    }
}

/// The target's shape at unit size, for the offset of the measured bearing point from the
/// reference point (module docs).
#[derive(Debug, Clone)]
pub struct AirframeShape {
    /// The mesh's vertices over its size, target-body axes.
    unit_vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    point: BearingPointFinder,
}

/// What finds the bearing point in a drawing of the shape, with its buffers.
#[derive(Debug, Clone)]
enum BearingPointFinder {
    /// The centroid of the union of the projected triangles.
    Centroid(SilhouetteCentroid),
    /// The midpoint of the projected vertices' farthest pair.
    LengthMidpoint(TruthProjector),
}

impl AirframeShape {
    /// The shape of a mesh (`vertices_ft`, `triangles`) whose size is `size_ft`, its bearing
    /// measured to `bearing_point`.
    pub fn of_mesh(
        vertices_ft: &[Vec3],
        triangles: &[[u32; 3]],
        size_ft: f64,
        bearing_point: BearingPoint,
    ) -> Self {
        Self {
            unit_vertices: vertices_ft.iter().map(|v| v / size_ft).collect(),
            triangles: triangles.to_vec(),
            point: match bearing_point {
                BearingPoint::Centroid => {
                    BearingPointFinder::Centroid(SilhouetteCentroid::default())
                }
                BearingPoint::LengthMidpoint => {
                    BearingPointFinder::LengthMidpoint(TruthProjector::new())
                }
            },
        }
    }

    /// Where the bearing point lies from the image of the reference point, (yI, zI), px, for
    /// the target at `scaled_position_camera` (R / b, camera axes) in the attitude
    /// `camera_from_body`, seen with focal length `focal_px`; `None` where part of the shape
    /// is behind the camera or its silhouette has no area.
    pub fn bearing_offset_px(
        &mut self,
        scaled_position_camera: &Vec3,
        camera_from_body: &Mat3,
        focal_px: f64,
    ) -> Option<[f64; 2]> {
        let camera = CameraIntrinsics {
            width_px: 1,
            height_px: 1,
            focal_px,
        };
        let pose = TargetPoseInCamera {
            position_body_ft: *scaled_position_camera,
            body_from_target: *camera_from_body,
        };
        let (y, z) = match &mut self.point {
            BearingPointFinder::Centroid(silhouette) => {
                silhouette.centroid(&self.unit_vertices, &self.triangles, &pose, &camera)?
            }
            BearingPointFinder::LengthMidpoint(projector) => {
                let ends = projector
                    .image_truth(&self.unit_vertices, &pose, &camera)?
                    .feret;
                let (u_px, v_px) = ends.midpoint_px();
                camera.image_from_pixel(u_px, v_px)
            }
        };
        let (y_reference, z_reference) = camera.image_from_body(scaled_position_camera)?;
        Some([y - y_reference, z - z_reference])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angles are those of the attitude (roll 0, pitch θ, yaw ψ) relative to the camera:
    /// the camera's optical axis in target-body axes.
    #[test]
    fn angles_round_trip_through_the_study_view() {
        for (yaw_deg, pitch_deg) in [(0.0, 0.0), (30.0, 40.0), (-75.0, 170.0), (10.0, -120.0)] {
            let angles = ViewAngles {
                yaw_rad: f64::to_radians(yaw_deg),
                pitch_rad: f64::to_radians(pitch_deg),
            };
            let axis_body = angles.attitude().body_from_ned() * Vec3::x();
            let back = ViewAngles::of_line_of_sight(&axis_body).expect("unit");
            assert!(
                (back.yaw_rad.to_degrees() - yaw_deg).abs() < 1e-9,
                "{back:?}"
            );
            assert!(
                (back.pitch_rad.to_degrees() - pitch_deg).abs() < 1e-9,
                "{back:?}"
            );
        }
    }

    /// A cross, 8 ft span (y) and 6 ft fuselage (x): from behind and from above the span,
    /// n = 1; side-on (whatever the pitch) the fuselage, 0.75; between the nodes the value and
    /// slope follow the span's exact foreshortening cos ψ.
    #[test]
    fn a_cross_reads_its_span_or_its_fuselage() {
        let cross = [
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::new(0.0, -4.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(-3.0, 0.0, 0.0),
        ];
        let table = AirframeTable::of_mesh(&cross, 8.0).expect("projects");
        let at = |yaw_deg: f64, pitch_deg: f64| {
            table.at(&ViewAngles {
                yaw_rad: yaw_deg.to_radians(),
                pitch_rad: pitch_deg.to_radians(),
            })
        };
        assert!((at(0.0, 0.0).length - 1.0).abs() < 1e-6);
        assert!((at(90.0, 37.0).length - 0.75).abs() < 1e-6);
        assert!((at(0.0, 90.0).length - 1.0).abs() < 1e-6);
        // Seen ψ off the tail in level flight the span reads 8 cos ψ while it exceeds the
        // fuselage's 6 sin ψ; between nodes the table is within a chord of cos.
        let n = at(31.0, 0.0);
        assert!((n.length - 31f64.to_radians().cos()).abs() < 1e-3, "{n:?}");
        assert!(
            (n.per_yaw_rad + 31f64.to_radians().sin()).abs() < 0.03,
            "{n:?}"
        );
        assert!(n.per_pitch_rad.abs() < 1e-6, "{n:?}");
    }

    /// The cross of the test above with a triangular fin on its tail (x-z plane): its
    /// vertices, its triangles (the cross as a rhombus) and its size.
    fn cross_with_fin() -> (Vec<Vec3>, Vec<[u32; 3]>, f64) {
        let vertices = vec![
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::new(0.0, -4.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(-3.0, 0.0, 0.0),
            Vec3::new(-2.0, 0.0, 0.0),
            Vec3::new(-3.0, 0.0, -1.5),
        ];
        (vertices, vec![[0, 1, 2], [0, 1, 3], [3, 4, 5]], 8.0)
    }

    /// Seen side-on from far away (the target flying north, the camera looking east, so its
    /// right is the target's aft): the rhombus has no area, the centroid is the fin's,
    /// (-8/3, 0, -1/2) ft from the reference point, and the maximal length runs from the
    /// nose (3, 0, 0) to the fin's tip (-3, 0, -1.5), its midpoint (0, 0, -0.75) ft; in the
    /// image, focal length times those over the range.
    #[test]
    fn the_bearing_offset_is_the_measured_points_from_the_reference_point() {
        let (vertices, triangles, size_ft) = cross_with_fin();
        let camera_from_body = Mat3::new(0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        let range_sizes = 1e4;
        let focal_px = 1e6;
        let scaled_position = Vec3::new(range_sizes, 0.0, 0.0);
        let px_per_ft = focal_px / (range_sizes * size_ft);
        for (point, expected_ft) in [
            (BearingPoint::Centroid, [8.0 / 3.0, 0.5]),
            (BearingPoint::LengthMidpoint, [0.0, 0.75]),
        ] {
            let mut shape = AirframeShape::of_mesh(&vertices, &triangles, size_ft, point);
            let offset = shape
                .bearing_offset_px(&scaled_position, &camera_from_body, focal_px)
                .expect("in front");
            for k in 0..2 {
                assert!(
                    (offset[k] - expected_ft[k] * px_per_ft).abs() < 1e-4 * px_per_ft,
                    "{point:?}: {offset:?} px"
                );
            }
        }
    }

    /// Close up, in perspective, the unit shape at R / b gives the offset of the shape at its
    /// size at R, whatever b: the image of the target drawn at its size, less the image of
    /// its reference point.
    #[test]
    fn the_bearing_offset_needs_no_size() {
        let (vertices, triangles, size_ft) = cross_with_fin();
        let camera = CameraIntrinsics {
            width_px: 1,
            height_px: 1,
            focal_px: 500.0,
        };
        let attitude = EulerAngles::new(0.2, -0.3, 1.1);
        let position_ft = Vec3::new(30.0, 6.0, -4.0);
        let pose = TargetPoseInCamera {
            position_body_ft: position_ft,
            body_from_target: attitude.body_from_ned(),
        };
        let (y, z) = SilhouetteCentroid::default()
            .centroid(&vertices, &triangles, &pose, &camera)
            .expect("an area");
        let (y0, z0) = camera.image_from_body(&position_ft).expect("in front");
        let mut shape =
            AirframeShape::of_mesh(&vertices, &triangles, size_ft, BearingPoint::Centroid);
        let offset = shape
            .bearing_offset_px(&(position_ft / size_ft), &pose.body_from_target, 500.0)
            .expect("in front");
        assert!((offset[0] - (y - y0)).abs() < 1e-9, "{offset:?}");
        assert!((offset[1] - (z - z0)).abs() < 1e-9, "{offset:?}");
        assert!(offset[0].hypot(offset[1]) > 1.0, "{offset:?}");
    }
}
