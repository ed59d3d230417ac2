//! Meshes from model files: [`LoadedMesh`], what a loader gives, and [`RawMesh`], what a file
//! holds before [`finish_mesh`] checks and repairs it (see the [assets documentation](super)).

use std::path::Path;
use std::sync::Arc;

use firmament_core::classic::mesh::Mesh;
use firmament_core::texture::TextureImage;
use glam::{DMat4, DVec3};

/// One mesh of a model file, with what the file says about its look.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    /// The triangles, validated (`Mesh::validate` passes); shared between the meshes of a file
    /// that draw the same primitive (a glTF mesh used by several nodes).
    pub mesh: Arc<Mesh>,
    /// Mesh → model-file root transform (a glTF node's world matrix; identity for OBJ).
    pub transform: DMat4,
    /// Base (diffuse) colour factor, linear RGBA, if the file gives one.
    pub base_color: Option<[f64; 4]>,
    /// Base colour texture, if the file gives one; shared between the meshes that use it.
    pub texture: Option<Arc<TextureImage>>,
}

/// A mesh as a file gives it, before the repairs of [`finish_mesh`].
#[derive(Debug, Clone, Default)]
pub(super) struct RawMesh {
    /// Vertex positions.
    pub(super) positions: Vec<[f32; 3]>,
    /// Per-vertex normals, if the file has them (one per position).
    pub(super) normals: Option<Vec<[f32; 3]>>,
    /// Per-vertex texture coordinates, OpenGL convention, if the file has them.
    pub(super) tex_coords: Option<Vec<[f32; 2]>>,
    /// Triangle list.
    pub(super) indices: Vec<u32>,
    /// Per-vertex fog coordinates (glTF `_FOG_COORD`), if the file has them.
    pub(super) fog_coords: Option<Vec<f32>>,
}

/// Checks a [`RawMesh`] and repairs what the [assets documentation](super) lists, logging it;
/// `file` and `label` (which mesh of the file) name it in messages.
pub(super) fn finish_mesh(raw: RawMesh, file: &Path, label: &str) -> Result<Mesh, String> {
    let file = file.display();
    let n = raw.positions.len();
    if n == 0 {
        return Err(format!("{label} has no vertices"));
    }
    if let Some((i, p)) = raw
        .positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
    {
        return Err(format!("{label}: vertex {i} has a non-finite position {p:?}"));
    }
    let tex_coords = match raw.tex_coords {
        None => vec![[0.0; 2]; n],
        Some(t) if t.len() != n => {
            return Err(format!("{label}: {} texture coordinates for {n} vertices", t.len()));
        }
        Some(t) => {
            if let Some((i, t)) = t.iter().enumerate().find(|(_, t)| !t.iter().all(|c| c.is_finite())) {
                return Err(format!("{label}: vertex {i} has non-finite texture coordinates {t:?}"));
            }
            t
        }
    };
    if let Some(normals) = &raw.normals {
        if normals.len() != n {
            return Err(format!("{label}: {} normals for {n} vertices", normals.len()));
        }
    }
    if !raw.indices.len().is_multiple_of(3) {
        return Err(format!(
            "{label}: {} indices, not a whole number of triangles",
            raw.indices.len()
        ));
    }
    if let Some(i) = raw.indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!(
            "{label}: index {i} is out of range (the mesh has {n} vertices)"
        ));
    }

    // Drop degenerate triangles; sum the others' unnormalised normals (twice their area) per vertex.
    let position = |i: u32| DVec3::from(raw.positions[i as usize].map(f64::from));
    let mut indices = Vec::with_capacity(raw.indices.len());
    let mut sums = vec![DVec3::ZERO; n];
    let mut dropped = 0_usize;
    for triangle in raw.indices.chunks_exact(3) {
        let (a, b, c) = (triangle[0], triangle[1], triangle[2]);
        let cross = (position(b) - position(a)).cross(position(c) - position(a));
        if a == b || b == c || a == c || cross == DVec3::ZERO {
            dropped += 1;
            continue;
        }
        indices.extend_from_slice(triangle);
        for v in triangle {
            sums[*v as usize] += cross;
        }
    }
    let total = raw.indices.len() / 3;
    if indices.is_empty() {
        return Err(if total == 0 {
            format!("{label} has no triangles")
        } else {
            format!("{label} has no triangles left: all {total} are degenerate (zero area or a repeated vertex)")
        });
    }
    if dropped > 0 {
        tracing::info!(
            "{file}: {label}: dropped {dropped} of {total} triangles as degenerate (zero area or a repeated vertex)"
        );
    }

    let mut fallbacks = 0_usize;
    let mut computed = |v: usize| -> [f32; 3] {
        let sum = sums[v];
        if sum == DVec3::ZERO {
            fallbacks += 1;
            [0.0, 0.0, 1.0]
        } else {
            // `sum` is finite (products of f32 coordinates cannot overflow an f64) and non-zero.
            sum.normalize().as_vec3().to_array()
        }
    };
    let normals = match raw.normals {
        None => {
            tracing::info!("{file}: {label} has no normals; computing smooth area-weighted vertex normals");
            (0..n).map(&mut computed).collect()
        }
        Some(given) => {
            let (mut replaced, mut renormalised) = (0_usize, 0_usize);
            let normals = given
                .iter()
                .enumerate()
                .map(|(v, normal)| {
                    let d = DVec3::from(normal.map(f64::from));
                    let length = d.length();
                    if !length.is_finite() || length == 0.0 {
                        replaced += 1;
                        computed(v)
                    } else if (length - 1.0).abs() > 1e-6 {
                        renormalised += 1;
                        (d / length).as_vec3().to_array()
                    } else {
                        *normal
                    }
                })
                .collect();
            if replaced > 0 {
                tracing::warn!(
                    "{file}: {label}: {replaced} vertex normals are zero or not finite; replaced by computed smooth normals"
                );
            }
            if renormalised > 0 {
                tracing::debug!("{file}: {label}: normalised {renormalised} vertex normals that were not unit length");
            }
            normals
        }
    };
    if fallbacks > 0 {
        tracing::info!(
            "{file}: {label}: {fallbacks} vertices have no triangle of non-zero area to take a normal from (or their \
             triangles' normals cancel); they get the normal (0, 0, 1)"
        );
    }

    let mesh = Mesh {
        positions: raw.positions,
        normals,
        tex_coords,
        indices,
        fog_coords: raw.fog_coords.unwrap_or_default(),
    };
    mesh.validate().map_err(|e| format!("{label}: {e}"))?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn is_unit(normal: [f32; 3]) -> bool {
        (f64::from(Vec3::from(normal).length()) - 1.0).abs() < 1e-6
    }

    fn raw(positions: &[[f32; 3]], indices: &[u32]) -> RawMesh {
        RawMesh {
            positions: positions.to_vec(),
            indices: indices.to_vec(),
            ..RawMesh::default()
        }
    }

    const FILE: &str = "test.obj";

    #[test]
    fn computed_normals_are_area_weighted() {
        // Vertex 0 is shared by a triangle of area 2 facing +z and one of area 0.5 facing +y.
        let positions = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
        ];
        let mesh = finish_mesh(raw(&positions, &[0, 1, 2, 0, 3, 4]), Path::new(FILE), "mesh").expect("valid");
        let expected = DVec3::new(0.0, 0.5, 2.0).normalize();
        assert!((DVec3::from(mesh.normals[0].map(f64::from)) - expected).length() < 1e-7);
        assert_eq!(mesh.normals[1], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[3], [0.0, 1.0, 0.0]);
        assert_eq!(mesh.tex_coords, vec![[0.0; 2]; 5]);
        assert!(mesh.normals.iter().all(|n| is_unit(*n)));
    }

    #[test]
    fn degenerate_triangles_are_dropped_and_lonely_vertices_get_plus_z() {
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [5.0, 5.0, 5.0],
        ];
        // (0, 1, 3) is collinear, (1, 1, 2) repeats a vertex; vertex 3 is only in a degenerate one, 4 in none.
        let mesh = finish_mesh(raw(&positions, &[0, 1, 2, 0, 1, 3, 1, 1, 2]), Path::new(FILE), "mesh").expect("valid");
        assert_eq!(mesh.indices, [0, 1, 2]);
        assert_eq!(mesh.normals[3], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[4], [0.0, 0.0, 1.0]);
        // Seen from -z the triangle is counter-clockwise: its normal is still +z by the cross product.
        let flipped = finish_mesh(raw(&positions, &[0, 2, 1]), Path::new(FILE), "mesh").expect("valid");
        assert_eq!(flipped.normals[0], [0.0, 0.0, -1.0]);
    }

    #[test]
    fn file_normals_are_repaired() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut m = raw(&positions, &[0, 1, 2]);
        m.normals = Some(vec![[0.0, 0.0, 0.0], [0.0, 3.0, 4.0], [f32::NAN, 0.0, 1.0]]);
        let mesh = finish_mesh(m, Path::new(FILE), "mesh").expect("valid");
        assert_eq!(mesh.normals[0], [0.0, 0.0, 1.0]);
        assert_eq!(mesh.normals[1], [0.0, 0.6, 0.8]);
        assert_eq!(mesh.normals[2], [0.0, 0.0, 1.0]);
    }

    #[test]
    fn broken_meshes_are_errors() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let error = |m: RawMesh| finish_mesh(m, Path::new(FILE), "mesh `x`").expect_err("broken");
        assert!(error(raw(&positions, &[0, 1, 1])).contains("all 1 are degenerate"));
        assert!(error(raw(&positions, &[])).contains("no triangles"));
        assert!(error(raw(&positions, &[0, 1, 3])).contains("index 3 is out of range"));
        assert!(error(raw(&positions, &[0, 1])).contains("2 indices"));
        assert!(error(raw(&[], &[])).contains("no vertices"));
        let mut nan = raw(&positions, &[0, 1, 2]);
        nan.positions[1][2] = f32::INFINITY;
        assert!(error(nan).contains("vertex 1 has a non-finite position"));
        let mut tex = raw(&positions, &[0, 1, 2]);
        tex.tex_coords = Some(vec![[0.0, 0.0]; 2]);
        assert!(error(tex).contains("2 texture coordinates for 3 vertices"));
    }
}
