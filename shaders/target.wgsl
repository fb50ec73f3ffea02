// Target silhouette and sky background, seen from the follower's camera.
// Layout must match `FrameUniforms` in src/render/uniforms.rs (192 bytes).
// Pixel noise is added on the CPU after readback (src/render/noise.rs): cheaper on lavapipe.

struct FrameUniforms {
    // Target-body point (ft, homogeneous) -> clip space; see src/render/projection.rs.
    clip_from_target: mat4x4<f32>,
    // Rotation target-body -> camera/body, for face normals.
    body_from_target: mat3x3<f32>,
    // Unit vector towards the light, camera/body axes (xyz).
    light_dir_body: vec4<f32>,
    // x: grey of faces turned away from the light, y: grey of faces facing it (0..1).
    target_grey: vec4<f32>,
    // Sky colour at the top and the bottom row (rgb, 0..1); w unused.
    sky_top: vec4<f32>,
    sky_bottom: vec4<f32>,
    // x: image height (px); y: first image row of the framebuffer (px); zw unused.
    image: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: FrameUniforms;

struct TargetVertex {
    @location(0) position_target_ft: vec3<f32>,
    @location(1) normal_target: vec3<f32>,
};

struct TargetFragment {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) normal_body: vec3<f32>,
};

@vertex
fn vs_target(v: TargetVertex) -> TargetFragment {
    var out: TargetFragment;
    out.clip = u.clip_from_target * vec4<f32>(v.position_target_ft, 1.0);
    out.normal_body = u.body_from_target * v.normal_target;
    return out;
}

@fragment
fn fs_target(f: TargetFragment) -> @location(0) vec4<f32> {
    // Two-sided Lambert: a face lit from either side is lit.
    let lambert = abs(dot(f.normal_body, u.light_dir_body.xyz));
    let g = mix(u.target_grey.x, u.target_grey.y, lambert);
    return vec4<f32>(g, g, g, 1.0);
}

@vertex
fn vs_background(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the viewport.
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_background(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let t = clamp((frag.y + u.image.y) / u.image.x, 0.0, 1.0);
    return vec4<f32>(mix(u.sky_top.rgb, u.sky_bottom.rgb, t), 1.0);
}
