//! The Kalman estimator stage (`[estimator] kind = "kalman"`): starts the filter of
//! [`super::kalman`] on the first measurement, fuses every camera frame at its capture time with
//! a covariance mapped from pixel noise through the sensing transform's Jacobian (a 20-pixel
//! silhouette at 200 ft counts for less than a 130-pixel one at 33 ft), or samples a continuous
//! sensor, and answers, for any instant and follower position, the estimate the guidance flies
//! on. It also records when b became known (σ_b / b̂ below a threshold).

use super::airframe::{AirframeShape, AirframeTable, ViewAngles};
use super::aspect::{body_axes_ned, pitched_by_alpha, target_span_aspect};
use super::bank::{WingLine, lateral_acceleration};
use super::kalman::{FilterEstimate, FilterNoise, FilterPrior, Gates, SwingModel, TargetFilter};
use super::merge::merged_measurement;
use super::reopening::{GateReopening, KeptOutFrame};
use super::trim_alpha::AlphaSchedule;
use super::{TargetEstimate, TargetTracker};
use crate::frames::{Mat3, Vec3};
use crate::scenario::{CovarianceAt, EstimatorSection, SizeBounds, SizeModel, TargetBank};
use crate::sensing::transform::image_from_relative_position;
use crate::sensing::{FrameRecord, scaled_position_jacobian, scaled_relative_position};
use crate::vision::{BlobStatus, ImageMeasurement};

/// With the span or airframe model, σ of a frame's maximal length when the span is not the
/// silhouette's longest dimension or the view is unknown, as a multiple of that length: the
/// frame then counts for its bearing only.
const BEARING_ONLY_LENGTH_SIGMAS: f64 = 10.0;

/// The Kalman estimator of a run.
#[derive(Debug, Clone)]
pub struct KalmanTracker {
    noise: FilterNoise,
    prior: FilterPrior,
    /// diag(σ_y², σ_z², σ_b²) × the inflation, px².
    pixel_covariance_px2: Mat3,
    /// The inflation on the pixel covariance.
    measurement_inflation: f64,
    /// The floor of a continuous sensor's variance per axis, scaled units².
    scaled_variance_floor: f64,
    focal_px: f64,
    /// b̂ is bounded to [min, max], ft (the guidance's projection bounds).
    size_bounds_ft: (f64, f64),
    known_sigma_fraction: f64,
    size_model: SizeModel,
    span_aspect_min: f64,
    /// The silhouette's shortest maximal length over the span at any view (0: no bound;
    /// `estimator.span_length_min_fraction`).
    span_length_min_fraction: f64,
    /// Where a frame's pixel covariance is mapped to r's (`estimator.covariance_at`).
    covariance_at: CovarianceAt,
    filter: Option<TargetFilter>,
    known_since_s: Option<f64>,
    /// The capture time of the latest measurement offered, fused or kept out by the gate, s.
    last_measured_s: Option<f64>,
    fused: u64,
    /// (capture time, s; νᵀ S⁻¹ ν) of every fused measurement after the first.
    innovations: Vec<(f64, f64)>,
    /// Measurements whose νᵀ S⁻¹ ν, or whose bearing's, exceeds these are not fused (∞: every
    /// one is).
    gates: Gates,
    /// Measurements the gate kept out.
    gated_out: u64,
    /// When a streak of frames the gate kept out re-opens it.
    reopening: GateReopening,
    /// Frames whose wing line was fused as the target's turn (`target_bank = "measured"`).
    bank_fused: u64,
    /// The airframe model's shape and its length model (`None` with the other models).
    airframe: Option<AirframeModel>,
    /// The airframe model's view of every frame it corrected.
    views: Vec<PredictedView>,
    /// With `target_bank = "measured"`, how the wing line's bank is read.
    bank: Option<BankReading>,
}

/// How a frame's wing line is read as the target's turn (`estimator.target_bank`).
#[derive(Debug, Clone, Copy)]
struct BankReading {
    /// σ of each end of the line across it, px.
    end_sigma_px: f64,
    /// σ of the turn beyond the line's noise, ft/s².
    accel_sigma_fps2: f64,
}

/// The airframe size model's set-up: the shape's table and the vision's length model.
#[derive(Debug, Clone)]
pub struct AirframeModel {
    /// n over view directions.
    pub table: AirframeTable,
    /// The shape at unit size, for the bearing point's offset from the reference point.
    pub shape: AirframeShape,
    /// σ of the inferred view direction beyond the filter's heading uncertainty, rad.
    pub view_sigma_rad: f64,
    /// How much the measured length reads short, px.
    pub length_bias_px: f64,
    /// [s₀, s₁] of σ(bI) = √(s₀² + (s₁ / bI)²), px and px².
    pub length_sigma_px: [f64; 2],
    /// The angle of attack the inferred attitude is pitched up by (`None`: zero).
    pub alpha: Option<AlphaSchedule>,
    /// σ of the relative error of n that no averaging removes (docs/equations.md, The
    /// airframe's shape): b̂ is off by that fraction whatever the frames, so σ_b has the floor
    /// b̂ times it.
    pub shape_sigma: f64,
}

impl AirframeModel {
    /// The model of an `[estimator]` section for the shape `shape` and its `table`.
    pub fn new(section: &EstimatorSection, table: AirframeTable, shape: AirframeShape) -> Self {
        Self {
            table,
            shape,
            view_sigma_rad: section.airframe_view_sigma_deg.to_radians(),
            length_bias_px: section.airframe_length_bias_px,
            length_sigma_px: section.airframe_length_sigma_px,
            alpha: None,
            shape_sigma: section.airframe_shape_sigma,
        }
    }

    /// The model with the inferred attitude pitched up by `alpha`'s angle of attack.
    pub fn with_alpha(self, alpha: AlphaSchedule) -> Self {
        Self {
            alpha: Some(alpha),
            ..self
        }
    }

    /// The body axes (NED from body) of a target flying at `velocity_ned_fps` with
    /// `accel_ned_fps2`: coordinated flight, pitched up by the angle of attack if known.
    fn body_axes_ned(&self, velocity_ned_fps: &Vec3, accel_ned_fps2: &Vec3) -> Option<Mat3> {
        let wind_axes = body_axes_ned(velocity_ned_fps, accel_ned_fps2)?;
        Some(match &self.alpha {
            Some(alpha) => pitched_by_alpha(
                &wind_axes,
                alpha.alpha_rad(velocity_ned_fps, accel_ned_fps2),
            ),
            None => wind_axes,
        })
    }

    /// The floor of σ_b at b̂ = `b_hat_ft`, ft: n's systematic error, added to the filter's
    /// own σ_b as a consider parameter (the filter cannot learn it, so it is not one of its
    /// states).
    fn size_sigma_floor_ft(&self, b_hat_ft: f64) -> f64 {
        b_hat_ft * self.shape_sigma
    }

    /// σ of a corrected length `b_i_px`, px.
    fn length_sigma_px(&self, b_i_px: f64) -> f64 {
        let [s0, s1] = self.length_sigma_px;
        s0.hypot(s1 / b_i_px.max(1.0))
    }
}

/// What the airframe model predicted for one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictedView {
    /// The frame's capture time, s.
    pub t_s: f64,
    /// The view direction inferred from the filter's estimate.
    pub angles: ViewAngles,
    /// n there.
    pub normalised_length: f64,
    /// Where the model put the bearing point from the reference point's image, (yI, zI), px.
    pub bearing_offset_px: [f64; 2],
}

impl KalmanTracker {
    /// The tracker of an `[estimator]` section for a camera of focal length `focal_px`,
    /// starting from b̂(0) = `b0_ft` and bounding b̂ to `size_bounds_ft`.
    pub fn new(
        section: &EstimatorSection,
        focal_px: f64,
        b0_ft: f64,
        size_bounds_ft: (f64, f64),
    ) -> Self {
        let [sy, sz, sb] = section.pixel_sigma_px;
        Self {
            noise: FilterNoise {
                jerk_psd: section.jerk_psd,
                inverse_size_psd: section.inverse_size_psd,
                gust_sigma_fps: section.target_gust_sigma_fps,
                gust_time_s: section.target_gust_time_s,
                swing: (section.leader_swing_period_s > 0.0).then(|| SwingModel {
                    omega_rps: std::f64::consts::TAU / section.leader_swing_period_s,
                    sigma_fps: section.leader_swing_sigma_fps,
                    time_s: section.leader_swing_time_s,
                }),
            },
            prior: FilterPrior {
                size_ft: b0_ft,
                inverse_size_sigma_per_ft: section.initial_inverse_size_sigma_per_ft,
                relative_velocity_sigma_fps: section.initial_relative_velocity_sigma_fps,
                acceleration_sigma_fps2: section.initial_acceleration_sigma_fps2,
                size_bounds_ft: (section.size_bounds == SizeBounds::Filter)
                    .then_some(size_bounds_ft),
            },
            pixel_covariance_px2: Mat3::from_diagonal(&Vec3::new(sy * sy, sz * sz, sb * sb))
                * section.measurement_inflation,
            measurement_inflation: section.measurement_inflation,
            scaled_variance_floor: section.scaled_sigma_floor.powi(2),
            focal_px,
            size_bounds_ft,
            known_sigma_fraction: section.known_sigma_fraction,
            size_model: section.size_model,
            span_aspect_min: section.span_aspect_min,
            span_length_min_fraction: section.span_length_min_fraction,
            covariance_at: section.covariance_at,
            filter: None,
            known_since_s: None,
            last_measured_s: None,
            fused: 0,
            innovations: Vec::new(),
            gates: Gates {
                innovation: gate_or_open(section.innovation_gate),
                bearing: gate_or_open(section.bearing_gate),
                bearing_range_ratio: section.bearing_gate_range_ratio,
            },
            gated_out: 0,
            reopening: GateReopening {
                after_s: if section.gate_reopen_s > 0.0 {
                    section.gate_reopen_s
                } else {
                    f64::INFINITY
                },
                range_ratio: section.gate_reopen_range_ratio,
                streak: None,
            },
            bank_fused: 0,
            airframe: None,
            views: Vec::new(),
            bank: (section.target_bank == TargetBank::Measured).then_some(BankReading {
                end_sigma_px: section.bank_end_sigma_px,
                accel_sigma_fps2: section.bank_accel_sigma_fps2,
            }),
        }
    }

    /// The tracker with the airframe size model's shape and length model (used when
    /// `estimator.size_model = "airframe"`).
    pub fn with_airframe(self, model: AirframeModel) -> Self {
        Self {
            airframe: Some(model),
            ..self
        }
    }

    /// With the airframe model once the filter runs: the frame's r* and covariance from its
    /// length corrected for the vision's short reading and divided by the normalised length
    /// n of the view the filter's estimate implies, the length's variance widened by n's
    /// slope times the view's uncertainty, and its bearing moved from the point the vision
    /// measures to the reference point by the shape's offset between them where the frame
    /// puts the target (`docs/equations.md`, The airframe's shape).
    fn airframe_measurement(
        &mut self,
        record: &FrameRecord,
        pixels: &ImageMeasurement,
    ) -> Option<(Vec3, Mat3)> {
        self.airframe.as_ref()?;
        let (velocity, acceleration) = self.predicted_target_motion(record)?;
        let heading_sigma_rad = self.filter.as_ref()?.heading_sigma_rad();
        let focal_px = self.focal_px;
        let model = self.airframe.as_mut()?;
        let ned_from_body = model.body_axes_ned(&velocity, &acceleration)?;
        let sight_camera = Vec3::new(focal_px, pixels.y_i_px, -pixels.z_i_px);
        let sight_body = ned_from_body.transpose() * record.ned_from_camera * sight_camera;
        let angles = ViewAngles::of_line_of_sight(&sight_body)?;
        let n = model.table.at(&angles);
        let view_sigma_rad = heading_sigma_rad.hypot(model.view_sigma_rad);
        let lengthened = ImageMeasurement {
            b_i_px: pixels.b_i_px + model.length_bias_px,
            ..*pixels
        };
        // The bearing point's offset for the target where this frame puts it (r* in camera
        // axes).
        let camera_from_ned = record.ned_from_camera.transpose();
        let bearing_offset_px = model
            .shape
            .bearing_offset_px(
                &(camera_from_ned
                    * scaled_relative_position(&lengthened, focal_px, &camera_from_ned)
                    * n.length),
                &(camera_from_ned * ned_from_body),
                focal_px,
            )
            .unwrap_or([0.0; 2]);
        let corrected = ImageMeasurement {
            y_i_px: pixels.y_i_px - bearing_offset_px[0],
            z_i_px: pixels.z_i_px - bearing_offset_px[1],
            ..lengthened
        };
        let relative_sigma = n.sigma(angles.yaw_rad, view_sigma_rad) / n.length;
        let r = scaled_relative_position(&corrected, focal_px, &camera_from_ned) * n.length;
        let at = self.linearisation_pixels(record, &corrected, n.length);
        let model = self.airframe.as_mut()?;
        let length_variance_px2 =
            model.length_sigma_px(at.b_i_px).powi(2) + (at.b_i_px * relative_sigma).powi(2);
        let mut pixel_covariance = self.pixel_covariance_px2;
        pixel_covariance[(2, 2)] = length_variance_px2 * self.measurement_inflation;
        let jacobian = scaled_position_jacobian(&at, focal_px, &record.ned_from_camera);
        let covariance = jacobian * pixel_covariance * jacobian.transpose() * n.length.powi(2);
        self.views.push(PredictedView {
            t_s: record.t_s,
            angles,
            normalised_length: n.length,
            bearing_offset_px,
        });
        Some((r, covariance))
    }

    /// The target's velocity and acceleration, ft/s and ft/s², the filter predicts at the
    /// frame's capture (None before it runs or while β̂ ≤ 0), which the size models infer its
    /// attitude from.
    fn predicted_target_motion(&mut self, record: &FrameRecord) -> Option<(Vec3, Vec3)> {
        self.filter
            .as_mut()?
            .predict_to(record.t_s, &record.follower_position_ned_ft);
        self.posterior_target_motion()
    }

    /// The target's velocity and acceleration, ft/s and ft/s², of the filter's posterior.
    fn posterior_target_motion(&self) -> Option<(Vec3, Vec3)> {
        let est = self.filter.as_ref()?.posterior();
        (est.beta_per_ft > 0.0).then(|| {
            (
                est.d_per_s / est.beta_per_ft,
                est.a_per_s2 / est.beta_per_ft,
            )
        })
    }

    /// The span's aspect factor in a frame, from the filter predicted to its capture (the
    /// span model once the filter runs; `None` otherwise).
    fn predicted_aspect(&mut self, record: &FrameRecord, pixels: &ImageMeasurement) -> Option<f64> {
        if self.size_model != SizeModel::Span {
            return None;
        }
        let (velocity, acceleration) = self.predicted_target_motion(record)?;
        target_span_aspect(
            &velocity,
            &acceleration,
            &record.ned_from_camera,
            (pixels.y_i_px, pixels.z_i_px),
            self.focal_px,
        )
    }

    /// For a frame whose view the filter cannot tell: the nearer end of the interval the
    /// length bounds R/b to whatever the view, [`span_length_min_fraction`, 1] times r*,
    /// where the filter's prediction lies outside it (docs/equations.md, The length's bounds
    /// at any view); None inside it, or without the bound.
    ///
    /// [`span_length_min_fraction`]: crate::scenario::EstimatorSection::span_length_min_fraction
    fn range_outside_length_bounds(&self, record: &FrameRecord, r_star: &Vec3) -> Option<f64> {
        if self.span_length_min_fraction <= 0.0 {
            return None;
        }
        let filter = self.filter.as_ref()?;
        let predicted = filter.estimate_at(record.t_s, &record.follower_position_ned_ft);
        let ratio = predicted.r.norm() / r_star.norm();
        if ratio < self.span_length_min_fraction {
            Some(self.span_length_min_fraction)
        } else if ratio > 1.0 {
            Some(1.0)
        } else {
            None
        }
    }

    /// The pixels the filter predicts for a frame: the image of its r̂ at the frame's capture
    /// divided by `scale` (the factor the frame's r* is multiplied by: the span's aspect or
    /// the airframe's n), r̂ being R/b (docs/equations.md, (3.3)-(3.12)). None before the
    /// filter runs or while the prediction is behind the camera.
    fn predicted_pixels(&self, record: &FrameRecord, scale: f64) -> Option<ImageMeasurement> {
        let filter = self.filter.as_ref()?;
        let predicted = filter
            .estimate_at(record.t_s, &record.follower_position_ned_ft)
            .r;
        let camera_from_ned = record.ned_from_camera.transpose();
        image_from_relative_position(&(predicted / scale), &camera_from_ned, 1.0, self.focal_px)
    }

    /// The pixels at which a frame's pixel covariance is mapped to r's
    /// (`estimator.covariance_at`): its own `measured`, or those the filter predicts
    /// ([`Self::predicted_pixels`], the measured ones where there are none).
    fn linearisation_pixels(
        &self,
        record: &FrameRecord,
        measured: &ImageMeasurement,
        scale: f64,
    ) -> ImageMeasurement {
        match self.covariance_at {
            CovarianceAt::Measurement => *measured,
            CovarianceAt::Prediction => self.predicted_pixels(record, scale).unwrap_or(*measured),
        }
    }

    /// Predicts to the measurement's time and fuses it (or starts the filter on it), unless
    /// its normalised innovation exceeds `estimator.innovation_gate` or its bearing's
    /// `estimator.bearing_gate`; whether it was fused.
    fn fuse(
        &mut self,
        t_s: f64,
        r_star: &Vec3,
        covariance: &Mat3,
        follower_position_ned_ft: &Vec3,
        follower_velocity_ned_fps: &Vec3,
    ) -> bool {
        self.last_measured_s = Some(t_s);
        match self.filter.as_mut() {
            None => {
                self.filter = Some(TargetFilter::new(
                    self.noise,
                    &self.prior,
                    r_star,
                    covariance,
                    t_s,
                    follower_position_ned_ft,
                    follower_velocity_ned_fps,
                ));
            }
            Some(filter) => {
                // The posterior stays at the last fused measurement when the gate keeps
                // this one out.
                let mut predicted = filter.clone();
                predicted.predict_to(t_s, follower_position_ned_ft);
                let gates = self.gates;
                let mut innovation = predicted.update_within(r_star, covariance, gates);
                if !innovation.fused {
                    let kept_out = KeptOutFrame {
                        t_s,
                        r_star,
                        covariance,
                        innovation: &innovation,
                    };
                    let gate = gates.innovation;
                    if let Some(taken) = self.reopening.take(&mut predicted, &kept_out, gate) {
                        innovation = taken;
                    }
                }
                if !innovation.fused {
                    self.gated_out += 1;
                    return false;
                }
                *filter = predicted;
                self.innovations.push((t_s, innovation.normalised_sq));
            }
        }
        self.fused += 1;
        self.reopening.end_streak();
        if self.known_since_s.is_none() && self.size_is_known() {
            self.known_since_s = Some(t_s);
        }
        true
    }

    /// Fuses a merged frame for its bearing alone ([`merged_measurement`]), once the filter
    /// predicts the frame's pixels.
    fn fuse_merged(&mut self, record: &FrameRecord, follower_velocity_ned_fps: &Vec3) {
        let (Some(joined), Some(predicted)) = (record.measured, self.predicted_pixels(record, 1.0))
        else {
            return;
        };
        let (r, covariance) = merged_measurement(
            &joined,
            &predicted,
            &self.pixel_covariance_px2,
            self.focal_px,
            &record.ned_from_camera,
            BEARING_ONLY_LENGTH_SIGMAS,
        );
        let position = record.follower_position_ned_ft;
        self.fuse(
            record.t_s,
            &r,
            &covariance,
            &position,
            follower_velocity_ned_fps,
        );
    }

    /// With `target_bank = "measured"`, fuses the frame's wing line as the target's
    /// acceleration across its velocity (`estimation::bank`), at the frame's capture, where
    /// the filter's view of the target puts the span at or above `span_aspect_min` (the line
    /// is then the span, not the fuselage).
    fn fuse_bank(&mut self, record: &FrameRecord, pixels: &ImageMeasurement) {
        let (Some(reading), Some(direction)) = (self.bank, record.length_direction) else {
            return;
        };
        // The filter's posterior is at the frame's capture: the frame was just fused.
        let Some((velocity, acceleration)) = self.posterior_target_motion() else {
            return;
        };
        let point_px = (pixels.y_i_px, pixels.z_i_px);
        let ned_from_camera = &record.ned_from_camera;
        let aspect = target_span_aspect(
            &velocity,
            &acceleration,
            ned_from_camera,
            point_px,
            self.focal_px,
        );
        if aspect.is_none_or(|s| s < self.span_aspect_min) {
            return;
        }
        let line = WingLine {
            point_px,
            direction,
            length_px: pixels.b_i_px,
        };
        let Some(turn) = lateral_acceleration(
            &line,
            ned_from_camera,
            self.focal_px,
            &velocity,
            reading.end_sigma_px,
        ) else {
            return;
        };
        let variance = turn.sigma_fps2.powi(2) + reading.accel_sigma_fps2.powi(2);
        let gate = self.gates.innovation;
        let Some(filter) = self.filter.as_mut() else {
            return;
        };
        if filter.update_lateral_acceleration(&turn.across_ned, turn.accel_fps2, variance, gate) {
            self.bank_fused += 1;
        }
    }

    /// b̂ = 1/β̂ within the bounds, and σ_b.
    fn bounded(&self, est: &FilterEstimate) -> TargetEstimate {
        let (min, max) = self.size_bounds_ft;
        let b_hat_ft = if est.beta_per_ft > 0.0 {
            est.size_ft().clamp(min, max)
        } else {
            max
        };
        let filter_sigma_ft = est.beta_sigma_per_ft * b_hat_ft * b_hat_ft;
        let floor_ft = self
            .airframe
            .as_ref()
            .map_or(0.0, |model| model.size_sigma_floor_ft(b_hat_ft));
        TargetEstimate {
            r: est.r,
            swing: est.swing,
            d_per_s: est.d_per_s,
            a_per_s2: est.a_per_s2,
            b_hat_ft,
            b_sigma_ft: if floor_ft > 0.0 {
                filter_sigma_ft.hypot(floor_ft)
            } else {
                filter_sigma_ft
            },
            b_sigma_reducible_ft: filter_sigma_ft,
        }
    }

    /// Whether σ_b / b̂ is below the threshold now.
    pub fn size_is_known(&self) -> bool {
        self.posterior()
            .is_some_and(|e| e.b_sigma_ft < self.known_sigma_fraction * e.b_hat_ft)
    }
}

impl TargetTracker for KalmanTracker {
    /// Fuses a camera frame (nothing when it measured nothing), the follower flying at
    /// `follower_velocity_ned_fps` (used only to start the filter). With the span model the
    /// frame's r* is corrected for the target's aspect predicted at its capture
    /// ([`super::aspect`]), or counts for its bearing only where the span is foreshortened
    /// below `estimator.span_aspect_min`; with the airframe model it is corrected for the
    /// airframe's normalised length and the vision's short reading
    /// ([`Self::airframe_measurement`]). The filter starts on the uncorrected frame.
    fn fuse_frame(&mut self, record: &FrameRecord, follower_velocity_ned_fps: &Vec3) {
        if record.status == BlobStatus::Merged {
            return self.fuse_merged(record, follower_velocity_ned_fps);
        }
        let (Some(r_star), Some(pixels)) = (record.r_measured, record.measured) else {
            return;
        };
        if let Some((r, covariance)) = self.airframe_measurement(record, &pixels) {
            let (position, velocity) =
                (record.follower_position_ned_ft, *follower_velocity_ned_fps);
            if self.fuse(record.t_s, &r, &covariance, &position, &velocity) {
                self.fuse_bank(record, &pixels);
            }
            return;
        }
        let mut r = r_star;
        let aspect = self.predicted_aspect(record, &pixels);
        // A size model that cannot tell the view once the filter runs (β̂ ≤ 0, a velocity
        // without a direction) does not know what the length measures: bearing only.
        let view_unknown = self.size_model != SizeModel::Apparent && self.filter.is_some();
        let (scale, bearing_only) = match aspect {
            Some(aspect) if aspect >= self.span_aspect_min => (aspect, false),
            None if !view_unknown => (1.0, false),
            _ => match self.range_outside_length_bounds(record, &r_star) {
                Some(bound) => (bound, false),
                None => (1.0, true),
            },
        };
        r *= scale;
        let at = self.linearisation_pixels(record, &pixels, scale);
        let jacobian = scaled_position_jacobian(&at, self.focal_px, &record.ned_from_camera);
        let mut pixel_covariance = self.pixel_covariance_px2;
        if bearing_only {
            pixel_covariance[(2, 2)] = (BEARING_ONLY_LENGTH_SIGMAS * at.b_i_px).powi(2);
        }
        let covariance = jacobian * pixel_covariance * jacobian.transpose() * (scale * scale);
        let fused = self.fuse(
            record.t_s,
            &r,
            &covariance,
            &record.follower_position_ned_ft,
            follower_velocity_ned_fps,
        );
        if fused {
            self.fuse_bank(record, &pixels);
        }
    }

    /// Fuses a continuous sensor's measurement r* taken now, with its own per-axis variance
    /// (the floor when smaller).
    fn fuse_sample(
        &mut self,
        t_s: f64,
        r_star: &Vec3,
        variance: f64,
        follower_position_ned_ft: &Vec3,
        follower_velocity_ned_fps: &Vec3,
    ) {
        let covariance = Mat3::identity() * variance.max(self.scaled_variance_floor);
        self.fuse(
            t_s,
            r_star,
            &covariance,
            follower_position_ned_ft,
            follower_velocity_ned_fps,
        );
    }

    /// The estimate the guidance flies on at `t_s` with the follower at
    /// `follower_position_ned_ft`; `None` before the first measurement.
    fn estimate_at(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> Option<TargetEstimate> {
        let filter = self.filter.as_ref()?;
        Some(self.bounded(&filter.estimate_at(t_s, follower_position_ned_ft)))
    }

    /// The estimate at the last fused measurement.
    fn posterior(&self) -> Option<TargetEstimate> {
        Some(self.bounded(&self.filter.as_ref()?.posterior()))
    }

    /// σ of the heading of the estimated target velocity, rad (infinite before the filter
    /// starts).
    fn heading_sigma_rad(&self) -> f64 {
        self.filter
            .as_ref()
            .map_or(f64::INFINITY, TargetFilter::heading_sigma_rad)
    }

    /// When σ_b / b̂ first fell below the threshold, s.
    fn known_since_s(&self) -> Option<f64> {
        self.known_since_s
    }

    /// The capture time of the latest measurement, fused or kept out by the gate, s.
    fn last_measured_s(&self) -> Option<f64> {
        self.last_measured_s
    }

    /// Measurements fused so far.
    fn fused(&self) -> u64 {
        self.fused
    }

    fn gated_out(&self) -> u64 {
        self.gated_out
    }

    fn bank_fused(&self) -> u64 {
        self.bank_fused
    }

    /// The mean νᵀ S⁻¹ ν of the measurements fused since `t_s`.
    fn mean_normalised_innovation_since(&self, t_s: f64) -> Option<f64> {
        let recent: Vec<f64> = self
            .innovations
            .iter()
            .filter(|(t, _)| *t >= t_s)
            .map(|(_, nis)| *nis)
            .collect();
        (!recent.is_empty()).then(|| recent.iter().sum::<f64>() / recent.len() as f64)
    }

    fn last_normalised_innovation(&self) -> Option<f64> {
        self.innovations.last().map(|(_, nis)| *nis)
    }

    /// β̂ = 1 / `size_ft` with σ_β = `sigma_ft` / b̂².
    fn take_size(&mut self, size_ft: f64, sigma_ft: f64) {
        if let Some(filter) = self.filter.as_mut() {
            filter.take_size(1.0 / size_ft, sigma_ft / (size_ft * size_ft));
        }
    }

    /// The airframe model's predicted views since `t_s`.
    fn predicted_views_since(&self, t_s: f64) -> Vec<PredictedView> {
        self.views
            .iter()
            .filter(|v| v.t_s >= t_s)
            .copied()
            .collect()
    }
}

/// A gate of `estimator.innovation_gate` or `bearing_gate`: ∞ (none) for 0.
fn gate_or_open(gate: f64) -> f64 {
    if gate > 0.0 { gate } else { f64::INFINITY }
}
