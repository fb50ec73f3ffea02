//! The estimator stage of the seed's adaptive laws: the law estimates b and d itself; this
//! stage hands it r, from a continuous sensor (perfect, noisy) at every integration stage, or
//! from the camera's latest delivered frame, held until the next and brought forward to the
//! present by the follower's own motion ([`HeldFrame::brought_forward`]). Before the camera's
//! first measurement the law idles.

use super::{LawEstimates, TargetMotionEstimate};
use crate::frames::Vec3;
use crate::sensing::FrameRecord;

/// A camera measurement as the guidance holds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeldFrame {
    /// r* of the frame.
    pub r: Vec3,
    /// When the frame was taken, s.
    pub t_s: f64,
    /// Where the follower was then, NED, ft.
    pub follower_position_ned_ft: Vec3,
}

impl HeldFrame {
    /// The frame's measurement, when it has one.
    pub fn of(record: &FrameRecord) -> Option<Self> {
        record.r_measured.map(|r| Self {
            r,
            t_s: record.t_s,
            follower_position_ned_ft: record.follower_position_ned_ft,
        })
    }

    /// The measurement brought forward to time `t_s`: the frame is a frame period plus the
    /// latency old, and in that time r has moved by the follower's own displacement, known
    /// from its navigation, over b̂, and by the target's drift d̂ (t - t_k) when the law
    /// estimates the scaled target velocity (velocity law):
    /// r ≈ r*(t_k) - (R_F(t) - R_F(t_k))/b̂ + d̂ (t - t_k). The seed assumed continuous,
    /// instantaneous measurements; without this the stale r* biases the adaptation every
    /// frame.
    pub fn brought_forward(
        &self,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        b_hat_ft: f64,
        target_motion: &TargetMotionEstimate,
    ) -> Vec3 {
        let own = (follower_position_ned_ft - self.follower_position_ned_ft) / b_hat_ft;
        let drift = match target_motion {
            TargetMotionEstimate::ScaledVelocity(d_hat) => *d_hat,
            TargetMotionEstimate::FilteredAccelerationBound(_) => Vec3::zeros(),
        };
        self.r - own + drift * (t_s - self.t_s)
    }
}

/// Where the guidance's measurement comes from now.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeasurementSource {
    /// The continuous sensor, evaluated at every integration stage (seed Chapters 4-6).
    Continuous,
    /// A camera frame held until the next arrives; `None` while the target is lost.
    Held(Option<HeldFrame>),
    /// No measurement has arrived yet: the guidance has not started.
    AwaitingFirst,
}

/// The estimator stage of the seed's adaptive laws: the measurement hold and its delay
/// compensation.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasurementHold {
    source: MeasurementSource,
    compensate_delay: bool,
    /// The latest frame that measured the target (held through lost frames, for pointing a
    /// gimbal at where it should be).
    last_measured: Option<HeldFrame>,
}

impl MeasurementHold {
    /// A hold for a continuous sensor, or for a camera (`continuous` false) whose frames are
    /// brought forward when `compensate_delay`.
    pub fn new(continuous: bool, compensate_delay: bool) -> Self {
        Self {
            source: if continuous {
                MeasurementSource::Continuous
            } else {
                MeasurementSource::AwaitingFirst
            },
            compensate_delay,
            last_measured: None,
        }
    }

    /// Where the measurement comes from now.
    pub fn source(&self) -> MeasurementSource {
        self.source
    }

    /// A frame's record reached the guidance: it is held from now on (a lost frame holds
    /// nothing). Returns the frame when it is the first measurement, for the guidance to
    /// start on.
    pub fn deliver(&mut self, record: &FrameRecord) -> Option<HeldFrame> {
        let frame = HeldFrame::of(record);
        let first = match (self.source, frame) {
            (MeasurementSource::AwaitingFirst, Some(first)) => Some(first),
            _ => None,
        };
        if frame.is_some() || self.source != MeasurementSource::AwaitingFirst {
            self.source = MeasurementSource::Held(frame);
        }
        if frame.is_some() {
            self.last_measured = frame;
        }
        first
    }

    /// The latest frame that measured the target.
    pub fn last_measured(&self) -> Option<HeldFrame> {
        self.last_measured
    }

    /// The held frame's measurement as the guidance is given it at `t_s` (brought forward
    /// when the hold compensates the delay, see [`HeldFrame::brought_forward`]).
    pub fn held_measurement(
        &self,
        frame: &HeldFrame,
        t_s: f64,
        follower_position_ned_ft: &Vec3,
        law: &LawEstimates,
    ) -> Vec3 {
        if self.compensate_delay {
            frame.brought_forward(
                t_s,
                follower_position_ned_ft,
                law.b_hat_ft,
                &law.target_motion,
            )
        } else {
            frame.r
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::BlobStatus;

    fn record(r: Option<Vec3>) -> FrameRecord {
        FrameRecord {
            index: 0,
            t_s: 1.0,
            status: if r.is_some() {
                BlobStatus::Ok
            } else {
                BlobStatus::NotFound
            },
            measured: None,
            truth: None,
            r_measured: r,
            follower_position_ned_ft: Vec3::new(10.0, 0.0, 0.0),
            ned_from_camera: crate::frames::Mat3::identity(),
            range_ft: 200.0,
            length_direction: None,
            centroid_vs_silhouette_px: None,
            background: None,
        }
    }

    /// A follower that flew 16 ft north since the frame, with b̂ = 8 ft and a target drifting
    /// at d̂ = [6, 0, 0] 1/s for 0.5 s: r moved by -2 + 3 on x.
    #[test]
    fn brought_forward_by_own_motion_and_drift() {
        let frame = HeldFrame::of(&record(Some(Vec3::new(25.0, 6.0, 4.0)))).expect("measured");
        let drift = TargetMotionEstimate::ScaledVelocity(Vec3::new(6.0, 0.0, 0.0));
        let now = frame.brought_forward(1.5, &Vec3::new(26.0, 0.0, 0.0), 8.0, &drift);
        assert_eq!(now, Vec3::new(26.0, 6.0, 4.0));
        let no_drift = TargetMotionEstimate::FilteredAccelerationBound(Vec3::new(6.0, 0.0, 0.0));
        let now = frame.brought_forward(1.5, &Vec3::new(26.0, 0.0, 0.0), 8.0, &no_drift);
        assert_eq!(now, Vec3::new(23.0, 6.0, 4.0));
    }

    /// Lost frames before the first measurement keep the guidance waiting; the first
    /// measured frame starts it; a lost frame afterwards holds nothing.
    #[test]
    fn first_measurement_starts_the_guidance() {
        let mut hold = MeasurementHold::new(false, true);
        assert_eq!(hold.deliver(&record(None)), None);
        assert_eq!(hold.source(), MeasurementSource::AwaitingFirst);
        let first = hold.deliver(&record(Some(Vec3::new(1.0, 2.0, 3.0))));
        assert!(first.is_some());
        assert!(matches!(hold.source(), MeasurementSource::Held(Some(_))));
        assert_eq!(hold.deliver(&record(Some(Vec3::new(1.0, 2.0, 3.0)))), None);
        hold.deliver(&record(None));
        assert_eq!(hold.source(), MeasurementSource::Held(None));
    }
}
