//! The loop's continuous part at (t, x), as RK4 evaluates it: the measurement the estimator
//! gives the guidance, the command frames' input, the guidance law, the gimbal's pointing,
//! the flight control and the plant, each stage timed apart.

use super::Simulation;
use super::build::mounted_camera;
use super::navigate::encoder_reading;
use crate::estimation::instrument::across_sight;
use crate::estimation::{GuidanceMeasurement, LawEstimates, TargetEstimate, TargetMotionEstimate};
use crate::follower::{Actuation, SlotLine};
use crate::frames::{Mat3, Vec3};
use crate::guidance::command::{CommandInput, ned_from_target_frame};
use crate::guidance::signals::{ExcitationOffset, FollowerCommand, GuidanceInput, GuidanceOutput};
use crate::scenario::{ExcitationFrame, InstrumentAxis};
use crate::sensing::TargetExpectation;
use crate::sensing::gimbal::{Gimbal, GimbalAngles};
use std::time::Instant;

/// One evaluation of the loop's continuous part at (t, x).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Evaluation {
    pub(super) guidance: GuidanceOutput,
    pub(super) actuation: Actuation,
}

/// `command` with `offset` added, in the command's own units.
fn offset_command(command: FollowerCommand, offset: Vec3) -> FollowerCommand {
    match command {
        FollowerCommand::Velocity(v) => FollowerCommand::Velocity(v + offset),
        FollowerCommand::Acceleration(a) => FollowerCommand::Acceleration(a + offset),
    }
}

impl Simulation {
    /// L_CB for a gimbal slice: the gimbal's angles over the fixed mount.
    pub(super) fn camera_from_body(&self, gimbal_x: &[f64]) -> Mat3 {
        mounted_camera(&self.own.mount, self.gimbal.as_ref(), gimbal_x)
    }

    /// The gimbal's command at (t, x): toward where the estimator predicts the target is, and
    /// searching about it once the target has been missing, since the start when it has not
    /// been seen yet (see [`Gimbal::command`]).
    pub(super) fn gimbal_command(&self, gimbal: &Gimbal, t_s: f64, x: &[f64]) -> GimbalAngles {
        let slices = self.layout.split(x);
        let line_of_sight = self.predicted_line_of_sight(t_s, x);
        let base_from_ned = self.navigated_base_from_ned(slices.follower);
        let missing_s = t_s - self.estimator.last_measured_s().unwrap_or(0.0);
        let angles = encoder_reading(&self.own.sensors, slices.gimbal);
        gimbal.command(&angles, line_of_sight, &base_from_ned, missing_s, t_s)
    }

    /// Where the estimator predicts the target is at (t, x), a line of sight NED from the
    /// follower's navigated position (None before the target is first measured).
    fn predicted_line_of_sight(&self, t_s: f64, x: &[f64]) -> Option<Vec3> {
        let slices = self.layout.split(x);
        let position = self.navigated_position_ned_ft(slices.follower);
        let law = self.guidance.estimates(slices.guidance);
        self.estimator.predicted_r(t_s, &position, law)
    }

    /// Where the follower expects the target at (t, x), and how large: the estimator's
    /// prediction (its span 1/|r̂| rad), or before the target is first measured the gimbal's
    /// cue (None without either).
    pub(super) fn expected_target(&self, t_s: f64, x: &[f64]) -> Option<TargetExpectation> {
        let predicted = self
            .predicted_line_of_sight(t_s, x)
            .map(|r| TargetExpectation {
                los_ned: r,
                span_rad: Some(1.0 / r.norm()),
            });
        predicted.or_else(|| {
            let cue = self.gimbal.as_ref().and_then(Gimbal::cue_ned)?;
            Some(TargetExpectation {
                los_ned: cue,
                span_rad: None,
            })
        })
    }

    /// The measurement the estimator stage gives the guidance at (t, x).
    pub(super) fn guidance_measurement(&self, t_s: f64, x: &[f64]) -> GuidanceMeasurement {
        let slices = self.layout.split(x);
        let position = self.navigated_position_ned_ft(slices.follower);
        self.estimator.guidance_measurement(
            t_s,
            &position,
            self.guidance.estimates(slices.guidance),
            || {
                let geometry = self.geometry_at(t_s, x);
                self.sensor.continuous_measurement(
                    &geometry.sensed_relative_ned_ft(),
                    &geometry.camera_from_ned(),
                )
            },
        )
    }

    /// The slot's line at (t, x) for the S-turns (`autopilot.weave_period_s`,
    /// `weave_half_width_ft`): the course of the target's estimated velocity (unit u), the
    /// follower's offset to its right, (R_c - R̂)·n, n the line's horizontal right-hand
    /// normal, R̂ = b̂ r̂ the Kalman estimate, how far it is ahead of its slot along the line,
    /// (R_c - R̂)·u, and where the slot lies from the target
    /// ([`crate::guidance::command::FormationCommand::slot_lead_and_offset_ft`]); `None` without an
    /// estimate or with a target not moving horizontally.
    pub(super) fn slot_line(&self, t_s: f64, x: &[f64]) -> Option<SlotLine> {
        let measurement = self.guidance_measurement(t_s, x);
        let GuidanceMeasurement::Now {
            estimate: Some(e), ..
        } = measurement
        else {
            return None;
        };
        let command_ned_ft = self.command_ned_ft(x, &measurement);
        let horizontal = e.d_per_s.x.hypot(e.d_per_s.y);
        (horizontal > 0.0).then(|| {
            let along = Vec3::new(e.d_per_s.x, e.d_per_s.y, 0.0) / horizontal;
            let right = Vec3::new(-along.y, along.x, 0.0);
            let slot_error_ft = command_ned_ft - e.r * e.b_hat_ft;
            let (slot_lead_ft, slot_offset_ft) = self
                .command
                .slot_lead_and_offset_ft(&command_ned_ft, &along);
            SlotLine {
                track_rad: e.d_per_s.y.atan2(e.d_per_s.x),
                cross_track_ft: slot_error_ft.dot(&right),
                ahead_of_slot_ft: slot_error_ft.dot(&along),
                slot_lead_ft,
                slot_offset_ft,
                turn_rate_rps: e.turn_rate_rps(),
            }
        })
    }

    /// The estimates b̂ and d̂ the guidance flies on at (t, x): the adaptive law's own, or the
    /// Kalman filter's (`None` before its first measurement).
    pub(super) fn estimates(
        &self,
        x: &[f64],
        measurement: &GuidanceMeasurement,
    ) -> Option<LawEstimates> {
        let guidance_x = self.layout.split(x).guidance;
        self.guidance.estimates(guidance_x).or(match measurement {
            GuidanceMeasurement::Now {
                estimate: Some(e), ..
            } => Some(LawEstimates {
                b_hat_ft: e.b_hat_ft,
                target_motion: TargetMotionEstimate::ScaledVelocity(e.d_per_s),
            }),
            _ => None,
        })
    }

    /// What the command frames follow at (t, x): the follower's attitude and rates, and the
    /// track of the target frame: the target's estimated velocity once it is trusted (the
    /// Kalman filter knows its heading; or the adaptive velocity law's d̂), none before (the
    /// frame holds). With the Kalman estimate the track leads by the frame's lag, d̂ + â τ, so that
    /// the frame does not trail a steadily turning target by its turn rate times τ.
    pub(super) fn command_input(
        &self,
        x: &[f64],
        measurement: &GuidanceMeasurement,
    ) -> CommandInput {
        let follower_x = self.layout.split(x).follower;
        let g = &self.scenario.guidance;
        let heading_gate_rad = g.command_target_heading_sigma_deg.to_radians();
        let track_ned = match (measurement, self.estimator.filter()) {
            (
                GuidanceMeasurement::Now {
                    estimate: Some(e), ..
                },
                Some(tracker),
            ) if tracker.heading_sigma_rad() < heading_gate_rad => {
                Some(e.d_per_s + e.a_per_s2 * g.command_target_lead_s)
            }
            (_, None) => match self.estimates(x, measurement) {
                Some(LawEstimates {
                    target_motion: TargetMotionEstimate::ScaledVelocity(d),
                    ..
                }) => Some(d),
                _ => None,
            },
            _ => None,
        };
        CommandInput {
            attitude: self.navigated_attitude(follower_x),
            body_rates_rps: self.follower.body_rates(follower_x),
            track_ned,
        }
    }

    /// The guidance input at (t, x) for a measurement: command, its rate, the excitation, the
    /// follower's navigation and the Kalman estimate.
    pub(super) fn guidance_input(
        &self,
        t_s: f64,
        x: &[f64],
        command: &CommandInput,
        r_measured: Option<Vec3>,
        estimate: Option<TargetEstimate>,
    ) -> GuidanceInput {
        let slices = self.layout.split(x);
        let (follower_x, command_x) = (slices.follower, slices.command);
        let (command_ned_ft, command_rate_ned_fps) = self.command.command(command_x, command);
        GuidanceInput {
            r_measured,
            command_ned_ft,
            command_rate_ned_fps,
            command_frame_rate_rps: self.command.shaping_frame_rate_rps(command_x, command),
            excitation: self.excitation_offset(t_s, command_x, command),
            follower: self.navigated_feedback(follower_x),
            estimate,
        }
    }

    /// The excitation's offset a sin(ωt) E at `t_s`, NED: E turned from its frame
    /// (`excitation.frame`) by the command's target frame at the command state `command_x`,
    /// the frame's turn included in the offset's rate.
    pub(super) fn excitation_offset(
        &self,
        t_s: f64,
        command_x: &[f64],
        command: &CommandInput,
    ) -> ExcitationOffset {
        let offset = self.excitation.command_offset(t_s);
        match self.scenario.excitation.frame {
            ExcitationFrame::Inertial => offset,
            ExcitationFrame::Target => {
                let (rotation, rotation_rate) = self.command.target_frame_turn(command_x, command);
                offset.turned(&rotation, &rotation_rate)
            }
        }
    }

    /// The excitation's unit direction E now, NED (turned from its frame as
    /// [`Self::excitation_offset`] turns it).
    pub(super) fn excitation_direction_ned(&self) -> Vec3 {
        let direction = self.excitation.direction();
        match self.scenario.excitation.frame {
            ExcitationFrame::Inertial => direction,
            ExcitationFrame::Target => {
                ned_from_target_frame(self.layout.split(&self.state).command) * direction
            }
        }
    }

    /// The direction the instrument reads the frames' increments along, NED: E, or with
    /// `estimator.instrument_axis = "across_slot"` E less its component on the slot's line
    /// of sight R_c / |R_c| now, which with `excitation.frame = "target"` and a command in
    /// the target frame is fixed in that frame as E is; a command in the body or heading
    /// frame turns with the follower, whose swing moves it, and the instrument's low-pass
    /// passes a twelfth of that wobble, as of E's (docs/equations.md, The instrument's
    /// direction).
    pub(super) fn instrument_direction_ned(&self) -> Vec3 {
        let direction = self.excitation_direction_ned();
        if self.scenario.estimator.instrument_axis == InstrumentAxis::Excitation {
            return direction;
        }
        let measurement = self.guidance_measurement(self.time_s(), &self.state);
        across_sight(&direction, &self.command_ned_ft(&self.state, &measurement))
    }

    /// R_c at x for a measurement, NED, ft: the slot the guidance flies to, without the
    /// excitation's offset.
    fn command_ned_ft(&self, x: &[f64], measurement: &GuidanceMeasurement) -> Vec3 {
        let input = self.command_input(x, measurement);
        self.command.command(self.layout.split(x).command, &input).0
    }

    /// ẋ of the whole state at (t, x), with what guidance and control decided there. The
    /// three stages are timed apart (see [`StageTimes`]).
    pub(super) fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> Evaluation {
        let started = Instant::now();
        let x_of = self.layout.split(x);
        let dx_of = self.layout.split_mut(dx);
        let measurement = self.guidance_measurement(t_s, x);
        let command = self.command_input(x, &measurement);
        self.command
            .derivative(x_of.command, &command, dx_of.command);
        if let Some(gimbal) = &self.gimbal {
            // The servo closes its loop on the encoders.
            let pointing = self.gimbal_command(gimbal, t_s, x);
            let angles = encoder_reading(&self.own.sensors, x_of.gimbal);
            gimbal.derivative(&angles, &pointing, dx_of.gimbal);
        }
        let mut out = match measurement {
            GuidanceMeasurement::NotYet => self.guidance.idle(x_of.guidance, dx_of.guidance),
            GuidanceMeasurement::Now { r, estimate } => {
                let input = self.guidance_input(t_s, x, &command, r, estimate);
                self.guidance
                    .derivative(x_of.guidance, &input, dx_of.guidance)
            }
        };
        if let Some(offset) = self.command_offset {
            out.command = offset_command(out.command, offset);
        }
        let guided = Instant::now();
        let actuation = self
            .follower
            .control(x_of.follower, &out.command, dx_of.follower);
        let controlled = Instant::now();
        self.follower
            .plant(x_of.follower, &actuation, dx_of.follower);
        let mut times = self.stage_times.get();
        times.guidance += guided - started;
        times.control += controlled - guided;
        times.plant += controlled.elapsed();
        self.stage_times.set(times);
        Evaluation {
            guidance: out,
            actuation,
        }
    }

    /// Guidance and control at the current state.
    pub(super) fn evaluate(&mut self) -> Evaluation {
        let mut scratch = std::mem::take(&mut self.scratch);
        let out = self.derivative(self.time_s(), &self.state, &mut scratch);
        self.scratch = scratch;
        out
    }
}
