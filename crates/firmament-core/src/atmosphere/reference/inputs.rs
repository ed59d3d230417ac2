//! What the reference integrates — an atmosphere, its suns, what stands in their light and how
//! hard to work ([`Reference`], [`ReferenceSettings`]) — and the part of a ray inside the air
//! ([`segment`]): what the integrator (`mod.rs`) and the path tracer (`path_tracer.rs`) both need.
//! The integrator's methods are in `mod.rs`.

use crate::atmosphere::clouds::CloudLayer;
use crate::atmosphere::rings::Rings;
use crate::atmosphere::spectrum::Spectrum;
use crate::atmosphere::surface::Surface;
use crate::atmosphere::{Atmosphere, Eclipser, Planet, Sun};
use crate::geometry::Ray;
use crate::occluder::Occluder;

/// How hard the reference works.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceSettings {
    /// Simpson panels along a view ray for single scattering (even).
    pub view_steps: usize,
    /// Monte Carlo paths per estimate of multiple scattering.
    pub paths: usize,
    /// Points per path segment at which the path tracer gathers once-scattered sunlight along
    /// the whole segment (0: only at the path's next collision, the default). Costs about this
    /// many sun transmittances per segment; worth it where little air is sunlit (twilight).
    pub line_samples: usize,
    /// Seed of the path tracer's random numbers.
    pub seed: u64,
    /// Radiance arriving from space in every direction, W·m⁻²·sr⁻¹·nm⁻¹ (zero for a real sky; a
    /// uniform value turns the path tracer into a white-furnace test).
    pub background: Spectrum,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        Self {
            view_steps: 1024,
            paths: 4096,
            line_samples: 0,
            seed: 0x5EED_F1A7,
            background: Spectrum::ZERO,
        }
    }
}

/// The visible part of a ray through the atmosphere, planet frame, metres along the ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Segment {
    /// Where the ray enters the atmosphere (0 when it starts inside).
    pub start: f64,
    /// Where it leaves it or meets the ground.
    pub end: f64,
    /// True when the segment ends on the ground.
    pub ends_on_ground: bool,
}

impl Segment {
    /// The part of the segment in front of an opaque surface at `limit` along the ray (`None`
    /// when the surface hides all of it), and whether the surface cut it short.
    pub(crate) fn before(self, limit: f64) -> (Option<Self>, bool) {
        if limit >= self.end {
            (Some(self), false)
        } else if limit <= self.start {
            (None, true)
        } else {
            let cut = Self {
                end: limit,
                ends_on_ground: false,
                ..self
            };
            (Some(cut), true)
        }
    }
}

/// The part of a planet-frame ray inside the atmosphere and above the ground, if any.
pub(crate) fn segment(planet: &Planet, ray: &Ray) -> Option<Segment> {
    let top = planet.atmosphere_top().intersect(ray)?;
    if top.far <= 0.0 {
        return None;
    }
    let start = top.near.max(0.0);
    let mut end = top.far;
    let mut ends_on_ground = false;
    if let Some(ground) = planet.surface().intersect(ray)
        && ground.far > 0.0
        && ground.near < end
    {
        end = ground.near.max(start);
        ends_on_ground = true;
    }
    Some(Segment {
        start,
        end,
        ends_on_ground,
    })
}

/// The reference integrator for one atmosphere lit by some suns, with optional opaque occluders
/// ([`Reference::with_occluders`]) and cloud layers ([`Reference::with_clouds`]).
#[derive(Debug, Clone)]
pub struct Reference {
    pub(super) atmosphere: Atmosphere,
    /// Suns in the planet frame (directions converted).
    pub(super) suns: Vec<Sun>,
    pub(super) settings: ReferenceSettings,
    /// Occluders in the planet frame, converted once: 6.4e6 m from the centre f64 still resolves
    /// about a nanometre, far below any shadow the tests look at.
    pub(super) occluders: Vec<Occluder>,
    /// Cloud layers, planet frame ([`Reference::with_clouds`]).
    pub(super) clouds: Vec<CloudLayer>,
    /// Bodies that eclipse the suns, planet frame ([`Reference::with_eclipsers`]).
    pub(super) eclipsers: Vec<Eclipser>,
    /// The planet's rings, whose shadow dims the suns ([`Reference::with_rings`]).
    pub(super) rings: Option<Rings>,
    /// The ground's albedo and water over the globe ([`Reference::with_surface`]); without one
    /// the medium's `ground_albedo` everywhere, no water.
    pub(super) surface: Option<Surface>,
}
