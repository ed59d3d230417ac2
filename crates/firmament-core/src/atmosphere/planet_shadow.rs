//! The light inside a planet's shadow, far behind it: what a moon receives in a lunar eclipse —
//! sunlight bent into the umbra by the planet's air and reddened on its way through it.
//!
//! # Model (Link's, "Théorie photométrique des éclipses de Lune", 1956, in the form of
//! García Muñoz & Pallé, "Lunar eclipse theory revisited", JQSRT 112, 2011)
//! A ray of sunlight passing the planet at impact parameter `b = R + h` (tangent altitude `h`,
//! `R` the planet's mean radius) crosses the air along a straight chord, keeping the
//! transmittance `T(h)` the f64 reference gives along it, and is bent towards the shadow's axis by
//! the refraction of a grazing ray through an exponential air, `δ(h) = (n₀ − 1)·(ρ(h)/ρ(0))·
//! √(2π(R + h)/H)` (`n₀ − 1` the refractivity at the surface, `H` the air's scale height where the
//! ray passes; 70′ at the surface for Earth: twice the horizontal refraction). At distance `D`
//! behind the planet it lands `r(b) = b − D·δ(h)` from the axis — on the far side when negative.
//! Rays below `cloud_top_m` pass only where the sky is clear, `clear_fraction` of the limb (Earth's
//! clouds cover about two thirds of it); above the air they go straight on.
//!
//! A point sun gives, by conservation of the light in each thin ring of impact parameters, the
//! irradiance `E₁(q) = Σ T(h)·b / (q·|dr/db|)` over the rings that land at `±q`, plus 1 where
//! straight sunlight passes (`q` beyond the top of the air); in units of the sunlight.
//! The real sun is a limb-darkened disc of angular radius α: each of its points shifts the pattern
//! by `D` times its offset, so `E(ρ) = ∫ w(s)·E₁(|ρ − D·s|) d²s`. Integrated over the landing
//! point `q` instead of `s` (`d²s = d²q / D²`), the factor `q` of the area cancels the `1/q` of the
//! focus on the axis: radially by the midpoint rule, over each circle's arc inside the sun's
//! image by Gauss–Legendre.
//!
//! With no air (no refraction, the solid planet opaque) the same integral is the eclipse of the
//! sun's disc by the planet's ([`crate::atmosphere::eclipse::hidden_fraction`]), which the tests
//! hold it to.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::reference::{Reference, ReferenceSettings};
use crate::atmosphere::{Atmosphere, Planet, Spectrum, Sun};

/// Entries of a shadow profile ([`PlanetShadow::light`]).
pub const SHADOW_ENTRIES: usize = 64;

/// Earth's air's refractivity `n − 1` at the surface in visible light (dry air at 15 °C,
/// 1013.25 hPa, 550 nm: Ciddor 1996), dimensionless.
pub const EARTH_REFRACTIVITY: f64 = 2.778e-4;

/// How the shadow is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowSettings {
    /// The air's refractivity `n − 1` at the surface, dimensionless (0: no refraction).
    pub refractivity: f64,
    /// The cloud tops, metres above the surface: rays passing lower keep only `clear_fraction` of
    /// their light.
    pub cloud_top_m: f64,
    /// The share of the limb where rays below the cloud tops pass (the clear sky), in [0, 1].
    pub clear_fraction: f64,
    /// Tangent altitudes sampled through the air.
    pub altitudes: usize,
    /// Midpoint steps across the sun's image for each entry.
    pub radial_steps: usize,
}

impl Default for ShadowSettings {
    /// Earth's: its refractivity; cloud tops at 10 km (this model's choice: a typical height of
    /// deep clouds' tops) over two thirds of the limb (a clear fraction of 0.35, after ISCCP's
    /// global cloud amount of about two thirds, Rossow & Schiffer 1999); 600 altitudes, 400 steps.
    fn default() -> Self {
        Self {
            refractivity: EARTH_REFRACTIVITY,
            cloud_top_m: 10_000.0,
            clear_fraction: 0.35,
            altitudes: 600,
            radial_steps: 400,
        }
    }
}

/// The light across a planet's shadow at one distance behind it, relative to the sunlight there.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanetShadow {
    /// Distance from the axis between entries, metres (entry `k` is `k·step_m` out).
    pub step_m: f64,
    /// The sunlight's share at each entry, per model wavelength: 1 in full sunlight.
    pub light: Vec<Spectrum>,
}

/// Rays through the air: each tangent altitude's impact parameter, landing distance, slope of the
/// landing distance and transmittance.
struct Rays {
    impact: Vec<f64>,
    landing: Vec<f64>,
    slope: Vec<f64>,
    transmittance: Vec<Spectrum>,
    /// The top of the air, metres from the centre: straight sunlight beyond.
    top: f64,
}

impl Rays {
    fn new(atmosphere: &Atmosphere, distance_m: f64, settings: &ShadowSettings) -> Self {
        let planet = atmosphere.planet;
        let radius = planet.mean_radius();
        let height = planet.atmosphere_height;
        let sphere = Atmosphere {
            planet: Planet::sphere(radius, height),
            ..atmosphere.clone()
        };
        let reference = Reference::new(sphere, &[], ReferenceSettings::default());
        let density = |h: f64| atmosphere.medium.molecular_density(h);
        let n = settings.altitudes.max(2);
        // Through clear sky down to the ground where clouds let any through, else from their tops.
        let bottom = if settings.clear_fraction > 0.0 {
            0.0
        } else {
            settings.cloud_top_m.clamp(0.0, height)
        };
        let mut rays = Self {
            impact: Vec::with_capacity(n),
            landing: Vec::with_capacity(n),
            slope: Vec::with_capacity(n),
            transmittance: Vec::with_capacity(n),
            top: radius + height,
        };
        for i in 0..n {
            let h = bottom + (height - bottom) * i as f64 / (n - 1) as f64;
            let b = radius + h;
            // The scale height where the ray passes, from the density's own slope.
            let dh = 10.0;
            let slope = (density(h + dh).max(1e-300).ln() - density((h - dh).max(0.0)).max(1e-300).ln())
                / (h + dh - (h - dh).max(0.0));
            let scale_height = if slope < 0.0 { -1.0 / slope } else { f64::INFINITY };
            let bend = settings.refractivity * density(h) * (2.0 * PI * b / scale_height).sqrt();
            let tangent = DVec3::new(b, 0.0, 0.0);
            let clear = if h < settings.cloud_top_m {
                settings.clear_fraction.clamp(0.0, 1.0)
            } else {
                1.0
            };
            let through = reference.transmittance_to_space(tangent, DVec3::Y)
                * reference.transmittance_to_space(tangent, -DVec3::Y)
                * clear;
            rays.impact.push(b);
            rays.landing.push(b - distance_m * bend);
            // dr/db = 1 + D·δ/H for δ ∝ e^(−h/H).
            rays.slope.push(1.0 + distance_m * bend / scale_height);
            rays.transmittance.push(through);
        }
        rays
    }

    /// The irradiance `q` metres from the axis behind a point sun, in units of the sunlight.
    fn point_sun(&self, q: f64) -> Spectrum {
        let mut light = if q >= self.top { Spectrum::ONE } else { Spectrum::ZERO };
        for target in [q, -q] {
            light += self.landing_at(target, q);
        }
        light
    }

    /// The light of the rays landing at signed distance `target` (|target| = q), by conservation
    /// in the ring of impact parameters that lands there: `T·b / (q·dr/db)`.
    fn landing_at(&self, target: f64, q: f64) -> Spectrum {
        let last = self.landing.len() - 1;
        if q <= 0.0 || target < self.landing[0] || target >= self.landing[last] {
            return Spectrum::ZERO;
        }
        let i = self.landing.partition_point(|&r| r <= target).clamp(1, last) - 1;
        let t = (target - self.landing[i]) / (self.landing[i + 1] - self.landing[i]);
        let impact = self.impact[i] + t * (self.impact[i + 1] - self.impact[i]);
        let slope = self.slope[i] + t * (self.slope[i + 1] - self.slope[i]);
        let transmittance = self.transmittance[i].lerp(self.transmittance[i + 1], t);
        transmittance * (impact / (q * slope))
    }
}

impl PlanetShadow {
    /// The light across `atmosphere`'s planet's shadow `distance_m` metres behind its centre, cast
    /// by `sun` (its angular radius and limb darkening seen from the planet), out to where the
    /// penumbra ends.
    pub fn new(atmosphere: &Atmosphere, sun: &Sun, distance_m: f64, settings: &ShadowSettings) -> Self {
        let rays = Rays::new(atmosphere, distance_m, settings);
        let image = distance_m * sun.angular_radius;
        let reach = rays.top + image;
        let step_m = reach / (SHADOW_ENTRIES - 1) as f64;
        let light = (0..SHADOW_ENTRIES)
            .map(|k| {
                convolve(
                    &rays,
                    k as f64 * step_m,
                    image,
                    sun.limb_darkening,
                    settings.radial_steps,
                )
            })
            .collect();
        Self { step_m, light }
    }

    /// The sunlight's share `rho_m` metres from the axis (linear between entries; 1 beyond).
    pub fn at(&self, rho_m: f64) -> Spectrum {
        let x = (rho_m / self.step_m).max(0.0);
        let i = x.floor() as usize;
        if i + 1 >= self.light.len() {
            return Spectrum::ONE;
        }
        self.light[i].lerp(self.light[i + 1], x - i as f64)
    }

    /// How far the shadow reaches from its axis, metres: the last entry's distance.
    pub fn reach_m(&self) -> f64 {
        self.step_m * (self.light.len() - 1) as f64
    }
}

/// `E(ρ) = (1/D²)∫∫ E₁(q)·w(|ρ − q|/D)·q dφ dq` over the sun's image (radius `image` = D·α)
/// around ρ: midpoint steps in q, 16-point Gauss–Legendre over each circle's arc inside it.
fn convolve(rays: &Rays, rho: f64, image: f64, u: f64, steps: usize) -> Spectrum {
    const NODES: [f64; 8] = [
        0.095_012_509_837_637_44,
        0.281_603_550_779_258_9,
        0.458_016_777_657_227_4,
        0.617_876_244_402_643_7,
        0.755_404_408_355_003,
        0.865_631_202_387_831_7,
        0.944_575_023_073_232_6,
        0.989_400_934_991_649_9,
    ];
    const WEIGHTS: [f64; 8] = [
        0.189_450_610_455_068_5,
        0.182_603_415_044_923_6,
        0.169_156_519_395_002_5,
        0.149_595_988_816_576_7,
        0.124_628_971_255_533_9,
        0.095_158_511_682_492_8,
        0.062_253_523_938_647_9,
        0.027_152_459_411_754_1,
    ];
    // The limb-darkened disc's weight per unit image area: I(s)/∫I dA.
    let norm = PI * image * image * (1.0 - u / 3.0);
    let weight = |s: f64| {
        let x = (s / image).min(1.0);
        (1.0 - u * (1.0 - (1.0 - x * x).sqrt())) / norm
    };
    let (q0, q1) = ((rho - image).max(0.0), rho + image);
    let dq = (q1 - q0) / steps as f64;
    let mut sum = Spectrum::ZERO;
    for i in 0..steps {
        let q = q0 + (i as f64 + 0.5) * dq;
        // The arc |ρ − q·e^{iφ}| < image: |φ| < φ₀.
        let phi0 = if rho <= 0.0 {
            PI
        } else {
            let c = (rho * rho + q * q - image * image) / (2.0 * rho * q);
            if c >= 1.0 {
                continue;
            }
            c.max(-1.0).acos()
        };
        let mut arc = 0.0;
        for (x, w) in NODES.iter().zip(WEIGHTS) {
            for phi in [phi0 * 0.5 * (1.0 + x), phi0 * 0.5 * (1.0 - x)] {
                let s = (rho * rho + q * q - 2.0 * rho * q * phi.cos()).max(0.0).sqrt();
                arc += w * 0.5 * phi0 * weight(s);
            }
        }
        // Both halves of the arc.
        sum += rays.point_sun(q) * (2.0 * arc * q * dq);
    }
    sum
}

#[cfg(test)]
mod tests;
