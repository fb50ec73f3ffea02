//! Multisampling only a window around the target (`render::window`) draws the frame the whole
//! multisampled image draws, over poses at every range of the seed's run, across the field of
//! view, partly outside the image, on a uniform and on a gradient sky: the same pixels but for
//! a few samples that lie on an edge (the window's projection moves vertices by a rounding
//! error, ~1e-5 px, which can put a sample on the other side of an edge).

mod render_support;

use render_support::*;
use wingman::render::camera::CameraIntrinsics;
use wingman::render::{RenderSettings, Renderer, Sky};

/// Frames of both renderers for the same poses: how many pixel channels differ, and by how
/// much at most.
fn compare(sky: Sky) -> (usize, u8, usize) {
    let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = 4;
    settings.background.sky = sky;
    let mesh = aircraft();
    let mut windowed = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
    settings.multisample_window = false;
    let mut whole = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let (mut differing, mut worst, mut drawn) = (0, 0u8, 0);
    for range_ft in [25.0, 60.0, 140.0, 250.0] {
        // Bearing (as a fraction of the range) and elevation, the last ones cut by the border.
        for (y, z) in [
            (0.0, 0.0),
            (0.2, -0.1),
            (-0.45, 0.3),
            (0.6, 0.0),
            (0.0, -0.42),
        ] {
            for attitude in [[0.0, 0.0, 0.0], [0.3, 0.9, 0.4], [-0.4, 1.1, 2.0]] {
                let p = pose([range_ft, y * range_ft, z * range_ft], attitude);
                let a = windowed
                    .render(&p, 0)
                    .unwrap_or_else(|e| panic!("{e}"))
                    .clone();
                let b = whole.render(&p, 0).unwrap_or_else(|e| panic!("{e}"));
                let mut any = false;
                for (x, y) in a.rgba.iter().zip(&b.rgba) {
                    let d = x.abs_diff(*y);
                    if d > 0 {
                        differing += 1;
                        worst = worst.max(d);
                    }
                    any |= d > 0;
                }
                drawn += usize::from(!any);
            }
        }
    }
    (differing, worst, drawn)
}

#[test]
fn windowed_frames_equal_whole_frames() {
    for sky in [
        Sky::Uniform {
            rgb: [175, 200, 230],
        },
        Sky::VerticalGradient {
            top_rgb: [150, 180, 225],
            bottom_rgb: [215, 225, 235],
        },
    ] {
        let (differing, worst, identical) = compare(sky);
        eprintln!(
            "{sky:?}: {differing} channels differ, by at most {worst}; {identical} of 60 frames identical"
        );
        // One sample of four: at most a quarter of the largest target-sky contrast (255).
        assert!(worst <= 64, "{sky:?}: a channel differs by {worst}");
        // A few edge pixels (3 channels each) in a few frames: measured 30-32 channels in
        // 10-11 frames; at most 20 pixels in at most 15 of the 60 frames.
        assert!(
            identical >= 45,
            "{sky:?}: only {identical} of 60 frames identical"
        );
        assert!(differing <= 3 * 20, "{sky:?}: {differing} channels differ");
    }
}
