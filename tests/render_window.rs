//! Drawing the target only in a window around it (`render::window`) draws the frame the whole
//! multisampled image draws, over poses at every range of the seed's run, across the field of
//! view, partly outside the image, on a uniform and on a gradient sky: the same pixels but for
//! a few samples that lie on an edge (the window's projection moves vertices by a rounding
//! error, ~1e-5 px, which can put a sample on the other side of an edge). And a frame drawn
//! and read back only in a region of the image holds exactly the bytes the whole
//! frame holds there.

use crate::render_support::*;
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{Background, ImageRegion, PixelNoise, RenderSettings, Renderer, Sky};

/// The 60 poses: every range of the seed's run, across the field of view (the last ones cut
/// by the border), three attitudes each.
fn poses() -> Vec<TargetPoseInCamera> {
    let mut out = Vec::new();
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
                out.push(pose([range_ft, y * range_ft, z * range_ft], attitude));
            }
        }
    }
    out
}

/// Frames of both renderers for the same poses: how many pixel channels differ, and by how
/// much at most.
fn compare(sky: Sky) -> (usize, u8, usize) {
    let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let mut settings = RenderSettings::new(cam);
    settings.msaa_samples = 4;
    settings.background.sky = sky;
    let mesh = aircraft();
    let mut windowed = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
    settings.target_window = false;
    let mut whole = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
    let (mut differing, mut worst, mut drawn) = (0, 0u8, 0);
    for p in poses() {
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

/// A frame drawn and read back in a region of the image holds the bytes the whole
/// frame holds there, exactly: the region's sky comes from a sky texture drawn by the whole
/// frame's sky pass, the target's window is planned from the pose alone, and the noise of a
/// pixel is keyed by its place in the image. Over the 60 poses above, regions around, beside,
/// across and away from the target, 1 and 4 samples, uniform and noisy gradient skies.
#[test]
fn region_frames_equal_the_whole_frame_there() {
    let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
    let mesh = aircraft();
    let regions = [
        ImageRegion {
            u0_px: 200,
            v0_px: 150,
            width_px: 240,
            height_px: 180,
        },
        ImageRegion {
            u0_px: 0,
            v0_px: 0,
            width_px: 333,
            height_px: 77,
        },
        ImageRegion {
            u0_px: 301,
            v0_px: 7,
            width_px: 339,
            height_px: 473,
        },
        ImageRegion {
            u0_px: 5,
            v0_px: 400,
            width_px: 1,
            height_px: 80,
        },
    ];
    let noisy_gradient = Background {
        sky: Sky::VerticalGradient {
            top_rgb: [150, 180, 225],
            bottom_rgb: [215, 225, 235],
        },
        noise: Some(PixelNoise {
            std_grey_levels: 4.0,
            seed: 3,
        }),
    };
    for (msaa_samples, background) in [
        (4, Background::default()),
        (1, Background::default()),
        (4, noisy_gradient),
        (1, noisy_gradient),
    ] {
        let mut settings = RenderSettings::new(cam);
        settings.msaa_samples = msaa_samples;
        settings.background = background;
        let mut renderer = Renderer::new(gpu(), settings, &mesh).unwrap_or_else(|e| panic!("{e}"));
        let mut compared = 0;
        for (k, p) in poses().iter().enumerate() {
            let whole = renderer
                .render(p, k as u64)
                .unwrap_or_else(|e| panic!("{e}"))
                .clone();
            let region = regions[k % regions.len()];
            let part = renderer
                .render_region(p, &region, k as u64)
                .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(
                (part.width_px, part.height_px),
                (region.width_px, region.height_px)
            );
            for v in 0..region.height_px {
                for u in 0..region.width_px {
                    let (iu, iv) = (u + region.u0_px, v + region.v0_px);
                    assert_eq!(
                        part.pixel(u, v),
                        whole.pixel(iu, iv),
                        "pose {k}, {msaa_samples} samples, {background:?}: pixel ({iu}, {iv})"
                    );
                }
            }
            compared += 1;
        }
        assert_eq!(compared, 60);
    }
}
