//! Command prefilters (Remark 10, (7.32)-(7.33)): stable low-pass filters whose states are
//! continuous states of the controller, so that the command derivatives the control laws need
//! come out of the filter equations instead of finite differences of noisy guidance commands.
//!
//! Each filter owns a slice of the controller's flat state and follows the stage pattern of
//! the crate: `initial_state`, then `derivative(x, command, dx) -> FilteredCommand`, integrated
//! by [`crate::integrate::Rk4`] with the rest of the simulation.

/// A filtered command and its derivative.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FilteredCommand {
    /// x_m, the filtered command.
    pub value: f64,
    /// ẋ_m, exact: the right-hand side of the filter equation.
    pub rate: f64,
}

/// The seed's prefilter with integral state (7.33), used for all four references V_c, φ_c,
/// θ_c, ψ_c as Remark 10 suggests:
/// ```text
/// ẋ_I = x_m - x_c
/// ẋ_m = -2 ζ ω (x_m - x_c) - ω² x_I
/// ```
/// x_m / x_c = (2ζω s + ω²)/(s² + 2ζω s + ω²): the error x_c - x_m = s²/(s² + 2ζω s + ω²) x_c
/// vanishes for constant *and ramp* commands, so a steadily turning course or a steadily
/// changing speed is followed without lag (a plain low-pass would lag a ramp by 2ζ/ω). ẋ_m
/// contains x_c itself, so it is as smooth as the command (continuous for a continuous
/// command). State `[x_I, x_m]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegralPrefilter {
    /// ω, rad/s.
    pub omega_rps: f64,
    /// ζ.
    pub zeta: f64,
}

impl IntegralPrefilter {
    /// Length of the state slice.
    pub const STATE_LEN: usize = 2;

    /// At rest at `value`: x_I = 0, x_m = value.
    pub fn initial_state(value: f64) -> [f64; 2] {
        [0.0, value]
    }

    /// (7.33): writes `[ẋ_I, ẋ_m]` into `dx[..2]` and returns x_m, ẋ_m. `x` and `dx` must hold
    /// at least two values.
    pub fn derivative(&self, x: &[f64], command: f64, dx: &mut [f64]) -> FilteredCommand {
        let (integral, value) = (x[0], x[1]);
        let error = value - command;
        let rate =
            -2.0 * self.zeta * self.omega_rps * error - self.omega_rps * self.omega_rps * integral;
        dx[0] = error;
        dx[1] = rate;
        FilteredCommand { value, rate }
    }
}

/// (7.33) with one more integrator, for references whose derivative feeds a control law:
/// ```text
/// ẋ_I = x_m - x_c
/// ẋ_m = v
/// v̇   = -a₁ v - a₂ (x_m - x_c) - a₃ x_I
/// ```
/// with (s + ω)(s² + 2ζω s + ω²) = s³ + a₁ s² + a₂ s + a₃, i.e. a₁ = (1 + 2ζ) ω,
/// a₂ = (1 + 2ζ) ω², a₃ = ω³. x_m / x_c = (a₂ s + a₃)/(s³ + a₁ s² + a₂ s + a₃): like (7.33) it
/// follows constant and ramp commands without steady error, but ẋ_m is a state, so the
/// derivative handed to the control law is continuous even when the command jumps (the seed's
/// (7.33) passes a jump in x_c straight into ẋ_m). State `[x_I, x_m, ẋ_m]`.
///
/// The zero at -a₃/a₂ = -ω/(1 + 2ζ) that follows ramps also makes a step in x_c overshoot
/// (by about half at ζ = 0.9). With `follows_ramps` off the filter is the low-pass
/// ẍ_m = ω² (x_c - x_m) - 2 ζ ω ẋ_m (x_I stays 0): no overshoot, a lag of 2ζ/ω behind a ramp.
/// An outer loop that closes on the aircraft's response (guidance on a camera's estimates)
/// wants the latter: its commands change at every frame, and each overshoot comes back to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothIntegralPrefilter {
    /// ω, rad/s.
    pub omega_rps: f64,
    /// ζ of the complex pole pair.
    pub zeta: f64,
    /// Follow ramps without lag (the integral form) or low-pass only.
    pub follows_ramps: bool,
}

impl SmoothIntegralPrefilter {
    /// Length of the state slice.
    pub const STATE_LEN: usize = 3;

    /// At rest at `value`.
    pub fn initial_state(value: f64) -> [f64; 3] {
        [0.0, value, 0.0]
    }

    /// Writes `[ẋ_I, ẋ_m, ẍ_m]` into `dx[..3]` and returns x_m, ẋ_m. `x` and `dx` must hold at
    /// least three values.
    pub fn derivative(&self, x: &[f64], command: f64, dx: &mut [f64]) -> FilteredCommand {
        let (integral, value, rate) = (x[0], x[1], x[2]);
        let w = self.omega_rps;
        let error = value - command;
        dx[1] = rate;
        if self.follows_ramps {
            let k = 1.0 + 2.0 * self.zeta;
            dx[0] = error;
            dx[2] = -k * w * rate - k * w * w * error - w * w * w * integral;
        } else {
            dx[0] = 0.0;
            dx[2] = -2.0 * self.zeta * w * rate - w * w * error;
        }
        FilteredCommand { value, rate }
    }
}

/// A second-order low-pass filter, ẍ_f = ω² (x_c - x_f) - 2 ζ ω ẋ_f: the command filter of
/// command-filtered backstepping (dynamic surface control). ẋ_f is a state, so it never
/// contains the raw command: the rate loop gets a smooth ṗ_c, q̇_c, ṙ_c. State `[x_f, ẋ_f]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecondOrderFilter {
    /// ω, rad/s.
    pub omega_rps: f64,
    /// ζ.
    pub zeta: f64,
}

impl SecondOrderFilter {
    /// Length of the state slice.
    pub const STATE_LEN: usize = 2;

    /// At rest at `value`.
    pub fn initial_state(value: f64) -> [f64; 2] {
        [value, 0.0]
    }

    /// Writes `[ẋ_f, ẍ_f]` into `dx[..2]` and returns x_f, ẋ_f. `x` and `dx` must hold at
    /// least two values.
    pub fn derivative(&self, x: &[f64], command: f64, dx: &mut [f64]) -> FilteredCommand {
        let (value, rate) = (x[0], x[1]);
        let accel = self.omega_rps * self.omega_rps * (command - value)
            - 2.0 * self.zeta * self.omega_rps * rate;
        dx[0] = rate;
        dx[1] = accel;
        FilteredCommand { value, rate }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Rk4;

    /// Both filters settle on a constant command with no steady error; (7.33) also follows a
    /// ramp without lag.
    #[test]
    fn steady_errors() {
        let integral = IntegralPrefilter {
            omega_rps: 1.0,
            zeta: 0.9,
        };
        let plain = SecondOrderFilter {
            omega_rps: 2.0,
            zeta: 0.9,
        };
        let mut x = [
            IntegralPrefilter::initial_state(50.0),
            SecondOrderFilter::initial_state(0.0),
            IntegralPrefilter::initial_state(0.0),
        ]
        .concat();
        let mut rk = Rk4::new(6);
        let dt = 0.01;
        for i in 0..4000 {
            rk.step(i as f64 * dt, dt, &mut x, |t, x, dx| {
                integral.derivative(&x[..2], 60.0, &mut dx[..2]);
                plain.derivative(&x[2..4], 0.3, &mut dx[2..4]);
                integral.derivative(&x[4..], 0.1 * t, &mut dx[4..]);
            });
        }
        assert!((x[1] - 60.0).abs() < 1e-6, "x_m = {}", x[1]);
        assert!((x[2] - 0.3).abs() < 1e-9, "x_f = {}", x[2]);
        assert!((x[5] - 4.0).abs() < 1e-6, "ramp x_m = {}", x[5]);
    }
}
