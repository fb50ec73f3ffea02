//! The Chapter 5 acceleration guidance law in a self-contained closed loop with a kinematic
//! follower (Ṙ_F = V_F, V̇_F = a_F) and perfect measurements r = (R_T - R_F) / b, b = 8 ft.
//! Invariants shown:
//! (a) the ẇ_f the law feeds back in (5.38) is the time derivative of w_f along the closed-loop
//!     trajectory (catches a wrong ḣ or ẏ_c, including the -b̂' y_c / b̂ term);
//! (b) with a straight-flying target (a_T = 0, so d = 0) the combined error ξ_a = [e; z̃]
//!     built from the TRUE z = x - (1/b) B (w + d) (5.2) decays by three orders of magnitude
//!     (Theorems 12-13);
//! (c) the seed's formation run (Section 5.7, Figs 5.2-5.4): b̂ → 8 ft, ‖d̂‖ grows and settles,
//!     a_F follows a_T, the relative position settles on R_c;
//! (d) interception (Remark 6) meets ‖R‖ < 2.4 ft;
//! (f) with noisy measurements y* = r + n (6.39)-(6.42) the loop stays bounded and b̂ near b.

use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use std::cell::Cell;
use std::f64::consts::PI;
use wingman::frames::Vec3;
use wingman::guidance::GuidanceInput;
use wingman::guidance::acceleration::AccelerationGuidance;
use wingman::guidance::signals::{AccelerationGuidanceOutput, ExcitationOffset};
use wingman::integrate::Rk4;
use wingman::scenario::{
    AccelerationSection, GuidanceSection, ObserverGainMode, TargetMotion, TargetSection,
};
use wingman::world::target::TargetMotionModel;

/// True target size b, ft (the seed's).
const B_FT: f64 = 8.0;
/// Offset of the guidance slice in the closed-loop state [R_F (3), V_F (3), guidance].
const G: usize = 6;

/// Excitation added to R_c: a constant-amplitude sinusoid (ft or scaled) along x.
#[derive(Clone, Copy)]
enum Excitation {
    Off,
    Ft { amplitude_ft: f64, omega_rps: f64 },
    Scaled { amplitude: f64, omega_rps: f64 },
}

struct ClosedLoop {
    law: AccelerationGuidance,
    target: TargetMotionModel,
    command_ned_ft: Vec3,
    excitation: Excitation,
    /// Measurement noise n added to r, held over each step.
    noise: Cell<Vec3>,
}

impl ClosedLoop {
    fn new(guidance: &GuidanceSection, target: &TargetSection, command_ned_ft: Vec3) -> Self {
        Self::with_section(
            &AccelerationSection::default(),
            guidance,
            target,
            command_ned_ft,
        )
    }

    fn with_section(
        section: &AccelerationSection,
        guidance: &GuidanceSection,
        target: &TargetSection,
        command_ned_ft: Vec3,
    ) -> Self {
        Self {
            law: AccelerationGuidance::new(section, guidance, None),
            target: TargetMotionModel::from_section(target).expect("closed form"),
            command_ned_ft,
            excitation: Excitation::Off,
            noise: Cell::new(Vec3::zeros()),
        }
    }

    /// Follower at the origin flying at V_F(0) (the seed's [50, 0, 0] ft/s: the target's).
    fn initial_state(&self, follower_velocity_fps: Vec3) -> Vec<f64> {
        let r0 = self.target.position_ned_ft(0.0) / B_FT;
        let mut x = vec![0.0, 0.0, 0.0];
        x.extend(follower_velocity_fps.as_slice());
        x.extend(self.law.initial_state(&r0));
        x
    }

    fn input(&self, t_s: f64, x: &[f64]) -> GuidanceInput {
        let follower = Vec3::new(x[0], x[1], x[2]);
        let e = Vec3::x();
        let (ft, ft_rate, scaled, scaled_rate) = match self.excitation {
            Excitation::Off => (0.0, 0.0, 0.0, 0.0),
            Excitation::Ft {
                amplitude_ft: a,
                omega_rps: w,
            } => (a * (w * t_s).sin(), a * w * (w * t_s).cos(), 0.0, 0.0),
            Excitation::Scaled {
                amplitude: a,
                omega_rps: w,
            } => (0.0, 0.0, a * (w * t_s).sin(), a * w * (w * t_s).cos()),
        };
        GuidanceInput {
            r_measured: Some(
                (self.target.position_ned_ft(t_s) - follower) / B_FT + self.noise.get(),
            ),
            command_ned_ft: self.command_ned_ft,
            command_rate_ned_fps: Vec3::zeros(),
            command_frame_rate_rps: Vec3::zeros(),
            excitation: ExcitationOffset {
                ned_ft: e * ft,
                rate_ned_fps: e * ft_rate,
                scaled: e * scaled,
                scaled_rate_per_s: e * scaled_rate,
            },
            follower: None,
            estimate: None,
        }
    }

    fn derivative(&self, t_s: f64, x: &[f64], dx: &mut [f64]) -> AccelerationGuidanceOutput {
        let out = self
            .law
            .derivative(&x[G..], &self.input(t_s, x), &mut dx[G..]);
        dx[0..3].copy_from_slice(&x[3..6]);
        dx[3..6].copy_from_slice(out.accel_cmd_ned_fps2.as_slice());
        out
    }

    /// Integrates with RK4 at `dt_s` for `ticks` steps; `observe(t, x, out)` sees the state
    /// and the law's output at every tick, t = 0 included. Stops early when it returns false.
    fn run(
        &self,
        x: &mut [f64],
        dt_s: f64,
        ticks: usize,
        mut observe: impl FnMut(f64, &[f64], &AccelerationGuidanceOutput) -> bool,
    ) {
        let mut rk = Rk4::new(x.len());
        let mut scratch = vec![0.0; x.len()];
        let out = self.derivative(0.0, x, &mut scratch);
        if !observe(0.0, x, &out) {
            return;
        }
        for k in 0..ticks {
            let t = k as f64 * dt_s;
            rk.step(t, dt_s, x, |t, x, dx| {
                self.derivative(t, x, dx);
            });
            self.law.enforce_bounds(&mut x[G..]);
            let t_end = (k + 1) as f64 * dt_s;
            let out = self.derivative(t_end, x, &mut scratch);
            if !observe(t_end, x, &out) {
                return;
            }
        }
    }
}

fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    (sum / n.max(1) as f64).sqrt()
}

/// The combined error ξ_a = [e; z̃] (12 values) from the true state: per axis
/// z_i = [r_i, ṙ_i - (w_i + d_i)/b] (5.2) with d = 0 (a_T = 0), e = z - z_m, z̃ = z - ẑ.
fn combined_error(lp: &ClosedLoop, t_s: f64, x: &[f64]) -> Vec<f64> {
    let r = (lp.target.position_ned_ft(t_s) - Vec3::new(x[0], x[1], x[2])) / B_FT;
    let r_rate = (lp.target.velocity_ned_fps(t_s) - Vec3::new(x[3], x[4], x[5])) / B_FT;
    let state = lp.law.unpack(&x[G..]);
    let w = state.w_fps;
    let mut xi = Vec::with_capacity(12);
    for i in 0..3 {
        let z = [r[i], r_rate[i] - w[i] / B_FT];
        let (z_m, z_hat) = (state.z_model[i], state.z_hat[i]);
        xi.extend([z[0] - z_m[0], z[1] - z_m[1]]);
        xi.extend([z[0] - z_hat[0], z[1] - z_hat[1]]);
    }
    xi
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// One sample of the derivative check.
struct Sample {
    w_f: Vec3,
    w_f_rate: Vec3,
    /// b̂ and d̂ strictly inside Ω_0: the projection is the identity.
    inside: bool,
}

/// (a) ẇ_f = d/dt w_f along the closed loop. The check is a central difference of w_f over
/// ±1 tick (1 ms) on the RK4 trajectory, whose truncation error is dt²/6 times the third
/// derivative of w_f, plus RK4's local error (1e-12). It runs over the first 20 s, while b̂
/// moves fastest, with R_c and a 4 ft excitation entering y_c through 1/b̂, so the
/// -b̂' y_c,ft / b̂² part of ẏ_c (times b̂ k1 in ẇ_f) is large; the test asserts that this
/// part is at least 100 times the tolerance, so omitting it would fail. Points where b̂ or d̂
/// touch their projection bounds are skipped: there Proj switches on within the 0.03 ft band
/// between Ω_0 and Ω_1 (ε = 1), i.e. within a tick, and no 1 ms difference resolves it
/// (without the shaping filter the 200 ft initial error drives b̂ from 4 to 30 and back to
/// 1 ft in the first 1.2 s).
#[test]
fn virtual_control_rate_is_its_derivative() {
    for (shaping_pole_rps, dt) in [(0.1, 1e-3), (0.0, 1e-4)] {
        let guidance = GuidanceSection {
            shaping_pole_rps,
            ..GuidanceSection::default()
        };
        let mut lp = ClosedLoop::new(
            &guidance,
            &TargetSection::default(),
            Vec3::new(32.0, 8.0, 0.0),
        );
        lp.excitation = Excitation::Ft {
            amplitude_ft: 4.0,
            omega_rps: 2.0 * PI / 3.0,
        };
        let mut x = lp.initial_state(Vec3::new(50.0, 0.0, 0.0));
        let mut samples: Vec<Sample> = Vec::new();
        let mut largest_b_rate_term: f64 = 0.0;
        let k1 = lp.law.axis(0).k[0];
        let ticks = (20.0 / dt) as usize;
        lp.run(&mut x, dt, ticks, |t, x, out| {
            let state = lp.law.unpack(&x[G..]);
            let (b_hat, d_hat) = (state.b_hat_ft, state.d_hat_fps);
            let inside = b_hat > guidance.b_min_ft
                && b_hat < guidance.b_max_ft
                && d_hat.norm() < AccelerationSection::default().d_hat_max_fps;
            samples.push(Sample {
                w_f: out.virtual_control_fps,
                w_f_rate: out.virtual_control_rate_fps2,
                inside,
            });
            // The ft part of y_c and its b̂' term in ẇ_f: b̂ k1 b̂' y_c,ft / b̂².
            let input = lp.input(t, x);
            let ft_part = if shaping_pole_rps > 0.0 {
                input.excitation.ned_ft
            } else {
                input.command_ned_ft + input.excitation.ned_ft
            };
            if inside {
                // Relative to the same scale as the check below.
                let term = k1 * out.b_hat_rate_fps * ft_part.amax() / b_hat;
                let scale = out.virtual_control_rate_fps2.amax().max(1.0);
                largest_b_rate_term = largest_b_rate_term.max(term.abs() / scale);
            }
            true
        });
        let tolerance = 5e-4;
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for k in 1..samples.len() - 1 {
            if !(samples[k - 1].inside && samples[k].inside && samples[k + 1].inside) {
                continue;
            }
            let fd = (samples[k + 1].w_f - samples[k - 1].w_f) / (2.0 * dt);
            // Relative to the size of ẇ_f (thousands of ft/s² in the first second without
            // shaping), absolute below 1 ft/s².
            let scale = samples[k].w_f_rate.amax().max(1.0);
            let e = (fd - samples[k].w_f_rate).amax() / scale;
            worst = worst.max(e);
            checked += 1;
        }
        println!(
            "shaping {shaping_pole_rps}, dt {dt}: {checked} points, worst |FD - ẇ_f| / max(|ẇ_f|, 1) = \
             {worst:.3e}, largest b̂' term relative to it {largest_b_rate_term:.3}"
        );
        assert!(
            checked > ticks * 9 / 10,
            "only {checked} points inside the bounds"
        );
        assert!(worst < tolerance, "worst {worst}");
        assert!(largest_b_rate_term > 100.0 * tolerance);
    }
}

/// (b) The closed-loop Lyapunov check. Target flying straight at [50, 0, 0] ft/s (a_T = 0, so
/// d ≡ 0), follower starting at the same velocity, R_c = [32, 8, 0] ft without shaping or
/// excitation, and the observer started off the true z by [1, 0.5] on every axis so that
/// ‖ξ_a(0)‖ ≈ 1.9. Theorem 13 with d = 0: ξ_a → 0. Asserted: ‖ξ_a‖ < 1e-3 ‖ξ_a(0)‖ at every
/// tick from 60 s to 100 s (measured: below that for good from 8.5 s; after 60 s at most
/// 2.5e-11 of its start, so the bound has a wide margin yet fails if ξ_a only stays bounded).
#[test]
fn combined_error_decays_for_straight_target() {
    let guidance = GuidanceSection {
        shaping_pole_rps: 0.0,
        ..GuidanceSection::default()
    };
    let target = TargetSection {
        motion: TargetMotion::Straight,
        straight_velocity_fps: [50.0, 0.0, 0.0],
        ..TargetSection::default()
    };
    let lp = ClosedLoop::new(&guidance, &target, Vec3::new(32.0, 8.0, 0.0));
    let mut x = lp.initial_state(Vec3::new(50.0, 0.0, 0.0));
    let mut state = lp.law.unpack(&x[G..]);
    for z_hat in state.z_hat.iter_mut() {
        *z_hat += nalgebra::Vector2::new(1.0, 0.5);
    }
    state.pack(&mut x[G..]);
    let xi0 = norm(&combined_error(&lp, 0.0, &x));
    assert!(xi0 > 1.0, "the start must be off the origin: {xi0}");
    let mut below_since: Option<f64> = None;
    let mut worst_after_60: f64 = 0.0;
    lp.run(&mut x, 1e-3, 100_000, |t, x, _| {
        let xi = norm(&combined_error(&lp, t, x)) / xi0;
        if xi < 1e-3 {
            below_since.get_or_insert(t);
        } else {
            below_since = None;
        }
        if t >= 60.0 {
            worst_after_60 = worst_after_60.max(xi);
        }
        true
    });
    println!(
        "‖ξ_a(0)‖ = {xi0:.3}; below 1e-3 of it since {below_since:?} s; worst after 60 s: \
         {worst_after_60:.2e}; b̂ = {:.3} ft",
        lp.law.unpack(&x[G..]).b_hat_ft
    );
    assert!(worst_after_60 < 1e-3, "ξ_a ratio {worst_after_60}");
}

/// One logged instant of the seed-like run.
struct Row {
    t_s: f64,
    accel_fps2: Vec3,
    target_accel_fps2: Vec3,
    relative_ft: Vec3,
}

/// Seed-like formation run: seed target profile, V_F(0) = [50, 0, 0], R_c = [32, 8, 0] ft,
/// shaping filter at -0.1 from r(0) (Chapter 4), defaults of `[acceleration]`.
fn seed_formation(excitation: Excitation) -> Formation {
    let mut lp = ClosedLoop::new(
        &GuidanceSection::default(),
        &TargetSection::default(),
        Vec3::new(32.0, 8.0, 0.0),
    );
    lp.excitation = excitation;
    let mut x = lp.initial_state(Vec3::new(50.0, 0.0, 0.0));
    let mut rows = Vec::with_capacity(140_001);
    let mut d_hat_120 = 0.0;
    let started = std::time::Instant::now();
    lp.run(&mut x, 1e-3, 140_000, |t, x, out| {
        if (t - 120.0).abs() < 5e-4 {
            d_hat_120 = lp.law.unpack(&x[G..]).d_hat_fps.norm();
        }
        rows.push(Row {
            t_s: t,
            accel_fps2: out.accel_cmd_ned_fps2,
            target_accel_fps2: lp.target.accel_ned_fps2(t),
            relative_ft: lp.target.position_ned_ft(t) - Vec3::new(x[0], x[1], x[2]),
        });
        true
    });
    println!(
        "140 s at dt = 1 ms: {:.3} s wall",
        started.elapsed().as_secs_f64()
    );
    Formation {
        rows,
        b_hat_ft: lp.law.unpack(&x[G..]).b_hat_ft,
        d_hat_norm: lp.law.unpack(&x[G..]).d_hat_fps.norm(),
        d_hat_norm_120: d_hat_120,
    }
}

/// What a seed-like formation run reports.
struct Formation {
    rows: Vec<Row>,
    /// b̂ at 140 s, ft.
    b_hat_ft: f64,
    /// ‖d̂‖ at 140 s and at 120 s (when the target stops manoeuvring).
    d_hat_norm: f64,
    d_hat_norm_120: f64,
}

/// RMS(a_F - a_T) / RMS(a_T) on `axis` over t in [60, 110] s, and the RMS of R - R_c over
/// the last 20 s.
fn tracking(rows: &[Row], axis: usize) -> (f64, f64) {
    let window: Vec<_> = rows
        .iter()
        .filter(|r| (60.0..=110.0).contains(&r.t_s))
        .collect();
    let difference = rms(window
        .iter()
        .map(|r| r.accel_fps2[axis] - r.target_accel_fps2[axis]));
    let target = rms(window.iter().map(|r| r.target_accel_fps2[axis]));
    let command = [32.0, 8.0, 0.0][axis];
    let position = rms(rows
        .iter()
        .filter(|r| r.t_s > 120.0)
        .map(|r| r.relative_ft[axis] - command));
    (difference / target, position)
}

/// (c) The seed's Section 5.7 run without excitation (the shaping filter's slow approach
/// from r(0) and the target's manoeuvres identify b on their own). Bounds are the issue's:
/// b̂ within 5% of 8 ft at 140 s (measured 8.12 ft); on every axis RMS(a_F - a_T) <
/// 0.25 RMS(a_T) over [60, 110] s (measured 0.07, 0.014, 0.05); position RMS vs R_c over the
/// last 20 s < 1.5 ft (measured 0.36, 0.09, 0.01 ft). ‖d̂‖ settles near the seed's Fig 5.4
/// value (measured 5.8): asserted in [3, 10], between "barely adapted" and half the bound,
/// and settled: the last 20 s (a_T = 0 after 120 s) add less than 1% (measured 0.0%).
#[test]
fn seed_formation_run_follows_target() {
    let run = seed_formation(Excitation::Off);
    let (b_hat, d_hat) = (run.b_hat_ft, run.d_hat_norm);
    println!(
        "b̂(140) = {b_hat:.3} ft, ‖d̂(140)‖ = {d_hat:.3}, ‖d̂(120)‖ = {:.3}",
        run.d_hat_norm_120
    );
    assert!((b_hat - B_FT).abs() < 0.05 * B_FT, "b̂ = {b_hat}");
    assert!((3.0..=10.0).contains(&d_hat), "‖d̂‖ = {d_hat}");
    assert!(d_hat - run.d_hat_norm_120 < 0.01 * d_hat);
    for axis in 0..3 {
        let (ratio, position) = tracking(&run.rows, axis);
        println!(
            "axis {axis}: RMS(a_F - a_T)/RMS(a_T) = {ratio:.3}, position RMS {position:.3} ft"
        );
        assert!(ratio < 0.25, "axis {axis}: ratio {ratio}");
        assert!(position < 1.5, "axis {axis}: position RMS {position}");
    }
}

/// (c') The same run with the Chapter 4 excitation on x (0.5 scaled = 4 ft at T = 3 s, held
/// at full amplitude: with the reference model's lag the y - y_c error keeps the intelligent
/// amplitude at k1). The axes it does not act on (y, z) still meet the bounds; x
/// carries the commanded oscillation b a ω² ≈ 17 ft/s² and is reported, not bounded.
#[test]
fn seed_formation_with_excitation_on_x() {
    let run = seed_formation(Excitation::Scaled {
        amplitude: 0.5,
        omega_rps: 2.0 * PI / 3.0,
    });
    let (b_hat, d_hat) = (run.b_hat_ft, run.d_hat_norm);
    println!("excited: b̂(140) = {b_hat:.3} ft, ‖d̂(140)‖ = {d_hat:.3}");
    assert!((b_hat - B_FT).abs() < 0.05 * B_FT, "b̂ = {b_hat}");
    for axis in 0..3 {
        let (ratio, position) = tracking(&run.rows, axis);
        println!(
            "axis {axis}: RMS(a_F - a_T)/RMS(a_T) = {ratio:.3}, position RMS {position:.3} ft"
        );
        if axis > 0 {
            assert!(ratio < 0.25, "axis {axis}: ratio {ratio}");
            assert!(position < 1.5, "axis {axis}: position RMS {position}");
        }
    }
}

/// Runs an interception (R_c = 0, no excitation) and returns (time of ‖R‖ < 2.4 ft, peak
/// ‖a_F‖ until then).
fn intercept(shaping_pole_rps: f64) -> (Option<f64>, f64) {
    let guidance = GuidanceSection {
        shaping_pole_rps,
        ..GuidanceSection::default()
    };
    let lp = ClosedLoop::new(&guidance, &TargetSection::default(), Vec3::zeros());
    let mut x = lp.initial_state(Vec3::new(50.0, 0.0, 0.0));
    let mut hit = None;
    let mut peak: f64 = 0.0;
    lp.run(&mut x, 1e-3, 140_000, |t, x, out| {
        peak = peak.max(out.accel_cmd_ned_fps2.norm());
        let range = (lp.target.position_ned_ft(t) - Vec3::new(x[0], x[1], x[2])).norm();
        if range < 2.4 {
            hit = Some(t);
        }
        hit.is_none()
    });
    (hit, peak)
}

/// (d) Remark 6: y_c ≡ 0 (shaping off) gives h = -K ẑ and b̂' = ρ Proj(b̂, y_aᵀ K ẑ). The
/// 200 ft initial error is then a step for the reference model: the follower meets
/// ‖R‖ < 2.4 ft within 1.2 s with accelerations of thousands of ft/s² (a kinematic follower
/// realises them; an aircraft could not). With the Chapter 4 shaping filter (y_c decays
/// from r(0) at 0.1 rad/s) it takes about a minute at under 20 ft/s². Both must intercept
/// within the 140 s run.
#[test]
fn interception_meets_radius() {
    for shaping_pole_rps in [0.0, 0.1] {
        let (hit, peak) = intercept(shaping_pole_rps);
        println!(
            "shaping {shaping_pole_rps}: ‖R‖ < 2.4 ft at {hit:?} s, peak ‖a_F‖ {peak:.1} ft/s²"
        );
        assert!(
            hit.is_some(),
            "no interception with shaping {shaping_pole_rps}"
        );
    }
}

/// (f) Chapter 6.3: white noise on r, drawn once per 1 ms tick (held over the RK4 step) with
/// σ = 0.134 per axis: SNR 25 dB relative to the command's power |R_c / b|² = 4.12² split
/// over three axes (σ² = 4.12² / 3 / 10^2.5). Seed target, shaping on, no excitation, fixed
/// Chapter 5 observer gain (the seed's 6.3.4 choice). The noise enters a_F directly, through
/// y*_a = 2y* - ... and through ḣ = -K ż̂ with ż̂ ∋ L y*: about (b̂ K L + 2) σ ≈ 4.6 ft/s² per
/// sample, RMS(a_F - a_T) ≈ 16 ft/s² measured. Asserted (bounded, Theorem 13 with noise,
/// (6.53)): b̂ within 10% of 8 ft (measured 7.66), position RMS vs R_c over the last 20 s
/// below 3 ft per axis (measured 1.5, 0.4, 0.05). The Riccati gain with the default weights
/// (L ≈ [46, 89], much larger) is reported, and only required to stay bounded (< 10 ft).
#[test]
fn noisy_measurements_stay_bounded() {
    for mode in [ObserverGainMode::Fixed, ObserverGainMode::Riccati] {
        let section = AccelerationSection {
            observer_gain_mode: mode,
            ..AccelerationSection::default()
        };
        let lp = ClosedLoop::with_section(
            &section,
            &GuidanceSection::default(),
            &TargetSection::default(),
            Vec3::new(32.0, 8.0, 0.0),
        );
        let sigma = (4.12f64.powi(2) / 3.0 / 10f64.powf(2.5)).sqrt();
        let normal = Normal::new(0.0, sigma).unwrap_or_else(|e| panic!("{e}"));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let mut x = lp.initial_state(Vec3::new(50.0, 0.0, 0.0));
        let mut errors: Vec<Vec3> = Vec::new();
        let mut accel_errors: Vec<Vec3> = Vec::new();
        lp.run(&mut x, 1e-3, 140_000, |t, x, out| {
            if t > 120.0 {
                let relative = lp.target.position_ned_ft(t) - Vec3::new(x[0], x[1], x[2]);
                errors.push(relative - lp.command_ned_ft);
            }
            if (60.0..=110.0).contains(&t) {
                accel_errors.push(out.accel_cmd_ned_fps2 - lp.target.accel_ned_fps2(t));
            }
            let n = Vec3::from_fn(|_, _| normal.sample(&mut rng));
            lp.noise.set(n);
            true
        });
        let b_hat = lp.law.unpack(&x[G..]).b_hat_ft;
        let position: Vec<f64> = (0..3).map(|i| rms(errors.iter().map(|e| e[i]))).collect();
        let accel: Vec<f64> = (0..3)
            .map(|i| rms(accel_errors.iter().map(|e| e[i])))
            .collect();
        println!(
            "{mode:?} L = {:?}: b̂ = {b_hat:.3} ft, ‖d̂‖ = {:.3}, position RMS {position:.3?} ft, \
             RMS(a_F - a_T) {accel:.2?} ft/s²",
            lp.law.axis(0).l,
            lp.law.unpack(&x[G..]).d_hat_fps.norm()
        );
        let (b_tolerance, position_bound) = match mode {
            ObserverGainMode::Fixed => (0.1, 3.0),
            ObserverGainMode::Riccati => (0.3, 10.0),
        };
        assert!((b_hat - B_FT).abs() < b_tolerance * B_FT, "b̂ = {b_hat}");
        assert!(position.iter().all(|p| *p < position_bound), "{position:?}");
    }
}
