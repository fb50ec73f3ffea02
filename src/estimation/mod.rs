//! The estimator stage, between sensing and guidance (docs/design.md, One tick): what the
//! guidance law is given at each instant.
//!
//! - `adaptive` (the seed's, [`hold`]): the law estimates b and d itself; this stage hands it
//!   r, continuous or the camera's held frame brought forward by the follower's own motion.
//!   The Kalman filter may run beside it for comparison (`estimator.log_kalman`).
//! - `kalman` ([`tracker`], [`kalman`]): a Kalman filter infers r, d, a and 1/b from the
//!   measurements and the follower's own velocity; the law flies on its estimate.

pub mod airframe;
pub mod aspect;
pub mod bank;
pub mod hold;
pub mod instrument;
pub mod kalman;
pub mod merge;
mod reopening;
pub mod tracker;
pub mod trim_alpha;

pub use hold::{HeldFrame, MeasurementHold, MeasurementSource};
pub use tracker::{AirframeModel, KalmanTracker, PredictedView};

use crate::frames::Vec3;
use crate::sensing::FrameRecord;

/// An estimate of how the target moves, in the estimating law's own terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TargetMotionEstimate {
    /// d̂ = V_T/b, the scaled target velocity, 1/s (velocity law, (4.5); the Kalman filter).
    ScaledVelocity(Vec3),
    /// d̂, the adaptive bound of the filtered target acceleration, ft/s (acceleration law,
    /// (5.41)).
    FilteredAccelerationBound(Vec3),
}

impl TargetEstimate {
    /// The target's turn rate over the ground, ω = (d̂ × â)·z / ‖d̂_h‖², rad/s, positive to
    /// the right (d̂ and â in the same unit of b, so b̂ cancels); 0 while it does not move
    /// horizontally.
    pub fn turn_rate_rps(&self) -> f64 {
        let (d, a) = (&self.d_per_s, &self.a_per_s2);
        let speed_squared = d.x * d.x + d.y * d.y;
        if speed_squared > 0.0 {
            (d.x * a.y - d.y * a.x) / speed_squared
        } else {
            0.0
        }
    }
}

impl TargetMotionEstimate {
    /// The estimate's vector, in its own unit.
    pub fn vector(&self) -> Vec3 {
        match self {
            Self::ScaledVelocity(v) | Self::FilteredAccelerationBound(v) => *v,
        }
    }
}

/// A law's own estimates b̂ and d̂ (the adaptive laws carry them in their state).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawEstimates {
    /// b̂, ft.
    pub b_hat_ft: f64,
    /// d̂, in the law's own terms.
    pub target_motion: TargetMotionEstimate,
}

/// What the guidance is given at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GuidanceMeasurement {
    /// No measurement has arrived yet: the law idles.
    NotYet,
    /// The measurement r the law is given (None while the target is lost) and, for the law
    /// on the Kalman estimate, the estimate (its r̂ is then the r given).
    Now {
        /// r, or r̂.
        r: Option<Vec3>,
        /// The Kalman estimate.
        estimate: Option<TargetEstimate>,
    },
}

/// The Kalman estimator's estimate at one instant, as the guidance flies on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetEstimate {
    /// r̂ = R̂/b.
    pub r: Vec3,
    /// The leader's swing in r̂, scaled (zero unless the estimator models one,
    /// `estimator.leader_swing_period_s`): r̂ less it is the leader's path, which the law flies.
    pub swing: Vec3,
    /// d̂ = V̂_T/b, 1/s.
    pub d_per_s: Vec3,
    /// â = â_T/b, 1/s².
    pub a_per_s2: Vec3,
    /// b̂ = 1/β̂ within the guidance's bounds, ft.
    pub b_hat_ft: f64,
    /// σ of b̂, ft: the filter's own and the size model's floor in quadrature.
    pub b_sigma_ft: f64,
    /// The filter's own σ of b̂, ft: what more measurements can still reduce (the
    /// excitation's measure of uncertainty; σ_b without the airframe model's shape floor,
    /// `estimator.airframe_shape_sigma`).
    pub b_sigma_reducible_ft: f64,
}

/// A filter that infers the target's relative position, motion and size from the
/// measurements and the follower's own motion. The guidance, the gimbal, the excitation and the
/// outputs use it through this interface only, so a new filter is one module implementing it
/// plus its arm in `Simulation::new`'s match on `estimator.kind`.
pub trait TargetTracker: std::fmt::Debug + Send {
    /// Fuses a camera frame (nothing when it measured nothing), the follower flying at
    /// `follower_velocity_ned_fps`.
    fn fuse_frame(&mut self, record: &FrameRecord, follower_velocity_ned_fps: &Vec3);

    /// Fuses a continuous sensor's measurement r* taken at `t_s`, of per-axis variance
    /// `variance` (scaled units²).
    fn fuse_sample(
        &mut self,
        t_s: f64,
        r_star: &Vec3,
        variance: f64,
        follower_position_ned_ft: &Vec3,
        follower_velocity_ned_fps: &Vec3,
    );

    /// The estimate at `t_s` with the follower at `follower_position_ned_ft`, b̂ within the
    /// guidance's bounds; `None` before the first measurement.
    fn estimate_at(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> Option<TargetEstimate>;

    /// The estimate at the last fused measurement (its b̂ and σ_b are the posterior's).
    fn posterior(&self) -> Option<TargetEstimate>;

    /// σ of the heading of the estimated target velocity, rad (infinite before the first
    /// measurement).
    fn heading_sigma_rad(&self) -> f64;

    /// When σ_b / b̂ first fell below the scenario's threshold, s.
    fn known_since_s(&self) -> Option<f64>;

    /// The capture time of the latest measurement of the target, fused or kept out by the
    /// innovation gate, s: the gimbal searches once none has come for a while, and a frame
    /// the gate keeps out measured something where the target was looked for.
    fn last_measured_s(&self) -> Option<f64>;

    /// Measurements fused so far.
    fn fused(&self) -> u64;

    /// Measurements the gates kept out so far (`estimator.innovation_gate`, `bearing_gate`).
    fn gated_out(&self) -> u64;

    /// Frames whose wing line was fused as the target's turn so far
    /// (`estimator.target_bank = "measured"`).
    fn bank_fused(&self) -> u64;

    /// The mean of the normalised innovations squared νᵀ S⁻¹ ν of the measurements fused at
    /// or after `t_s` (3 when the filter's model holds: χ² with 3 degrees of freedom); `None`
    /// when none was.
    fn mean_normalised_innovation_since(&self, t_s: f64) -> Option<f64>;

    /// The normalised innovation squared νᵀ S⁻¹ ν of the latest measurement fused; `None`
    /// before the first.
    fn last_normalised_innovation(&self) -> Option<f64>;

    /// What the airframe size model predicted for the frames it corrected at or after `t_s`
    /// (none with the other size models).
    fn predicted_views_since(&self, t_s: f64) -> Vec<PredictedView>;

    /// Takes b̂ = `size_ft` with σ `sigma_ft` from another reading of the size
    /// (`estimator.size_from`), every state moved with it by its covariance with the size;
    /// nothing before the filter starts.
    fn take_size(&mut self, size_ft: f64, sigma_ft: f64);
}

/// What a run's filter says at one instant, for the outputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FilterReading {
    /// The run has no filter (the adaptive law without `estimator.log_kalman`).
    NoFilter,
    /// The filter waits for its first measurement.
    Starting,
    /// The filter's estimate.
    Estimate(TargetEstimate),
}

impl FilterReading {
    /// Whether the run has a filter.
    pub fn is_present(&self) -> bool {
        !matches!(self, Self::NoFilter)
    }

    /// The estimate, once there is one.
    pub fn estimate(&self) -> Option<TargetEstimate> {
        match self {
            Self::Estimate(e) => Some(*e),
            Self::NoFilter | Self::Starting => None,
        }
    }
}

/// What became of a camera frame delivered to the estimator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Delivery {
    /// It is the guidance's first measurement.
    pub first: bool,
    /// The estimator the guidance flies on took it as a measurement of the target: one
    /// (`Ok`) that the adaptive law holds, or that the Kalman filter fused (its innovation
    /// gate did not keep it out). Such a frame is trusted.
    pub trusted: bool,
}

/// The estimator of a run.
#[derive(Debug)]
pub enum Estimator {
    /// The seed's adaptive laws, fed by the measurement hold; a filter beside them when it is
    /// logged.
    Adaptive {
        /// The measurement hold.
        hold: MeasurementHold,
        /// The filter run for comparison.
        beside: Option<Box<dyn TargetTracker>>,
    },
    /// A filter; the law flies on its estimate.
    OnFilter(Box<dyn TargetTracker>),
}

impl Estimator {
    /// A camera frame reached the guidance, the follower flying at `follower_velocity_ned_fps`:
    /// whether it is the guidance's first measurement (for the law's filters to start on) and
    /// whether the estimator the guidance flies on took it.
    pub fn deliver(&mut self, record: &FrameRecord, follower_velocity_ned_fps: &Vec3) -> Delivery {
        let fused_before = self.filter().map_or(0, |t| t.fused());
        if let Some(tracker) = self.filter_mut() {
            tracker.fuse_frame(record, follower_velocity_ned_fps);
        }
        match self {
            Self::Adaptive { hold, .. } => Delivery {
                first: hold.deliver(record).is_some(),
                trusted: record.r_measured.is_some(),
            },
            Self::OnFilter(tracker) => Delivery {
                first: fused_before == 0 && tracker.fused() > 0,
                trusted: tracker.fused() > fused_before && record.r_measured.is_some(),
            },
        }
    }

    /// A continuous sensor's measurement r* of per-axis variance `variance` was taken now:
    /// the filter fuses it (the adaptive law reads the sensor itself).
    pub fn sample(
        &mut self,
        t_s: f64,
        r_star: &Vec3,
        variance: f64,
        follower_position_ned_ft: &Vec3,
        follower_velocity_ned_fps: &Vec3,
    ) {
        if let Some(tracker) = self.filter_mut() {
            tracker.fuse_sample(
                t_s,
                r_star,
                variance,
                follower_position_ned_ft,
                follower_velocity_ned_fps,
            );
        }
    }

    /// What the guidance is given at `t_s` with the follower at `follower_position_ned_ft`:
    /// the adaptive law's measurement (`continuous` evaluates a continuous sensor; a held
    /// frame is brought forward with the law's own estimates `law`), or the filter's estimate.
    pub fn guidance_measurement(
        &self,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        law: Option<LawEstimates>,
        continuous: impl FnOnce() -> Option<Vec3>,
    ) -> GuidanceMeasurement {
        match self {
            Self::Adaptive { hold, .. } => match (hold.source(), law) {
                (MeasurementSource::AwaitingFirst, _) => GuidanceMeasurement::NotYet,
                (MeasurementSource::Continuous, _) => GuidanceMeasurement::Now {
                    r: continuous(),
                    estimate: None,
                },
                (MeasurementSource::Held(frame), Some(law)) => GuidanceMeasurement::Now {
                    r: frame
                        .map(|f| hold.held_measurement(&f, t_s, follower_position_ned_ft, &law)),
                    estimate: None,
                },
                (MeasurementSource::Held(frame), None) => GuidanceMeasurement::Now {
                    r: frame.map(|f| f.r),
                    estimate: None,
                },
            },
            Self::OnFilter(tracker) => match tracker.estimate_at(t_s, follower_position_ned_ft) {
                None => GuidanceMeasurement::NotYet,
                Some(estimate) => GuidanceMeasurement::Now {
                    r: Some(estimate.r),
                    estimate: Some(estimate),
                },
            },
        }
    }

    /// Where the estimator predicts the target is at `t_s`, r (scaled units, NED), with the
    /// follower at `follower_position_ned_ft`: the filter's r̂, or the latest frame that
    /// measured the target brought forward with the law's estimates `law` (the direction a
    /// gimbal points at); `None` before any measurement.
    pub fn predicted_r(
        &self,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        law: Option<LawEstimates>,
    ) -> Option<Vec3> {
        match self {
            Self::Adaptive { hold, .. } => {
                let frame = hold.last_measured()?;
                Some(match law {
                    Some(law) => hold.held_measurement(&frame, t_s, follower_position_ned_ft, &law),
                    None => frame.r,
                })
            }
            Self::OnFilter(tracker) => tracker
                .estimate_at(t_s, follower_position_ned_ft)
                .map(|e| e.r),
        }
    }

    /// When the latest measurement of the target was taken, s (`None` before any).
    pub fn last_measured_s(&self) -> Option<f64> {
        match self {
            Self::Adaptive { hold, .. } => hold.last_measured().map(|f| f.t_s),
            Self::OnFilter(tracker) => tracker.last_measured_s(),
        }
    }

    /// The filter takes b̂ = `size_ft` with σ `sigma_ft` from another reading of the size
    /// (see [`TargetTracker::take_size`]).
    pub fn take_size(&mut self, size_ft: f64, sigma_ft: f64) {
        if let Some(tracker) = self.filter_mut() {
            tracker.take_size(size_ft, sigma_ft);
        }
    }

    /// The filter, when the run has one (flying on it, or beside the adaptive law).
    pub fn filter(&self) -> Option<&dyn TargetTracker> {
        match self {
            Self::Adaptive { beside, .. } => beside.as_deref(),
            Self::OnFilter(tracker) => Some(tracker.as_ref()),
        }
    }

    fn filter_mut(&mut self) -> Option<&mut (dyn TargetTracker + 'static)> {
        match self {
            Self::Adaptive { beside, .. } => beside.as_deref_mut(),
            Self::OnFilter(tracker) => Some(tracker.as_mut()),
        }
    }

    /// What the filter says at `t_s` with the follower at `follower_position_ned_ft`.
    pub fn filter_reading(&self, t_s: f64, follower_position_ned_ft: &Vec3) -> FilterReading {
        match self.filter() {
            None => FilterReading::NoFilter,
            Some(f) => f
                .estimate_at(t_s, follower_position_ned_ft)
                .map_or(FilterReading::Starting, FilterReading::Estimate),
        }
    }
}
