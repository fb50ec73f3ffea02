//! The sensors acting at a tick: a camera frame delivered to the estimator (the first one
//! starts the law's filters), or a continuous sensor's sample for the filter.

use super::{SimError, Simulation};
use crate::estimation::GuidanceMeasurement;
use crate::frames::Vec3;
use crate::sensing::{CaptureGeometry, FrameRecord};
use std::time::Instant;

impl Simulation {
    /// The sensors act at the current tick: a camera frame that reaches the guidance goes to
    /// the estimator (the first starts the law's filters), a continuous sensor's new sample
    /// to the Kalman filter when there is one.
    pub(super) fn sense(&mut self) -> Result<(), SimError> {
        let t_s = self.time_s();
        let mut geometry = self.capture_geometry();
        if self.sensor.is_frame_tick(self.tick) {
            geometry.expected = self.expected_target(t_s, &self.state);
        }
        let delivered =
            self.sensor
                .sample(self.tick, t_s, &geometry)
                .map_err(|e| SimError::Camera {
                    t_s,
                    source: Box::new(e),
                })?;
        let started = Instant::now();
        let velocity = geometry.navigation.velocity_ned_fps;
        let first = match delivered {
            Some(record) => {
                self.losses.record(record.t_s, record.r_measured.is_some());
                if let Some(on_target) = record.on_target() {
                    self.false_locks.record(record.t_s, on_target);
                }
                let stamped = self.stamped(&record, &velocity);
                let delivery = self.estimator.deliver(&stamped, &velocity);
                self.feed_instrument(&stamped, delivery.trusted);
                if let Some(camera) = self.sensor.camera_mut() {
                    camera.settle(record.index, delivery.trusted);
                }
                delivery.first
            }
            None => {
                self.sample_continuous(&geometry, &velocity);
                false
            }
        };
        if first
            && let GuidanceMeasurement::Now { r: Some(r0), .. } =
                self.guidance_measurement(t_s, &self.state)
        {
            let guidance_x = self.layout.split_mut(&mut self.state).guidance;
            self.guidance.start_at(guidance_x, &r0);
        }
        let mut times = self.stage_times.get();
        times.estimator += started.elapsed();
        self.stage_times.set(times);
        Ok(())
    }

    /// With `estimator.size_from = "excitation"`, the frame goes to the instrument (the
    /// filter's r̂ at its capture when the filter took it, nothing otherwise), and the filter
    /// takes the instrument's size once its σ / b̂ is below `instrument_take_fraction` and
    /// b̂ is within the guidance's bounds.
    fn feed_instrument(&mut self, record: &FrameRecord, trusted: bool) {
        if self.instrument.is_none() {
            return;
        }
        let direction_ned = self.instrument_direction_ned();
        let Some(instrument) = self.instrument.as_mut() else {
            return;
        };
        let posterior = (self.estimator.filter())
            .and_then(|t| t.posterior())
            .filter(|_| trusted);
        let measured = posterior
            .as_ref()
            .map(|e| (&e.r, &record.follower_position_ned_ft));
        let amplitude = self.excitation.amplitude_at(record.t_s);
        instrument.add_frame(record.t_s, amplitude, &direction_ned, measured);
        let Some(reading) = instrument.estimate() else {
            return;
        };
        let (e, g) = (&self.scenario.estimator, &self.scenario.guidance);
        if reading.sigma_ft < e.instrument_take_fraction * reading.size_ft
            && (g.b_min_ft..=g.b_max_ft).contains(&reading.size_ft)
        {
            self.estimator.take_size(reading.size_ft, reading.sigma_ft);
        }
    }

    /// A continuous sensor's sample for the Kalman filter, when this tick draws one.
    pub(super) fn sample_continuous(
        &mut self,
        geometry: &CaptureGeometry,
        follower_velocity_ned_fps: &Vec3,
    ) {
        if self.estimator.filter().is_none() || !self.sensor.is_sample_tick(self.tick) {
            return;
        }
        let body_from_ned = geometry.camera_from_ned();
        let relative = &geometry.sensed_relative_ned_ft();
        if let Some(r_star) = self.sensor.continuous_measurement(relative, &body_from_ned) {
            let variance = self.sensor.continuous_variance(&r_star, &body_from_ned);
            self.estimator.sample(
                self.time_s(),
                &r_star,
                variance,
                &geometry.navigation.position_ned_ft,
                follower_velocity_ned_fps,
            );
        }
    }
}
