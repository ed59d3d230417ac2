//! The ground near the camera under a physical sky: the planet's surface as a mesh objects can
//! shadow ([`ground_patch`]), and the light it bounces up onto the undersides of objects
//! ([`Ground`]).
//!
//! The patch is a disc on the sphere of the surface's mean radius of curvature `√(M·N)` at the
//! camera's foot point (M meridional, N prime vertical), reaching a little past the horizon of a
//! camera near the ground (at most [`MAX_GROUND_EXTENT_M`], the aerial-perspective volume's
//! range): within it the ellipsoid and that sphere part by millimetres. Beyond it, the sky pass
//! draws the ground from its LUTs, as it does for every camera too high for the patch to reach
//! its horizon.
//!
//! Light from below (Ramamoorthi & Hanrahan's concern, the sky's spherical harmonics ringing into
//! downward normals, is avoided by not using them here): a surface of unit normal `n` sees the
//! sky over the view factor `(1 + n·up)/2` and an infinite Lambertian ground over `(1 − n·up)/2`
//! — exact for a uniform sky and ground (Siegel & Howell, "Thermal Radiation Heat Transfer",
//! view factor of a tilted plane). The ground's radiance is its albedo × the irradiance on it
//! (sun, shadowed where objects shadow it, plus sky) / π.
//!
//! Over a planet with a surface ([`crate::atmosphere::surface`]) the patch carries the surface's
//! albedo as a texture ([`surface_texture`]), so where the sky pass takes over at its edge the
//! ground keeps its colours; the light it bounces up is the albedo at the camera's foot point's.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use glam::{DMat4, DVec3, DVec4};

use super::lighting::Material;
use super::mesh::Mesh;
use super::scene::SceneObject;
use crate::atmosphere::Planet;

/// The farthest the ground patch reaches from the camera's foot point, metres (the
/// aerial-perspective volume's range).
pub const MAX_GROUND_EXTENT_M: f64 = 100_000.0;
/// Rings of the patch, from 0.25 m out to its edge in geometric steps.
const RINGS: u32 = 96;
/// Vertices per ring.
const SEGMENTS: u32 = 128;
/// The innermost ring's radius, metres.
const INNER_RING_M: f64 = 0.25;

/// The ground near the camera and the light it bounces up.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    /// The surface patch: drawn and shadowed like an object, casting nothing.
    pub object: SceneObject,
    /// Unit world-frame up at the camera's foot point.
    pub up: DVec3,
    /// The camera's height above the patch's centre, metres.
    pub camera_height_m: f64,
    /// The sky's irradiance on a horizontal surface / π, linear sRGB radiance (cd/m²).
    pub sky: DVec4,
    /// The ground's radiance from the direct suns: albedo × Σ E·T·cos θ / π (cd/m²), unshadowed.
    pub bounced_sun: DVec4,
    /// The ground's radiance from the sky: albedo × the sky's irradiance / π (cd/m²).
    pub bounced_sky: DVec4,
}

/// Mean radius of curvature `√(M·N)` of `planet`'s surface at the planet-frame unit normal `up`,
/// metres (the equatorial radius taken as the mean of the x and y radii).
pub fn mean_radius_of_curvature(planet: &Planet, up: DVec3) -> f64 {
    let a = 0.5 * (planet.radii.x + planet.radii.y);
    let b = planet.radii.z;
    let e2 = 1.0 - (b * b) / (a * a);
    let sin2 = (up.z * up.z).min(1.0);
    let w = 1.0 - e2 * sin2;
    let n = a / w.sqrt();
    let m = a * (1.0 - e2) / (w * w.sqrt());
    (m * n).sqrt()
}

/// How far the patch reaches for a camera `height_m` above ground on a surface of radius of
/// curvature `radius_m`: a quarter past the horizon, in powers of two from 1 km (so small moves
/// reuse the mesh), at most [`MAX_GROUND_EXTENT_M`].
pub fn ground_extent(radius_m: f64, height_m: f64) -> f64 {
    let h = height_m.max(1.0);
    let horizon = (2.0 * radius_m * h + h * h).sqrt();
    let mut extent = 1024.0;
    while extent < 1.25 * horizon && extent < MAX_GROUND_EXTENT_M {
        extent *= 2.0;
    }
    extent.min(MAX_GROUND_EXTENT_M)
}

/// A disc of radius `extent_m` on a sphere of radius `radius_m`, centred on the origin with the
/// sphere's centre at `(0, 0, −radius_m)`: rings in geometric steps from the centre, normals of
/// the sphere, counter-clockwise seen from above. Shared between calls with the same arguments
/// (metre-rounded radius), so a renderer uploads it once.
pub fn ground_patch(radius_m: f64, extent_m: f64) -> Arc<Mesh> {
    /// Patches by (radius, extent), metres.
    type Patches = HashMap<(u64, u64), Arc<Mesh>>;
    static CACHE: OnceLock<Mutex<Patches>> = OnceLock::new();
    let key = (radius_m.round() as u64, extent_m.round() as u64);
    let mut cache = CACHE
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if cache.len() > 8 {
        cache.clear();
    }
    Arc::clone(
        cache
            .entry(key)
            .or_insert_with(|| Arc::new(build_patch(key.0 as f64, key.1 as f64))),
    )
}

fn build_patch(radius: f64, extent: f64) -> Mesh {
    let mut mesh = Mesh::default();
    let mut push = |rho: f64, phi: f64| {
        let (x, y) = (rho * phi.cos(), rho * phi.sin());
        // The sphere's drop below the tangent plane, R − √(R² − ρ²), without cancellation.
        let z = -rho * rho / (radius + (radius * radius - rho * rho).max(0.0).sqrt());
        let n = DVec3::new(x, y, z + radius) / radius;
        mesh.positions.push([x as f32, y as f32, z as f32]);
        mesh.normals.push(n.normalize().as_vec3().to_array());
        mesh.tex_coords
            .push([surface_texture_coord(x / extent), surface_texture_coord(y / extent)]);
    };
    push(0.0, 0.0);
    let ratio = (extent / INNER_RING_M).powf(1.0 / f64::from(RINGS - 1));
    for ring in 0..RINGS {
        let rho = INNER_RING_M * ratio.powi(ring as i32);
        for s in 0..SEGMENTS {
            push(rho, std::f64::consts::TAU * f64::from(s) / f64::from(SEGMENTS));
        }
    }
    let at = |ring: u32, s: u32| 1 + ring * SEGMENTS + s % SEGMENTS;
    for s in 0..SEGMENTS {
        mesh.indices.extend([0, at(0, s), at(0, s + 1)]);
    }
    for ring in 0..RINGS - 1 {
        for s in 0..SEGMENTS {
            let (a, b, c, d) = (at(ring, s), at(ring, s + 1), at(ring + 1, s), at(ring + 1, s + 1));
            mesh.indices.extend([a, c, d, a, d, b]);
        }
    }
    mesh
}

/// Texels across the surface texture of a ground patch ([`surface_texture`]).
pub const SURFACE_TEXTURE_SIDE: u32 = 32;

/// Where the patch point at `x` (−1 … 1: across its square, in units of its extent) reads a
/// surface texture: from the first texel's centre to the last's, so that GL's repeat never
/// blends in the far side.
fn surface_texture_coord(x: f64) -> f32 {
    let n = f64::from(SURFACE_TEXTURE_SIDE);
    ((0.5 + 0.5 * (n - 1.0) * (x.clamp(-1.0, 1.0) + 1.0)) / n) as f32
}

/// The patch point (−1 … 1, in units of its extent) at texel `i`'s centre: the inverse of
/// [`surface_texture_coord`].
fn surface_texel_point(i: u32) -> f64 {
    2.0 * f64::from(i) / f64::from(SURFACE_TEXTURE_SIDE - 1) - 1.0
}

/// The ground patch under a camera at world point `camera` over `planet` (posed in the world
/// frame), of material `albedo` (ambient = diffuse, no specular); `None` below the surface. Also
/// the world up and the camera's height at the foot point.
pub fn ground_object(planet: &Planet, camera: DVec3, albedo: DVec4) -> Option<(SceneObject, DVec3, f64)> {
    let p = planet.to_planet_frame(camera);
    let height = planet.altitude(p);
    if !height.is_finite() || height < 0.0 {
        return None;
    }
    let up_planet = planet.up(p);
    let foot = p - up_planet * height;
    let rotation = planet.orientation.normalize();
    let up = rotation * up_planet;
    let foot_world = rotation * foot + planet.center;
    // Any horizontal x: the patch is round.
    let hint = if up.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let x = (hint - up * hint.dot(up)).normalize();
    let y = up.cross(x);
    let model = DMat4::from_cols(x.extend(0.0), y.extend(0.0), up.extend(0.0), foot_world.extend(1.0));
    let radius = mean_radius_of_curvature(planet, up_planet);
    let mesh = ground_patch(radius, ground_extent(radius, height));
    let material = Material {
        ambient: albedo,
        diffuse: albedo,
        specular: DVec4::new(0.0, 0.0, 0.0, 1.0),
        ..Material::default()
    };
    Some((SceneObject::new(mesh, model, material), up, height))
}

/// Lays `surface`'s albedo over the ground patch `object` (made by [`ground_object`] for the
/// same `planet`): a [`SURFACE_TEXTURE_SIDE`]² texture of the map over the patch's square, and
/// the material's ambient and diffuse colours set to its largest albedo per channel, the texels
/// being the albedo over it (GL's modulate multiplies them; 8-bit texels keep their precision
/// relative to the patch's brightest ground). `as_rgb` turns an albedo per model wavelength into
/// the linear sRGB albedo the object pass lights.
pub fn surface_texture(
    planet: &Planet,
    surface: &crate::atmosphere::surface::Surface,
    object: &mut SceneObject,
    as_rgb: impl Fn(crate::atmosphere::Spectrum) -> DVec3,
) {
    let n = SURFACE_TEXTURE_SIDE;
    let extent = object
        .mesh
        .positions
        .iter()
        .map(|p| f64::from(p[0]).abs().max(f64::from(p[1]).abs()))
        .fold(0.0, f64::max);
    let rotation = planet.orientation.normalize();
    // Texel (s, t), bottom row first as in GL, at the patch point (x, y) of its centre.
    let albedos: Vec<DVec3> = (0..n * n)
        .map(|k| {
            let (s, t) = (k % n, k / n);
            let (x, y) = (surface_texel_point(s) * extent, surface_texel_point(t) * extent);
            let world = object.model.transform_point3(DVec3::new(x, y, 0.0));
            let planet_point = rotation.inverse() * (world - planet.center);
            as_rgb(surface.at(planet.up(planet_point)).albedo)
        })
        .collect();
    let scale = albedos.iter().fold(DVec3::splat(1e-4), |m, a| m.max(*a));
    let texels = albedos
        .iter()
        .map(|a| {
            let v = (*a / scale * 255.0).round().clamp(DVec3::ZERO, DVec3::splat(255.0));
            [v.x as u8, v.y as u8, v.z as u8, 255]
        })
        .collect();
    let material = Material {
        ambient: scale.extend(1.0),
        diffuse: scale.extend(1.0),
        ..object.front
    };
    object.front = material;
    object.back = material;
    object.texture = Some(super::scene::ObjectTexture {
        image: Arc::new(crate::texture::TextureImage {
            width: n,
            height: n,
            texels,
        }),
        filter: crate::texture::TextureFilter::Linear,
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::presets;

    #[test]
    fn the_patch_follows_the_surface_to_its_edge() {
        let mut planet = presets::earth().planet;
        planet = planet.posed_at(45f64.to_radians(), 10f64.to_radians());
        let camera = DVec3::new(0.0, 0.0, 1.7);
        let (object, up, height) = ground_object(&planet, camera, DVec4::splat(0.3)).unwrap();
        assert!((height - 1.7).abs() < 1e-6 && up.distance(DVec3::Z) < 1e-9);
        let mesh = &object.mesh;
        let extent = ground_extent(
            mean_radius_of_curvature(&planet, planet.up(planet.to_planet_frame(camera))),
            1.7,
        );
        assert!(extent >= 1.25 * (2.0 * 6.37e6 * 1.7f64).sqrt());
        // Every vertex lies on the ellipsoid to within a few centimetres.
        let worst = mesh
            .positions
            .iter()
            .map(|v| {
                let w = object
                    .model
                    .transform_point3(DVec3::new(v[0].into(), v[1].into(), v[2].into()));
                planet.altitude(planet.to_planet_frame(w)).abs()
            })
            .fold(0.0, f64::max);
        assert!(worst < 0.05, "{worst} m off the ellipsoid");
        assert!(mesh.validate().is_ok());
        // Counter-clockwise from above: the first triangle's normal points up.
        let t = mesh.triangles().next().unwrap();
        assert!(mesh.triangle_cross(t).z > 0.0);
    }

    #[test]
    fn the_patch_is_shared_and_grows_with_height() {
        let r = 6.37e6;
        assert!(Arc::ptr_eq(&ground_patch(r, 8192.0), &ground_patch(r + 0.2, 8192.0)));
        assert!(ground_extent(r, 2.0) < ground_extent(r, 200.0));
        assert_eq!(ground_extent(r, 10_000.0), MAX_GROUND_EXTENT_M);
    }

    #[test]
    fn a_sphere_s_radius_of_curvature_is_its_radius() {
        let planet = Planet::sphere(1000.0, 10.0);
        let r = mean_radius_of_curvature(&planet, DVec3::new(0.6, 0.0, 0.8));
        assert!((r - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn a_surface_s_albedo_lies_on_the_patch_where_the_map_has_it() {
        use crate::atmosphere::surface::{Surface, SurfaceMap};
        // West of longitude 0 albedo 0.4, east of it 0.1 (two texels; bilinear between their
        // centres at ∓90°, so 0.25 ∓ 0.15·λ/90° near 0°), water nowhere.
        let map = SurfaceMap::new(2, 1, vec![[0.4, 0.4, 0.4, 0.0], [0.1, 0.1, 0.1, 0.0]]).unwrap();
        let surface = Surface::new(map);
        let planet = Planet::sphere(6.36e6, 6e4).posed_at(0.0, 0.0);
        let camera = DVec3::new(0.0, 0.0, 5000.0);
        let (mut object, _, _) = ground_object(&planet, camera, DVec4::splat(0.3)).unwrap();
        surface_texture(&planet, &surface, &mut object, |a| a);
        let texture = object.texture.as_ref().expect("a texture");
        let scale = object.front.diffuse;
        // Every texel times the material is the map at the texel's centre (world → planet).
        let n = SURFACE_TEXTURE_SIDE;
        let extent = MAX_GROUND_EXTENT_M;
        for (s, t) in [(0, 0), (n - 1, 5), (7, n - 1), (n / 2, n / 2)] {
            let (x, y) = (surface_texel_point(s) * extent, surface_texel_point(t) * extent);
            let world = object.model.transform_point3(DVec3::new(x, y, 0.0));
            let up = planet.up(planet.to_planet_frame(world));
            let want = surface.at(up).albedo.x;
            let got = f64::from(texture.image.texel(s, t).unwrap()[0]) / 255.0 * scale.x;
            assert!(
                (got - want).abs() < 0.5 / 255.0 * scale.x + 1e-9,
                "({s}, {t}): {got} vs {want}"
            );
        }
        // East (the patch's +x at longitude 0 looks along the world's east) is darker.
        let row = |s: u32| texture.image.texel(s, n / 2).unwrap()[0];
        assert!(row(0) != row(n - 1));
        // The mesh reads the texture between its first and last texel centres, the rim at them.
        let (first, last) = (0.5 / n as f32, 1.0 - 0.5 / n as f32);
        assert!(
            object
                .mesh
                .tex_coords
                .iter()
                .all(|uv| uv.iter().all(|v| (first - 1e-6..=last + 1e-6).contains(v)))
        );
        assert!((surface_texture_coord(1.0) - last).abs() < 1e-7 && (surface_texture_coord(-1.0) - first).abs() < 1e-7);
        assert!((surface_texel_point(n - 1) - 1.0).abs() < 1e-12);
    }
}
