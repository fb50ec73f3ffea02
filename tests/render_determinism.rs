//! Rendering is a pure function of (settings, mesh, pose, frame index) on one machine: the same
//! inputs give identical bytes, also from two threads sharing one device.
//! Pixel noise is keyed by (seed, frame index) and has the requested standard deviation.

use crate::render_support::*;
use wingman::render::camera::CameraIntrinsics;
use wingman::render::{Background, CameraImage, PixelNoise, RenderSettings, Renderer, Sky};

fn renderer(settings: RenderSettings) -> Renderer {
    match Renderer::new(gpu(), settings, &aircraft()) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    }
}

fn noisy_settings(std_grey_levels: f64, seed: u64) -> RenderSettings {
    let mut s = RenderSettings::new(CameraIntrinsics::from_hfov(320, 240, 50.0));
    s.background = Background {
        sky: Sky::VerticalGradient {
            top_rgb: [150, 180, 220],
            bottom_rgb: [200, 210, 220],
        },
        noise: Some(PixelNoise {
            std_grey_levels,
            seed,
        }),
    };
    s
}

fn frame_of(
    r: &mut Renderer,
    p: &wingman::render::camera::TargetPoseInCamera,
    k: u64,
) -> CameraImage {
    match r.render(p, k) {
        Ok(f) => f.clone(),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn same_pose_twice_gives_identical_bytes() {
    let p = pose([30.0, 2.0, -1.0], [0.2, -0.1, 0.7]);
    for msaa in [1, 4] {
        let mut s = RenderSettings::new(CameraIntrinsics::from_hfov(320, 240, 50.0));
        s.msaa_samples = msaa;
        let mut r = renderer(s);
        let a = frame_of(&mut r, &p, 0);
        let _other = frame_of(&mut r, &pose([50.0, -3.0, 2.0], [0.0, 0.0, 0.0]), 1);
        let b = frame_of(&mut r, &p, 2);
        assert!(a == b, "{msaa} samples: frames differ");
        // A fresh renderer on the same device agrees too.
        let c = frame_of(&mut renderer(s), &p, 0);
        assert!(a == c, "{msaa} samples: fresh renderer differs");
    }
}

#[test]
fn two_threads_sharing_the_device_agree() {
    let p = pose([25.0, 1.0, 0.5], [0.1, 0.2, -0.4]);
    let settings = noisy_settings(6.0, 42);
    let reference = frame_of(&mut renderer(settings), &p, 7);
    let frames: Vec<CameraImage> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2)
            .map(|_| {
                scope.spawn(|| {
                    let mut r = renderer(settings);
                    (0..20).map(|_| frame_of(&mut r, &p, 7)).last()
                })
            })
            .collect();
        handles
            .into_iter()
            .filter_map(|h| h.join().ok().flatten())
            .collect()
    });
    assert_eq!(frames.len(), 2);
    assert!(frames.iter().all(|f| *f == reference));
}

#[test]
fn noise_depends_on_seed_and_frame_index_only() {
    let p = pose([25.0, 1.0, 0.5], [0.1, 0.2, -0.4]);
    let mut r = renderer(noisy_settings(6.0, 42));
    let a = frame_of(&mut r, &p, 3);
    let b = frame_of(&mut r, &p, 4);
    let a_again = frame_of(&mut r, &p, 3);
    let other_seed = frame_of(&mut renderer(noisy_settings(6.0, 43)), &p, 3);
    assert!(a == a_again);
    assert!(a != b);
    assert!(a != other_seed);
}

#[test]
fn noise_has_the_requested_standard_deviation() {
    // Target behind the camera: uniform sky plus noise only.
    let mut s = noisy_settings(8.0, 7);
    s.background.sky = Sky::Uniform {
        rgb: [128, 128, 128],
    };
    let frame = frame_of(&mut renderer(s), &pose([-50.0, 0.0, 0.0], [0.0; 3]), 11);
    let red: Vec<f64> = frame
        .rgba
        .chunks_exact(4)
        .map(|p| f64::from(p[0]))
        .collect();
    let n = red.len() as f64;
    let mean = red.iter().sum::<f64>() / n;
    let var = red.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    // 76 800 samples: the sample std's own std is 8/sqrt(2n) ≈ 0.02; 8-bit rounding adds
    // 1/12 to the variance (std 8.005). Allow 0.15 for both, and 0.1 on the mean (std 0.03).
    assert!((var.sqrt() - 8.0).abs() < 0.15, "std {}", var.sqrt());
    assert!((mean - 128.0).abs() < 0.1, "mean {mean}");
    // Same value on R, G and B (grey noise).
    assert!(
        frame
            .rgba
            .chunks_exact(4)
            .all(|p| p[0] == p[1] && p[1] == p[2])
    );
}
