//! The seed's Chapter 4 interception run (Figures 4.6-4.7): ‖R‖ < 2.4 ft is met at the time
//! the seed reports (t = 44.8 s, Section 4.4), within a second, and the run stops there.

use crate::common;

use wingman::output::summary::RunStatus;

#[test]
fn interception_at_seed_time() {
    let report = common::run("seed_ch4_intercept", &[]);
    let s = &report.summary;
    assert_eq!(s.status, RunStatus::Intercepted);
    let t = s.intercept_time_s.expect("intercepted");
    assert!((t - 44.8).abs() < 1.0, "intercept at {t} s");
    // The run stops at interception: the last logged row is that instant.
    let last = report.logged.last().expect("rows");
    assert!((last.t_s - t).abs() < 1e-9);
    assert!(last.relative_ned_ft.norm() < 2.4);
    assert!(s.min_range_ft < 2.4);
    // Fig 4.7: the shaping filter keeps follower speeds at tens of ft/s, not hundreds.
    let top_speed = report
        .logged
        .iter()
        .map(|s| s.follower_velocity_ned_fps.norm())
        .fold(0.0, f64::max);
    assert!(top_speed < 100.0, "top speed {top_speed} ft/s");
}
