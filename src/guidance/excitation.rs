//! Intelligent excitation (4.31, 2.28): R*_c = R_c + a(t) sin(ωt) E, with an amplitude that
//! grows with the recent tracking error and fades to k3 once the error is small. With a camera
//! the amplitude may be bounded by the field of view ([`ViewBound`]), in feet and degrees at
//! the target's estimated size, whatever units it is set in.

use super::signals::{ExcitationErrors, ExcitationOffset};
use crate::frames::Vec3;
use crate::scenario::{ExcitationError, ExcitationMode, ExcitationSection, ExcitationUnits};
use std::collections::VecDeque;

/// What the camera's field of view allows the excitation (`excitation.fov_fraction`): the
/// bearing swing a/L of an offset a at the commanded range L plus the half angle the target
/// subtends there, atan(b̂ / 2L), stays within `fraction` of the half field of view θ along the
/// excitation's direction: a ≤ L tan(f θ - atan(b̂ / 2L)) ft (0 when the target alone fills
/// that much). In scaled units that is divided by b̂, so a target larger than the prior is not
/// swung further in feet: the bound follows the estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewBound {
    /// f, in (0, 1].
    pub fraction: f64,
    /// L, the commanded range, ft.
    pub range_ft: f64,
    /// tan θ, the half field of view along the excitation's direction.
    pub tan_half_fov: f64,
}

impl ViewBound {
    /// The largest offset, ft, for a target of size `size_ft`.
    pub fn max_offset_ft(&self, size_ft: f64) -> f64 {
        let target_half_rad = (0.5 * size_ft / self.range_ft).atan();
        let swing_rad = self.fraction * self.tan_half_fov.atan() - target_half_rad;
        self.range_ft * swing_rad.max(0.0).tan()
    }
}

/// Amplitude state of the intelligent excitation. Fed once per tick with eᵀe; evaluated at
/// any time within the next step.
#[derive(Debug, Clone)]
pub struct Excitation {
    mode: ExcitationMode,
    units: ExcitationUnits,
    error: ExcitationError,
    period_s: f64,
    omega_rps: f64,
    k1: f64,
    k2: f64,
    k3: f64,
    k_sigma: f64,
    direction: Vec3,
    dt_s: f64,
    /// Continuous mode: eᵀe samples of the last period, oldest first.
    window: VecDeque<f64>,
    /// Σ window · dt.
    window_integral: f64,
    /// Per-period mode: ∫ eᵀe since the current period began.
    period_integral: f64,
    /// Index of the period the per-period integral belongs to.
    period_index: u64,
    amplitude: f64,
    amplitude_rate: f64,
    /// The field of view's bound, if any.
    view: Option<ViewBound>,
    /// b̂ the bound is taken at, ft (the prior until the estimator has one).
    size_ft: f64,
    /// The window the excitation acts in, [start, end], s.
    window_s: [f64; 2],
}

impl Excitation {
    /// Excitation from its scenario section for a simulation with step `dt_s`, its amplitude
    /// bounded by the field of view `view` (when given) at b̂ = `size_ft` until the estimator
    /// reports one.
    pub fn new(
        section: &ExcitationSection,
        dt_s: f64,
        view: Option<ViewBound>,
        size_ft: f64,
    ) -> Self {
        let direction = Vec3::from(section.direction);
        let (k1, k3) = (section.k1, section.k3);
        let mut excitation = Self {
            mode: section.mode,
            units: section.units,
            error: section.error,
            period_s: section.period_s,
            omega_rps: 2.0 * std::f64::consts::PI / section.period_s,
            k1,
            k2: section.k2,
            k3,
            k_sigma: section.k_sigma,
            direction: direction / direction.norm(),
            dt_s,
            window: VecDeque::new(),
            window_integral: 0.0,
            period_integral: 0.0,
            period_index: 0,
            amplitude: if section.mode == ExcitationMode::Off {
                0.0
            } else {
                k1
            },
            amplitude_rate: 0.0,
            view,
            size_ft,
            window_s: [section.start_s, section.end_s],
        };
        excitation.apply_view_bound();
        excitation
    }

    /// The field of view's bound at b̂, in the excitation's units (infinite without one).
    fn view_cap(&self) -> f64 {
        self.view.map_or(f64::INFINITY, |view| {
            let cap_ft = view.max_offset_ft(self.size_ft);
            match self.units {
                ExcitationUnits::Ft => cap_ft,
                ExcitationUnits::Scaled => cap_ft / self.size_ft,
            }
        })
    }

    /// Holds a(t) within the field of view's bound (ȧ = 0 while it holds it there).
    fn apply_view_bound(&mut self) {
        let cap = self.view_cap();
        if self.amplitude > cap {
            self.amplitude = cap;
            self.amplitude_rate = 0.0;
        }
    }

    /// Records what the amplitude follows at the end of the step that ends at `t_end_s`: the
    /// energy eᵀe of the error the section asks for (measured or estimated), or the
    /// estimator's σ_b, ft (`uncertainty` mode; none before the filter starts: a = k1); and
    /// the estimator's (b̂, σ_b), ft, when it has them, which the field of view's bound
    /// follows.
    pub fn record_errors(
        &mut self,
        t_end_s: f64,
        errors: &ExcitationErrors,
        size_ft: Option<(f64, f64)>,
    ) {
        if let Some((b_hat_ft, _)) = size_ft {
            self.size_ft = b_hat_ft;
        }
        if self.mode.follows_the_filter() {
            self.amplitude = size_ft.map_or(self.k1, |(b_hat_ft, sigma_ft)| {
                let uncertainty = match self.mode {
                    ExcitationMode::RelativeUncertainty => sigma_ft / b_hat_ft,
                    _ => sigma_ft,
                };
                (self.k_sigma * uncertainty).min(self.k1 - self.k3) + self.k3
            });
            self.amplitude_rate = 0.0;
        } else {
            let error = match self.error {
                ExcitationError::Measured => errors.measured,
                ExcitationError::Estimated => errors.estimated,
            };
            self.record(t_end_s, error.norm_squared());
        }
        self.apply_view_bound();
    }

    /// Records eᵀe over the step that ends at `t_end_s` and updates a(t) and ȧ(t).
    pub fn record(&mut self, t_end_s: f64, error_sq: f64) {
        match self.mode {
            ExcitationMode::Off
            | ExcitationMode::Uncertainty
            | ExcitationMode::RelativeUncertainty => {}
            ExcitationMode::Continuous => self.record_continuous(t_end_s, error_sq),
            ExcitationMode::PerPeriod => self.record_per_period(t_end_s, error_sq),
        }
    }

    /// Sliding window: a = min(k2 ∫_{t-T}^{t} eᵀe, k1 - k3) + k3 for t ≥ T, k1 before.
    fn record_continuous(&mut self, t_end_s: f64, error_sq: f64) {
        let window_len = (self.period_s / self.dt_s).round().max(1.0) as usize;
        self.window.push_back(error_sq);
        self.window_integral += error_sq * self.dt_s;
        let mut dropped = 0.0;
        if self.window.len() > window_len {
            dropped = self.window.pop_front().unwrap_or(0.0);
            self.window_integral -= dropped * self.dt_s;
        }
        // Re-sum once per window to keep round-off from accumulating.
        if self.window.len() == window_len
            && ((t_end_s / self.dt_s).round() as u64).is_multiple_of(window_len as u64)
        {
            self.window_integral = self.window.iter().sum::<f64>() * self.dt_s;
        }
        if t_end_s + 0.5 * self.dt_s < self.period_s {
            self.amplitude = self.k1;
            self.amplitude_rate = 0.0;
            return;
        }
        let growing = self.k2 * self.window_integral;
        if growing < self.k1 - self.k3 {
            self.amplitude = growing + self.k3;
            self.amplitude_rate = self.k2 * (error_sq - dropped);
        } else {
            self.amplitude = self.k1;
            self.amplitude_rate = 0.0;
        }
    }

    /// Per period (2.28): the integral over the last whole period sets a for the next one.
    fn record_per_period(&mut self, t_end_s: f64, error_sq: f64) {
        self.period_integral += error_sq * self.dt_s;
        let index = ((t_end_s + 0.5 * self.dt_s) / self.period_s).floor() as u64;
        if index > self.period_index {
            self.amplitude = (self.k2 * self.period_integral).min(self.k1 - self.k3) + self.k3;
            self.period_integral = 0.0;
            self.period_index = index;
        }
        self.amplitude_rate = 0.0;
    }

    /// E, the unit direction in the excitation's frame.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// The window w(t) the amplitude is multiplied by, and ẇ: 0 outside
    /// [`excitation.start_s`, `excitation.end_s`], 1 inside but for a raised-cosine fade of one
    /// period at either end, so that the command neither jumps nor turns sharply there (none
    /// at a start of 0: the excitation starts with the run, as the seed's).
    fn window(&self, t_s: f64) -> (f64, f64) {
        let [start_s, end_s] = self.window_s;
        let fade = |since_s: f64| {
            let phase = std::f64::consts::PI * since_s / self.period_s;
            (
                0.5 * (1.0 - phase.cos()),
                0.5 * std::f64::consts::PI / self.period_s * phase.sin(),
            )
        };
        if t_s < start_s || t_s >= end_s {
            (0.0, 0.0)
        } else if start_s > 0.0 && t_s < start_s + self.period_s {
            fade(t_s - start_s)
        } else if t_s > end_s - self.period_s {
            let (w, w_dot) = fade(end_s - t_s);
            (w, -w_dot)
        } else {
            (1.0, 0.0)
        }
    }

    /// a(t) w(t), the amplitude within the excitation's window, in its units.
    pub fn amplitude_at(&self, t_s: f64) -> f64 {
        self.amplitude * self.window(t_s).0
    }

    /// The offset a w sin(ωt) E, in the excitation's units, and its time derivative (a and ȧ
    /// held over the step; w the window, [`Self::window`]).
    pub fn offset(&self, t_s: f64) -> (Vec3, Vec3) {
        if self.mode == ExcitationMode::Off {
            return (Vec3::zeros(), Vec3::zeros());
        }
        let (w, w_dot) = self.window(t_s);
        let (a, a_dot) = (
            self.amplitude * w,
            self.amplitude_rate * w + self.amplitude * w_dot,
        );
        let (s, c) = (self.omega_rps * t_s).sin_cos();
        let offset = self.direction * (a * s);
        let rate = self.direction * (a_dot * s + a * self.omega_rps * c);
        (offset, rate)
    }

    /// The offset at `t_s` in the units the laws take it in (see [`ExcitationOffset`]).
    pub fn command_offset(&self, t_s: f64) -> ExcitationOffset {
        let (offset, rate) = self.offset(t_s);
        match self.units {
            ExcitationUnits::Ft => ExcitationOffset {
                ned_ft: offset,
                rate_ned_fps: rate,
                ..ExcitationOffset::default()
            },
            ExcitationUnits::Scaled => ExcitationOffset {
                scaled: offset,
                scaled_rate_per_s: rate,
                ..ExcitationOffset::default()
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(mode: ExcitationMode) -> ExcitationSection {
        ExcitationSection {
            mode,
            k2: 10.0,
            ..ExcitationSection::default()
        }
    }

    /// The field of view's bound: formation.toml's geometry (L = 33 ft, 60° horizontal field
    /// of view, f = 0.7) allows the 8 ft target L tan(21° - 6.9°) ≈ 8.3 ft and the 20 ft
    /// one L tan(21° - 16.9°) ≈ 2.4 ft; a target filling the view gets none.
    #[test]
    fn view_bound_shrinks_with_the_target() {
        let view = ViewBound {
            fraction: 0.7,
            range_ft: 32.0f64.hypot(8.0),
            tan_half_fov: 30f64.to_radians().tan(),
        };
        assert!(
            (view.max_offset_ft(8.0) - 8.3).abs() < 0.1,
            "{}",
            view.max_offset_ft(8.0)
        );
        assert!(
            (view.max_offset_ft(20.0) - 2.4).abs() < 0.1,
            "{}",
            view.max_offset_ft(20.0)
        );
        assert_eq!(view.max_offset_ft(40.0), 0.0);
    }

    /// In scaled units the bound follows b̂: the amplitude in feet, a b̂, never exceeds the
    /// view's offset, however large the estimate grows.
    #[test]
    fn scaled_amplitude_is_bounded_in_feet() {
        let view = ViewBound {
            fraction: 0.7,
            range_ft: 33.0,
            tan_half_fov: 30f64.to_radians().tan(),
        };
        let uncertain = ExcitationSection {
            mode: ExcitationMode::Uncertainty,
            k1: 0.4,
            k3: 0.0,
            k_sigma: 1.0,
            ..ExcitationSection::default()
        };
        let mut ex = Excitation::new(&uncertain, 0.01, Some(view), 4.0);
        let errors = ExcitationErrors::default();
        ex.record_errors(0.01, &errors, Some((8.0, 1.0)));
        assert_eq!(
            ex.amplitude, 0.4,
            "3.2 ft is inside the 8 ft target's bound"
        );
        for b_hat_ft in [16.0, 20.0, 25.0] {
            ex.record_errors(0.02, &errors, Some((b_hat_ft, 1.0)));
            let offset_ft = ex.amplitude * b_hat_ft;
            assert!(
                offset_ft <= view.max_offset_ft(b_hat_ft) + 1e-12,
                "{b_hat_ft}"
            );
            assert!(offset_ft < 0.4 * b_hat_ft, "{b_hat_ft}: bound not applied");
        }
    }

    /// With the relative uncertainty, targets of 8 and 20 ft known to the same fraction are
    /// swung by the same feet (k_σ σ_b / b̂); with the uncertainty in feet the larger one is
    /// swung 2.5 times as far.
    #[test]
    fn relative_uncertainty_swings_every_size_alike() {
        let amplitude_ft = |mode, b_hat_ft: f64| {
            let section = ExcitationSection {
                mode,
                units: ExcitationUnits::Ft,
                k1: 30.0,
                k3: 0.0,
                k_sigma: 63.0,
                ..ExcitationSection::default()
            };
            let mut ex = Excitation::new(&section, 0.01, None, 4.0);
            ex.record_errors(
                0.01,
                &ExcitationErrors::default(),
                Some((b_hat_ft, 0.01 * b_hat_ft)),
            );
            ex.amplitude
        };
        let relative = [8.0, 20.0].map(|b| amplitude_ft(ExcitationMode::RelativeUncertainty, b));
        assert!(
            relative.iter().all(|a| (a - 0.63).abs() < 1e-12),
            "{relative:?}"
        );
        let absolute = [8.0, 20.0].map(|b| amplitude_ft(ExcitationMode::Uncertainty, b));
        assert!(
            (absolute[1] / absolute[0] - 2.5).abs() < 1e-12,
            "{absolute:?}"
        );
    }

    /// During the first period the amplitude is k1.
    #[test]
    fn first_period_is_k1() {
        let mut ex = Excitation::new(&section(ExcitationMode::Continuous), 0.01, None, 8.0);
        for i in 1..290 {
            ex.record(i as f64 * 0.01, 0.0);
            assert_eq!(ex.amplitude, 0.5);
        }
    }

    /// With a constant eᵀe = c, the window integral is c T, so a = min(k2 c T, k1 - k3) + k3.
    #[test]
    fn continuous_amplitude_follows_window_integral() {
        let dt = 0.001;
        let mut ex = Excitation::new(&section(ExcitationMode::Continuous), dt, None, 8.0);
        let c = 0.01;
        for i in 1..=5000 {
            ex.record(i as f64 * dt, c);
        }
        let expected = 10.0 * c * 3.0 + 0.0002;
        assert!((ex.amplitude - expected).abs() < 1e-9, "{}", ex.amplitude);
        // A large error saturates at k1.
        for i in 5001..=9000 {
            ex.record(i as f64 * dt, 1.0);
        }
        assert!((ex.amplitude - 0.5).abs() < 1e-12);
        // Zero error for a whole period: the floor k3.
        for i in 9001..=12100 {
            ex.record(i as f64 * dt, 0.0);
        }
        assert!((ex.amplitude - 0.0002).abs() < 1e-12);
    }

    /// Per period: the amplitude changes only at period boundaries.
    #[test]
    fn per_period_amplitude_is_held() {
        let dt = 0.01;
        let mut ex = Excitation::new(&section(ExcitationMode::PerPeriod), dt, None, 8.0);
        let mut values = Vec::new();
        for i in 1..=900 {
            ex.record(i as f64 * dt, 0.001);
            values.push(ex.amplitude);
        }
        // Periods end at ticks 300, 600, 900: a changes there and nowhere else.
        for (i, w) in values.windows(2).enumerate() {
            let tick = i + 2;
            if tick % 300 != 0 {
                assert_eq!(w[0], w[1], "changed at tick {tick}");
            }
        }
        assert!((values[899] - (10.0 * 0.001 * 3.0 + 0.0002)).abs() < 1e-9);
    }

    /// The offset's derivative is the time derivative of the offset (a held).
    #[test]
    fn offset_rate_is_derivative() {
        let ex = Excitation::new(&section(ExcitationMode::Continuous), 0.001, None, 8.0);
        let t = 1.3;
        let h = 1e-6;
        let fd = (ex.offset(t + h).0 - ex.offset(t - h).0) / (2.0 * h);
        assert!((fd - ex.offset(t).1).norm() < 1e-6);
    }

    /// The window: nothing before its start or after its end, the whole amplitude between the
    /// fades, and through the fades an offset whose rate is its derivative (no jump, no kink).
    #[test]
    fn the_window_fades_the_swing_in_and_out() {
        let windowed = ExcitationSection {
            mode: ExcitationMode::Uncertainty,
            period_s: 4.0,
            k1: 0.8,
            start_s: 30.0,
            end_s: 120.0,
            ..ExcitationSection::default()
        };
        let ex = Excitation::new(&windowed, 0.001, None, 8.0);
        for t_s in [0.0, 29.9, 120.0, 139.0] {
            assert_eq!(ex.offset(t_s), (Vec3::zeros(), Vec3::zeros()), "t = {t_s}");
            assert_eq!(ex.amplitude_at(t_s), 0.0);
        }
        for t_s in [34.0, 70.0, 115.9] {
            assert_eq!(ex.amplitude_at(t_s), 0.8, "t = {t_s}");
        }
        assert!(
            (ex.amplitude_at(32.0) - 0.4).abs() < 1e-12,
            "half way through the fade in"
        );
        assert!(
            (ex.amplitude_at(118.0) - 0.4).abs() < 1e-12,
            "and through the fade out"
        );
        let h = 1e-6;
        for t_s in [30.5, 31.7, 33.9, 116.1, 117.3, 119.8] {
            let fd = (ex.offset(t_s + h).0 - ex.offset(t_s - h).0) / (2.0 * h);
            assert!((fd - ex.offset(t_s).1).norm() < 1e-6, "t = {t_s}");
        }
    }
}
