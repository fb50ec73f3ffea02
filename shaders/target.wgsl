// Target silhouette and sky background, seen from the follower's camera.
// Layout must match `FrameUniforms` in src/render/uniforms.rs (352 bytes).
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
    // x: image height (px); y: first image row of the framebuffer (px); z: its first
    // column (px); w unused.
    image: vec4<f32>,
    // The world scene (src/render/scene.rs), used where flags.x is 1.
    // Camera axes -> NED, the true camera orientation.
    ned_from_camera: mat3x3<f32>,
    // The true camera position, NED, ft (xyz).
    camera_ned_ft: vec4<f32>,
    // x, y: principal point (px); z: focal length (px).
    optics: vec4<f32>,
    // x: ground's NED down (ft); y: field side (ft); z: road spacing (ft); w: road width (ft).
    ground: vec4<f32>,
    // x: cloud sheet's NED down (ft); y: lattice spacing (ft); z: density threshold.
    clouds: vec4<f32>,
    // xyz: unit vector towards the sun, NED; w: glare strength.
    sun: vec4<f32>,
    // x: haze visibility (ft).
    haze: vec4<f32>,
    // x: world scene on; y: ground on; z: clouds on; w: seed.
    flags: vec4<u32>,
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
    if (u.flags.x == 1u) {
        return vec4<f32>(with_glare(vec3<f32>(g, g, g), ray_ned(f.clip.xy)), 1.0);
    }
    return vec4<f32>(g, g, g, 1.0);
}

// One triangle covering the viewport.
fn full_viewport(i: u32) -> vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@vertex
fn vs_background(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return full_viewport(i);
}

@fragment
fn fs_background(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let t = clamp((frag.y + u.image.y) / u.image.x, 0.0, 1.0);
    return vec4<f32>(mix(u.sky_top.rgb, u.sky_bottom.rgb, t), 1.0);
}

// ---- The world scene (src/render/scene.rs mirrors the noise and the backdrop) ----

@vertex
fn vs_scene(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return full_viewport(i);
}

// Unit NED direction of the ray through framebuffer position `frag` (pixel centres at +0.5).
fn ray_ned(frag: vec2<f32>) -> vec3<f32> {
    let u_px = frag.x + u.image.z;
    let v_px = frag.y + u.image.y;
    let camera = vec3<f32>(u.optics.z, u_px - u.optics.x, v_px - u.optics.y);
    return normalize(u.ned_from_camera * camera);
}

fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A value in [0, 1) for lattice point (i, j) of stream `salt`.
fn lattice(i: i32, j: i32, salt: u32) -> f32 {
    let h = pcg(bitcast<u32>(i) ^ pcg(bitcast<u32>(j) ^ pcg(u.flags.w ^ salt)));
    return f32(h >> 8u) / 16777216.0;
}

fn value_noise(p: vec2<f32>, salt: u32) -> f32 {
    let cell = floor(p);
    let f = p - cell;
    let s = f * f * (3.0 - 2.0 * f);
    let i = i32(cell.x);
    let j = i32(cell.y);
    let bottom = mix(lattice(i, j, salt), lattice(i + 1, j, salt), s.x);
    let top = mix(lattice(i, j + 1, salt), lattice(i + 1, j + 1, salt), s.x);
    return mix(bottom, top, s.y);
}

fn cloud_density(p: vec2<f32>) -> f32 {
    let detail = vec2<f32>(p.x * 2.3 + 17.0, p.y * 2.3 + 31.0);
    return 0.65 * value_noise(p, 1u) + 0.35 * value_noise(detail, 2u);
}

// Fields of four crops, each shaded by its own hash, with roads along every k-th edge, as a
// pixel whose footprint on the ground is `footprint_ft` across sees them: fields smaller than
// the footprint fade to the crops' mean colour and a road narrower than it to its share of
// the pixel (a camera's pixel integrates what it sees; point samples of fields and roads
// finer than a pixel alias, and the pattern then changes from frame to frame).
fn ground_colour(p: vec2<f32>, footprint_ft: f32) -> vec3<f32> {
    let cell = floor(p / u.ground.y);
    let i = i32(cell.x);
    let j = i32(cell.y);
    let crop = u32(lattice(i, j, 3u) * 4.0);
    var colour = vec3<f32>(0.36, 0.50, 0.25);
    if (crop == 1u) {
        colour = vec3<f32>(0.58, 0.52, 0.30);
    } else if (crop == 2u) {
        colour = vec3<f32>(0.45, 0.60, 0.30);
    } else if (crop == 3u) {
        colour = vec3<f32>(0.42, 0.32, 0.22);
    }
    colour = colour * (0.85 + 0.3 * lattice(i, j, 4u));
    let crops_mean = vec3<f32>(0.4525, 0.485, 0.2675);
    colour = mix(colour, crops_mean, smoothstep(0.2, 1.0, footprint_ft / u.ground.y));
    let period = u.ground.z;
    let off_road = abs(p - period * round(p / period));
    let road_ft = u.ground.w;
    if (min(off_road.x, off_road.y) < 0.5 * max(road_ft, footprint_ft)) {
        let share = min(1.0, road_ft / max(footprint_ft, 1e-6));
        colour = mix(colour, vec3<f32>(0.47, 0.47, 0.47), share);
    }
    return colour;
}

// The sky's colour by elevation: horizon at 0, zenith straight up.
fn sky_colour(d: vec3<f32>) -> vec3<f32> {
    let up = sqrt(clamp(-d.z, 0.0, 1.0));
    return mix(u.sky_bottom.rgb, u.sky_top.rgb, up);
}

// Distance along unit ray d from the camera to the horizontal plane at `down_ft` (< 0: none).
fn plane_distance(d: vec3<f32>, down_ft: f32) -> f32 {
    if (abs(d.z) < 1e-6) {
        return -1.0;
    }
    return (down_ft - u.camera_ned_ft.z) / d.z;
}

// The glare around the sun, added towards white.
fn with_glare(colour: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if (u.sun.w <= 0.0) {
        return colour;
    }
    let angle = acos(clamp(dot(d, u.sun.xyz), -1.0, 1.0));
    let veil = u.sun.w * exp(-pow(angle / 0.10472, 2.0));
    return mix(colour, vec3<f32>(1.0, 1.0, 1.0), veil);
}

@fragment
fn fs_scene(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let d = ray_ned(frag.xy);
    var colour = sky_colour(d);
    var distance = 1e30;
    if (d.z > 0.0) {
        colour = u.sky_bottom.rgb;
    }
    let ground_t = plane_distance(d, u.ground.x);
    // Where the ray meets the ground, and the pixel's footprint there (derivatives are taken
    // before any branch: they need every pixel of the quad).
    let p = u.camera_ned_ft.xy + ground_t * d.xy;
    let footprint_ft = max(length(dpdx(p)), length(dpdy(p)));
    if (u.flags.y == 1u && ground_t > 0.0) {
        let fog = exp(-ground_t / u.haze.x);
        colour = mix(u.sky_bottom.rgb, ground_colour(p, footprint_ft), fog);
        distance = ground_t;
    } else if (dot(d, u.sun.xyz) > 0.99996) {
        // The sun's disc, 0.5° in radius (cos 0.5° = 0.99996): twice the real sun's.
        colour = vec3<f32>(1.0, 1.0, 0.97);
    }
    let cloud_t = plane_distance(d, u.clouds.x);
    if (u.flags.z == 1u && cloud_t > 0.0 && cloud_t < distance) {
        let p = (u.camera_ned_ft.xy + cloud_t * d.xy) / u.clouds.y;
        let density = cloud_density(p);
        let opacity = smoothstep(u.clouds.z - 0.03, u.clouds.z + 0.03, density);
        let lit = 0.82 + 0.12 * clamp(-u.sun.z, 0.0, 1.0);
        let cloud = vec3<f32>(lit, lit, lit * 1.02);
        colour = mix(colour, cloud, opacity * exp(-cloud_t / u.haze.x));
    }
    return vec4<f32>(with_glare(colour, d), 1.0);
}
