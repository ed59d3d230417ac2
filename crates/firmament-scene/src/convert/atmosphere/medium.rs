//! `[atmosphere]`: the body's medium with the scene's overrides.

use firmament_core::atmosphere::medium::Constituents;
use firmament_core::atmosphere::{DensityLayer, DensityProfile, Medium, Phase, Spectrum, Wavelengths};

use super::terms;

use crate::checks::{check, non_negative, positive};
use crate::error::SceneError;
use crate::model::{AtmosphereSection, Body, MiePhaseName};
use crate::spectrum::SceneSpectrum;

/// The medium and the model wavelengths, every value checked: the body's constituents with the
/// shorthand keys' changes, the body's own free-form terms (Venus, Titan: no shorthand keys), or
/// `[[atmosphere.terms]]`.
pub(super) fn medium(section: &AtmosphereSection, body: Body) -> Result<(Medium, Wavelengths), SceneError> {
    let base = body.atmosphere();
    let a = section;
    let wavelengths = match a.wavelengths {
        Some(w) => {
            let [x, y, z] = w;
            check(
                w.iter().all(|v| v.is_finite() && (360.0..=830.0).contains(v)) && x != y && y != z && x != z,
                "atmosphere.wavelengths",
                SceneSpectrum(w),
                "needs three different wavelengths within [360, 830] nm",
            )?;
            Wavelengths(w)
        }
        None => base.wavelengths,
    };
    let mut ground_albedo = base.medium.ground_albedo;
    if let Some(albedo) = a.ground_albedo {
        check(
            albedo.0.iter().all(|v| (0.0..=1.0).contains(v)),
            "atmosphere.ground_albedo",
            albedo,
            "every value must lie in [0, 1]",
        )?;
        ground_albedo = albedo.spectrum();
    }
    let terms = match &a.terms {
        Some(entries) => {
            if let Some(key) = shorthand_key(a) {
                return Err(SceneError::invalid(
                    "atmosphere.terms",
                    format!("{} terms", entries.len()),
                    format!("replaces the body's medium and its shorthand keys: remove atmosphere.{key}"),
                ));
            }
            terms::terms(entries, wavelengths)?
        }
        // A body whose medium is free-form terms (Venus, Titan) keeps them when no shorthand key
        // is set.
        None if base.medium.constituents().is_none() && shorthand_key(a).is_none() => base.medium.terms,
        None => constituents(a, body, &base.medium)?.terms(),
    };
    Ok((Medium { terms, ground_albedo }, wavelengths))
}

/// The first shorthand key of the medium `a` sets.
fn shorthand_key(a: &AtmosphereSection) -> Option<&'static str> {
    let spectra = [
        ("rayleigh_scattering", a.rayleigh_scattering.is_some()),
        ("rayleigh_scale_height", a.rayleigh_scale_height.is_some()),
        ("mie_scattering", a.mie_scattering.is_some()),
        ("mie_extinction", a.mie_extinction.is_some()),
        ("mie_scale_height", a.mie_scale_height.is_some()),
        ("mie_g", a.mie_g.is_some()),
        ("mie_phase", a.mie_phase.is_some()),
        ("ozone_absorption", a.ozone_absorption.is_some()),
        ("ozone_bottom", a.ozone_bottom.is_some()),
        ("ozone_peak", a.ozone_peak.is_some()),
        ("ozone_top", a.ozone_top.is_some()),
    ];
    spectra.iter().find(|(_, set)| *set).map(|(key, _)| *key)
}

/// The body's molecules, aerosols and absorbing gas with the shorthand keys' changes.
fn constituents(a: &AtmosphereSection, body: Body, base: &Medium) -> Result<Constituents, SceneError> {
    let mut medium = base.constituents().ok_or_else(|| {
        SceneError::invalid(
            "planet.body",
            body.name(),
            format!(
                "has no molecules-aerosols-gas medium for the shorthand keys (atmosphere.{}): its air is \
                 free-form terms; give the whole medium as [[atmosphere.terms]] instead",
                shorthand_key(a).unwrap_or("rayleigh_scattering")
            ),
        )
    })?;
    if let Some(s) = coefficient("atmosphere.rayleigh_scattering", a.rayleigh_scattering)? {
        medium.rayleigh.scattering = s;
    }
    if let Some(h) = scale_height("atmosphere.rayleigh_scale_height", a.rayleigh_scale_height)? {
        medium.rayleigh.density = h;
    }
    if let Some(s) = coefficient("atmosphere.mie_scattering", a.mie_scattering)? {
        medium.mie.scattering = s;
    }
    if let Some(s) = coefficient("atmosphere.mie_extinction", a.mie_extinction)? {
        medium.mie.extinction = s;
    }
    if (medium.mie.extinction - medium.mie.scattering).min_element() < 0.0 {
        let (scattering, extinction) = (medium.mie.scattering.to_array(), medium.mie.extinction.to_array());
        return Err(if a.mie_extinction.is_some() {
            SceneError::invalid(
                "atmosphere.mie_extinction",
                SceneSpectrum(extinction),
                format!(
                    "must be >= atmosphere.mie_scattering ({}) at every wavelength (extinction is \
                     scattering plus absorption)",
                    SceneSpectrum(scattering)
                ),
            )
        } else {
            SceneError::invalid(
                "atmosphere.mie_scattering",
                SceneSpectrum(scattering),
                format!(
                    "must be <= the mie extinction ({} m⁻¹, {}'s; set atmosphere.mie_extinction too) \
                     at every wavelength",
                    SceneSpectrum(extinction),
                    body.name()
                ),
            )
        });
    }
    if let Some(h) = scale_height("atmosphere.mie_scale_height", a.mie_scale_height)? {
        medium.mie.density = h;
    }
    let g = a.mie_g.unwrap_or(medium.mie.phase.g());
    check(
        g > -1.0 && g < 1.0,
        "atmosphere.mie_g",
        g,
        "must lie strictly between -1 and 1",
    )?;
    let kind = a.mie_phase.unwrap_or(match medium.mie.phase {
        Phase::HenyeyGreenstein { .. } => MiePhaseName::HenyeyGreenstein,
        _ => MiePhaseName::CornetteShanks,
    });
    medium.mie.phase = match kind {
        MiePhaseName::CornetteShanks => Phase::CornetteShanks { g },
        MiePhaseName::HenyeyGreenstein => Phase::HenyeyGreenstein { g },
    };

    if let Some(s) = coefficient("atmosphere.ozone_absorption", a.ozone_absorption)? {
        medium.absorber.absorption = s;
    }
    if let Some(tent) = ozone_tent(a, body, &medium.absorber.density)? {
        medium.absorber.density = tent;
    }
    Ok(medium)
}

/// A coefficient in m⁻¹, if given: every value finite and >= 0.
pub(super) fn coefficient(key: &str, value: Option<SceneSpectrum>) -> Result<Option<Spectrum>, SceneError> {
    let Some(value) = value else { return Ok(None) };
    check(
        value.is_finite_non_negative(),
        key,
        value,
        "every value must be a finite number >= 0 (m⁻¹)",
    )?;
    Ok(Some(value.spectrum()))
}

/// An exponential profile `e^(−h/H)` for a scale height `H` in metres, if given.
pub(super) fn scale_height(key: &str, value: Option<f64>) -> Result<Option<DensityProfile>, SceneError> {
    let Some(h) = value else { return Ok(None) };
    positive(key, h, " metres")?;
    Ok(Some(DensityProfile::single(DensityLayer::exponential(h))))
}

/// The ozone tent with the scene's corners, if it sets any: the ones it leaves out come from the
/// body's tent (a body without one needs all three).
fn ozone_tent(a: &AtmosphereSection, body: Body, base: &DensityProfile) -> Result<Option<DensityProfile>, SceneError> {
    let given = [a.ozone_bottom, a.ozone_peak, a.ozone_top];
    if given.iter().all(Option::is_none) {
        return Ok(None);
    }
    let keys = [
        "atmosphere.ozone_bottom",
        "atmosphere.ozone_peak",
        "atmosphere.ozone_top",
    ];
    let body_tent = tent_corners(base);
    let mut corners = [0.0; 3];
    for (i, slot) in corners.iter_mut().enumerate() {
        *slot = match (given[i], body_tent) {
            (Some(v), _) => {
                non_negative(keys[i], v)?;
                v
            }
            (None, Some(tent)) => tent[i],
            (None, None) => {
                return Err(SceneError::WrongType {
                    key: keys[i].to_owned(),
                    message: format!(
                        "missing: {} has no ozone layer to take it from; give ozone_bottom, ozone_peak and \
                         ozone_top together (metres)",
                        body.name()
                    ),
                });
            }
        };
    }
    let [bottom, peak, top] = corners;
    check(
        peak > bottom,
        keys[1],
        peak,
        &format!("must be above atmosphere.ozone_bottom ({bottom} m)"),
    )?;
    check(
        top > peak,
        keys[2],
        top,
        &format!("must be above atmosphere.ozone_peak ({peak} m)"),
    )?;
    Ok(Some(DensityProfile::tent(bottom, peak, top)))
}

/// Bottom, peak and top of a profile made by [`DensityProfile::tent`], or `None` for any other.
fn tent_corners(profile: &DensityProfile) -> Option<[f64; 3]> {
    let [rise, fall] = profile.layers;
    if rise.linear_term > 0.0 && fall.linear_term < 0.0 {
        let bottom = -rise.constant_term / rise.linear_term;
        let top = -fall.constant_term / fall.linear_term;
        Some([bottom, rise.width, top])
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tent_corners_invert_the_core_tent() {
        let [bottom, peak, top] = tent_corners(&DensityProfile::tent(10_000.0, 25_000.0, 40_000.0)).expect("a tent");
        assert!((bottom - 10_000.0).abs() < 1e-9 && peak == 25_000.0 && (top - 40_000.0).abs() < 1e-9);
        assert_eq!(tent_corners(&DensityProfile::single(DensityLayer::EMPTY)), None);
    }
}
