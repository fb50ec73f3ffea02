//! A leader straight above: in the target's slowest turn a platoon's link sinks below its
//! climbing leader, which then stands 73-84° above it (docs/findings.md, The camera looks up
//! to 90° in the platoon). formation.toml without turbulence, the target 50 ft straight above
//! the follower (89° up) and flying level with it, the camera cued at it: with
//! platoon.toml's tilt range the camera measures it from the first frame; with the 60° the
//! platoon had before, the target lies 29° beyond the tilt limit, on the image's edge, and
//! the run stops as lost. Without turbulence or pixel noise the run does not depend on
//! `run.seed` (streams 1-3 give identical telemetry).

use crate::common::{self, repo_root};
use wingman::output::summary::{RunStatus, Summary};
use wingman::scenario::Scenario;

fn target_above(tilt_limits_deg: [f64; 2]) -> Summary {
    let tilt = format!(
        "camera.gimbal.tilt_limits_deg=[{}, {}]",
        tilt_limits_deg[0], tilt_limits_deg[1]
    );
    common::run(
        "formation",
        &[
            "run.duration_s=8",
            "output.frames_every=0",
            "target.motion=\"straight\"",
            "target.initial_position_ft=[1, 0, -50]",
            "target.straight_velocity_fps=[50, 0, 0]",
            "atmosphere.turbulence=\"off\"",
            "camera.gimbal.cue=\"target\"",
            &tilt,
        ],
    )
    .summary
}

#[test]
fn the_platoons_camera_keeps_a_leader_straight_above() {
    let platoon = Scenario::load(&repo_root().join("scenarios/platoon.toml"), &[]).expect("load");
    let s = target_above(platoon.camera.gimbal.tilt_limits_deg);
    assert_eq!(s.status, RunStatus::Completed, "{:?}", s.message);
    assert_eq!(s.lost_frames, 0, "{:?}", s.loss_episodes);
    let s = target_above([-120.0, 60.0]);
    assert_eq!(s.status, RunStatus::Lost, "{:?}", s.loss_episodes);
}
