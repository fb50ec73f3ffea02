// Target silhouette and sky background, seen from the follower's camera.
// Layout must match `FrameUniforms` in src/render/renderer.rs (208 bytes).

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
    // x: noise standard deviation (0..1 units), y: image height (px), z: 1 if noise on.
    noise: vec4<f32>,
    // Noise key: seed low/high word, frame index low/high word.
    noise_key: vec4<u32>,
};

@group(0) @binding(0) var<uniform> u: FrameUniforms;

// PCG hash (Jarzynski & Olano 2020): a well-mixed u32 from a u32.
fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Standard normal sample for pixel (x, y) of this frame, by Box-Muller on two hashed uniforms.
fn gaussian(pixel: vec2<u32>) -> f32 {
    let k = u.noise_key;
    let h1 = pcg(pixel.x ^ pcg(pixel.y ^ pcg(k.x ^ pcg(k.y ^ pcg(k.z ^ pcg(k.w))))));
    let h2 = pcg(h1);
    let u1 = (f32(h1 >> 8u) + 0.5) / 16777216.0;
    let u2 = f32(h2 >> 8u) / 16777216.0;
    return sqrt(-2.0 * log(u1)) * cos(6.283185307 * u2);
}

fn with_noise(rgb: vec3<f32>, frag: vec4<f32>) -> vec4<f32> {
    var c = rgb;
    if (u.noise.z > 0.5) {
        let n = u.noise.x * gaussian(vec2<u32>(frag.xy));
        c = c + vec3<f32>(n, n, n);
    }
    return vec4<f32>(clamp(c, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}

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
    return with_noise(vec3<f32>(g, g, g), f.clip);
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
    let t = clamp(frag.y / u.noise.y, 0.0, 1.0);
    return with_noise(mix(u.sky_top.rgb, u.sky_bottom.rgb, t), frag);
}
