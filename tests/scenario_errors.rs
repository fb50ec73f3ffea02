//! Bad scenarios never crash: each gives a one-line error on stderr that names the file and
//! the problem, exit code 2, and writes no outputs.

use std::path::Path;
use std::process::Command;

/// The smallest scenario that is not empty.
const MINIMAL: &str = "[run]\nseed = 1\n";

fn wingman_run(scenario: &Path, extra: &[&str], out: &Path) -> (i32, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_wingman"))
        .arg("run")
        .arg(scenario)
        .arg("--out")
        .arg(out)
        .arg("--quiet")
        .args(extra)
        .output()
        .expect("binary runs");
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// Writes `text` as a scenario, runs it and checks exit code 2 and a one-line message that
/// contains every `expected` fragment.
fn assert_rejected(text: &str, extra: &[&str], expected: &[&str]) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text).expect("write scenario");
    let out = dir.path().join("out");
    let (code, stderr) = wingman_run(&path, extra, &out);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "not one line: {stderr}"
    );
    // A value from a `--set` is blamed on it, never on the file.
    if extra.contains(&"--set") {
        assert!(
            stderr.contains("error: --set "),
            "--set not named: {stderr}"
        );
    } else {
        assert!(stderr.contains("bad.toml"), "file not named: {stderr}");
    }
    assert!(stderr.len() < 200, "{} characters: {stderr}", stderr.len());
    // The temporary folder's random name may hold "u8" or "f64" itself.
    let message = stderr.replace(&path.display().to_string(), "bad.toml");
    for rust_name in ["f64", "u32", "u64", "u8", "struct "] {
        assert!(!message.contains(rust_name), "Rust type name: {stderr}");
    }
    for fragment in expected {
        assert!(
            stderr.contains(fragment),
            "`{fragment}` missing from: {stderr}"
        );
    }
    assert!(!out.exists(), "outputs written for a bad scenario");
}

#[test]
fn syntax_error() {
    // Where as file:line:column, then what is wrong.
    assert_rejected(
        "[run\nduration_s = 1\n",
        &[],
        &["bad.toml:1:5", "expected `]`"],
    );
}

#[test]
fn unknown_key() {
    assert_rejected("[guidance]\nsigmaa = 3.0\n", &[], &["sigmaa"]);
}

#[test]
fn unknown_section() {
    assert_rejected("[guidence]\nk = 3.0\n", &[], &["guidence"]);
}

#[test]
fn negative_dt() {
    assert_rejected(
        "[run]\ndt_s = -0.001\n",
        &[],
        &["run.dt_s = -0.001", "[0.00001, 0.1]"],
    );
}

#[test]
fn b0_outside_bounds() {
    assert_rejected(
        "[guidance]\nb0_ft = 0.5\nb_min_ft = 1.0\nb_max_ft = 30.0\n",
        &[],
        &["guidance.b0_ft = 0.5", "b_min_ft = 1", "b_max_ft = 30"],
    );
}

#[test]
fn wrong_type() {
    assert_rejected("[run]\ndt_s = \"fast\"\n", &[], &["dt_s"]);
}

#[test]
fn bad_override() {
    assert_rejected(MINIMAL, &["--set", "run.dt_s=0"], &["run.dt_s = 0"]);
    assert_rejected(MINIMAL, &["--set", "nodot=1"], &["nodot=1"]);
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("nowhere.toml");
    let (code, stderr) = wingman_run(&path, &[], &dir.path().join("out"));
    assert_eq!(code, 2);
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("nowhere.toml") && stderr.contains("cannot read"),
        "{stderr}"
    );
}

/// The Chapter 5-6 keys: the law, the acceleration section's design conditions, the noisy
/// sensor's sample period and SNR reference, the estimator's covariance weights.
#[test]
fn chapter_5_and_6_keys() {
    assert_rejected("[guidance]\nlaw = \"jerk\"\n", &[], &["law", "jerk"]);
    assert_rejected(
        "[guidance]\nlaw = \"acceleration\"\n[acceleration]\nobserver_gain = [1.0, 1.6]\n",
        &[],
        &[
            "acceleration.observer_gain = [1.0, 1.6]",
            "l1 >= acceleration.lambda_rps = 2",
        ],
    );
    assert_rejected(
        "[sensor]\nmode = \"noisy\"\nsample_period_s = 0.0015\n",
        &[],
        &["sensor.sample_period_s = 0.0015", "run.dt_s = 0.001"],
    );
    assert_rejected(
        "[sensor]\nmode = \"noisy\"\nsnr_reference = \"command\"\n[guidance]\nmission = \"intercept\"\n",
        &[],
        &[
            "sensor.snr_reference",
            "\"signal\" when the command is zero",
        ],
    );
    assert_rejected(
        "[sensor]\nmode = \"noisy\"\nnoise_on = \"pixels\"\n[camera]\nhfov_deg = 0.0\n",
        &[],
        &["camera.hfov_deg = 0", "(0, 179)"],
    );
    assert_rejected(
        "[guidance]\nestimator_noise_psd = 0.0\n",
        &[],
        &["guidance.estimator_noise_psd = 0", "> 0"],
    );
    assert_rejected(
        MINIMAL,
        &["--set", "follower.initial_velocity_fps=[50.0, nan, 0.0]"],
        &["follower.initial_velocity_fps", "three finite numbers"],
    );
}

/// A fragment is a blob shorter than a fraction of the expected length: a fraction of 1 or
/// more would call the target whole a fragment.
#[test]
fn a_fragment_fraction_is_under_one() {
    assert_rejected(
        "[camera]\nselection_fragment_fraction = 1.0\n",
        &[],
        &["camera.selection_fragment_fraction = 1", "[0, 1)"],
    );
}

/// A merge is a blob longer than the target can be: a ratio of 1 or less would call the
/// target whole a merge.
#[test]
fn a_merge_ratio_is_over_one() {
    assert_rejected(
        "[camera]\nselection_merge_ratio = 0.9\n",
        &[],
        &["camera.selection_merge_ratio = 0.9", "[1.01, 100]"],
    );
}

/// A roll axis that levels the pan axis turns less than a quarter turn either way.
#[test]
fn a_roll_axis_range_is_within_a_quarter_turn() {
    assert_rejected(
        "[camera.gimbal]\nkind = \"roll_pan_tilt\"\nroll_limits_deg = [-100.0, 60.0]\n",
        &[],
        &[
            "camera.gimbal.roll_limits_deg = [-100, 60]",
            "-90 <= min <= 0 <= max <= 90",
        ],
    );
}

/// A gate on the bearing's normalised square is not negative (0: none), and the factor off
/// the predicted range beyond which it weighs a frame is at least 1 (1: every frame).
#[test]
fn a_bearing_gate_and_its_range_ratio_are_in_range() {
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\nbearing_gate = -1.0\n",
        &[],
        &["estimator.bearing_gate = -1", "[0, 1000000]"],
    );
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\nbearing_gate_range_ratio = 0.5\n",
        &[],
        &["estimator.bearing_gate_range_ratio = 0.5", "[1, 1000000]"],
    );
}

/// The leader's swing: a period of 0 (none) or at least 0.1 s, a wander time no shorter than
/// the period, which keeps the oscillator underdamped, and not the follower's own excitation
/// period.
#[test]
fn a_leader_swing_is_in_range() {
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\nleader_swing_period_s = 0.05\n",
        &[],
        &[
            "estimator.leader_swing_period_s = 0.05",
            "0 (none) or [0.1, 1000]",
        ],
    );
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\nleader_swing_period_s = 4\nleader_swing_time_s = 3\n",
        &[],
        &["estimator.leader_swing_time_s = 3", "[4, 10000]"],
    );
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\nleader_swing_period_s = 3\n\
         [excitation]\nmode = \"continuous\"\nperiod_s = 3\n",
        &[],
        &["estimator.leader_swing_period_s = 3", "excitation.period_s"],
    );
}

/// The size from the excitation needs the Kalman filter, a camera and an excitation, and
/// its settings are in range.
#[test]
fn the_size_from_the_excitation_needs_the_filter_a_camera_and_a_swing() {
    let wants = [
        "estimator.size_from = \"excitation\"",
        "estimator.kind = \"kalman\"",
    ];
    for rest in [
        "",
        "kind = \"kalman\"\n",
        "kind = \"kalman\"\n[sensor]\nmode = \"camera\"\n[excitation]\nmode = \"off\"\n",
    ] {
        assert_rejected(
            &format!("[estimator]\nsize_from = \"excitation\"\n{rest}"),
            &[],
            &wants,
        );
    }
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\ninstrument_min_blocks = 1\n",
        &[],
        &["estimator.instrument_min_blocks = 1", "[2, 1000]"],
    );
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\ninstrument_q = 0\n",
        &[],
        &["estimator.instrument_q = 0", "[0.5, 100]"],
    );
    assert_rejected(
        "[estimator]\nkind = \"kalman\"\ninstrument_direction_periods = -1\n",
        &[],
        &["estimator.instrument_direction_periods = -1", "[0, 100]"],
    );
}

/// The excitation's frame turns with the command's target frame, so it needs it; its window
/// holds a fade in and a fade out.
#[test]
fn the_excitations_frame_and_window_are_checked() {
    assert_rejected(
        "[excitation]\nframe = \"target\"\n",
        &[],
        &[
            "excitation.frame = \"target\"",
            "guidance.command_frame = \"target\"",
        ],
    );
    assert_rejected(
        "[excitation]\nperiod_s = 4.0\nstart_s = 30.0\nend_s = 35.0\n",
        &[],
        &["excitation.end_s = 35", "two periods"],
    );
    assert_rejected(
        "[excitation]\nstart_s = -1.0\n",
        &[],
        &["excitation.start_s = -1"],
    );
}

/// An excitation that follows the Kalman filter's σ_b needs the filter: the error names the
/// mode as the scenario spells it.
#[test]
fn an_excitation_on_the_filters_uncertainty_needs_the_filter() {
    for mode in ["uncertainty", "relative_uncertainty"] {
        assert_rejected(
            &format!("[excitation]\nmode = \"{mode}\"\n"),
            &[],
            &[&format!("excitation.mode = \"{mode}\""), "estimator.kind"],
        );
    }
}

/// The 6-DOF follower's keys: its step (the roll mode and servos are 10-25 ms fast), its
/// trimmed start, the air it flies in and its controller are checked like every other key.
#[test]
fn aircraft_follower_values_are_checked() {
    assert_rejected(
        "[follower]\nmodel = \"aircraft\"\n[run]\ndt_s = 0.01\n",
        &[],
        &[
            "run.dt_s = 0.01",
            "<= 0.005",
            "follower.model = \"aircraft\"",
        ],
    );
    assert_rejected(
        "[follower]\nmodel = \"aircraft\"\ninitial_velocity_fps = [50.0, 0.0, 5.0]\n",
        &[],
        &[
            "follower.initial_velocity_fps",
            "[n, e, 0]",
            "[35, 100] ft/s",
        ],
    );
    assert_rejected(
        "[follower]\nmodel = \"aircraft\"\ninitial_velocity_fps = [20.0, 0.0, 0.0]\n",
        &[],
        &["follower.initial_velocity_fps", "[35, 100] ft/s"],
    );
    assert_rejected(
        "[atmosphere]\nturbulence = \"hurricane\"\n",
        &[],
        &["hurricane"],
    );
    assert_rejected(
        "[atmosphere.disturbances]\ndrag_factor = 20.0\n",
        &[],
        &["atmosphere.disturbances.drag_factor = 20", "[0, 10]"],
    );
    assert_rejected(
        "[autopilot]\nmax_airspeed_cmd_fps = 30.0\n",
        &[],
        &[
            "autopilot.max_airspeed_cmd_fps = 30",
            "autopilot.min_airspeed_cmd_fps = 35",
        ],
    );
    assert_rejected(
        "[autopilot]\nweave_deficit_fps = -1.0\n",
        &[],
        &["autopilot.weave_deficit_fps = -1", "[0, 20]"],
    );
    assert_rejected(
        "[autopilot]\nweave_deficit_fps = 2.0\n",
        &[],
        &[
            "autopilot.weave_deficit_fps = 2",
            "autopilot.weave_half_width_ft = 0",
        ],
    );
    assert_rejected(
        "[autopilot]\nweave_lead_ft = 0.0\n",
        &[],
        &["autopilot.weave_lead_ft = 0", "[0.1, 100]"],
    );
    assert_rejected(
        "[autopilot]\nweave_outside_turn_dps = 120.0\n",
        &[],
        &["autopilot.weave_outside_turn_dps = 120", "[0, 90]"],
    );
    assert_rejected(
        "[acceleration]\nshortfall_time_constant_s = 0.0\n",
        &[],
        &["acceleration.shortfall_time_constant_s = 0", "[0.01, 1000]"],
    );
    assert_rejected(
        "[guidance]\nk_aircraft = 0.0\n",
        &[],
        &["guidance.k_aircraft = 0", "[0.001, 100]"],
    );
}

/// A kinematic target over the ground feels no gusts to share.
#[test]
fn a_kinematic_target_over_the_ground_has_no_gusts_to_share() {
    assert_rejected(
        "[target]\ngusts = \"shared\"\n",
        &[],
        &[
            "target.gusts = \"shared\"",
            "target.model = \"aircraft\"",
            "target.path = \"in_air_mass\"",
        ],
    );
}

/// The image pipeline's expected length comes from one of two sources, named.
#[test]
fn an_expected_length_names_its_two_sources() {
    assert_rejected(
        "[camera]\nexpected_length = \"filtered\"\n",
        &[],
        &["expected_length", "last_measured", "estimated"],
    );
}

/// Where a value came from: the file's line and column, or the `--set` argument alone.
#[test]
fn origin_is_line_and_column_or_the_set_argument() {
    assert_rejected(
        "[run]\nseed = 1\ndt_s = \"fast\"\n",
        &[],
        &["bad.toml:3:8:", "run.dt_s = \"fast\"", "a number"],
    );
    assert_rejected(
        MINIMAL,
        &["--set", "run.dt_s=fast"],
        &["--set run.dt_s=fast:", "a number"],
    );
    assert_rejected(
        "[guidance]\nsigmaa = 3.0\n",
        &[],
        &["bad.toml:2:", "guidance.sigmaa", "did you mean sigma"],
    );
    assert_rejected(
        "[run]\nlog_every = -1\n",
        &[],
        &["run.log_every = -1", "an integer in [1, 1000000]"],
    );
}

/// Numbers are printed short: 1e308, not 309 digits.
#[test]
fn numbers_are_short() {
    assert_rejected(
        "[run]\nduration_s = 1e308\n",
        &[],
        &["run.duration_s = 1e308", "[0.001, 100000]"],
    );
}

/// A file with nothing in it (or only comments) is an error, not the defaults.
#[test]
fn empty_file_is_an_error() {
    assert_rejected("", &[], &["empty"]);
    assert_rejected("# nothing but a comment\n", &[], &["empty"]);
}

/// Values that passed validation and failed later are rejected up front, naming the key: a
/// field of view whose focal length is infinite, a rising air mass the trim cannot hold.
#[test]
fn late_failures_are_rejected_up_front() {
    assert_rejected(
        "[sensor]\nmode = \"camera\"\n[camera]\nrate_hz = 25.0\nhfov_deg = 1e-320\n",
        &[],
        &["camera.hfov_deg = 1e-320", "focal length"],
    );
    assert_rejected(
        "[follower]\nmodel = \"aircraft\"\n[run]\ndt_s = 0.002\n[atmosphere]\nwind_ned_fps = [0.0, 0.0, 3.0]\n",
        &[],
        &["atmosphere.wind_ned_fps", "[n, e, 0]"],
    );
}

/// A run that would log 10^10 rows is refused before it starts, with the estimate and the
/// key to change.
#[test]
fn runs_beyond_the_resource_limits_are_refused() {
    assert_rejected(
        MINIMAL,
        &[
            "--set",
            "run.duration_s=1e5",
            "--set",
            "run.dt_s=1e-5",
            "--set",
            "run.log_every=1",
        ],
        &["--set run.log_every=1", "1.00e10 telemetry rows", "2000000"],
    );
}

/// Every key of the resolved scenario can be set with `--set`: each is set to its own
/// resolved value (arrays and strings as TOML writes them) and the scenario loads.
#[test]
fn every_key_can_be_set() {
    let resolved = wingman::scenario::Scenario::default().to_toml_string();
    let table: toml::Table = resolved.parse().expect("resolved scenario parses");
    let mut overrides = Vec::new();
    collect_overrides("", &table, &mut overrides);
    assert!(overrides.len() > 150, "only {} keys", overrides.len());
    assert!(
        overrides
            .iter()
            .any(|o| o.starts_with("atmosphere.disturbances.drag_factor="))
    );
    for set in &overrides {
        let result = wingman::scenario::Scenario::from_toml_str(
            "",
            std::path::Path::new("s.toml"),
            std::slice::from_ref(set),
        );
        assert!(result.is_ok(), "--set {set}: {}", result.unwrap_err());
    }
}

fn collect_overrides(prefix: &str, table: &toml::Table, out: &mut Vec<String>) {
    for (key, value) in table {
        let key = format!("{prefix}{key}");
        match value {
            toml::Value::Table(t) => collect_overrides(&format!("{key}."), t, out),
            other => out.push(format!("{key}={other}")),
        }
    }
}

/// A string-choice key given something else shows the value and lists its strings.
#[test]
fn string_choices_show_the_value_and_the_strings() {
    for (key, value, choice) in [
        ("target.motion", "1", "\"seed_profile\", \"straight\""),
        ("sensor.mode", "[1, 2]", "\"perfect\""),
        ("guidance.law", "true", "\"velocity\" or \"acceleration\""),
    ] {
        let set = format!("{key}={value}");
        let said = format!("{key} = {value} is invalid: allowed ");
        assert_rejected(MINIMAL, &["--set", &set], &[&said, choice]);
    }
    assert_rejected(
        "[camera.gimbal]\nkind = 3\n",
        &[],
        &["bad.toml:2:8:", "camera.gimbal.kind = 3", "\"pan_tilt\""],
    );
}

/// Whole numbers too large or negative for their key quote the key's own range, never a
/// Rust type's; run.seed's stated range is what TOML can write (2^63 - 1).
#[test]
fn integers_quote_the_range_of_their_key() {
    for value in ["-640", "0", "99999999999999999999999"] {
        assert_rejected(
            &format!("[camera]\nwidth_px = {value}\n"),
            &[],
            &[&format!("camera.width_px = {value}"), "[8, 8192]"],
        );
    }
    assert_rejected(
        MINIMAL,
        &["--set", "camera.width_px=-640"],
        &["camera.width_px = -640", "[8, 8192]"],
    );
    for value in ["9223372036854775808", "99999999999999999999999", "-1"] {
        assert_rejected(
            &format!("[run]\nseed = {value}\n"),
            &[],
            &[&format!("run.seed = {value}"), "[0, 9223372036854775807]"],
        );
    }
    let largest = ["run.seed=9223372036854775807".to_string()];
    let loaded = wingman::scenario::Scenario::from_toml_str("", Path::new("s.toml"), &largest);
    assert_eq!(
        loaded.expect("largest seed").run.seed,
        9_223_372_036_854_775_807
    );
}

/// A key given twice, an unknown section and an unknown top-level key are named with their
/// line and column.
#[test]
fn duplicates_and_unknown_sections_are_placed() {
    assert_rejected(
        "[run]\nseed = 1\nseed = 2\n",
        &[],
        &["bad.toml:3:1:", "duplicate key run.seed"],
    );
    assert_rejected(
        "[run]\nseed = 1\n[bogus_section]\nx = 1\n",
        &[],
        &["bad.toml:3:", "unknown key bogus_section"],
    );
    assert_rejected(
        "bogus = 1\n[run]\nseed = 1\n",
        &[],
        &["bad.toml:1:", "unknown key bogus"],
    );
}

/// `--set` of a key or section the schema does not have is blamed on the `--set` argument.
#[test]
fn unknown_set_keys_are_blamed_on_the_set_argument() {
    assert_rejected(
        MINIMAL,
        &["--set", "bogus.key=1"],
        &["--set bogus.key=1:", "bogus"],
    );
}

/// Bounds are printed short: a tiny bound from another key is no 50-digit float.
#[test]
fn bounds_are_short() {
    assert_rejected(
        "[excitation]\nk1 = 1e-30\n",
        &[],
        &["excitation.k3 = 0.0002", "allowed [0, 1e-30]"],
    );
}

/// Values no aircraft can have are refused before anything is written, with their range:
/// positions of 1e308 ft, a signal-to-noise ratio of 0 dB or below, a gain of 5e-324.
#[test]
fn physically_meaningless_values_are_refused_up_front() {
    for (set, expected) in [
        ("target.initial_position_ft=[1e308,0,0]", "[-1e6, 1e6] ft"),
        ("follower.initial_position_ft=[0,-2e6,0]", "[-1e6, 1e6] ft"),
        ("guidance.command_ft=[1e308,0,0]", "[-1e6, 1e6] ft"),
        ("sensor.snr_db=0", "(0, 200] dB"),
        ("sensor.snr_db=-5", "(0, 200] dB"),
        ("guidance.estimator_gain=5e-324", "[1e-9, 1e9]"),
        ("guidance.k=5e-324", "[1e-9, 1e9]"),
        ("acceleration.chi=1e300", "[1e-9, 1e9]"),
    ] {
        let key = set.split('=').next().expect("key");
        assert_rejected(MINIMAL, &["--set", set], &[key, expected]);
    }
}

/// Every key is checked whatever mode uses it: a camera key with a perfect or noisy sensor,
/// a waypoint with another motion.
#[test]
fn every_key_is_checked_in_every_mode() {
    assert_rejected(
        "[sensor]\nmode = \"perfect\"\n",
        &["--set", "camera.hfov_deg=nan"],
        &["camera.hfov_deg = NaN", "(0, 179)"],
    );
    assert_rejected(
        "[sensor]\nmode = \"noisy\"\n[camera]\nmsaa_samples = 3\n",
        &[],
        &["camera.msaa_samples = 3", "1 or 4"],
    );
    assert_rejected(
        "[target]\nmotion = \"straight\"\n[[target.waypoints]]\nposition_ft = [0.0, nan, 0.0]\nspeed_fps = 50.0\n",
        &[],
        &["target.waypoints[0].position_ft"],
    );
}
