//! Fixed-function lighting: the OpenGL 2.1 specification, §2.14.1 "Lighting", equation (2.1) and
//! the definitions after it, plus the SuperBible's per-fragment Phong variant (seed 004).
//!
//! For one vertex (or fragment, with Phong shading) at eye-space position `V` with unit normal `n`:
//!
//! ```text
//! c = e_cm + a_cm·a_cs + Σ_i att_i · spot_i · [ a_cm·a_cli + (n ⊙ VP_pli)·d_cm·d_cli
//!                                                + f_i·(n ⊙ ĥ_i)^s_rm · s_cm·s_cli ]
//! ```
//!
//! with `x ⊙ y = max(x·y, 0)`, `VP_pli` the unit vector from `V` to the light, `f_i = 1` when
//! `n ⊙ VP_pli ≠ 0`, `ĥ_i` the normalised half vector `VP_pli + VP_e` (local viewer) or
//! `VP_pli + (0, 0, 1)` (infinite viewer). With separate specular colour the specular sum goes to
//! a secondary colour added after texturing. Alpha is the material's diffuse alpha. Both colours
//! are clamped to `[0, 1]` after lighting unless vertex colour clamping is off
//! ([`LightModel::clamp_vertex_color`]); the fragment stage clamps what it receives either way
//! ([`LitColor::clamped`]), so the switch only changes what Gouraud shading interpolates.

use glam::{DVec3, DVec4};

/// One light, in eye space, with GL's parameter names. Angles in degrees as in `glLightf`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// `GL_AMBIENT` (`a_cli`).
    pub ambient: DVec4,
    /// `GL_DIFFUSE` (`d_cli`).
    pub diffuse: DVec4,
    /// `GL_SPECULAR` (`s_cli`).
    pub specular: DVec4,
    /// `GL_POSITION` in eye space (`P_pli`): `w = 0` directional (towards the light), `w ≠ 0`
    /// positional.
    pub position: DVec4,
    /// `GL_SPOT_DIRECTION` in eye space (`s_dli`).
    pub spot_direction: DVec3,
    /// `GL_SPOT_EXPONENT` (`s_rli`), in [0, 128].
    pub spot_exponent: f64,
    /// `GL_SPOT_CUTOFF` (`c_rli`), degrees, in [0, 90] or exactly 180 (no spot).
    pub spot_cutoff: f64,
    /// `GL_CONSTANT_ATTENUATION` (`k_0i`).
    pub constant_attenuation: f64,
    /// `GL_LINEAR_ATTENUATION` (`k_1i`), per unit distance.
    pub linear_attenuation: f64,
    /// `GL_QUADRATIC_ATTENUATION` (`k_2i`), per unit distance squared.
    pub quadratic_attenuation: f64,
}

impl Light {
    /// GL's initial state for light `index` (table 6.11 of the 2.1 specification): light 0 has
    /// white diffuse and specular, the others black; all at `(0, 0, 1, 0)` with no spot.
    pub fn gl_default(index: usize) -> Self {
        let on = if index == 0 {
            DVec4::ONE
        } else {
            DVec4::new(0.0, 0.0, 0.0, 1.0)
        };
        Self {
            ambient: DVec4::new(0.0, 0.0, 0.0, 1.0),
            diffuse: on,
            specular: on,
            position: DVec4::new(0.0, 0.0, 1.0, 0.0),
            spot_direction: DVec3::new(0.0, 0.0, -1.0),
            spot_exponent: 0.0,
            spot_cutoff: 180.0,
            constant_attenuation: 1.0,
            linear_attenuation: 0.0,
            quadratic_attenuation: 0.0,
        }
    }
}

/// A material (front or back), with GL's parameter names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// `GL_AMBIENT` (`a_cm`).
    pub ambient: DVec4,
    /// `GL_DIFFUSE` (`d_cm`); its alpha is the lit colour's alpha.
    pub diffuse: DVec4,
    /// `GL_SPECULAR` (`s_cm`).
    pub specular: DVec4,
    /// `GL_EMISSION` (`e_cm`).
    pub emission: DVec4,
    /// `GL_SHININESS` (`s_rm`), in [0, 128].
    pub shininess: f64,
}

impl Default for Material {
    /// GL's initial material: ambient 0.2, diffuse 0.8, no specular or emission, shininess 0.
    fn default() -> Self {
        Self {
            ambient: DVec4::new(0.2, 0.2, 0.2, 1.0),
            diffuse: DVec4::new(0.8, 0.8, 0.8, 1.0),
            specular: DVec4::new(0.0, 0.0, 0.0, 1.0),
            emission: DVec4::new(0.0, 0.0, 0.0, 1.0),
            shininess: 0.0,
        }
    }
}

/// How the specular term is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpecularModel {
    /// The fixed-function half vector (Blinn): `(n ⊙ ĥ)^s`.
    #[default]
    Blinn,
    /// The SuperBible's Phong model: `(reflect(−L, n) ⊙ V̂_e)^s`, with `V̂_e` the unit vector to
    /// the eye. (The book's listing dots `n` with `R`, which ignores the viewer: a slip we do not
    /// copy.)
    Phong,
}

/// `glLightModel` state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightModel {
    /// `GL_LIGHT_MODEL_AMBIENT` (`a_cs`); GL's initial value is 0.2 grey.
    pub ambient: DVec4,
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER`: half vectors towards the eye instead of +z.
    pub local_viewer: bool,
    /// `GL_LIGHT_MODEL_TWO_SIDE`: back faces use the back material and the negated normal.
    pub two_side: bool,
    /// `GL_LIGHT_MODEL_COLOR_CONTROL = GL_SEPARATE_SPECULAR_COLOR`.
    pub separate_specular: bool,
    /// `GL_CLAMP_VERTEX_COLOR` (`glClampColor`, OpenGL 3.0 "Clamping or Masking"): lit colours
    /// are clamped to [0, 1] at the vertex, before interpolation. On is GL's initial state and
    /// all that fixed-function GL before 3.0 does; off is what a vertex shader's own outputs get
    /// (GLSL never clamps user-defined varyings), so colours above 1 at the vertices reach the
    /// fragments at full weight, as in the SuperBible's ADSGouraud shader.
    pub clamp_vertex_color: bool,
}

impl Default for LightModel {
    fn default() -> Self {
        Self {
            ambient: DVec4::new(0.2, 0.2, 0.2, 1.0),
            local_viewer: false,
            two_side: false,
            separate_specular: false,
            clamp_vertex_color: true,
        }
    }
}

/// The result of lighting one point: primary and secondary (separate specular) colours.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LitColor {
    /// Emission, ambient, diffuse (and specular unless separate); alpha = material diffuse alpha.
    pub primary: DVec4,
    /// The specular sum when separate specular is on; black otherwise. Alpha 0.
    pub secondary: DVec4,
}

impl LitColor {
    /// The final colour without a texture: primary + secondary, clamped (GL's colour sum).
    pub fn sum(&self) -> DVec4 {
        let c = self.primary + DVec4::new(self.secondary.x, self.secondary.y, self.secondary.z, 0.0);
        c.clamp(DVec4::ZERO, DVec4::ONE)
    }

    /// Both colours clamped to [0, 1]. GL clamps them after lighting when vertex colour clamping
    /// is on, and again as the fragment stage takes them: fragment colour clamping, on for a
    /// fixed-point framebuffer (`GL_CLAMP_FRAGMENT_COLOR`'s initial `GL_FIXED_ONLY`), clamps the
    /// texture environment's inputs and the colour sum, and a shader's output on write.
    pub fn clamped(&self) -> Self {
        let clamp = |c: DVec4| c.clamp(DVec4::ZERO, DVec4::ONE);
        Self {
            primary: clamp(self.primary),
            secondary: clamp(self.secondary),
        }
    }

    /// Smooth (Gouraud) shading: the colours lit at a triangle's three `vertices`, blended by a
    /// fragment's barycentric `weights` (perspective-correct, as GL interpolates). Colours blend
    /// as lighting left them — above 1 when vertex clamping is off — and the fragment stage then
    /// clamps the blend ([`Self::clamped`]).
    pub fn blend(vertices: [Self; 3], weights: [f64; 3]) -> Self {
        let [a, b, c] = vertices;
        let [wa, wb, wc] = weights;
        Self {
            primary: wa * a.primary + wb * b.primary + wc * c.primary,
            secondary: wa * a.secondary + wb * b.secondary + wc * c.secondary,
        }
    }
}

/// Everything that lights a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Lighting<'a> {
    /// Enabled lights (any number; GL guarantees 8).
    pub lights: &'a [Light],
    /// Light model.
    pub model: LightModel,
    /// Front material.
    pub front: Material,
    /// Back material (used for back faces when `model.two_side`).
    pub back: Material,
    /// Specular model.
    pub specular: SpecularModel,
}

fn dot_clamped(a: DVec3, b: DVec3) -> f64 {
    a.dot(b).max(0.0)
}

impl Lighting<'_> {
    /// Lights a point at eye-space `position` with eye-space `normal` (normalised here, like
    /// `GL_NORMALIZE`). `front_facing` selects the material when two-sided lighting is on. The
    /// colours are clamped to [0, 1] when `model.clamp_vertex_color` is on (GL's default).
    pub fn shade(&self, position: DVec3, normal: DVec3, front_facing: bool) -> LitColor {
        let lit = self.shade_unclamped(position, normal, front_facing);
        if self.model.clamp_vertex_color {
            lit.clamped()
        } else {
            lit
        }
    }

    /// [`Self::shade`] without GL's clamping to [0, 1]: the same equation in radiance units, for
    /// objects lit by a physical sky.
    pub fn shade_unclamped(&self, position: DVec3, normal: DVec3, front_facing: bool) -> LitColor {
        let back = self.model.two_side && !front_facing;
        let (m, n) = if back {
            (&self.back, -normal.normalize_or_zero())
        } else {
            (&self.front, normal.normalize_or_zero())
        };
        let mut color = m.emission + m.ambient * self.model.ambient;
        let mut specular_sum = DVec4::ZERO;
        let to_eye = (-position).normalize_or_zero();
        for light in self.lights {
            let (to_light, attenuation) = if light.position.w == 0.0 {
                (light.position.truncate().normalize_or_zero(), 1.0)
            } else {
                let p = light.position.truncate() / light.position.w;
                let d = p - position;
                let dist = d.length();
                let k = light.constant_attenuation
                    + light.linear_attenuation * dist
                    + light.quadratic_attenuation * dist * dist;
                (d.normalize_or_zero(), if k > 0.0 { 1.0 / k } else { 0.0 })
            };
            let spot = if light.spot_cutoff == 180.0 {
                1.0
            } else {
                let cos_angle = (-to_light).dot(light.spot_direction.normalize_or_zero());
                if cos_angle >= light.spot_cutoff.to_radians().cos() {
                    cos_angle.max(0.0).powf(light.spot_exponent)
                } else {
                    0.0
                }
            };
            let factor = attenuation * spot;
            let n_dot_l = dot_clamped(n, to_light);
            color += factor * (m.ambient * light.ambient + n_dot_l * m.diffuse * light.diffuse);
            if n_dot_l != 0.0 {
                let s = match self.specular {
                    SpecularModel::Blinn => {
                        let eye = if self.model.local_viewer { to_eye } else { DVec3::Z };
                        dot_clamped(n, (to_light + eye).normalize_or_zero())
                    }
                    SpecularModel::Phong => {
                        let eye = if self.model.local_viewer { to_eye } else { DVec3::Z };
                        let reflected = (-to_light) - 2.0 * (-to_light).dot(n) * n;
                        dot_clamped(reflected, eye)
                    }
                };
                // GL defines 0^0 = 1 for the specular power (shininess 0 gives full specular).
                let power = if m.shininess == 0.0 { 1.0 } else { s.powf(m.shininess) };
                specular_sum += factor * power * m.specular * light.specular;
            }
        }
        let spec_rgb = DVec4::new(specular_sum.x, specular_sum.y, specular_sum.z, 0.0);
        let (primary, secondary) = if self.model.separate_specular {
            (color, spec_rgb)
        } else {
            (color + spec_rgb, DVec4::ZERO)
        };
        LitColor {
            primary: DVec4::new(primary.x, primary.y, primary.z, m.diffuse.w),
            secondary: DVec4::new(secondary.x, secondary.y, secondary.z, 0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgb(r: f64, g: f64, b: f64) -> DVec4 {
        DVec4::new(r, g, b, 1.0)
    }

    #[test]
    fn gl_defaults_light_a_facing_surface_to_the_textbook_value() {
        // Light 0 defaults: directional along +z, white. Default material, scene ambient 0.2.
        // c = 0.2·0.2 (scene) + 0 (light ambient) + 1·0.8·1 (diffuse) + 0 (no specular) = 0.84.
        let lights = [Light::gl_default(0)];
        let l = Lighting {
            lights: &lights,
            model: LightModel::default(),
            front: Material::default(),
            back: Material::default(),
            specular: SpecularModel::Blinn,
        };
        let c = l.shade(DVec3::new(0.0, 0.0, -5.0), DVec3::Z, true);
        assert!(
            (c.primary - DVec4::new(0.84, 0.84, 0.84, 1.0)).length() < 1e-15,
            "{c:?}"
        );
        assert!(Light::gl_default(3).diffuse.truncate() == DVec3::ZERO);
    }

    #[test]
    fn superbible_ads_at_the_highlight() {
        // SuperBible ADS: ambient 0.1, diffuse (0, 0, 1), white specular, shininess 128, light at
        // eye-space (−100, 100, 100). At the point where n is the half vector the specular is 1.
        let light = Light {
            position: DVec4::new(-100.0, 100.0, 100.0, 1.0),
            ambient: DVec4::new(0.0, 0.0, 0.0, 1.0),
            ..Light::gl_default(0)
        };
        let material = Material {
            ambient: rgb(0.1, 0.1, 0.1),
            diffuse: rgb(0.0, 0.0, 1.0),
            specular: rgb(1.0, 1.0, 1.0),
            emission: DVec4::new(0.0, 0.0, 0.0, 1.0),
            shininess: 128.0,
        };
        let model = LightModel {
            ambient: rgb(1.0, 1.0, 1.0),
            ..LightModel::default()
        };
        let lights = [light];
        let l = Lighting {
            lights: &lights,
            model,
            front: material,
            back: material,
            specular: SpecularModel::Blinn,
        };
        let p = DVec3::new(0.0, 0.0, -4.0);
        let to_light = (light.position.truncate() - p).normalize();
        let h = (to_light + DVec3::Z).normalize();
        let c = l.shade(p, h, true);
        // 0.1 ambient + (n·L) blue + 1.0 specular white, clamped.
        let n_dot_l = h.dot(to_light);
        assert!((c.primary.x - 1.0f64.min(0.1 + 1.0)).abs() < 1e-12);
        assert!((c.primary.z - (0.1 + n_dot_l + 1.0).min(1.0)).abs() < 1e-12);
        // Facing away from the light: only the ambient term.
        let away = l.shade(p, -to_light, true);
        assert!((away.primary - rgb(0.1, 0.1, 0.1)).length() < 1e-12, "{away:?}");
    }

    #[test]
    fn attenuation_spot_and_separate_specular() {
        let light = Light {
            position: DVec4::new(0.0, 0.0, 0.0, 1.0),
            spot_direction: DVec3::NEG_Z,
            spot_cutoff: 30.0,
            spot_exponent: 2.0,
            constant_attenuation: 1.0,
            linear_attenuation: 0.5,
            quadratic_attenuation: 0.25,
            ..Light::gl_default(0)
        };
        let material = Material {
            ambient: DVec4::new(0.0, 0.0, 0.0, 0.5),
            diffuse: DVec4::new(1.0, 1.0, 1.0, 0.5),
            specular: rgb(1.0, 0.0, 0.0),
            shininess: 1.0,
            ..Material::default()
        };
        let model = LightModel {
            ambient: DVec4::ZERO,
            separate_specular: true,
            local_viewer: true,
            two_side: true,
            clamp_vertex_color: true,
        };
        let lights = [light];
        let l = Lighting {
            lights: &lights,
            model,
            front: material,
            back: Material::default(),
            specular: SpecularModel::Blinn,
        };
        // On the spot axis at distance 2: att = 1/(1 + 1 + 1) = 1/3, spot = 1, n·L = 1.
        let c = l.shade(DVec3::new(0.0, 0.0, -2.0), DVec3::Z, true);
        assert!((c.primary.y - 1.0 / 3.0).abs() < 1e-12 && (c.primary.w - 0.5).abs() < 1e-15);
        assert!((c.secondary.x - 1.0 / 3.0).abs() < 1e-12 && c.secondary.y == 0.0);
        // 20° off axis: inside the 30° cutoff, spot = cos²(20°), distance 2 along that ray.
        let dir = DVec3::new(20f64.to_radians().sin(), 0.0, -20f64.to_radians().cos());
        let c = l.shade(dir * 2.0, -dir, true);
        assert!((c.primary.y - 20f64.to_radians().cos().powi(2) / 3.0).abs() < 1e-12);
        // 40° off axis: outside the cone.
        let dir = DVec3::new(40f64.to_radians().sin(), 0.0, -40f64.to_radians().cos());
        assert_eq!(l.shade(dir * 2.0, -dir, true).primary.truncate(), DVec3::ZERO);
        // Two-sided: a back face uses the back material and the flipped normal.
        let back = l.shade(DVec3::new(0.0, 0.0, -2.0), DVec3::NEG_Z, false);
        assert!((back.primary.y - 0.8 / 3.0).abs() < 1e-12, "{back:?}");
    }

    #[test]
    fn unclamped_vertex_colours_interpolate_at_full_value() {
        // Diffuse 1.6 under a white light along +z: a vertex facing the light is lit 1.6, one
        // whose normal makes cos θ = 1/4 with it 0.4. Half way between them GL interpolates
        // (1.6 + 0.4)/2 = 1.0 when vertex colours are not clamped, (1 + 0.4)/2 = 0.7 when they are.
        let lights = [Light::gl_default(0)];
        let material = Material {
            ambient: DVec4::ZERO,
            diffuse: rgb(1.6, 1.6, 1.6),
            ..Material::default()
        };
        let midpoint = |clamp_vertex_color: bool| {
            let l = Lighting {
                lights: &lights,
                model: LightModel {
                    ambient: DVec4::ZERO,
                    clamp_vertex_color,
                    ..LightModel::default()
                },
                front: material,
                back: material,
                specular: SpecularModel::Blinn,
            };
            let p = DVec3::new(0.0, 0.0, -4.0);
            let oblique = DVec3::new(15f64.sqrt(), 0.0, 1.0);
            let (bright, dim) = (l.shade(p, DVec3::Z, true), l.shade(p, oblique, true));
            assert!((dim.primary.x - 0.4).abs() < 1e-12, "{dim:?}");
            LitColor::blend([bright, dim, dim], [0.5, 0.5, 0.0]).clamped()
        };
        let unclamped = midpoint(false);
        assert!((unclamped.primary.x - 1.0).abs() < 1e-12, "{unclamped:?}");
        let clamped = midpoint(true);
        assert!((clamped.primary.x - 0.7).abs() < 1e-12, "{clamped:?}");
        // Alpha (the material's diffuse alpha) is 1 either way; nothing reaches the secondary.
        assert_eq!((unclamped.primary.w, unclamped.secondary), (1.0, DVec4::ZERO));
    }

    #[test]
    fn phong_specular_depends_on_the_viewer() {
        let light = Light {
            position: DVec4::new(0.0, 1.0, 1.0, 0.0),
            ..Light::gl_default(0)
        };
        let material = Material {
            diffuse: DVec4::new(0.0, 0.0, 0.0, 1.0),
            ambient: DVec4::ZERO,
            specular: rgb(1.0, 1.0, 1.0),
            shininess: 10.0,
            ..Material::default()
        };
        let lights = [light];
        let model = LightModel {
            ambient: DVec4::ZERO,
            local_viewer: true,
            ..LightModel::default()
        };
        let l = Lighting {
            lights: &lights,
            model,
            front: material,
            back: material,
            specular: SpecularModel::Phong,
        };
        // The reflection of the light about +y... a surface facing +z at the origin-side point
        // where the reflected ray (0, −1, 1)/√2 points at the eye gets full specular.
        let to_eye = DVec3::new(0.0, -1.0, 1.0).normalize();
        let p = -to_eye * 3.0;
        let full = l.shade(p, DVec3::Z, true);
        assert!((full.primary.x - 1.0).abs() < 1e-12, "{full:?}");
        // Another viewer position sees less.
        let off = l.shade(DVec3::new(0.0, 0.0, -3.0), DVec3::Z, true);
        assert!(off.primary.x < 0.9);
    }
}
