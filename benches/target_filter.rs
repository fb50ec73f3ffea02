//! Per-frame cost of the range-and-size filter (`estimation::kalman`): one prediction to the
//! next frame and one update, with the white-jerk model alone (the target-motion states
//! inert, `estimator.target_gust_sigma_fps = 0`), with the gust velocity's states, and with
//! those and the target's bank fused beside the frame (`estimator.target_bank = "measured"`:
//! the iterated update of its acceleration across its velocity). Run with
//! `cargo bench --bench target_filter`.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wingman::estimation::kalman::{FilterNoise, FilterPrior, TargetFilter};
use wingman::frames::{Mat3, Vec3};

fn one_frame(c: &mut Criterion) {
    let prior = FilterPrior {
        size_ft: 4.0,
        inverse_size_sigma_per_ft: 0.15,
        relative_velocity_sigma_fps: 15.0,
        acceleration_sigma_fps2: 3.0,
        size_bounds_ft: None,
    };
    let white_jerk = FilterNoise::without_gust(1e-4, 1e-7);
    let gust = FilterNoise {
        gust_sigma_fps: 0.8,
        gust_time_s: 1.5,
        ..white_jerk
    };
    let covariance = Mat3::identity() * 1e-4;
    let frame_s = 1.0 / 30.0;
    let cases = [
        ("white_jerk", white_jerk, false),
        ("gust", gust, false),
        ("gust_and_bank", gust, true),
    ];
    for (name, noise, bank) in cases {
        let mut filter = TargetFilter::new(
            noise,
            &prior,
            &Vec3::new(4.0, 1.0, 0.0),
            &covariance,
            0.0,
            &Vec3::zeros(),
            &Vec3::new(50.0, 0.0, 0.0),
        );
        let mut k = 0u32;
        c.bench_function(&format!("target_filter/{name}"), |b| {
            b.iter(|| {
                k += 1;
                let t_s = f64::from(k) * frame_s;
                let follower = Vec3::new(50.0 * t_s, (t_s * 2.0).sin(), 0.0);
                filter.predict_to(t_s, &follower);
                let r_star = Vec3::new(4.0, 1.0 - follower.y / 8.0, 0.0);
                black_box(filter.update(black_box(&r_star), &covariance));
                if bank {
                    let across = Vec3::new(0.0, 1.0, 0.0);
                    let turn_fps2 = 2.0 * (t_s * 0.5).sin();
                    black_box(filter.update_lateral_acceleration(&across, turn_fps2, 1.0, 16.3));
                }
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = one_frame
}
criterion_main!(benches);
