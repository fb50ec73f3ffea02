//! A run stepped from outside ([`LiveRun`], what the Python package drives) is the run
//! `wingman run` writes: the same logged snapshots and the same summary, all but its wall
//! times, for a camera run that completes and for one that loses its target (the same end,
//! at the same tick); and a command offset set from outside is what the follower flies.

use crate::common;

use wingman::frames::Vec3;
use wingman::guidance::signals::FollowerCommand;
use wingman::output::live::LiveRun;
use wingman::output::summary::Summary;

/// The summary as JSON without the keys that are wall times.
fn without_wall_times(summary: &Summary) -> serde_json::Value {
    let mut json: serde_json::Value = serde_json::from_str(&summary.to_json()).expect("json");
    let object = json.as_object_mut().expect("object");
    for key in ["wall_s", "realtime_factor", "per_frame_ms", "stage_wall_s"] {
        object.remove(key).expect("a timing key");
    }
    json
}

/// Steps `scenarios/<name>.toml` with `overrides` from outside and through `wingman run`'s
/// driver, and compares the two.
fn assert_same_run(name: &str, overrides: &[&str]) -> Summary {
    let scenario = common::load(name, overrides);
    let written = common::run(name, overrides);
    let mut live = LiveRun::new(&scenario, name, None).expect("set-up");
    while live.step().is_none() {}
    assert_eq!(live.logged(), written.logged.as_slice(), "telemetry");
    let summary = live.summary();
    assert_eq!(
        without_wall_times(&summary),
        without_wall_times(&written.summary)
    );
    // No more ticks after the end.
    let ticks = live.simulation().tick();
    live.step();
    assert_eq!(live.simulation().tick(), ticks);
    summary
}

#[test]
fn a_live_camera_run_is_the_written_one() {
    let summary = assert_same_run("formation", &["run.duration_s=3", "run.seed=2"]);
    assert_eq!(summary.status.name(), "completed");
    assert_eq!(summary.frames, 90);
}

#[test]
fn a_live_run_loses_its_target_where_the_written_one_does() {
    // A 10° field of view: the target leaves the image.
    let overrides = [
        "run.duration_s=8",
        "camera.hfov_deg=10",
        "run.stop_after_lost_s=1",
    ];
    let summary = assert_same_run("vision_ch4_formation", &overrides);
    assert_eq!(summary.status.name(), "lost", "{:?}", summary.message);
}

#[test]
fn the_follower_flies_the_offset_command() {
    let scenario = common::load("seed_ch4_formation", &["run.duration_s=2"]);
    let mut plain = LiveRun::new(&scenario, "plain", None).expect("set-up");
    let mut pushed = LiveRun::new(&scenario, "pushed", None).expect("set-up");
    let offset = Vec3::new(0.0, 5.0, 0.0);
    pushed.simulation_mut().set_command_offset(Some(offset));
    let velocity = |run: &LiveRun| match run.simulation().snapshot().guidance.command {
        FollowerCommand::Velocity(v) => v,
        FollowerCommand::Acceleration(_) => panic!("velocity law"),
    };
    let east_ft = |run: &LiveRun| run.simulation().snapshot().follower_position_ned_ft.y;
    // At once the command is the guidance's plus the offset (the guidance has seen no
    // error yet); the kinematic follower realises it.
    plain.step();
    pushed.step();
    let commanded = velocity(&pushed) - velocity(&plain);
    assert!((commanded - offset).norm() < 0.05, "{commanded}");
    // Then the guidance answers the error the offset makes, but the follower has moved east.
    plain.run_until(1.0);
    pushed.run_until(1.0);
    let moved_ft = east_ft(&pushed) - east_ft(&plain);
    assert!((0.3..5.0).contains(&moved_ft), "{moved_ft}");
}
