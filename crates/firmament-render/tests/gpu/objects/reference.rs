//! The CPU reference for the object pass: casts each pixel's eye ray at the frame's triangles in
//! `f64` and evaluates the core's statement of the GL equations there — lighting
//! (`Lighting::shade`), texturing (`TextureImage::sample`, `GL_MODULATE`), colour sum and fog —
//! with the interpolation GL does: Gouraud colours (`LitColor::blend`) and fog coordinates
//! perspective-correct between the vertices (ray barycentrics are exactly that), Phong normals
//! the same way, flat shading the colour of the triangle's last vertex.

use firmament_core::Camera;
use firmament_core::classic::lighting::{Light, Lighting, LitColor, Material};
use firmament_core::classic::scene::{ObjectLayer, SceneFog, SceneObject, Shading};
use glam::{DMat3, DVec2, DVec3, DVec4};

/// One object's triangles in eye space, and the lights it sees.
struct EyeObject<'a> {
    object: &'a SceneObject,
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    lights: Vec<Light>,
}

/// A frame's objects prepared for ray casting.
pub(crate) struct Reference<'a> {
    layer: &'a ObjectLayer,
    camera: Camera,
    objects: Vec<EyeObject<'a>>,
}

/// Möller–Trumbore: (t, u, v) of the ray from the origin along `d` through triangle (a, b, c).
fn hit(d: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = -a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

fn rgb(c: DVec4) -> DVec3 {
    c.truncate()
}

impl<'a> Reference<'a> {
    /// Prepares `layer` as seen by `camera` (with the target's aspect).
    pub(crate) fn new(layer: &'a ObjectLayer, camera: Camera) -> Self {
        let view = camera.view_matrix();
        let lights = layer
            .lighting
            .equations()
            .map_or_else(Vec::new, |c| c.lights.iter().map(|l| l.in_eye_space(&view)).collect());
        let objects = layer
            .objects
            .iter()
            .map(|object| {
                let model_view = view * object.model;
                let normal_matrix = DMat3::from_mat4(model_view).inverse().transpose();
                let mesh = &object.mesh;
                // The object's own light colours replace the frame's, index by index.
                let mut lights = lights.clone();
                for (light, &color) in lights.iter_mut().zip(&object.light_colors) {
                    light.diffuse = color;
                    light.specular = color;
                }
                EyeObject {
                    lights,
                    object,
                    positions: mesh
                        .positions
                        .iter()
                        .map(|p| model_view.transform_point3(DVec3::from(p.map(f64::from))))
                        .collect(),
                    normals: mesh
                        .normals
                        .iter()
                        .map(|n| normal_matrix * DVec3::from(n.map(f64::from)))
                        .collect(),
                }
            })
            .collect();
        Self { layer, camera, objects }
    }

    fn lighting<'b>(&self, object: &'b EyeObject<'_>) -> Option<Lighting<'b>> {
        self.layer.lighting.equations().map(|c| Lighting {
            lights: &object.lights,
            model: c.model,
            front: object.object.front,
            back: object.object.back,
            specular: c.specular,
        })
    }

    /// The colour GL's equations give at normalised device coordinates `ndc`, with its alpha;
    /// `None` where no triangle is hit.
    pub(crate) fn pixel(&self, ndc: DVec2) -> Option<DVec4> {
        let inverse_projection = self.camera.projection_matrix().inverse();
        let p = inverse_projection * DVec4::new(ndc.x, ndc.y, 1.0, 1.0);
        let d = (p.truncate() / p.w).normalize();
        let (object, (t, u, v), [a, b, c]) = self
            .objects
            .iter()
            .flat_map(|o| {
                o.object.mesh.indices.chunks_exact(3).filter_map(move |tri| {
                    let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
                    hit(d, o.positions[a], o.positions[b], o.positions[c]).map(|h| (o, h, [a, b, c]))
                })
            })
            .min_by(|x, y| x.1.0.total_cmp(&y.1.0))?;
        let w = [1.0 - u - v, u, v];
        let interpolate = |f: &dyn Fn(usize) -> DVec4| f(a) * w[0] + f(b) * w[1] + f(c) * w[2];
        let (pa, pb, pc) = (object.positions[a], object.positions[b], object.positions[c]);
        // Counter-clockwise seen from the eye: the face normal points back along the ray.
        let front_facing = (pb - pa).cross(pc - pa).dot(pa) < 0.0;
        let m: &Material = &object.object.front;
        let LitColor { primary, secondary } = match self.lighting(object) {
            None => LitColor {
                primary: m.diffuse.clamp(DVec4::ZERO, DVec4::ONE),
                secondary: DVec4::ZERO,
            },
            Some(lighting) => {
                let shading = self.layer.lighting.equations().map_or(Shading::Gouraud, |c| c.shading);
                let clamps = self.layer.lighting.clamps();
                let shade = |p: DVec3, n: DVec3| {
                    if clamps {
                        lighting.shade(p, n, front_facing)
                    } else {
                        lighting.shade_unclamped(p, n, front_facing)
                    }
                };
                let lit = |i: usize| shade(object.positions[i], object.normals[i]);
                let fragment = match shading {
                    Shading::Flat => lit(c),
                    Shading::Gouraud => LitColor::blend([lit(a), lit(b), lit(c)], w),
                    Shading::Phong => {
                        let n = interpolate(&|i| object.normals[i].extend(0.0)).truncate();
                        shade(d * t, n)
                    }
                };
                // The fragment stage clamps what it receives: colours a vertex left above 1
                // (`clamp_vertex_color` off) only now.
                if clamps { fragment.clamped() } else { fragment }
            }
        };
        let primary = match &object.object.texture {
            None => primary,
            Some(texture) => {
                let st = interpolate(&|i| {
                    let [s, t] = object.object.mesh.tex_coords[i];
                    DVec4::new(f64::from(s), f64::from(t), 0.0, 0.0)
                });
                primary * texture.image.sample(st.x, st.y, texture.filter)
            }
        };
        let sum = rgb(primary) + rgb(secondary);
        let sum = if self.layer.lighting.clamps() {
            sum.clamp(DVec3::ZERO, DVec3::ONE)
        } else {
            sum
        };
        let color = sum.extend(primary.w.clamp(0.0, 1.0));
        let position = d * t;
        Some(match self.layer.fog {
            SceneFog::None => color,
            SceneFog::Classic(fog) => {
                let mesh = &object.object.mesh;
                let vertex_fog = |i: usize| {
                    mesh.fog_coords
                        .get(i)
                        .map_or(object.object.fog_coord, |&c| f64::from(c))
                };
                let coordinate =
                    interpolate(&|i| DVec4::splat(fog.coordinate.of(object.positions[i], vertex_fog(i)))).x;
                fog.mode.apply(color, fog.color, coordinate)
            }
            SceneFog::Height {
                fog,
                color: fog_color,
                sun,
            } => {
                let world = self.camera.view_matrix().inverse().transform_point3(position);
                let f = fog.transmittance(self.camera.position, world);
                let view = (world - self.camera.position).normalize();
                let fog_color = sun.map_or(fog_color, |sun| sun.inscattered(fog_color, view));
                (rgb(color) * f + rgb(fog_color) * (1.0 - f)).extend(color.w)
            }
        })
    }
}
