//! Built-in triangle meshes generated exactly like the OpenGL libraries that seeded firmament.
//!
//! The classic (OpenGL fixed-function) lighting path is checked against scenes that were first
//! drawn with two C libraries, so its spheres are not "a" sphere but *their* spheres:
//!
//! - [`Mesh::glt_sphere`] is GLTools' `gltMakeSphere` (OpenGL SuperBible, 5th edition) together
//!   with the vertex de-duplication of `GLTriangleBatch::AddTriangle`;
//! - [`Mesh::glu_sphere`] and [`Mesh::glu_sphere_untextured`] are SGI's reference libGLU
//!   `gluSphere` (`GLU_FILL`, `GLU_SMOOTH`, `GLU_OUTSIDE`), with the `GL_QUAD_STRIP`s and
//!   `GL_TRIANGLE_FAN`s it draws turned into a triangle list.
//!
//! [`Mesh::quad`] and [`Mesh::cube`] are plain shapes of our own.
//!
//! # Conventions
//! Triangle lists; a triangle is front-facing when its vertices run counter-clockwise seen from
//! the side its normals point to (OpenGL's default `glFrontFace(GL_CCW)`). Normals are unit
//! length, per vertex. Positions are in metres; texture coordinates have `(0, 0)` at the lower
//! left of the image as in OpenGL.
//!
//! # Why `f32`
//! Unlike the rest of the core, a [`Mesh`] holds `f32`: the two C libraries compute in `float`
//! (GLTools entirely; libGLU in `double` rounded into `float` caches and `glVertex3f`), and the
//! de-duplication in GLTools compares `float`s against a `1e-5` tolerance. Computing in `f64` would
//! give different vertices, and in rare cases a different vertex count. Every generator here
//! repeats the C code's `float` operations in the same order, so the results are the C results bit
//! for bit (see each generator for the assumptions).

use std::collections::HashMap;

use glam::DVec3;

use crate::error::CoreError;

/// The most cells per side [`Mesh::quad`] takes (`4096² = 16.8 M` cells).
pub const MAX_QUAD_SUBDIVISIONS: u32 = 4096;

/// The most slices, and the most stacks, [`Mesh::glt_sphere`] takes.
pub const MAX_GLT_SPHERE_DIVISIONS: u32 = 4096;

/// libGLU's `CACHE_SIZE` in `quad.c`: `gluSphere` silently lowers `slices` and `stacks` to
/// `CACHE_SIZE - 1 = 239`, and so do [`Mesh::glu_sphere`] and [`Mesh::glu_sphere_untextured`].
pub const GLU_CACHE_SIZE: u32 = 240;

/// How far a normal's length may be from 1 for [`Mesh::validate`].
pub const NORMAL_LENGTH_TOLERANCE: f64 = 1e-5;

/// An indexed triangle mesh: per-vertex positions, normals and texture coordinates, and a
/// triangle list of indices into them (counter-clockwise front faces).
///
/// `f32` on purpose: see the [module documentation](crate::classic::mesh).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions, metres.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates `(s, t)`, one per position.
    pub tex_coords: Vec<[f32; 2]>,
    /// Triangle list: three indices into the vertex arrays per triangle.
    pub indices: Vec<u32>,
    /// Per-vertex fog coordinates (GL's `glFogCoordPointer`), one per position, or empty when
    /// the mesh has none. Read only by fog whose coordinate is
    /// [`FogCoordinate::Vertex`](crate::classic::fog::FogCoordinate::Vertex).
    pub fog_coords: Vec<f32>,
}

impl Mesh {
    /// GLTools' `gltMakeSphere(batch, radius, slices, stacks)` (OpenGL SuperBible, 5th edition,
    /// `GLTools/src/GLTools.cpp`), fed through `GLTriangleBatch::AddTriangle`
    /// (`GLTools/src/GLTriangleBatch.cpp`) exactly: same positions, normals, texture
    /// coordinates, triangle order, winding, vertex order and vertex de-duplication.
    ///
    /// The sphere is centred at the origin with its poles on the z axis, `+z` at `t = 1` (stack 0)
    /// and `-z` at `t = 0`; longitude `θ` runs from `+y` towards `-x`
    /// (`x = −sin θ·sin ρ`, `y = cos θ·sin ρ`, `z = cos ρ`) and `s` from 0 to 1 with it. Each of the
    /// `slices × stacks` cells gives two triangles, `(v0, v1, v2)` and `(v1, v3, v2)`, where `v0`,
    /// `v2` are on the upper ring at `θ_j`, `θ_{j+1}` and `v1`, `v3` on the lower one: all
    /// `slices·stacks·6` indices, counter-clockwise seen from outside.
    ///
    /// `AddTriangle` normalises the three normals (`n · (1/sqrtf(|n|²))`), then reuses the first
    /// earlier vertex whose position, normal and texture coordinate all agree to within `1e-5`
    /// per component (`m3dCloseEnough`, `fabs(a − b) < 1e-5f`), else appends the vertex. That
    /// gives `(stacks + 1)·(slices + 1)` vertices: the seam (`s = 0` and `s = 1`) and the pole
    /// vertices (one per `s`) stay separate because their texture coordinates differ.
    ///
    /// Quirks reproduced: the pole rings are `slices + 1` coincident vertices, so the first
    /// triangle of every top cell has zero area; `π` is `(float)3.141592653589` (8.7e-8 above π)
    /// and `ρ + dρ` is rounded in `float`, so the last ring may land just past the south pole
    /// (for 26 × 13 on a circle of radius `3.3e-7·radius`), which makes the bottom cells' second
    /// triangles slivers of area ~1e-8 with reversed winding.
    ///
    /// Followed from the source (read in several public copies of GLTools, e.g. the
    /// `liwenlongonly/GLTools` and `zijuan0810/supberbile5` repositories on GitHub, and
    /// `math3d.h` for `m3dNormalizeVector3` / `m3dCloseEnough`). Assumptions we could not check
    /// against a running build:
    /// - `float` arithmetic is IEEE single precision without excess precision (SSE/ARM, not
    ///   x87's `FLT_EVAL_METHOD == 2`) and without fused multiply-add contraction;
    /// - `sin`/`cos` of a `float` are the `double` functions, the result rounded to `float`
    ///   (what C and pre-2016 C++ `<math.h>` do). Where C++ overloads pick `sinf`/`cosf`
    ///   instead, a few arguments round differently (for 26 × 13 with glibc, two of them, by one
    ///   ulp): positions may then differ in the last bit, never the topology.
    ///
    /// Deliberate differences: indices are `u32` (GLTools stores `GLushort`, which silently wraps
    /// beyond 65 536 vertices); the de-duplication looks only at nearby vertices through a hash
    /// grid instead of scanning them all, which finds the same first match.
    ///
    /// # Errors
    /// [`CoreError::Invalid`] when `radius` is not finite and > 0, `slices` is not in
    /// `3..=4096` or `stacks` not in `2..=4096` ([`MAX_GLT_SPHERE_DIVISIONS`]).
    pub fn glt_sphere(radius: f32, slices: u32, stacks: u32) -> Result<Self, CoreError> {
        if !(radius.is_finite() && radius > 0.0) {
            return invalid("radius", radius.to_string(), "must be finite and > 0");
        }
        check_count("slices", slices, 3, MAX_GLT_SPHERE_DIVISIONS, "must be in 3..=4096")?;
        check_count("stacks", stacks, 2, MAX_GLT_SPHERE_DIVISIONS, "must be in 2..=4096")?;

        let (fslices, fstacks) = (slices as f32, stacks as f32);
        let pi = GLT_PI;
        let drho = pi / fstacks;
        let dtheta = 2.0_f32 * pi / fslices;
        let ds = 1.0_f32 / fslices;
        let dt = 1.0_f32 / fstacks;
        let mut t = 1.0_f32;

        let mut batch = TriangleBatch::with_capacity(slices as usize * stacks as usize * 6);
        for i in 0..stacks {
            let rho = i as f32 * drho;
            let srho = c_sin(rho);
            let crho = c_cos(rho);
            let srhodrho = c_sin(rho + drho);
            let crhodrho = c_cos(rho + drho);

            let mut s = 0.0_f32;
            let mut vertex = [[0.0_f32; 3]; 4];
            let mut normal = [[0.0_f32; 3]; 4];
            let mut texture = [[0.0_f32; 2]; 4];
            for j in 0..slices {
                // `j == slices` never holds inside the loop; kept as in the C.
                let theta = if j == slices { 0.0 } else { j as f32 * dtheta };
                let stheta = -c_sin(theta);
                let ctheta = c_cos(theta);
                set_vertex(
                    &mut vertex[0],
                    &mut normal[0],
                    [stheta * srho, ctheta * srho, crho],
                    radius,
                );
                texture[0] = [s, t];
                set_vertex(
                    &mut vertex[1],
                    &mut normal[1],
                    [stheta * srhodrho, ctheta * srhodrho, crhodrho],
                    radius,
                );
                texture[1] = [s, t - dt];

                let theta = if j + 1 == slices { 0.0 } else { (j + 1) as f32 * dtheta };
                let stheta = -c_sin(theta);
                let ctheta = c_cos(theta);
                s += ds;
                set_vertex(
                    &mut vertex[2],
                    &mut normal[2],
                    [stheta * srho, ctheta * srho, crho],
                    radius,
                );
                texture[2] = [s, t];
                set_vertex(
                    &mut vertex[3],
                    &mut normal[3],
                    [stheta * srhodrho, ctheta * srhodrho, crhodrho],
                    radius,
                );
                texture[3] = [s, t - dt];

                batch.add_triangle(&vertex, &mut normal, &texture);
                // "Rearrange for next triangle": v0 = v1, v1 = v3 (normals as AddTriangle left them).
                vertex[0] = vertex[1];
                normal[0] = normal[1];
                texture[0] = texture[1];
                vertex[1] = vertex[3];
                normal[1] = normal[3];
                texture[1] = texture[3];
                batch.add_triangle(&vertex, &mut normal, &texture);
            }
            t -= dt;
        }
        Ok(batch.mesh)
    }

    /// libGLU's `gluSphere(quadric, radius, slices, stacks)` with texture coordinates on
    /// (`gluQuadricTexture(q, GL_TRUE)`), `GLU_FILL`, `GLU_SMOOTH` and `GLU_OUTSIDE`: `stacks`
    /// `GL_QUAD_STRIP`s from the north pole down, the pole rows included (with texturing the
    /// poles are strips of `slices + 1` coincident vertices, one per `s`, not fans).
    ///
    /// Followed from SGI's reference `src/libutil/quad.c` (SGI Free Software License B; read in
    /// the `claudeha/glu` repository, the same code as Mesa's `src/glu/sgi/libutil/quad.c`), with
    /// `SIN`/`COS` being the `double` `sin`/`cos` (`gluint.h` without `_EXTENSIONS_`):
    /// - `slices` and `stacks` are first lowered to `CACHE_SIZE − 1 = 239` ([`GLU_CACHE_SIZE`]);
    /// - angles are `(float)(2·PI·i/slices)` and `(float)(PI·j/stacks)` in `double`, their sines
    ///   and cosines rounded to `float`; ring radii and heights are `(float)(radius·sin(angle))`
    ///   and `(float)(radius·cos(angle))` computed in `double`, and "to make sure it comes to a
    ///   point" the pole ring radii are exactly 0;
    /// - vertex `i` of a ring is `(r·sin φ_i, r·cos φ_i, z)`: longitude runs from `+y` towards
    ///   `+x`, and texture coordinates are `(1 − i/slices, 1 − j/stacks)` in `float`;
    /// - normals are `(sin φ·sin θ, cos φ·sin θ, cos θ)` from the `float` caches, not
    ///   renormalised (unit to `f32` rounding).
    ///
    /// Vertices are the `glVertex3f` calls in order, none merged (immediate mode does not share
    /// vertices): `stacks·2·(slices + 1)` of them, strip `j` alternating ring `j + 1` (even) and
    /// ring `j` (odd) for `i = 0..=slices`. The quad strip `v0, v1, …` gives quads
    /// `(v2k, v2k+1, v2k+3, v2k+2)` (OpenGL 2.1 §2.6.1), counter-clockwise seen from outside. How
    /// a quad becomes triangles is left to the implementation (for a convex quad either diagonal
    /// covers the same pixels; only interpolation differs); we split it along `v2k`–`v2k+3`, as
    /// Mesa does, into `(v2k, v2k+1, v2k+3)` and `(v2k+2, v2k, v2k+3)`: both keep the quad's
    /// winding and end on `v2k+3`, the quad's provoking vertex for flat shading (GL 2.1 table 2.2:
    /// vertex `2i + 2` of quad `i`, counting from 1), so a flat-shaded quad is one colour. At the poles
    /// two of a quad's corners coincide, so one triangle of each pole quad has exactly zero area
    /// (the first at the north pole, the second at the south pole): `2·slices·stacks` triangles,
    /// `2·slices` of them degenerate.
    ///
    /// Same floating-point assumptions as [`Mesh::glt_sphere`] (IEEE `float` without excess
    /// precision or contraction).
    ///
    /// # Errors
    /// [`CoreError::Invalid`] when `radius` is not finite and > 0 (also after rounding to `f32`),
    /// `slices < 3` or `stacks < 2`.
    pub fn glu_sphere(radius: f64, slices: u32, stacks: u32) -> Result<Self, CoreError> {
        glu_sphere(radius, slices, stacks, true)
    }

    /// libGLU's `gluSphere` as [`Mesh::glu_sphere`] but without texture coordinates (the
    /// quadric's default): then the two pole rows are `GL_TRIANGLE_FAN`s around a single pole
    /// vertex, and only the `stacks − 2` middle rows are quad strips.
    ///
    /// A fan `f0, f1, …` gives triangles `(f0, fk, fk+1)`, counter-clockwise seen from outside
    /// (the north fan runs its ring from `i = slices` down to 0, the south one up). The pole
    /// vertex's normal is the one `gluSphere` sets before `glBegin`: `(0, 0, 1)` in the north; in
    /// the south the C code reads `sinCache2a[stacks]`, an entry of the *slices* cache, which is
    /// uninitialised when `stacks > slices`; we then use 0 there, giving `(−0, −0, −1)` (any value
    /// the C could read from a `[−1, 1]` cache moves it by less than `9e-8`).
    ///
    /// `tex_coords` holds OpenGL's initial current texture coordinate `(0, 0)` for every vertex,
    /// as the C code never sets one. `2·(slices + 2) + (stacks − 2)·2·(slices + 1)` vertices and
    /// `2·slices·(stacks − 1)` triangles, none degenerate.
    ///
    /// # Errors
    /// As [`Mesh::glu_sphere`].
    pub fn glu_sphere_untextured(radius: f64, slices: u32, stacks: u32) -> Result<Self, CoreError> {
        glu_sphere(radius, slices, stacks, false)
    }

    /// A square in the xy-plane centred at the origin, `size` metres on a side, split into
    /// `subdivisions × subdivisions` cells of two triangles each. The front faces `+z` (normals
    /// `+z`, counter-clockwise seen from `+z`); texture coordinates run from `(0, 0)` at
    /// `(−size/2, −size/2)` to `(1, 1)` at `(+size/2, +size/2)`.
    ///
    /// Vertices are row by row from `−y`, each row from `−x`: vertex `(i, j)` (column `i`, row
    /// `j`) is number `j·(subdivisions + 1) + i`. Cell `(i, j)` gives triangles `(a, b, c)` and
    /// `(a, c, d)` with `a = (i, j)`, `b = (i + 1, j)`, `c = (i + 1, j + 1)`, `d = (i, j + 1)`.
    /// Coordinates are computed in `f64` and rounded to `f32`; the edges are exactly `±size/2`.
    ///
    /// # Errors
    /// [`CoreError::Invalid`] when `size` is not finite and > 0 (also after rounding to `f32`) or
    /// `subdivisions` is not in `1..=4096` ([`MAX_QUAD_SUBDIVISIONS`]).
    pub fn quad(size: f64, subdivisions: u32) -> Result<Self, CoreError> {
        check_length("size", size)?;
        check_count(
            "subdivisions",
            subdivisions,
            1,
            MAX_QUAD_SUBDIVISIONS,
            "must be in 1..=4096",
        )?;
        let n = subdivisions as usize;
        let half = size / 2.0;
        // Exactly -half at k = 0 and +half at k = n.
        let coordinate = |k: usize| -> (f32, f32) {
            let u = k as f64 / n as f64;
            let p = if k == n { half } else { -half + size * u };
            (p as f32, u as f32)
        };
        let mut mesh = Self::default();
        mesh.positions.reserve((n + 1) * (n + 1));
        for j in 0..=n {
            let (y, t) = coordinate(j);
            for i in 0..=n {
                let (x, s) = coordinate(i);
                mesh.positions.push([x, y, 0.0]);
                mesh.normals.push([0.0, 0.0, 1.0]);
                mesh.tex_coords.push([s, t]);
            }
        }
        let row = (n + 1) as u32;
        mesh.indices.reserve(6 * n * n);
        for j in 0..subdivisions {
            for i in 0..subdivisions {
                let a = j * row + i;
                let (b, c, d) = (a + 1, a + row + 1, a + row);
                mesh.indices.extend_from_slice(&[a, b, c, a, c, d]);
            }
        }
        Ok(mesh)
    }

    /// An axis-aligned cube centred at the origin, `size` metres on a side: 6 faces of 4 vertices
    /// (24, so each face has its own flat normal and texture coordinates) and 2 triangles per face
    /// (12), counter-clockwise seen from outside.
    ///
    /// Faces in the order `+x, −x, +y, −y, +z, −z`. Each face has axes `u`, `v` with `u × v` =
    /// its normal; its vertices are the corners at `(−u, −v), (+u, −v), (+u, +v), (−u, +v)` with
    /// texture coordinates `(0, 0), (1, 0), (1, 1), (0, 1)`, and its triangles `(0, 1, 2)`,
    /// `(0, 2, 3)`. The side faces have `v = +z` (the image upright, z being up); `+z` has
    /// `u = +x, v = +y` and `−z` has `u = +x, v = −y`.
    ///
    /// # Errors
    /// [`CoreError::Invalid`] when `size` is not finite and > 0 (also after rounding to `f32`).
    pub fn cube(size: f64) -> Result<Self, CoreError> {
        check_length("size", size)?;
        let h = (size / 2.0) as f32;
        const FACES: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]),
        ];
        const CORNERS: [(f32, f32); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let mut mesh = Self::default();
        for (normal, u, v) in FACES {
            let base = mesh.positions.len() as u32;
            for (cu, cv) in CORNERS {
                mesh.positions
                    .push(std::array::from_fn(|k| h * (normal[k] + cu * u[k] + cv * v[k])));
                mesh.normals.push(normal);
                mesh.tex_coords.push([(cu + 1.0) / 2.0, (cv + 1.0) / 2.0]);
            }
            mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|k| base + k));
        }
        Ok(mesh)
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The number of triangles (`indices.len() / 3`).
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The triangles, three vertex indices each, in order.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]])
    }

    /// `(b − a) × (c − a)` in `f64` for the triangle `[a, b, c]`: twice its area times its unit
    /// normal, pointing to the side from which it runs counter-clockwise. Panics when an index is
    /// out of range (see [`Mesh::validate`]).
    pub fn triangle_cross(&self, triangle: [u32; 3]) -> DVec3 {
        let [a, b, c] = triangle.map(|i| DVec3::from(self.positions[i as usize].map(f64::from)));
        (b - a).cross(c - a)
    }

    /// The signed volume enclosed, `Σ a · (b × c) / 6` over the triangles, in m³: positive when a
    /// closed mesh's front faces point outwards. Panics when an index is out of range.
    pub fn signed_volume(&self) -> f64 {
        self.triangles()
            .map(|t| {
                let [a, b, c] = t.map(|i| DVec3::from(self.positions[i as usize].map(f64::from)));
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// Checks that the mesh is well formed: one normal and one texture coordinate per position,
    /// a whole number of triangles, every index in range, positions and texture coordinates
    /// finite, normals of unit length to within [`NORMAL_LENGTH_TOLERANCE`].
    ///
    /// # Errors
    /// [`CoreError::Invalid`] naming the first rule broken (`mesh.normals`, `mesh.tex_coords`,
    /// `mesh.indices` or `mesh.positions`).
    pub fn validate(&self) -> Result<(), CoreError> {
        let n = self.positions.len();
        if self.normals.len() != n {
            return invalid(
                "mesh.normals",
                format!("{} normals for {n} positions", self.normals.len()),
                "needs one normal per position",
            );
        }
        if self.tex_coords.len() != n {
            return invalid(
                "mesh.tex_coords",
                format!("{} texture coordinates for {n} positions", self.tex_coords.len()),
                "needs one texture coordinate per position",
            );
        }
        if !self.indices.len().is_multiple_of(3) {
            return invalid(
                "mesh.indices",
                format!("{} indices", self.indices.len()),
                "must be a multiple of 3",
            );
        }
        if let Some(i) = self.indices.iter().find(|&&i| i as usize >= n) {
            return invalid(
                "mesh.indices",
                i.to_string(),
                "must be less than the number of vertices",
            );
        }
        if let Some(p) = self.positions.iter().find(|p| !p.iter().all(|c| c.is_finite())) {
            return invalid("mesh.positions", format!("{p:?}"), "must be finite");
        }
        if let Some(t) = self.tex_coords.iter().find(|t| !t.iter().all(|c| c.is_finite())) {
            return invalid("mesh.tex_coords", format!("{t:?}"), "must be finite");
        }
        if !self.fog_coords.is_empty() && self.fog_coords.len() != n {
            return invalid(
                "mesh.fog_coords",
                format!("{} fog coordinates for {n} positions", self.fog_coords.len()),
                "needs one fog coordinate per position, or none",
            );
        }
        if let Some(c) = self.fog_coords.iter().find(|c| !c.is_finite()) {
            return invalid("mesh.fog_coords", c.to_string(), "must be finite");
        }
        let off_unit = |v: &[f32; 3]| {
            let length = DVec3::from(v.map(f64::from)).length();
            let error = (length - 1.0).abs();
            error.is_nan() || error > NORMAL_LENGTH_TOLERANCE
        };
        if let Some(v) = self.normals.iter().find(|v| off_unit(v)) {
            return invalid("mesh.normals", format!("{v:?}"), "must be unit length (to within 1e-5)");
        }
        Ok(())
    }
}

fn invalid<T>(field: &'static str, value: String, rule: &'static str) -> Result<T, CoreError> {
    Err(CoreError::Invalid { field, value, rule })
}

fn check_count(field: &'static str, value: u32, min: u32, max: u32, rule: &'static str) -> Result<(), CoreError> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        invalid(field, value.to_string(), rule)
    }
}

/// A length given in `f64` for an `f32` mesh: finite and > 0 before and after rounding.
fn check_length(field: &'static str, value: f64) -> Result<(), CoreError> {
    let single = value as f32;
    if value.is_finite() && value > 0.0 && single.is_finite() && single > 0.0 {
        Ok(())
    } else {
        invalid(
            field,
            value.to_string(),
            "must be finite and > 0, also as an f32 (up to 3.4e38)",
        )
    }
}

/// GLTools' `(GLfloat)(3.141592653589)`: the C's truncated π, which rounds to the same `f32` as π.
#[expect(clippy::approx_constant, reason = "the C's own truncated value of π, kept verbatim")]
const GLT_PI: f32 = 3.141_592_653_589_f64 as f32;

/// C's `(float)sin(x)` for a `float` `x`: the `double` sine rounded to `float`.
fn c_sin(x: f32) -> f32 {
    f64::from(x).sin() as f32
}

/// C's `(float)cos(x)` for a `float` `x`.
fn c_cos(x: f32) -> f32 {
    f64::from(x).cos() as f32
}

/// `vNormal[k] = (x, y, z); vVertex[k] = (x, y, z) · fRadius` from `gltMakeSphere`.
fn set_vertex(vertex: &mut [f32; 3], normal: &mut [f32; 3], unit: [f32; 3], radius: f32) {
    *normal = unit;
    *vertex = unit.map(|c| c * radius);
}

/// `m3dNormalizeVector3`: `u · (1 / sqrtf(u0·u0 + u1·u1 + u2·u2))` in `float`.
fn m3d_normalize(u: &mut [f32; 3]) {
    let length = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let scale = 1.0_f32 / length;
    for c in u.iter_mut() {
        *c *= scale;
    }
}

/// `m3dCloseEnough(a, b, 0.00001f)`: `fabs(a - b) < e` with the difference rounded to `float`.
fn close_enough(a: f32, b: f32) -> bool {
    (a - b).abs() < GLT_EPSILON
}

/// `GLTriangleBatch::AddTriangle`'s tolerance.
const GLT_EPSILON: f32 = 0.000_01;

/// Side of the hash-grid cells on texture coordinates used to find candidates for a match. Two
/// coordinates that `close_enough` accepts differ by less than `1.0000001e-5`, a tenth of a cell,
/// so they lie in the same or neighbouring cells.
const GLT_GRID_CELL: f64 = 1e-4;

fn glt_cell(t: [f32; 2]) -> [i64; 2] {
    // `as` saturates, so huge or non-finite coordinates still get a (shared) cell.
    t.map(|c| (f64::from(c) / GLT_GRID_CELL).floor() as i64)
}

/// `GLTriangleBatch` while it is being filled (`BeginMesh` … `AddTriangle` …).
struct TriangleBatch {
    mesh: Mesh,
    /// Vertex indices by texture-coordinate cell, ascending within each cell.
    grid: HashMap<[i64; 2], Vec<u32>>,
}

impl TriangleBatch {
    fn with_capacity(indices: usize) -> Self {
        let mut mesh = Mesh::default();
        mesh.indices.reserve(indices);
        Self {
            mesh,
            grid: HashMap::new(),
        }
    }

    /// `AddTriangle(verts, vNorms, vTexCoords)`: normalises `normals[0..3]` in place (as the C
    /// does to the caller's array), then adds or reuses each vertex.
    fn add_triangle(&mut self, vertices: &[[f32; 3]; 4], normals: &mut [[f32; 3]; 4], tex_coords: &[[f32; 2]; 4]) {
        for n in &mut normals[..3] {
            m3d_normalize(n);
        }
        for k in 0..3 {
            let index = match self.find(&vertices[k], &normals[k], &tex_coords[k]) {
                Some(index) => index,
                None => {
                    let index = self.mesh.positions.len() as u32;
                    self.mesh.positions.push(vertices[k]);
                    self.mesh.normals.push(normals[k]);
                    self.mesh.tex_coords.push(tex_coords[k]);
                    self.grid.entry(glt_cell(tex_coords[k])).or_default().push(index);
                    index
                }
            };
            self.mesh.indices.push(index);
        }
    }

    /// The first (lowest-numbered) stored vertex that matches on all eight components, as the
    /// C's linear scan finds it.
    fn find(&self, position: &[f32; 3], normal: &[f32; 3], tex_coord: &[f32; 2]) -> Option<u32> {
        let [cs, ct] = glt_cell(*tex_coord);
        let mut best: Option<u32> = None;
        for ds in -1..=1_i64 {
            for dt in -1..=1_i64 {
                let Some(bucket) = self.grid.get(&[cs.wrapping_add(ds), ct.wrapping_add(dt)]) else {
                    continue;
                };
                let first = bucket.iter().copied().find(|&i| {
                    let i = i as usize;
                    let m = &self.mesh;
                    (0..3).all(|c| close_enough(m.positions[i][c], position[c]))
                        && (0..3).all(|c| close_enough(m.normals[i][c], normal[c]))
                        && (0..2).all(|c| close_enough(m.tex_coords[i][c], tex_coord[c]))
                });
                if let Some(i) = first {
                    best = Some(best.map_or(i, |b| b.min(i)));
                }
            }
        }
        best
    }
}

/// `gluSphere` with `GLU_FILL`, `GLU_SMOOTH`, `GLU_OUTSIDE`, texture coordinates on or off.
fn glu_sphere(radius: f64, slices: u32, stacks: u32, texture: bool) -> Result<Mesh, CoreError> {
    check_length("radius", radius)?;
    check_count("slices", slices, 3, u32::MAX, "must be >= 3")?;
    check_count("stacks", stacks, 2, u32::MAX, "must be >= 2")?;
    let slices = slices.min(GLU_CACHE_SIZE - 1) as usize;
    let stacks = stacks.min(GLU_CACHE_SIZE - 1) as usize;
    let pi = std::f64::consts::PI; // 3.14159265358979323846

    let cache = GLU_CACHE_SIZE as usize;
    let (mut sin1a, mut cos1a) = (vec![0.0_f32; cache], vec![0.0_f32; cache]);
    let (mut sin1b, mut cos1b) = (vec![0.0_f32; cache], vec![0.0_f32; cache]);
    let (mut sin2b, mut cos2b) = (vec![0.0_f32; cache], vec![0.0_f32; cache]);
    for i in 0..slices {
        let angle = (2.0 * pi * i as f64 / slices as f64) as f32;
        sin1a[i] = c_sin(angle);
        cos1a[i] = c_cos(angle);
    }
    for j in 0..=stacks {
        let angle = (pi * j as f64 / stacks as f64) as f32;
        sin2b[j] = c_sin(angle);
        cos2b[j] = c_cos(angle);
        sin1b[j] = (radius * f64::from(angle).sin()) as f32;
        cos1b[j] = (radius * f64::from(angle).cos()) as f32;
    }
    // "Make sure it comes to a point"
    sin1b[0] = 0.0;
    sin1b[stacks] = 0.0;
    sin1a[slices] = sin1a[0];
    cos1a[slices] = cos1a[0];
    // With GLU_SMOOTH, sinCache2a/cosCache2a are copies of sinCache1a/cosCache1a (the
    // `[slices]` entry included). Entries past `slices` stay 0 here; the C leaves them
    // uninitialised and reads `[stacks]` of them for the south pole fan's normal.
    let (sin2a, cos2a) = (&sin1a, &cos1a);

    let mut gl = Immediate::default();
    let (start, finish) = if texture {
        (0, stacks)
    } else {
        // North pole fan (the j == 0 iteration).
        let (sintemp2, z_high) = (sin1b[1], cos1b[1]);
        let (sintemp3, costemp3) = (sin2b[1], cos2b[1]);
        gl.normal = [sin2a[0] * sin2b[0], cos2a[0] * sin2b[0], cos2b[0]];
        gl.begin();
        gl.vertex([0.0, 0.0, radius as f32]);
        for i in (0..=slices).rev() {
            gl.normal = [sin2a[i] * sintemp3, cos2a[i] * sintemp3, costemp3];
            gl.vertex([sintemp2 * sin1a[i], sintemp2 * cos1a[i], z_high]);
        }
        gl.end_triangle_fan();

        // South pole fan (the j == stacks - 1 iteration).
        let (sintemp2, z_high) = (sin1b[stacks - 1], cos1b[stacks - 1]);
        let (sintemp3, costemp3) = (sin2b[stacks - 1], cos2b[stacks - 1]);
        gl.normal = [
            sin2a[stacks] * sin2b[stacks],
            cos2a[stacks] * sin2b[stacks],
            cos2b[stacks],
        ];
        gl.begin();
        gl.vertex([0.0, 0.0, (-radius) as f32]);
        for i in 0..=slices {
            gl.normal = [sin2a[i] * sintemp3, cos2a[i] * sintemp3, costemp3];
            gl.vertex([sintemp2 * sin1a[i], sintemp2 * cos1a[i], z_high]);
        }
        gl.end_triangle_fan();
        (1, stacks - 1)
    };

    for j in start..finish {
        let (z_low, z_high) = (cos1b[j], cos1b[j + 1]);
        let (sintemp1, sintemp2) = (sin1b[j], sin1b[j + 1]);
        let (sintemp3, costemp3) = (sin2b[j + 1], cos2b[j + 1]);
        let (sintemp4, costemp4) = (sin2b[j], cos2b[j]);
        gl.begin();
        for i in 0..=slices {
            let s = 1.0 - i as f32 / slices as f32;
            gl.normal = [sin2a[i] * sintemp3, cos2a[i] * sintemp3, costemp3];
            if texture {
                gl.tex_coord = [s, 1.0 - (j + 1) as f32 / stacks as f32];
            }
            gl.vertex([sintemp2 * sin1a[i], sintemp2 * cos1a[i], z_high]);
            gl.normal = [sin2a[i] * sintemp4, cos2a[i] * sintemp4, costemp4];
            if texture {
                gl.tex_coord = [s, 1.0 - j as f32 / stacks as f32];
            }
            gl.vertex([sintemp1 * sin1a[i], sintemp1 * cos1a[i], z_low]);
        }
        gl.end_quad_strip();
    }
    Ok(gl.mesh)
}

/// Just enough OpenGL immediate mode: the current normal and texture coordinate, `glVertex3f`,
/// and `glEnd` turning the primitive into triangles.
#[derive(Default)]
struct Immediate {
    mesh: Mesh,
    normal: [f32; 3],
    tex_coord: [f32; 2],
    /// Index of the primitive's first vertex (set by `begin`).
    first: u32,
}

impl Immediate {
    fn begin(&mut self) {
        self.first = self.mesh.positions.len() as u32;
    }

    fn vertex(&mut self, position: [f32; 3]) {
        self.mesh.positions.push(position);
        self.mesh.normals.push(self.normal);
        self.mesh.tex_coords.push(self.tex_coord);
    }

    fn count(&self) -> u32 {
        self.mesh.positions.len() as u32 - self.first
    }

    /// `GL_TRIANGLE_FAN` `f0, f1, …`: triangles `(f0, fk, fk+1)`.
    fn end_triangle_fan(&mut self) {
        let f = self.first;
        for k in 1..self.count().saturating_sub(1) {
            self.mesh.indices.extend_from_slice(&[f, f + k, f + k + 1]);
        }
    }

    /// `GL_QUAD_STRIP` `v0, v1, …`: quads `(v2k, v2k+1, v2k+3, v2k+2)`, each split along
    /// `v2k`–`v2k+3` into `(v2k, v2k+1, v2k+3)` and `(v2k+2, v2k, v2k+3)`: both end on the quad's
    /// provoking vertex `v2k+3`, so flat shading colours the whole quad as GL does.
    fn end_quad_strip(&mut self) {
        let f = self.first;
        for k in 0..(self.count() / 2).saturating_sub(1) {
            let [a, b, c, d] = [2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2].map(|v| f + v);
            self.mesh.indices.extend_from_slice(&[a, b, c, d, a, c]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangle soup `gltMakeSphere` hands to `AddTriangle`, de-duplicated by the C's linear
    /// scan over every vertex so far.
    fn naive_glt(radius: f32, slices: u32, stacks: u32) -> Mesh {
        let mut soup = Vec::new();
        let pi = GLT_PI;
        let (drho, dtheta) = (pi / stacks as f32, 2.0_f32 * pi / slices as f32);
        let (ds, dt) = (1.0_f32 / slices as f32, 1.0_f32 / stacks as f32);
        let mut t = 1.0_f32;
        for i in 0..stacks {
            let rho = i as f32 * drho;
            let (srho, crho) = (c_sin(rho), c_cos(rho));
            let (srd, crd) = (c_sin(rho + drho), c_cos(rho + drho));
            let mut s = 0.0_f32;
            for j in 0..slices {
                let th0 = j as f32 * dtheta;
                let th1 = if j + 1 == slices { 0.0 } else { (j + 1) as f32 * dtheta };
                let (st0, ct0) = (-c_sin(th0), c_cos(th0));
                let (st1, ct1) = (-c_sin(th1), c_cos(th1));
                let v0 = ([st0 * srho, ct0 * srho, crho], [s, t]);
                let v1 = ([st0 * srd, ct0 * srd, crd], [s, t - dt]);
                s += ds;
                let v2 = ([st1 * srho, ct1 * srho, crho], [s, t]);
                let v3 = ([st1 * srd, ct1 * srd, crd], [s, t - dt]);
                soup.extend([v0, v1, v2, v1, v3, v2]);
            }
            t -= dt;
        }
        let mut mesh = Mesh::default();
        for (unit, tc) in soup {
            let position = unit.map(|c| c * radius);
            let mut normal = unit;
            m3d_normalize(&mut normal);
            let found = (0..mesh.positions.len()).find(|&i| {
                (0..3).all(|c| close_enough(mesh.positions[i][c], position[c]))
                    && (0..3).all(|c| close_enough(mesh.normals[i][c], normal[c]))
                    && (0..2).all(|c| close_enough(mesh.tex_coords[i][c], tc[c]))
            });
            let index = found.unwrap_or_else(|| {
                mesh.positions.push(position);
                mesh.normals.push(normal);
                mesh.tex_coords.push(tc);
                mesh.positions.len() - 1
            });
            mesh.indices.push(index as u32);
        }
        mesh
    }

    fn p64(p: [f32; 3]) -> DVec3 {
        DVec3::from(p.map(f64::from))
    }

    /// Index of grid vertex (row, column) in `glt_sphere(_, 26, 13)`, from the order in which
    /// `AddTriangle` first meets them: stack 0 interleaves rows 0 and 1, later stacks add a row.
    fn glt_index(row: u32, column: u32) -> u32 {
        match row {
            0 => 2 * column,
            1 => 2 * column + 1,
            _ => 54 + (row - 2) * 27 + column,
        }
    }

    #[test]
    fn glt_sphere_superbible_counts_and_index_layout() {
        let m = Mesh::glt_sphere(1.0, 26, 13).expect("valid");
        m.validate().expect("well formed");
        // (stacks + 1) rows × (slices + 1) columns: seam columns and pole rows stay separate.
        assert_eq!(m.vertex_count(), 14 * 27);
        assert_eq!(m.indices.len(), 26 * 13 * 6);
        let mut expected = Vec::new();
        for i in 0..13 {
            for j in 0..26 {
                let (v0, v1, v2, v3) = (
                    glt_index(i, j),
                    glt_index(i + 1, j),
                    glt_index(i, j + 1),
                    glt_index(i + 1, j + 1),
                );
                expected.extend([v0, v1, v2, v1, v3, v2]);
            }
        }
        assert_eq!(m.indices, expected);
        for row in 0..=13 {
            for column in 0..=26 {
                let [s, t] = m.tex_coords[glt_index(row, column) as usize];
                assert!((s - column as f32 / 26.0).abs() < 1e-6, "s at {row},{column}: {s}");
                assert!((t - (1.0 - row as f32 / 13.0)).abs() < 1e-6, "t at {row},{column}: {t}");
            }
        }
    }

    #[test]
    fn glt_sphere_first_vertices_by_hand() {
        let m = Mesh::glt_sphere(1.0, 26, 13).expect("valid");
        let pi = GLT_PI;
        assert_eq!(pi.to_bits(), std::f32::consts::PI.to_bits());
        let drho = pi / 13.0;
        let dtheta = 2.0 * pi / 26.0;
        let (srd, crd) = (c_sin(drho), c_cos(drho));
        // Vertex 0: north pole, θ = 0: (−0·0, 1·0, 1), (s, t) = (0, 1).
        assert_eq!(
            m.positions[0].map(f32::to_bits),
            [(-0.0_f32).to_bits(), 0, 1.0_f32.to_bits()]
        );
        assert_eq!(m.normals[0], [0.0, 0.0, 1.0]);
        assert_eq!(m.tex_coords[0], [0.0, 1.0]);
        // Vertex 1: ring 1 at θ = 0: (−0, sin(π/13), cos(π/13)), (0, 1 − 1/13).
        assert_eq!(m.positions[1], [-0.0, srd, crd]);
        assert!((srd - 0.239_315_66).abs() < 1e-7 && (crd - 0.970_941_8).abs() < 1e-7);
        assert_eq!(m.tex_coords[1], [0.0, 1.0 - 1.0 / 13.0]);
        // Vertex 2: north pole again but s = 1/26, so a new vertex.
        assert_eq!(m.positions[2][2], 1.0);
        assert_eq!(m.tex_coords[2], [1.0 / 26.0, 1.0]);
        // Vertex 3: ring 1 at θ = 2π/26 (= π/13, so −sin²(π/13), sin·cos(π/13)).
        let expected = [-c_sin(dtheta) * srd, c_cos(dtheta) * srd, crd];
        assert_eq!(m.positions[3], expected);
        assert!((expected[0] + 0.057_272_0).abs() < 1e-6 && (expected[1] - 0.232_361_2).abs() < 1e-6);
        assert_eq!(m.tex_coords[3], [1.0 / 26.0, 1.0 - 1.0 / 13.0]);
        // Normals: position normalised by m3dNormalizeVector3 (radius 1).
        let mut n = expected;
        m3d_normalize(&mut n);
        assert_eq!(m.normals[3], n);
        // The first four triangles: (0, 1, 2), (1, 3, 2), (2, 3, 4), (3, 5, 4).
        assert_eq!(m.indices[..12], [0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4]);
    }

    #[test]
    fn glt_sphere_geometry_and_winding() {
        for radius in [1.0_f32, 2.5] {
            let m = Mesh::glt_sphere(radius, 26, 13).expect("valid");
            for (p, n) in m.positions.iter().zip(&m.normals) {
                let (p, n) = (p64(*p), p64(*n));
                assert!((p.length() - f64::from(radius)).abs() < 1e-6 * f64::from(radius), "{p}");
                assert!((n - p / f64::from(radius)).length() < 1e-6, "{n} vs {p}");
            }
            let (mut zero, mut slivers) = (Vec::new(), Vec::new());
            for (k, t) in m.triangles().enumerate() {
                let cross = m.triangle_cross(t);
                let outward = t.map(|i| p64(m.positions[i as usize])).iter().sum::<DVec3>();
                if cross == DVec3::ZERO {
                    zero.push(k);
                } else if cross.length() < 1e-6 {
                    assert!(cross.dot(outward) < 0.0, "the south pole slivers are reversed");
                    slivers.push(k);
                } else {
                    assert!(cross.dot(outward) > 0.0, "triangle {k} {t:?} is not CCW from outside");
                }
            }
            // Stack 0: every first triangle (two corners on the north pole) has exactly zero area.
            assert_eq!(zero, (0..26).map(|j| 2 * j).collect::<Vec<_>>());
            // Stack 12: every second triangle has two corners on the last ring, which lies one ulp
            // of ρ past the south pole (radius 3.3e-7): tiny and reversed.
            assert_eq!(slivers, (0..26).map(|j| 12 * 52 + 2 * j + 1).collect::<Vec<_>>());
            let volume = m.signed_volume();
            let ball = 4.0 / 3.0 * std::f64::consts::PI * f64::from(radius).powi(3);
            assert!(volume > 0.97 * ball && volume < ball, "{volume} vs {ball}");
        }
        let m = Mesh::glt_sphere(1.0, 26, 13).expect("valid");
        let south = m.positions[glt_index(13, 0) as usize];
        assert_eq!(
            south[1],
            c_sin(12.0 * (std::f32::consts::PI / 13.0) + std::f32::consts::PI / 13.0)
        );
        assert!((f64::from(south[1]) + 3.258e-7).abs() < 1e-10, "{south:?}");
    }

    #[test]
    fn glt_sphere_grid_search_matches_the_linear_scan() {
        for (radius, slices, stacks) in [(1.0, 26, 13), (3.0, 7, 3), (1e-3, 12, 6), (1e-9, 5, 4), (1e4, 3, 2)] {
            let fast = Mesh::glt_sphere(radius, slices, stacks).expect("valid");
            assert_eq!(fast, naive_glt(radius, slices, stacks), "{radius} {slices} {stacks}");
        }
        // A tiny radius puts every position within 1e-5 of every other: the normals and texture
        // coordinates still keep the (stacks + 1)·(slices + 1) grid apart.
        assert_eq!(Mesh::glt_sphere(1e-9, 5, 4).expect("valid").vertex_count(), 5 * 6);
    }

    #[test]
    fn glt_sphere_larger_meshes_stay_consistent() {
        let m = Mesh::glt_sphere(10.0, 128, 64).expect("valid");
        m.validate().expect("well formed");
        assert_eq!(m.vertex_count(), 65 * 129);
        assert_eq!(m.indices.len(), 128 * 64 * 6);
    }

    fn glu_ring(radius: f64, slices: usize, stacks: usize, i: usize, j: usize) -> [f32; 3] {
        let pi = std::f64::consts::PI;
        let phi = (2.0 * pi * (i % slices) as f64 / slices as f64) as f32;
        let theta = (pi * j as f64 / stacks as f64) as f32;
        let r = if j == 0 || j == stacks {
            0.0
        } else {
            (radius * f64::from(theta).sin()) as f32
        };
        [r * c_sin(phi), r * c_cos(phi), (radius * f64::from(theta).cos()) as f32]
    }

    fn check_glu_geometry(m: &Mesh, radius: f64) -> (Vec<usize>, f64) {
        m.validate().expect("well formed");
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let (p, n) = (p64(*p), p64(*n));
            assert!((p.length() - radius).abs() < 1e-6 * radius, "{p}");
            assert!((n - p / radius).length() < 1e-6, "{n} vs {p}");
        }
        let mut degenerate = Vec::new();
        for (k, t) in m.triangles().enumerate() {
            let cross = m.triangle_cross(t);
            if cross == DVec3::ZERO {
                degenerate.push(k);
                continue;
            }
            let outward = t.map(|i| p64(m.positions[i as usize])).iter().sum::<DVec3>();
            assert!(cross.dot(outward) > 0.0, "triangle {k} {t:?} is not CCW from outside");
        }
        (degenerate, m.signed_volume())
    }

    #[test]
    fn glu_sphere_textured() {
        let (radius, slices, stacks) = (2.0, 26, 13);
        let m = Mesh::glu_sphere(radius, slices as u32, stacks as u32).expect("valid");
        assert_eq!(m.vertex_count(), stacks * 2 * (slices + 1));
        assert_eq!(m.triangle_count(), 2 * slices * stacks);
        let (degenerate, volume) = check_glu_geometry(&m, radius);
        // One per pole quad: the first triangle of each north quad, the second of each south one.
        let last = 2 * slices * (stacks - 1);
        let expected: Vec<usize> = (0..slices)
            .map(|k| 2 * k)
            .chain((0..slices).map(|k| last + 2 * k + 1))
            .collect();
        assert_eq!(degenerate, expected);
        assert!(volume > 0.97 * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3));
        // Strip j, slice i: vertex 2i on ring j + 1, 2i + 1 on ring j.
        for j in 0..stacks {
            for i in 0..=slices {
                let base = j * 2 * (slices + 1) + 2 * i;
                assert_eq!(m.positions[base], glu_ring(radius, slices, stacks, i, j + 1), "{i} {j}");
                assert_eq!(m.positions[base + 1], glu_ring(radius, slices, stacks, i, j), "{i} {j}");
                let s = 1.0 - i as f32 / slices as f32;
                assert_eq!(m.tex_coords[base], [s, 1.0 - (j + 1) as f32 / stacks as f32]);
                assert_eq!(m.tex_coords[base + 1], [s, 1.0 - j as f32 / stacks as f32]);
            }
        }
        // By hand: the first strip starts on ring 1 below +y, then the north pole.
        let (sin, cos) = f64::from((std::f64::consts::PI / 13.0) as f32).sin_cos();
        assert_eq!(m.positions[0], [0.0, (2.0 * sin) as f32, (2.0 * cos) as f32]);
        assert_eq!(m.positions[1], [0.0, 0.0, 2.0]);
        assert_eq!(m.normals[1], [0.0, 0.0, 1.0]);
        assert_eq!(m.tex_coords[0], [1.0, 1.0 - 1.0 / 13.0]);
        assert_eq!(m.tex_coords[1], [1.0, 1.0]);
        // Longitude runs from +y towards +x.
        assert!(m.positions[2][0] > 0.0 && m.positions[2][1] > 0.0);
        assert_eq!(m.indices[..6], [0, 1, 3, 2, 0, 3]);
    }

    #[test]
    fn glu_sphere_quads_flat_shade_as_one_colour() {
        // GL flat-shades a quad-strip quad with its last vertex (v2k+3): both triangles of each
        // quad must end on it, the split diagonal being v2k–v2k+3.
        let m = Mesh::glu_sphere(1.0, 8, 4).expect("valid");
        for (q, quad) in m.indices.chunks_exact(6).enumerate() {
            assert_eq!(quad[2], quad[5], "quad {q}: {quad:?}");
            assert_eq!([quad[0], quad[2]], [quad[4], quad[5]], "quad {q}: one diagonal");
        }
    }

    #[test]
    fn glu_sphere_untextured_uses_pole_fans() {
        let (radius, slices, stacks) = (1.0, 26, 13);
        let m = Mesh::glu_sphere_untextured(radius, slices as u32, stacks as u32).expect("valid");
        assert_eq!(m.vertex_count(), 2 * (slices + 2) + (stacks - 2) * 2 * (slices + 1));
        assert_eq!(m.triangle_count(), 2 * slices * (stacks - 1));
        let (degenerate, _) = check_glu_geometry(&m, radius);
        assert!(degenerate.is_empty(), "{degenerate:?}");
        assert!(m.tex_coords.iter().all(|t| *t == [0.0, 0.0]));
        // North fan: the pole, then ring 1 from i = slices (= i = 0) down to 0.
        assert_eq!(m.positions[0], [0.0, 0.0, 1.0]);
        assert_eq!(m.normals[0], [0.0, 0.0, 1.0]);
        assert_eq!(m.positions[1], glu_ring(radius, slices, stacks, 0, 1));
        assert_eq!(m.positions[2], glu_ring(radius, slices, stacks, slices - 1, 1));
        assert_eq!(m.indices[..6], [0, 1, 2, 0, 2, 3]);
        // South fan: the pole, then ring stacks − 1 from i = 0 up.
        let south = slices + 2;
        assert_eq!(m.positions[south], [0.0, 0.0, -1.0]);
        assert_eq!(m.positions[south + 1], glu_ring(radius, slices, stacks, 0, stacks - 1));
        assert_eq!(m.positions[south + 2], glu_ring(radius, slices, stacks, 1, stacks - 1));
        // The middle strips are the textured sphere's, without their texture coordinates.
        let textured = Mesh::glu_sphere(radius, slices as u32, stacks as u32).expect("valid");
        let strip = 2 * (slices + 1);
        assert_eq!(
            m.positions[2 * south..],
            textured.positions[strip..(stacks - 1) * strip]
        );
        assert_eq!(m.normals[2 * south..], textured.normals[strip..(stacks - 1) * strip]);
    }

    #[test]
    fn glu_sphere_south_pole_normal_reads_the_slices_cache() {
        // stacks <= slices: sinCache2a[stacks]·sin(π_f), a tiny x, y.
        let m = Mesh::glu_sphere_untextured(1.0, 8, 4).expect("valid");
        let n = m.normals[8 + 2];
        assert_eq!(n[2], -1.0);
        assert!(n[0] != 0.0 && n[0].abs() < 1e-7, "{n:?}");
        // stacks > slices: uninitialised in C, 0 here.
        let m = Mesh::glu_sphere_untextured(1.0, 4, 8).expect("valid");
        assert_eq!(m.normals[4 + 2].map(f32::abs), [0.0, 0.0, 1.0]);
        check_glu_geometry(&m, 1.0);
    }

    #[test]
    fn glu_sphere_clamps_to_the_cache_size() {
        let big = Mesh::glu_sphere(1.0, 1000, 240).expect("valid");
        assert_eq!(big, Mesh::glu_sphere(1.0, 239, 239).expect("valid"));
        assert_eq!(big.vertex_count(), 239 * 2 * 240);
        let small = Mesh::glu_sphere_untextured(1.0, 3, 2).expect("valid");
        assert_eq!(small.triangle_count(), 6);
        check_glu_geometry(&small, 1.0);
    }

    #[test]
    fn quad_counts_winding_bounds_and_tex_coords() {
        for (size, n) in [(2.0, 1_u32), (3.0, 4), (0.1, 7)] {
            let m = Mesh::quad(size, n).expect("valid");
            m.validate().expect("well formed");
            let side = (n + 1) as usize;
            assert_eq!(m.vertex_count(), side * side);
            assert_eq!(m.indices.len(), 6 * (n * n) as usize);
            let h = (size / 2.0) as f32;
            assert_eq!(m.positions[0], [-h, -h, 0.0]);
            assert_eq!(m.tex_coords[0], [0.0, 0.0]);
            assert_eq!(*m.positions.last().expect("vertices"), [h, h, 0.0]);
            assert_eq!(*m.tex_coords.last().expect("vertices"), [1.0, 1.0]);
            assert_eq!(m.positions[n as usize], [h, -h, 0.0]);
            assert_eq!(m.tex_coords[n as usize], [1.0, 0.0]);
            for (p, t) in m.positions.iter().zip(&m.tex_coords) {
                assert!(p[0].abs() <= h && p[1].abs() <= h && p[2] == 0.0);
                let expected = [
                    (f64::from(p[0]) + size / 2.0) / size,
                    (f64::from(p[1]) + size / 2.0) / size,
                ];
                assert!((f64::from(t[0]) - expected[0]).abs() < 1e-6 && (f64::from(t[1]) - expected[1]).abs() < 1e-6);
            }
            assert!(m.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
            let mut area = 0.0;
            for t in m.triangles() {
                let cross = m.triangle_cross(t);
                assert!(cross.z > 0.0 && cross.x == 0.0 && cross.y == 0.0, "{t:?}");
                area += cross.z / 2.0;
            }
            assert!((area - size * size).abs() < 1e-6 * size * size);
        }
    }

    #[test]
    fn cube_counts_winding_normals_and_bounds() {
        let size = 3.0;
        let m = Mesh::cube(size).expect("valid");
        m.validate().expect("well formed");
        assert_eq!(m.vertex_count(), 24);
        assert_eq!(m.triangle_count(), 12);
        for t in m.triangles() {
            let cross = m.triangle_cross(t);
            for i in t {
                let n = p64(m.normals[i as usize]);
                assert!((cross.normalize() - n).length() < 1e-12, "{t:?}: {cross} vs {n}");
                // Flat face: every vertex on the face's plane, h along its normal.
                assert_eq!(p64(m.positions[i as usize]).dot(n), size / 2.0);
            }
        }
        for (p, t) in m.positions.iter().zip(&m.tex_coords) {
            assert!(p.iter().all(|c| c.abs() == 1.5), "{p:?}");
            assert!(t.iter().all(|c| *c == 0.0 || *c == 1.0), "{t:?}");
        }
        // Every face has all four texture corners, (0, 0) first.
        for face in m.tex_coords.chunks(4) {
            assert_eq!(face, [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        }
        // Side faces upright: texture t grows with z.
        for face in 0..4 {
            assert!(m.positions[4 * face + 3][2] > m.positions[4 * face][2]);
        }
        assert!((m.signed_volume() - size * size * size).abs() < 1e-9);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let field = |r: Result<Mesh, CoreError>| match r {
            Err(CoreError::Invalid { field, .. }) => field,
            other => panic!("expected an error, got {other:?}"),
        };
        for radius in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert_eq!(field(Mesh::glt_sphere(radius, 26, 13)), "radius");
        }
        assert_eq!(field(Mesh::glt_sphere(1.0, 2, 13)), "slices");
        assert_eq!(field(Mesh::glt_sphere(1.0, 4097, 13)), "slices");
        assert_eq!(field(Mesh::glt_sphere(1.0, 26, 1)), "stacks");
        assert_eq!(field(Mesh::glt_sphere(1.0, 26, 4097)), "stacks");
        for radius in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e39, 1e-50] {
            assert_eq!(field(Mesh::glu_sphere(radius, 26, 13)), "radius");
            assert_eq!(field(Mesh::glu_sphere_untextured(radius, 26, 13)), "radius");
            assert_eq!(field(Mesh::quad(radius, 4)), "size");
            assert_eq!(field(Mesh::cube(radius)), "size");
        }
        assert_eq!(field(Mesh::glu_sphere(1.0, 2, 13)), "slices");
        assert_eq!(field(Mesh::glu_sphere_untextured(1.0, 26, 1)), "stacks");
        assert_eq!(field(Mesh::quad(1.0, 0)), "subdivisions");
        assert_eq!(field(Mesh::quad(1.0, 4097)), "subdivisions");
        let err = Mesh::quad(1.0, 0).expect_err("invalid");
        assert_eq!(err.to_string(), "subdivisions = 0: must be in 1..=4096");
    }

    #[test]
    fn validate_catches_broken_meshes() {
        let good = Mesh::quad(1.0, 1).expect("valid");
        let field = |m: &Mesh| match m.validate() {
            Err(CoreError::Invalid { field, .. }) => field,
            other => panic!("expected an error, got {other:?}"),
        };
        let mut m = good.clone();
        m.indices[4] = 4;
        assert_eq!(field(&m), "mesh.indices");
        let mut m = good.clone();
        m.indices.pop();
        assert_eq!(field(&m), "mesh.indices");
        let mut m = good.clone();
        m.normals[2] = [0.0, 0.0, 1.001];
        assert_eq!(field(&m), "mesh.normals");
        let mut m = good.clone();
        m.normals.pop();
        assert_eq!(field(&m), "mesh.normals");
        let mut m = good.clone();
        m.tex_coords.push([0.0, 0.0]);
        assert_eq!(field(&m), "mesh.tex_coords");
        let mut m = good;
        m.positions[0][1] = f32::NAN;
        assert_eq!(field(&m), "mesh.positions");
    }
}
