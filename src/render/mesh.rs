//! The target's triangle mesh in target-body axes (x forward, y right wing, z down, ft, origin at
//! the centre of gravity), loaded from a Wavefront OBJ file.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

use crate::frames::Vec3;

/// The seed's target aircraft (8 ft span), as committed in `assets/target_aircraft.obj`.
pub const TARGET_AIRCRAFT_OBJ: &str = include_str!("../../assets/target_aircraft.obj");

/// Path of the committed target aircraft asset, relative to the crate root.
pub const TARGET_AIRCRAFT_OBJ_PATH: &str = "assets/target_aircraft.obj";

/// Largest mesh file read, bytes (64 MiB: about a million triangles of OBJ text).
pub const MAX_MESH_FILE_BYTES: u64 = 64 << 20;

/// Why a target mesh could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be opened or read.
    #[error("cannot read target mesh {path}: {source}")]
    Read {
        /// The mesh file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The OBJ text could not be parsed.
    #[error("cannot parse target mesh {path} as OBJ: {source}")]
    Parse {
        /// The mesh file.
        path: PathBuf,
        /// What the OBJ parser said.
        source: tobj::LoadError,
    },
    /// The file holds no triangle.
    #[error("target mesh {path} has no triangles (expected `f` lines with 3 or more vertices)")]
    NoTriangles {
        /// The mesh file.
        path: PathBuf,
    },
    /// The path is not a regular file (a folder, a device, a pipe).
    #[error("target mesh {path} is not a regular file")]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// The file is larger than [`MAX_MESH_FILE_BYTES`].
    #[error("target mesh {path} is larger than the limit of {} MiB", MAX_MESH_FILE_BYTES >> 20)]
    TooLarge {
        /// The mesh file.
        path: PathBuf,
    },
    /// Every triangle has zero area: nothing to draw.
    #[error("target mesh {path} has no area (every triangle is degenerate)")]
    ZeroArea {
        /// The mesh file.
        path: PathBuf,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("target mesh {path}: vertex {index} is not finite")]
    NonFiniteVertex {
        /// The mesh file.
        path: PathBuf,
        /// 0-based vertex index.
        index: usize,
    },
    /// The scale factor is not a finite positive number.
    #[error("target mesh {path}: scale factor {scale} must be finite and > 0")]
    BadScale {
        /// The mesh file.
        path: PathBuf,
        /// The scale factor given.
        scale: f64,
    },
}

/// A triangle mesh of the target in target-body axes, ft.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TargetMesh {
    /// Vertex positions in target-body axes, ft.
    pub vertices_ft: Vec<Vec3>,
    /// Triangles as indices into `vertices_ft`.
    pub triangles: Vec<[u32; 3]>,
}

impl TargetMesh {
    /// Loads an OBJ file (all objects merged, polygons triangulated) and multiplies every vertex
    /// by `scale` (e.g. b / 8 ft to resize the 8 ft seed aircraft to a span b).
    pub fn load_obj(path: &Path, scale: f64) -> Result<Self, MeshError> {
        let read_error = |source| MeshError::Read {
            path: path.to_path_buf(),
            source,
        };
        let file = File::open(path).map_err(read_error)?;
        if !file.metadata().map_err(read_error)?.is_file() {
            return Err(MeshError::NotAFile {
                path: path.to_path_buf(),
            });
        }
        // A file that grows while it is read is cut at the limit too.
        let mut bytes = Vec::new();
        file.take(MAX_MESH_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(read_error)?;
        if bytes.len() as u64 > MAX_MESH_FILE_BYTES {
            return Err(MeshError::TooLarge {
                path: path.to_path_buf(),
            });
        }
        Self::from_obj_reader(&mut bytes.as_slice(), scale, path)
    }

    /// The mesh with every vertex multiplied by `factor`.
    pub fn scaled(mut self, factor: f64) -> Self {
        for v in &mut self.vertices_ft {
            *v *= factor;
        }
        self
    }

    /// Total area of the triangles, ft².
    pub fn area_ft2(&self) -> f64 {
        let v = &self.vertices_ft;
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| v[i as usize]);
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .sum()
    }

    /// The committed seed target aircraft (8 ft span) times `scale`, parsed from the copy of
    /// `assets/target_aircraft.obj` built into the binary.
    pub fn target_aircraft(scale: f64) -> Result<Self, MeshError> {
        Self::from_obj_reader(
            &mut TARGET_AIRCRAFT_OBJ.as_bytes(),
            scale,
            Path::new(TARGET_AIRCRAFT_OBJ_PATH),
        )
    }

    /// Parses OBJ text from a reader; `path` only names the source in error messages.
    /// Material libraries are ignored: the renderer shades the target itself.
    pub fn from_obj_reader(
        reader: &mut impl BufRead,
        scale: f64,
        path: &Path,
    ) -> Result<Self, MeshError> {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(MeshError::BadScale {
                path: path.to_path_buf(),
                scale,
            });
        }
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        let (models, _materials) = tobj::load_obj_buf(reader, &options, |_| Ok(Default::default()))
            .map_err(|source| MeshError::Parse {
                path: path.to_path_buf(),
                source,
            })?;
        let mut mesh = TargetMesh::default();
        for model in &models {
            let base = mesh.vertices_ft.len();
            for p in model.mesh.positions.chunks_exact(3) {
                let v = Vec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])) * scale;
                if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
                    return Err(MeshError::NonFiniteVertex {
                        path: path.to_path_buf(),
                        index: mesh.vertices_ft.len(),
                    });
                }
                mesh.vertices_ft.push(v);
            }
            let count = mesh.vertices_ft.len() - base;
            for t in model.mesh.indices.chunks_exact(3) {
                // tobj checks indices against the file's vertices; keep only in-model ones.
                if t.iter().all(|&i| (i as usize) < count) {
                    let base = base as u32;
                    mesh.triangles.push([t[0] + base, t[1] + base, t[2] + base]);
                }
            }
        }
        if mesh.triangles.is_empty() {
            return Err(MeshError::NoTriangles {
                path: path.to_path_buf(),
            });
        }
        let area = mesh.area_ft2();
        if !(area.is_finite() && area > 0.0) {
            return Err(MeshError::ZeroArea {
                path: path.to_path_buf(),
            });
        }
        Ok(mesh)
    }

    /// Largest distance between two vertices, ft: the target's maximal size b of (3.12).
    pub fn max_dimension_ft(&self) -> f64 {
        super::diameter::diameter(&self.vertices_ft)
    }

    /// The mesh as OBJ text (`v` and `f` lines, 1-based), after `# `-prefixed header lines.
    pub fn to_obj_string(&self, header: &str) -> String {
        let mut out = String::new();
        for line in header.lines() {
            let _ = writeln!(out, "# {line}");
        }
        let _ = writeln!(out, "o target");
        for v in &self.vertices_ft {
            let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
        }
        for t in &self.triangles {
            let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_file_names_the_path() {
        let err = TargetMesh::load_obj(Path::new("no/such/mesh.obj"), 1.0).unwrap_err();
        let msg = err.to_string();
        assert!(matches!(err, MeshError::Read { .. }));
        assert!(msg.contains("no/such/mesh.obj"), "{msg}");
    }

    #[test]
    fn file_without_faces_is_rejected() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let err =
            TargetMesh::from_obj_reader(&mut text.as_bytes(), 1.0, Path::new("x.obj")).unwrap_err();
        assert!(matches!(err, MeshError::NoTriangles { .. }), "{err}");
        assert!(err.to_string().contains("x.obj"));
    }

    #[test]
    fn quads_are_triangulated_and_scaled() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        let mesh =
            TargetMesh::from_obj_reader(&mut text.as_bytes(), 2.0, Path::new("q.obj")).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert!((mesh.max_dimension_ft() - 2.0 * 2f64.sqrt()).abs() < 1e-12);
    }

    /// A device that never ends, a folder and a degenerate mesh are refused at once.
    #[test]
    fn unbounded_folder_and_flat_inputs_are_refused() {
        let err = TargetMesh::load_obj(Path::new("/dev/zero"), 1.0).unwrap_err();
        assert!(matches!(err, MeshError::NotAFile { .. }), "{err}");
        let err = TargetMesh::load_obj(Path::new("."), 1.0).unwrap_err();
        assert!(
            matches!(err, MeshError::NotAFile { .. } | MeshError::Read { .. }),
            "{err}"
        );
        let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
        let err =
            TargetMesh::from_obj_reader(&mut text.as_bytes(), 1.0, Path::new("l.obj")).unwrap_err();
        assert!(matches!(err, MeshError::ZeroArea { .. }), "{err}");
    }

    /// A file over the limit is refused without parsing it.
    #[test]
    fn oversized_file_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("big.obj");
        let file = File::create(&path).expect("create");
        file.set_len(MAX_MESH_FILE_BYTES + 1).expect("sparse file");
        let err = TargetMesh::load_obj(&path, 1.0).unwrap_err();
        assert!(matches!(err, MeshError::TooLarge { .. }), "{err}");
    }

    #[test]
    fn bad_scale_is_rejected() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        for scale in [0.0, -1.0, f64::NAN] {
            let err = TargetMesh::from_obj_reader(&mut text.as_bytes(), scale, Path::new("s.obj"))
                .unwrap_err();
            assert!(matches!(err, MeshError::BadScale { .. }));
        }
    }

    #[test]
    fn obj_text_round_trips() {
        let text = "v 0 0 0\nv 1 0.5 0\nv 0 1 -0.25\nf 1 2 3\n";
        let mesh =
            TargetMesh::from_obj_reader(&mut text.as_bytes(), 1.0, Path::new("r.obj")).unwrap();
        let again = TargetMesh::from_obj_reader(
            &mut mesh.to_obj_string("hdr").as_bytes(),
            1.0,
            Path::new("r2.obj"),
        )
        .unwrap();
        assert_eq!(mesh, again);
    }
}
