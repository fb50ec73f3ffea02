//! The seed's Chapter 7 acceleration-guidance run (Figures 7.7-7.13): the 6-DOF follower
//! flying V_F = V_F(0) + ∫ a_F under the Chapter 7 flight controller, the acceleration law on
//! r measured at SNR 25 dB, the excitation on the y command. Shown: the criteria
//! ([`common::assert_seed_ch7_criteria`]) and b̂ within 10% of 8 ft.

use crate::common;

use wingman::output::summary::RunStatus;

#[test]
fn acceleration_guidance_flies_the_seed_run_on_the_6dof_follower() {
    let report = common::run("seed_ch7_acceleration", &[]);
    let s = &report.summary;
    let a = s.aircraft.as_ref().expect("6-DOF run");
    println!(
        "b̂ = {:.3} ft, ‖d̂‖ = {:.2} ft/s, RMS last 20 s {:.3?} ft, SNR {:?} dB, wall {:.3} s; {a:?}",
        s.b_hat_final_ft, s.d_hat_norm_final, s.rms_error_last20s_ft, s.noise_snr_db, s.wall_s
    );
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.steps, 70_000);
    common::assert_seed_ch7_criteria(&report);
    // Measured 7.75 ft (Chapter 6's kinematic run: 7.71 ft).
    assert!(
        (s.b_hat_final_ft - 8.0).abs() < 0.1 * 8.0,
        "{}",
        s.b_hat_final_ft
    );
    // The integrated command stays a flyable velocity: the aircraft realises it within the
    // compensation's reach (a wound-up V_F would leave the airspeed band above).
    for row in &report.logged {
        let a = row.aircraft.as_ref().expect("aircraft rows");
        assert!(
            a.velocity_cmd_ned_fps.norm() < 100.0,
            "V_F at {} s",
            row.t_s
        );
    }
}
