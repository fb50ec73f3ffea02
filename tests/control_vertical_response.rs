//! The Chapter 7 controller's vertical response to a velocity command (docs/findings.md, Group
//! tracking, The last link's pitch prefilter): the 6-DOF follower flown by its flight controller
//! alone in calm air at 45 ft/s, its commanded velocity's down component a 4 ft/s sinusoid.
//! A link follows its leader's height through this loop, so what it leaves of a leader's
//! vertical motion at period T is |1 − G(T)|, G the vertical velocity's answer to its command.
//!
//! Invariants: (1) with the [autopilot] defaults (the integral-form pitch prefilter at 2 rad/s)
//! a 4 s motion is left at more than its own size (|1 − G| 1.29, measured); (2) with the
//! [autopilot] section of scenarios/platoon.toml's last link (its pitch prefilter at 4 rad/s,
//! its damped course loop) it is left at under 0.85 of it (0.77, measured), every period from
//! 3 to 12 s is left at less than with the defaults, and none is answered by more than 1.15
//! times (1.08 at most, measured).

use crate::common::flight::sinusoid_answer;
use crate::common::repo_root;
use wingman::frames::Vec3;
use wingman::output::group::load_checked;
use wingman::scenario::AutopilotSection;

/// |G(T)| and |1 − G(T)|: how much of a leader's vertical motion at `period_s` the aircraft
/// answers, and how much it leaves as error.
fn gain_and_left(section: &AutopilotSection, period_s: f64) -> (f64, f64) {
    let (re, im) = sinusoid_answer(section, period_s, Vec3::new(0.0, 0.0, 1.0));
    (re.hypot(im), (1.0 - re).hypot(im))
}

#[test]
fn the_seeds_pitch_prefilter_leaves_a_4_s_motion_whole() {
    let (_, left) = gain_and_left(&AutopilotSection::default(), 4.0);
    assert!(left > 1.1, "|1 - G| {left:.2} at 4 s");
}

/// The [autopilot] section of platoon.toml's last link, f3.
fn last_links_autopilot() -> AutopilotSection {
    let path = repo_root().join("scenarios/platoon.toml");
    let group = load_checked(&path, &[]).expect("valid").expect("a group");
    let last = group.followers.last().expect("followers");
    assert_eq!(last.name, "f3");
    last.scenario.autopilot.clone()
}

#[test]
fn a_fast_pitch_prefilter_follows_it() {
    let fast = last_links_autopilot();
    assert_eq!(fast.pitch_prefilter_omega_rps, 4.0);
    let seed = AutopilotSection::default();
    for period_s in [3.0, 4.0, 5.0, 6.0, 8.0, 12.0] {
        let (gain, left) = gain_and_left(&fast, period_s);
        let (_, seed_left) = gain_and_left(&seed, period_s);
        assert!(gain < 1.15, "gain {gain:.2} at {period_s} s");
        assert!(
            left < seed_left,
            "|1 - G| {left:.2} against {seed_left:.2} at {period_s} s"
        );
        if period_s == 4.0 {
            assert!(left < 0.85, "|1 - G| {left:.2} at 4 s");
        }
    }
}
