//! Lunar eclipses at a real date: where the Moon stands in the Earth's shadow, and the shadow's
//! light across it ([`firmament_core::atmosphere::planet_shadow`]), for the night sky's Moon and
//! the moonlight.
//!
//! Positions are geometric (no refraction), in the observer's East-North-Up frame, kilometres:
//! the Moon from Meeus ch. 47 (topocentric), the Earth's centre from the observer's geocentric
//! position (Meeus ch. 11), the shadow's axis away from the Sun (NREL's SPA; the Sun's parallax
//! moves the axis by ~16 km at the Moon).

use std::sync::Mutex;

use firmament_core::astro::Instant;
use firmament_core::astro::moon::{MOON_RADIUS_KM, moon_view, observer_geocentric_km};
use firmament_core::astro::sidereal::{
    Nutation, equatorial_to_horizon_matrix, greenwich_apparent_sidereal_time, local_sidereal_time,
};
use firmament_core::atmosphere::planet_shadow::{PlanetShadow, SHADOW_ENTRIES, ShadowSettings};
use firmament_core::atmosphere::{Atmosphere, Spectrum, Sun};
use firmament_core::sky::night::{MoonShadow, mean_over_face};
use glam::DVec3;

use crate::model::Scene;

/// The Earth's shadow on the Moon at one instant.
pub(crate) struct LunarEclipse {
    /// The shadow across the Moon, linear RGB shares (for the night sky's disc).
    pub(crate) shadow: MoonShadow,
    /// The shadow's profile, per model wavelength.
    profile: PlanetShadow,
    /// Unit East-North-Up direction from the observer to the Moon.
    direction: DVec3,
}

impl LunarEclipse {
    /// The sunlight's share averaged over the Moon's face the observer sees, per model
    /// wavelength (for the moonlight).
    pub(crate) fn mean(&self) -> Spectrum {
        let (axis, offset) = (self.shadow.axis, self.shadow.offset);
        let moon_radius_m = MOON_RADIUS_KM * 1000.0;
        mean_over_face(self.direction, |normal| {
            let across = offset + normal - axis * normal.dot(axis);
            self.profile.at(across.length() * moon_radius_m)
        })
    }
}

/// How finely the cache tells the Moon's distances apart, metres: a profile for 10 km nearer or
/// farther differs by about one part in 10⁵ (the shadow scales with the distance), and the
/// Moon's distance changes by 10 km in some minutes — so the viewer and a time-lapse reuse one
/// profile for as long.
const DISTANCE_BIN_M: f64 = 10_000.0;

/// One cached shadow profile: what it depends on (the atmosphere without its pose, the sun's
/// angular radius and limb darkening as bits, the distance bin) and the profile.
struct CachedProfile {
    atmosphere: Atmosphere,
    sun: (u64, u64),
    bin: i64,
    profile: PlanetShadow,
}

/// How many profiles the cache keeps: the night sky's Moon and the Moon as a body stand in
/// neighbouring bins (the body is placed refracted), and a time-lapse moves on bin by bin.
const CACHED_PROFILES: usize = 4;

/// The last shadow profiles computed, the newest last (72 ms each to build:
/// docs/PERFORMANCE.md).
static PROFILES: Mutex<Vec<CachedProfile>> = Mutex::new(Vec::new());

/// The light across `atmosphere`'s planet's shadow `distance_m` behind it, cast by `sun`, with
/// Earth's refraction and clouds ([`ShadowSettings::default`]); cached, the distance binned.
pub(crate) fn profile(atmosphere: &Atmosphere, sun: &Sun, distance_m: f64) -> PlanetShadow {
    // The profile depends on the planet's size, not on where it stands or how it is turned.
    let mut unposed = atmosphere.clone();
    unposed.planet.center = DVec3::ZERO;
    unposed.planet.orientation = glam::DQuat::IDENTITY;
    let key_sun = (sun.angular_radius.to_bits(), sun.limb_darkening.to_bits());
    let bin = (distance_m / DISTANCE_BIN_M).round() as i64;
    let mut cache = PROFILES.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(i) = cache
        .iter()
        .position(|c| c.bin == bin && c.sun == key_sun && c.atmosphere == unposed)
    {
        let hit = cache.remove(i);
        let profile = hit.profile.clone();
        cache.push(hit);
        return profile;
    }
    let profile = PlanetShadow::new(&unposed, sun, bin as f64 * DISTANCE_BIN_M, &ShadowSettings::default());
    if cache.len() == CACHED_PROFILES {
        cache.remove(0);
    }
    cache.push(CachedProfile {
        atmosphere: unposed,
        sun: key_sun,
        bin,
        profile: profile.clone(),
    });
    profile
}

/// The Earth's shadow on the Moon at `instant` seen from `[planet]`'s place at `height_m`, with the
/// Earth's air `atmosphere` and its sun `sun` (size and limb darkening), or `None` when the Moon
/// is clear of the penumbra. `sun_direction` is the Sun's geometric East-North-Up direction.
pub(crate) fn lunar_eclipse(
    scene: &Scene,
    instant: &Instant,
    height_m: f64,
    sun_direction: DVec3,
    atmosphere: &Atmosphere,
    sun: &Sun,
) -> Option<LunarEclipse> {
    let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
    let nutation = Nutation::low_precision(instant);
    let lst = local_sidereal_time(greenwich_apparent_sidereal_time(instant, &nutation), lon.to_radians());
    let to_enu = equatorial_to_horizon_matrix(lst, lat.to_radians());
    let earth = -(to_enu * observer_geocentric_km(lat.to_radians(), height_m, lst));
    let view = moon_view(instant, lat, lon, height_m);
    let moon = view.direction * view.equatorial.distance_km;
    let axis = -sun_direction.normalize();
    let from_earth = moon - earth;
    let distance_km = from_earth.dot(axis);
    if distance_km <= 0.0 {
        return None;
    }
    let across = from_earth - axis * distance_km;
    let distance_m = distance_km * 1000.0;
    // Cheap test first: the penumbra's reach is the planet's radius plus the sun's image.
    let reach_km = (atmosphere.planet.radii.max_element() + atmosphere.planet.atmosphere_height) / 1000.0
        + distance_km * sun.angular_radius;
    if across.length() > reach_km + 1.05 * MOON_RADIUS_KM {
        return None;
    }
    let profile = profile(atmosphere, sun, distance_m);
    let moon_radius_m = MOON_RADIUS_KM * 1000.0;
    let conversion = atmosphere.spectral_conversion();
    let white = conversion.linear_srgb(sun.irradiance);
    let light = std::array::from_fn::<_, SHADOW_ENTRIES, _>(|k| {
        let c = conversion.linear_srgb(sun.irradiance * profile.light[k]);
        let share = |a: f64, b: f64| if b > 0.0 { (a / b).max(0.0) } else { 0.0 };
        DVec3::new(share(c.r, white.r), share(c.g, white.g), share(c.b, white.b))
    });
    let shadow = MoonShadow {
        axis,
        offset: across / MOON_RADIUS_KM,
        step: profile.step_m / moon_radius_m,
        light,
    };
    Some(LunarEclipse {
        shadow,
        profile,
        direction: view.direction,
    })
}
