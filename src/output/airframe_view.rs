//! The summary's `airframe_view_last20s`: the view of the target the airframe size model
//! inferred (`estimation::airframe`) and the normalised maximal length it predicted there,
//! beside the true view and the projected mesh's true normalised length.

use crate::estimation::PredictedView;
use crate::estimation::airframe::ViewAngles;
use crate::frames::Vec3;
use crate::sim::Snapshot;
use serde::Serialize;

/// The airframe model's view against the truth, over a run's last seconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AirframeView {
    /// The target's yaw relative to the line of sight the filter's estimate implied (mean),
    /// deg: 0 seen from behind, ±90 side-on (nose right: +).
    pub predicted_yaw_deg: f64,
    /// Its pitch relative to the line of sight (circular mean), deg: 0 from behind, 90 from
    /// above, 180 from the front.
    pub predicted_pitch_deg: f64,
    /// The true yaw, from the target's attitude and the true line of sight (mean), deg.
    pub true_yaw_deg: f64,
    /// The true pitch (circular mean), deg.
    pub true_pitch_deg: f64,
    /// The normalised maximal length n the model predicted (mean).
    pub predicted_normalised_length: f64,
    /// The projected mesh's maximal length over the target's size at the true range (mean).
    pub true_normalised_length: f64,
    /// Where the model put the bearing point (`camera.bearing_point`) from the image of the
    /// target's reference point, (yI, zI), px (mean).
    pub predicted_bearing_offset_px: [f64; 2],
    /// Where the vision measured it from the true image of the reference point, px (mean).
    pub measured_bearing_offset_px: [f64; 2],
}

impl AirframeView {
    /// Over the frames since `from_s`: the model's `predicted` views, and the truth of the
    /// distinct logged frames that measured the target (camera of focal length `focal_px`,
    /// target of size `size_ft`). `None` without predictions or truth.
    pub fn since(
        predicted: &[PredictedView],
        logged: &[Snapshot],
        focal_px: f64,
        size_ft: f64,
        from_s: f64,
    ) -> Option<Self> {
        let (predicted_yaw_deg, predicted_pitch_deg) =
            mean_angles(predicted.iter().map(|v| v.angles))?;
        let mut truths: Vec<(ViewAngles, f64, [f64; 2])> = Vec::new();
        let mut last_index = None;
        for s in logged.iter().filter(|s| s.t_s >= from_s - 1e-9) {
            let Some(frame) = s.frame.filter(|f| last_index != Some(f.index)) else {
                continue;
            };
            last_index = Some(frame.index);
            let sight_body = s.target.attitude.body_from_ned() * s.relative_ned_ft;
            // A frame measured `Ok` (the only ones with an r*, and the only ones fused).
            let measured = frame.measured.filter(|_| frame.r_measured.is_some());
            if let (Some(truth), Some(measured), Some(angles)) = (
                frame.truth,
                measured,
                ViewAngles::of_line_of_sight(&sight_body),
            ) {
                let n = truth.apparent_size_ft(focal_px, frame.range_ft) / size_ft;
                let offset = [
                    measured.y_i_px - truth.y_i_px,
                    measured.z_i_px - truth.z_i_px,
                ];
                truths.push((angles, n, offset));
            }
        }
        let (true_yaw_deg, true_pitch_deg) = mean_angles(truths.iter().map(|t| t.0))?;
        let mean = |values: &mut dyn Iterator<Item = f64>| {
            let (sum, count) = values.fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
            sum / count as f64
        };
        Some(Self {
            predicted_yaw_deg,
            predicted_pitch_deg,
            true_yaw_deg,
            true_pitch_deg,
            predicted_normalised_length: mean(&mut predicted.iter().map(|v| v.normalised_length)),
            true_normalised_length: mean(&mut truths.iter().map(|t| t.1)),
            predicted_bearing_offset_px: [0, 1]
                .map(|k| mean(&mut predicted.iter().map(|v| v.bearing_offset_px[k]))),
            measured_bearing_offset_px: [0, 1].map(|k| mean(&mut truths.iter().map(|t| t.2[k]))),
        })
    }
}

/// The mean yaw and the circular mean pitch of `angles`, deg (`None` without any).
fn mean_angles(angles: impl Iterator<Item = ViewAngles>) -> Option<(f64, f64)> {
    let mut sum = Vec3::zeros();
    let mut count = 0usize;
    for a in angles {
        sum += Vec3::new(a.yaw_rad, a.pitch_rad.cos(), a.pitch_rad.sin());
        count += 1;
    }
    (count > 0).then(|| {
        let yaw = sum.x / count as f64;
        (yaw.to_degrees(), sum.z.atan2(sum.y).to_degrees())
    })
}
