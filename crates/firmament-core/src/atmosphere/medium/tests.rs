use super::*;
use crate::atmosphere::presets;

#[test]
fn earths_constituents_round_trip_through_terms() {
    let medium = presets::earth().medium;
    assert_eq!(medium.terms.len(), 3);
    let constituents = medium.constituents().expect("Earth's air is the three constituents");
    assert_eq!(Medium::from_constituents(&constituents, medium.ground_albedo), medium);
    // The aerosols absorb what they extinguish beyond what they scatter.
    assert!((medium.terms[1].absorption.y - 0.444e-6).abs() < 1e-18);
}

#[test]
fn coefficients_sum_the_terms() {
    let medium = presets::earth().medium;
    let h = 3_000.0;
    let local = medium.at(h);
    let mut extinction = Spectrum::ZERO;
    for (term, scattering) in medium.terms.iter().zip(local.scattering) {
        assert_eq!(scattering, term.scattering * term.density.at(h));
        extinction += (term.scattering + term.absorption) * term.density.at(h);
    }
    assert!((local.extinction - extinction).abs().max_element() < 1e-20);
    let nu = 0.3;
    let want = local.scattering[0] * rayleigh_phase(nu) + local.scattering[1] * cornette_shanks(0.8, nu);
    assert!((medium.scattering_phase(&local, nu) - want).abs().max_element() < 1e-20);
}

#[test]
fn free_form_media_are_not_constituents() {
    let mut medium = presets::earth().medium;
    medium.terms.push(medium.terms[0].clone());
    assert!(medium.constituents().is_none());
    medium.terms.truncate(3);
    medium.terms[1].phase = Phase::Rayleigh;
    assert!(medium.constituents().is_none());
}

#[test]
fn bad_terms_name_the_key_and_the_rule() {
    let earth = presets::earth().medium;
    let mut cases: Vec<(Medium, &str, &str)> = Vec::new();
    let mut empty = earth.clone();
    empty.terms.clear();
    cases.push((empty, "atmosphere.terms", "1 to 8"));
    let mut many = earth.clone();
    many.terms = vec![earth.terms[0].clone(); MAX_TERMS + 1];
    cases.push((many, "atmosphere.terms", "1 to 8"));
    let mut negative = earth.clone();
    negative.terms[2].absorption.y = -1e-6;
    cases.push((negative, "atmosphere.terms[2].absorption", ">= 0"));
    let mut nan = earth.clone();
    nan.terms[0].scattering.x = f64::NAN;
    cases.push((nan, "atmosphere.terms[0].scattering", "finite"));
    let mut g = earth.clone();
    g.terms[1].phase = Phase::HenyeyGreenstein { g: 1.0 };
    cases.push((g, "atmosphere.terms[1].phase.g", "between -1 and 1"));
    for (medium, key, rule) in cases {
        let message = medium.validate().unwrap_err().to_string();
        assert!(message.contains(key) && message.contains(rule), "{message}");
    }
    earth.validate().unwrap();
}

/// An exponential scatterer's vertical optical depth is `σ·H·(1 − e^(−top/H))` in closed form.
#[test]
fn the_vertical_scattering_depth_of_an_exponential_term_is_its_closed_form() {
    let atmosphere = crate::atmosphere::presets::earth();
    let mut medium = atmosphere.medium.clone();
    medium.terms.truncate(1);
    let top = atmosphere.planet.atmosphere_height;
    let scale_height = 8_000.0;
    let want = medium.terms[0].scattering * scale_height * (1.0 - (-top / scale_height).exp());
    let got = medium.vertical_scattering_depth(0.0, top);
    assert!(((got - want) / want).abs().max_element() < 1e-5, "{got} vs {want}");
    // Above h the depth is σ·H·(e^(−h/H) − e^(−top/H)): at 0.1 of the 440 nm column, h = 18.4 km.
    let blue = medium.terms[0].scattering.z * scale_height;
    let target = 0.1 * blue * (1.0 - (-top / scale_height).exp());
    let want = -scale_height * (target / blue + (-top / scale_height).exp()).ln();
    let got = medium.altitude_of_scattering_depth(top, target);
    assert!((got - want).abs() <= top / 1024.0, "{got} vs {want}");
}
