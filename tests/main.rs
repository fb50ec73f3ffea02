//! The behaviour tests, one file per claim (docs/design.md, Tests), built as one test binary.
//!
//! Each file of tests/ is a module here rather than a test target of its own: the whole suite
//! links once instead of once per file (each link carries wgpu and the simulator), and
//! libtest runs the files' tests side by side on its threads, so that a file with one long
//! closed-loop run no longer holds the machine's other cores idle. One file's tests:
//! `cargo test --release --test behaviour FILE::`.

mod common;
mod render_support;

mod acceleration_closed_loop;
mod aircraft_actuators;
mod aircraft_data_file;
mod aircraft_disturbances;
mod aircraft_dryden;
mod aircraft_rigid_body;
mod aircraft_trim_holds;
mod airframe_table_rendered;
mod bank_reference_limit;
mod camera_window;
mod cluster_files;
mod cluster_job_array;
mod code_health;
mod control_course_response;
mod control_energy_loop;
mod control_flight;
mod control_prefilter;
mod covariance_at;
mod excitation_view_bound;
mod false_lock;
mod formation;
mod formation_crosswind;
mod formation_moderate_air;
mod frame_captions;
mod gate_reopen;
mod gimbal_cue_search;
mod group_chain;
mod group_crossing;
mod group_scenario_errors;
mod guidance_sees_no_truth;
mod horizon_crossing;
mod live_run;
mod merged_frames;
mod mesa_quiet;
mod navigation_inertial_own_motion;
mod navigation_ins_statistics;
mod navigation_mount_misalignment;
mod navigation_perfect_reproduces;
mod navigation_stamp_jitter;
mod output_folder_lock;
mod output_folder_reuse;
mod output_full_disk;
mod outputs_doc;
mod path_stretching;
mod readme_first_run;
mod render_bank;
mod render_determinism;
mod render_golden;
mod render_group;
mod render_matches_geometry;
mod render_mesh_asset;
mod render_no_adapter_hint;
mod render_out_checks;
mod render_scene;
mod render_vision_matches_truth;
mod render_window;
mod run_interrupted;
mod run_lost_target;
mod run_outputs;
mod run_scene;
mod scenario_assets;
mod scenario_errors;
mod scenario_fuzz;
mod scenario_reference;
mod scene_slot;
mod scene_target_colour;
mod seed_ch4_formation;
mod seed_ch4_intercept;
mod seed_ch5_formation;
mod seed_ch5_intercept;
mod seed_ch6_acceleration_noise;
mod seed_ch6_velocity_noise;
mod seed_ch7_acceleration;
mod seed_ch7_velocity;
mod seed_ch7_velocity_camera;
mod side_on_pass;
mod speed_floor;
mod study_apparent_size;
mod study_case_statuses;
mod study_out_folder;
mod study_sweep;
mod target_aircraft;
mod target_bank;
mod target_tracks;
mod video_export;
mod vision_ch4_filter;
mod vision_ch4_formation;
