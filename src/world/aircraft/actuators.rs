//! Actuators: a first-order lag towards the position-limited command, its rate clamped to the
//! rate limit. Each actuator's position is a continuous state of the plant.

use crate::scenario::check::{self, Check};

use super::state::Controls;

/// Limits and lag of one actuator, in its own unit (rad for surfaces, fraction for throttle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActuatorLimits {
    /// Lowest position.
    pub min: f64,
    /// Highest position.
    pub max: f64,
    /// Largest |rate| of the position, per second.
    pub rate_limit_per_s: f64,
    /// Time constant τ of the lag, s.
    pub time_constant_s: f64,
}

impl ActuatorLimits {
    /// `value` clamped into [min, max].
    pub fn clamp(&self, value: f64) -> f64 {
        value.clamp(self.min, self.max)
    }

    /// Rate of the position: δ̇ = sat_rate((sat_pos(δ_cmd) - δ) / τ). A non-finite command holds
    /// the actuator where it is (a real servo ignores a garbage command; the caller's own checks
    /// report it).
    pub fn rate(&self, position: f64, command: f64) -> f64 {
        if !command.is_finite() {
            return 0.0;
        }
        let rate = (self.clamp(command) - position) / self.time_constant_s;
        rate.clamp(-self.rate_limit_per_s, self.rate_limit_per_s)
    }

    fn validate(&self, name: &str) -> Check {
        check::require(
            self.min.is_finite() && self.max.is_finite() && self.min < self.max,
            &format!("{name}.min"),
            self.min,
            format!("finite and < {name}.max = {}", self.max),
        )?;
        check::positive(&format!("{name}.rate_limit_per_s"), self.rate_limit_per_s)?;
        check::positive(&format!("{name}.time_constant_s"), self.time_constant_s)
    }
}

/// The four actuators of [`Controls`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Actuators {
    /// Elevator δe, rad.
    pub elevator: ActuatorLimits,
    /// Aileron δa, rad.
    pub aileron: ActuatorLimits,
    /// Rudder δr, rad.
    pub rudder: ActuatorLimits,
    /// Throttle δT in [0, 1].
    pub throttle: ActuatorLimits,
}

impl Actuators {
    /// Every position clamped into its limits.
    pub fn clamp(&self, controls: &Controls) -> Controls {
        Controls {
            throttle: self.throttle.clamp(controls.throttle),
            elevator_rad: self.elevator.clamp(controls.elevator_rad),
            aileron_rad: self.aileron.clamp(controls.aileron_rad),
            rudder_rad: self.rudder.clamp(controls.rudder_rad),
        }
    }

    /// Rates of the positions towards the commands (see [`ActuatorLimits::rate`]).
    pub fn rates(&self, positions: &Controls, commands: &Controls) -> Controls {
        Controls {
            throttle: self.throttle.rate(positions.throttle, commands.throttle),
            elevator_rad: self
                .elevator
                .rate(positions.elevator_rad, commands.elevator_rad),
            aileron_rad: self
                .aileron
                .rate(positions.aileron_rad, commands.aileron_rad),
            rudder_rad: self.rudder.rate(positions.rudder_rad, commands.rudder_rad),
        }
    }

    /// Whether every position lies within its limits.
    pub fn contains(&self, controls: &Controls) -> bool {
        *controls == self.clamp(controls)
    }

    pub(super) fn validate(&self) -> Check {
        self.elevator.validate("actuators.elevator")?;
        self.aileron.validate("actuators.aileron")?;
        self.rudder.validate("actuators.rudder")?;
        self.throttle.validate("actuators.throttle")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn servo() -> ActuatorLimits {
        ActuatorLimits {
            min: -0.5,
            max: 0.5,
            rate_limit_per_s: 2.0,
            time_constant_s: 0.05,
        }
    }

    #[test]
    fn small_error_is_a_first_order_lag() {
        // 0.01 rad error / 0.05 s = 0.2 rad/s, below the 2 rad/s limit.
        assert!((servo().rate(0.0, 0.01) - 0.2).abs() < 1e-12);
    }

    #[test]
    fn large_error_is_rate_limited_and_command_position_limited() {
        assert_eq!(servo().rate(0.0, 10.0), 2.0);
        assert_eq!(servo().rate(0.0, -10.0), -2.0);
        // At the limit a command beyond it asks for no motion.
        assert_eq!(servo().rate(0.5, 10.0), 0.0);
    }

    #[test]
    fn non_finite_command_holds() {
        assert_eq!(servo().rate(0.1, f64::NAN), 0.0);
        assert_eq!(servo().rate(0.1, f64::INFINITY), 0.0);
    }
}
