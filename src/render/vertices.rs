//! The target's vertices as the GPU draws them: un-indexed and flat-shaded.

use bytemuck::{Pod, Zeroable};

use crate::render::mesh::TargetMesh;

/// One vertex of the un-indexed, flat-shaded target: position and its face's normal.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub(super) struct TargetVertex {
    position_target_ft: [f32; 3],
    normal_target: [f32; 3],
}

impl TargetVertex {
    /// Position at shader location 0, normal at 1.
    const ATTRIBUTES: [wgpu::VertexAttribute; 2] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];

    /// The layout of a vertex buffer of these vertices.
    pub(super) fn buffer_layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<TargetVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// Three vertices per triangle, each carrying its face's unit normal (zero if degenerate);
/// an error says why `mesh` cannot be drawn (no triangles, or a missing vertex).
pub(super) fn flat_shaded_vertices(mesh: &TargetMesh) -> Result<Vec<TargetVertex>, String> {
    if mesh.triangles.is_empty() {
        return Err("no triangles".into());
    }
    let mut out = Vec::with_capacity(3 * mesh.triangles.len());
    for (k, t) in mesh.triangles.iter().enumerate() {
        let corner = |i: u32| {
            mesh.vertices_ft.get(i as usize).copied().ok_or_else(|| {
                format!(
                    "triangle {k} refers to vertex {i} of {}",
                    mesh.vertices_ft.len()
                )
            })
        };
        let (a, b, c) = (corner(t[0])?, corner(t[1])?, corner(t[2])?);
        let n = (b - a).cross(&(c - a));
        let n = if n.norm() > 0.0 { n.normalize() } else { n };
        let normal_target = [n.x as f32, n.y as f32, n.z as f32];
        for p in [a, b, c] {
            out.push(TargetVertex {
                position_target_ft: [p.x as f32, p.y as f32, p.z as f32],
                normal_target,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Vec3;

    #[test]
    fn degenerate_mesh_is_rejected() {
        let mesh = TargetMesh {
            vertices_ft: vec![Vec3::zeros()],
            triangles: vec![[0, 0, 5]],
        };
        assert!(flat_shaded_vertices(&mesh).is_err());
        assert!(flat_shaded_vertices(&TargetMesh::default()).is_err());
    }
}
