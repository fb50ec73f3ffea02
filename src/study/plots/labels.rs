//! What a study plot calls a `results.csv` column or a scenario key: words and a unit
//! (`rms_error_last20s_norm_ft` is "RMS slot error over the last 20 s, ft"), the names of the
//! default outcomes and common keys spelled out, any other name split from its unit suffix.

/// Default outcomes and common axis keys, in words (hats allowed).
const KNOWN: [(&str, &str); 17] = [
    (
        "rms_error_last20s_norm_ft",
        "RMS slot error over the last 20 s, ft",
    ),
    ("b_hat_final_ft", "b̂ at the end, ft"),
    ("min_range_ft", "closest range, ft"),
    ("lost_frames", "frames without the target"),
    ("centroid_rms_px", "centroid RMS error, px"),
    ("centroid_rms_deg", "centroid RMS error, deg"),
    ("length_rms_px", "length RMS error, px"),
    ("length_rms_deg", "length RMS error, deg"),
    ("size_measured_ft", "size from the measured length, ft"),
    ("size_mesh_ft", "size from the projected mesh, ft"),
    ("size_four_point_ft", "size from the four-point model, ft"),
    ("ratio_measured_true", "measured / true size"),
    ("lost_target", "lost the target (1 yes, 0 no)"),
    ("camera.hfov_deg", "horizontal field of view, deg"),
    ("camera.noise_std_grey", "pixel noise σ, grey levels"),
    ("camera.latency_frames", "latency, frames"),
    ("run.seed", "seed"),
];

/// Unit suffixes of column and key names, and the unit they stand for.
const UNITS: [(&str, &str); 14] = [
    ("_ft", "ft"),
    ("_fps2", "ft/s²"),
    ("_fps", "ft/s"),
    ("_px", "px"),
    ("_deg", "deg"),
    ("_rad", "rad"),
    ("_rps", "rad/s"),
    ("_ms", "ms"),
    ("_s", "s"),
    ("_hz", "Hz"),
    ("_db", "dB"),
    ("_grey", "grey levels"),
    ("_frames", "frames"),
    ("_pct", "%"),
];

/// A column's or key's label: its words and unit.
pub fn label(name: &str) -> String {
    if let Some((_, words)) = KNOWN.iter().find(|(n, _)| *n == name) {
        return words.to_string();
    }
    // A flattened summary entry (`rms_error_last20s_ft.0`) keeps its index after the unit.
    let (stem, index) = match name.rsplit_once('.') {
        Some((stem, i)) if i.chars().all(|c| c.is_ascii_digit()) => (stem, Some(i)),
        _ => (name, None),
    };
    let unit = UNITS.iter().find(|(suffix, _)| stem.ends_with(suffix));
    let words = unit.map_or(stem, |(suffix, _)| &stem[..stem.len() - suffix.len()]);
    let mut text = words.replace('_', " ");
    if let Some(i) = index {
        text.push_str(&format!(" [{i}]"));
    }
    if let Some((_, unit)) = unit {
        text.push_str(&format!(", {unit}"));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::label;

    #[test]
    fn names_become_words_with_units() {
        assert_eq!(
            label("rms_error_last20s_norm_ft"),
            "RMS slot error over the last 20 s, ft"
        );
        assert_eq!(label("camera.hfov_deg"), "horizontal field of view, deg");
        assert_eq!(label("camera.rate_hz"), "camera.rate, Hz");
        assert_eq!(label("rms_error_last20s_ft.2"), "rms error last20s [2], ft");
        assert_eq!(label("b_known_time_s"), "b known time, s");
        assert_eq!(label("frames"), "frames");
        for name in ["b_hat_final_ft", "centroid_rms_px", "min_range_ft"] {
            assert!(!label(name).contains('_'), "{name}: {}", label(name));
        }
    }
}
