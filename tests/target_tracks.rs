//! The target's trajectory sources fly what they promise (docs/equations.md,
//! Trajectory sources for the target): a waypoint track passes every waypoint, in order,
//! within its reach radius (the turn radius V²/(g tan φ_max) at the faster of the two legs'
//! speeds, 134 ft at 50 ft/s and 30°) and at its height, inside its bank, climb and
//! acceleration limits; a random track stays inside its envelope and its rate limits with
//! continuous velocity and acceleration over a long run, covers the envelope, and each seed
//! flies its own path (the same seed the same); a CSV track written from a flown track is
//! reproduced; a bad CSV track is a scenario error (exit 2) naming the file and the line,
//! before anything is written; the shipped CSV track covers its scenario.

use crate::common;

use std::path::Path;
use wingman::frames::{GRAVITY_FPS2, Vec3};
use wingman::scenario::{Scenario, TargetMotion, TargetSection, Waypoint};
use wingman::world::target::{TargetModel, TargetState};
use wingman::world::trajectory::{
    SampledTrack, random_track, reach_radius_ft, read_track, waypoint_track,
};

/// The track every `step_s` from 0 to `end_s`.
fn samples(track: &SampledTrack, end_s: f64, step_s: f64) -> Vec<(f64, TargetState)> {
    let n = (end_s / step_s).round() as usize;
    (0..=n)
        .map(|i| {
            let t = i as f64 * step_s;
            (t, track.state(t))
        })
        .collect()
}

fn horizontal(v: &Vec3) -> f64 {
    v.x.hypot(v.y)
}

/// dV/dt along the velocity.
fn along_accel(s: &TargetState) -> f64 {
    s.velocity_ned_fps.dot(&s.accel_ned_fps2) / s.velocity_ned_fps.norm()
}

fn course() -> TargetSection {
    let wp = |n: f64, e: f64, d: f64, speed_fps: f64| Waypoint {
        position_ft: [n, e, d],
        speed_fps,
    };
    TargetSection {
        motion: TargetMotion::Waypoints,
        waypoints: vec![
            wp(1200.0, 50.0, 30.0, 50.0),   // ahead
            wp(1300.0, 900.0, -20.0, 60.0), // sharp right, climbing 50 ft
            wp(200.0, 700.0, -20.0, 40.0),  // back the way it came, slower
            wp(300.0, 850.0, 10.0, 45.0),   // close abeam: a tight turn, descending
            wp(900.0, 0.0, 10.0, 55.0),
        ],
        ..TargetSection::default()
    }
}

#[test]
fn waypoint_track_passes_every_waypoint_in_order() {
    let target = course();
    let track = waypoint_track(&target, 300.0);
    let states = samples(&track, 300.0, 0.01);
    let bank_limit = target.bank_limit_deg.to_radians();
    let mut from = 0;
    let mut speed_before = target.waypoints[0].speed_fps;
    for (i, w) in target.waypoints.iter().enumerate() {
        let at = Vec3::from(w.position_ft);
        let reach = reach_radius_ft(speed_before.max(w.speed_fps), bank_limit, 2.0);
        let k = (from..states.len())
            .find(|k| horizontal(&(states[*k].1.position_ned_ft - at)) <= reach)
            .unwrap_or_else(|| panic!("waypoint {i} never passed within {reach:.1} ft"));
        let height_error = (states[k].1.position_ned_ft.z - at.z).abs();
        assert!(
            height_error < 2.0,
            "waypoint {i}: {height_error:.2} ft off its height"
        );
        // The next one is passed later.
        from = k + 1;
        speed_before = w.speed_fps;
    }
    for (t, s) in &states {
        let v = s.velocity_ned_fps;
        assert!(
            s.attitude.phi_rad.abs() <= bank_limit + 1e-3, // drawn from the interpolated acceleration
            "bank at {t}: {s:?}"
        );
        assert!(
            v.z.abs() <= target.climb_rate_max_fps + 1e-9,
            "climb at {t}"
        );
        assert!(
            along_accel(s).abs() <= target.accel_max_fps2 + 1e-6,
            "accel at {t}"
        );
    }
    // After the last waypoint: straight and level on.
    let end = &states[states.len() - 1].1;
    assert!(end.velocity_ned_fps.z.abs() < 1e-3 && end.attitude.phi_rad.abs() < 1e-3);
    assert!((end.velocity_ned_fps.norm() - 55.0).abs() < 1e-3);
}

/// One seed's track over `end_s` against its envelope; returns the extremes it reached:
/// (smallest and largest bank, climb rate, speed).
fn check_envelope(target: &TargetSection, seed: u64, end_s: f64) -> [(f64, f64); 3] {
    let e = &target.random;
    let track = random_track(target, seed, end_s);
    let dt = 0.001;
    let states = samples(&track, end_s, dt);
    let mut extremes = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    // The roll rate between knots (0.1 s apart), where the bank is the point mass's.
    let roll_step = target.roll_rate_max_dps.to_radians() * 0.1;
    for pair in states.iter().step_by(100).collect::<Vec<_>>().windows(2) {
        let (t, a, b) = (
            pair[0].0,
            pair[0].1.attitude.phi_rad,
            pair[1].1.attitude.phi_rad,
        );
        assert!(
            (b - a).abs() <= roll_step + 1e-9,
            "roll rate at {t}: {a} -> {b}"
        );
    }
    for pair in states.windows(2) {
        let ((t, a), (_, b)) = (&pair[0], &pair[1]);
        let (speed, climb, bank) = (
            b.velocity_ned_fps.norm(),
            -b.velocity_ned_fps.z,
            b.attitude.phi_rad,
        );
        // The bank is drawn from the interpolated acceleration: within 1e-3 rad (0.06°) of the
        // integrated point mass's, which keeps it exactly.
        assert!(
            bank.abs() <= e.bank_max_deg.to_radians() + 1e-3,
            "bank {bank} at {t}"
        );
        assert!(
            climb.abs() <= e.climb_rate_max_fps + 1e-9,
            "climb {climb} at {t}"
        );
        assert!(
            speed >= e.speed_min_fps - 1e-9 && speed <= e.speed_max_fps + 1e-9,
            "{speed} at {t}"
        );
        assert!(
            along_accel(b).abs() <= target.accel_max_fps2 + 1e-6,
            "accel at {t}"
        );
        assert!(
            b.accel_ned_fps2.z.abs() <= target.vertical_accel_max_fps2 + 1e-6,
            "at {t}"
        );
        // Continuous velocity and acceleration: no jump between samples 1 ms apart (the
        // largest acceleration the limits allow is about 20 ft/s², the largest jerk about
        // 25 ft/s³).
        assert!(
            (b.velocity_ned_fps - a.velocity_ned_fps).norm() < 0.03,
            "velocity jump at {t}"
        );
        assert!(
            (b.accel_ned_fps2 - a.accel_ned_fps2).norm() < 0.05,
            "acceleration jump at {t}"
        );
        for (extreme, value) in extremes.iter_mut().zip([bank, climb, speed]) {
            *extreme = (extreme.0.min(value), extreme.1.max(value));
        }
    }
    extremes
}

#[test]
fn random_track_stays_in_its_envelope_and_seeds_differ() {
    let target = TargetSection {
        motion: TargetMotion::Random,
        ..TargetSection::default()
    };
    let e = &target.random;
    for seed in 1..=3 {
        let [bank, climb, speed] = check_envelope(&target, seed, 1000.0);
        // The draws cover the envelope: both turns, climbs and descents, slow and fast.
        let bank_max = e.bank_max_deg.to_radians();
        assert!(
            bank.0 < -0.8 * bank_max && bank.1 > 0.8 * bank_max,
            "seed {seed}: {bank:?}"
        );
        let climb_max = e.climb_rate_max_fps;
        assert!(
            climb.0 < -0.8 * climb_max && climb.1 > 0.8 * climb_max,
            "{climb:?}"
        );
        let range = e.speed_max_fps - e.speed_min_fps;
        assert!(
            speed.0 < e.speed_min_fps + 0.2 * range,
            "seed {seed}: {speed:?}"
        );
        assert!(
            speed.1 > e.speed_max_fps - 0.2 * range,
            "seed {seed}: {speed:?}"
        );
    }
    let at = |seed| {
        random_track(&target, seed, 120.0)
            .state(120.0)
            .position_ned_ft
    };
    assert_eq!(at(1), at(1));
    for (a, b) in [(1, 2), (1, 3), (2, 3)] {
        let apart = (at(a) - at(b)).norm();
        assert!(apart > 100.0, "seeds {a} and {b} end {apart:.1} ft apart");
    }
}

/// Writes `track` every 0.1 s over `end_s` as a CSV track, with or without velocities.
fn write_csv(path: &Path, track: &SampledTrack, end_s: f64, with_velocity: bool) {
    let mut text = String::from("# a flown track\nt_s,n_ft,e_ft,d_ft");
    text += if with_velocity {
        ",vn_fps,ve_fps,vd_fps\n"
    } else {
        "\n"
    };
    for (t, s) in samples(track, end_s, 0.1) {
        let (p, v) = (s.position_ned_ft, s.velocity_ned_fps);
        text += &format!("{t},{},{},{}", p.x, p.y, p.z);
        if with_velocity {
            text += &format!(",{},{},{}", v.x, v.y, v.z);
        }
        text += "\n";
    }
    std::fs::write(path, text).expect("track written");
}

#[test]
fn csv_track_reproduces_the_flown_track() {
    let dir = tempfile::tempdir().expect("temp dir");
    let target = TargetSection::default();
    let flown = random_track(&target, 5, 60.0);
    let start = flown.state(0.0).position_ned_ft;
    // (velocities given?, largest position, velocity and acceleration errors). The knots are
    // 0.1 s apart: an acceleration differenced from them is smeared by the jerk's jumps (the
    // roll-rate-limited entries, up to about 25 ft/s³), by about 0.5 ft/s² once and 2 ft/s²
    // differenced twice from positions alone (measured: 0.43 and 2.25).
    for (with_velocity, tolerance) in [(true, [1e-3, 0.01, 1.0]), (false, [0.01, 0.1, 3.0])] {
        let path = dir.path().join("flown.csv");
        write_csv(&path, &flown, 60.0, with_velocity);
        let played = read_track(&path, start, 60.0).expect("a good track");
        let mut worst = [0.0f64; 3];
        for (t, truth) in samples(&flown, 60.0, 0.01) {
            let got = played.state(t);
            let errors = [
                (got.position_ned_ft - truth.position_ned_ft).norm(),
                (got.velocity_ned_fps - truth.velocity_ned_fps).norm(),
                (got.accel_ned_fps2 - truth.accel_ned_fps2).norm(),
            ];
            for (w, e) in worst.iter_mut().zip(errors) {
                *w = w.max(e);
            }
        }
        for (w, tol) in worst.iter().zip(tolerance) {
            assert!(
                w < &tol,
                "velocities given: {with_velocity}: errors {worst:?}"
            );
        }
    }
    // Moved to another start, the track keeps its shape.
    let shifted = read_track(&dir.path().join("flown.csv"), Vec3::zeros(), 60.0).expect("good");
    let moved = shifted.state(33.3).position_ned_ft - flown.state(33.3).position_ned_ft;
    assert!((moved + start).norm() < 1e-3, "{moved:?}");
}

#[test]
fn bad_csv_tracks_are_scenario_errors_naming_file_and_line() {
    let header = "t_s,n_ft,e_ft,d_ft\n";
    let cases = [
        (
            "time goes back",
            format!("{header}0,0,0,0\n2,1,0,0\n1,2,0,0\n9,3,0,0\n"),
            4,
            "not after",
        ),
        (
            "NaN",
            format!("{header}0,0,0,0\n5,NaN,0,0\n9,3,0,0\n"),
            3,
            "n_ft = `NaN`",
        ),
        (
            "not a number",
            format!("{header}0,0,0,0\n5,1,0,0\n9,3,east,0\n"),
            4,
            "e_ft = `east`",
        ),
        (
            "one row",
            format!("# one\n{header}0,0,0,0\n"),
            3,
            "at least 2",
        ),
        (
            "short",
            format!("{header}0,0,0,0\n4.5,1,0,0\n"),
            3,
            "shorter than run.duration_s = 5",
        ),
        (
            "no d_ft",
            "t_s,n_ft,e_ft\n0,0,0\n9,1,0\n".to_string(),
            1,
            "missing column `d_ft`",
        ),
    ];
    for (what, text, line, says) in cases {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("bad.csv"), text).expect("track");
        let scenario = "[run]\nduration_s = 5.0\n[output]\nplots = false\n\
                        [target]\nmotion = \"csv\"\ntrack = \"bad.csv\"\n";
        std::fs::write(dir.path().join("s.toml"), scenario).expect("scenario");
        let (code, stderr) =
            common::wingman_cli_in(dir.path(), &["run", "s.toml", "--quiet", "--out", "out"]);
        assert_eq!(code, 2, "{what}: {stderr}");
        assert!(
            stderr.contains(&format!("bad.csv:{line}: ")),
            "{what}: {stderr}"
        );
        assert!(
            stderr.contains(says) && stderr.contains("target.track"),
            "{what}: {stderr}"
        );
        assert!(!dir.path().join("out").exists(), "{what}: output written");
    }
}

/// The shipped track is found from the scenario's folder and plays for its whole run, from
/// the scenario's R_T(0), at the speeds a small aircraft flies.
#[test]
fn shipped_csv_track_covers_its_scenario() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/formation_csv_track.toml");
    let scenario = Scenario::load(&path, &[]).expect("the shipped scenario loads");
    assert_eq!(scenario.target.motion, TargetMotion::Csv);
    let start = Vec3::from(scenario.target.initial_position_ft);
    let duration_s = scenario.run.duration_s;
    let track = read_track(Path::new(&scenario.target.track), start, duration_s).expect("good");
    assert!(track.end_s() >= duration_s);
    assert!((track.state(0.0).position_ned_ft - start).norm() < 1e-9);
    for (t, s) in samples(&track, duration_s, 0.1) {
        let speed = s.velocity_ned_fps.norm();
        assert!((25.0..=80.0).contains(&speed), "{speed} ft/s at {t}");
        // The flown aircraft's manoeuvres and turbulence reach 0.9 g.
        assert!(s.accel_ned_fps2.norm() < 1.5 * GRAVITY_FPS2, "at {t}");
    }
}
