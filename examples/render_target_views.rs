//! Saves the target seen from ahead, behind, above, the side and three-quarter, 20 ft away, as
//! PNGs: `cargo run --release --example render_target_views OUT_DIR`.

use std::path::PathBuf;

use wingman::frames::{EulerAngles, Vec3};
use wingman::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use wingman::render::{GpuContext, RenderSettings, Renderer, TargetMesh};

fn main() -> anyhow::Result<()> {
    let out_dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let gpu = GpuContext::new()?;
    let mesh = TargetMesh::target_aircraft(1.0)?;
    let settings = RenderSettings::new(CameraIntrinsics::from_hfov(640, 480, 30.0));
    let mut renderer = Renderer::new(&gpu, settings, &mesh)?;
    let deg = |d: f64| d.to_radians();
    // Target attitude relative to the camera, as 3-2-1 angles of target-from-camera.
    let views = [
        ("behind", EulerAngles::new(0.0, 0.0, 0.0)),
        ("ahead", EulerAngles::new(0.0, 0.0, deg(180.0))),
        ("side", EulerAngles::new(0.0, 0.0, deg(90.0))),
        ("above", EulerAngles::new(0.0, deg(-90.0), 0.0)),
        (
            "three_quarter",
            EulerAngles::new(deg(20.0), deg(-25.0), deg(135.0)),
        ),
    ];
    for (name, attitude) in views {
        let pose = TargetPoseInCamera {
            position_body_ft: Vec3::new(20.0, 0.0, 0.0),
            body_from_target: attitude.body_from_ned().transpose(),
        };
        let path = out_dir.join(format!("view_{name}.png"));
        renderer.render(&pose, 0)?.save_png(&path)?;
        println!("{}", path.display());
    }
    Ok(())
}
