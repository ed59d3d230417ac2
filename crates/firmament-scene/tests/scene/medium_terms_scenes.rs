//! `[[atmosphere.terms]]` (issue 30): the medium as free-form terms — the shorthand keys' three
//! terms written out, spectra from formulas, profiles and phase functions of every kind, and
//! every rule they break naming the key.

use firmament_core::atmosphere::medium::{Density, Phase};
use firmament_core::atmosphere::{DensityProfile, Medium, presets};
use firmament_core::frame::Sky;
use firmament_scene::Scene;

use crate::support::from_text;

fn medium_of(scene: &Scene) -> Medium {
    match scene.frame_at(None).expect("frame").sky {
        Sky::Atmosphere(sky) => sky.atmosphere.medium,
        _ => panic!("expected an atmosphere sky"),
    }
}

fn message(text: &str) -> String {
    from_text(text).expect_err("should fail").to_string()
}

/// Earth's three terms written out as `[[atmosphere.terms]]`, every number as the preset has it.
pub(crate) fn earth_terms_toml() -> String {
    let earth = presets::earth().medium;
    let [rayleigh, mie, ozone] = &earth.terms[..] else {
        panic!("three terms")
    };
    let list = |s: firmament_core::atmosphere::Spectrum| format!("[{:?}, {:?}, {:?}]", s.x, s.y, s.z);
    let Density::Profile(tent) = ozone.density else {
        panic!("a tent")
    };
    let [rise, fall] = tent.layers;
    format!(
        "[[atmosphere.terms]]\nname = \"molecules\"\nscattering = {}\nprofile = \"exponential\"\nscale_height = 8000.0\n\
         [[atmosphere.terms]]\nname = \"haze\"\nscattering = {}\nabsorption = {}\nprofile = \"exponential\"\n\
         scale_height = 1200.0\nphase = \"cornette_shanks\"\ng = 0.8\n\
         [[atmosphere.terms]]\nname = \"ozone\"\nabsorption = {}\nprofile = \"layers\"\n\
         layers = [{{ width = {:?}, linear_term = {:?}, constant_term = {:?} }}, \
         {{ linear_term = {:?}, constant_term = {:?} }}]\n",
        list(rayleigh.scattering),
        list(mie.scattering),
        list(mie.absorption),
        list(ozone.absorption),
        rise.width,
        rise.linear_term,
        rise.constant_term,
        fall.linear_term,
        fall.constant_term,
    )
}

#[test]
fn the_shorthand_and_its_terms_written_out_are_the_same_medium() {
    let shorthand = medium_of(&from_text("preset = \"earth-noon\"\n").expect("valid"));
    let explicit = medium_of(&from_text(&format!("preset = \"earth-noon\"\n{}", earth_terms_toml())).expect("valid"));
    assert_eq!(shorthand, explicit);
}

#[test]
fn formulas_give_rayleigh_and_angstrom_spectra() {
    // N₂ at sea level: σ = 5.1e-31 m² at 550 nm, N = 2.547e25 m⁻³; λ⁻⁴ to 680 and 440 nm by hand.
    let text = "preset = \"earth-noon\"\n\
                [[atmosphere.terms]]\nscattering = { rayleigh = { cross_section = 5.1e-31, number_density = 2.547e25 } }\n\
                profile = \"exponential\"\nscale_height = 8000.0\n\
                [[atmosphere.terms]]\nscattering = { angstrom = { coefficient = 2e-5, exponent = 1.3, reference_wavelength = 500 } }\n\
                absorption = 1e-6\nprofile = \"constant\"\nphase = \"henyey_greenstein\"\ng = 0.7\n";
    let medium = medium_of(&from_text(text).expect("valid"));
    let at_550 = 5.1e-31 * 2.547e25;
    let want = [
        at_550 * (550.0f64 / 680.0).powi(4),
        at_550,
        at_550 * (550.0f64 / 440.0).powi(4),
    ];
    for (got, want) in medium.terms[0].scattering.to_array().into_iter().zip(want) {
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
    }
    let want = [680.0, 550.0, 440.0].map(|l: f64| 2e-5 * (l / 500.0).powf(-1.3));
    for (got, want) in medium.terms[1].scattering.to_array().into_iter().zip(want) {
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
    }
    assert_eq!(medium.terms[1].absorption.to_array(), [1e-6; 3]);
    assert_eq!(medium.terms[1].phase, Phase::HenyeyGreenstein { g: 0.7 });
    assert_eq!(
        medium.terms[1].density,
        Density::Profile(DensityProfile::single(
            firmament_core::atmosphere::DensityLayer::constant()
        ))
    );
    // The ground keeps the body's albedo.
    assert_eq!(medium.ground_albedo, presets::earth().medium.ground_albedo);
}

#[test]
fn tables_and_two_lobes_reach_the_core() {
    let text = "preset = \"earth-noon\"\n\
                [[atmosphere.terms]]\nscattering = 1e-5\nprofile = \"table\"\n\
                profile_table = [[0.0, 1.0], [5000.0, 0.5], [20000.0, 0.0]]\n\
                phase = \"table\"\nphase_table = [[0.0, 2.0], [90.0, 1.0], [180.0, 2.0]]\n\
                [[atmosphere.terms]]\nscattering = 2e-6\nprofile = \"tent\"\nbottom = 0.0\npeak = 1000.0\ntop = 3000.0\n\
                phase = \"dual_henyey_greenstein\"\ng = 0.8\ng_back = -0.3\nblend = 0.9\n";
    let medium = medium_of(&from_text(text).expect("valid"));
    assert!((medium.terms[0].density.at(2500.0) - 0.75).abs() < 1e-12);
    // Normalised on load: the table integrates to 1 over the sphere.
    let Phase::Table(table) = &medium.terms[0].phase else {
        panic!("a table")
    };
    assert!((Phase::Table(table.clone()).legendre_coefficient(0) - 1.0).abs() < 1e-9);
    assert!((medium.terms[1].density.at(2000.0) - 0.5).abs() < 1e-12);
    assert!((medium.terms[1].phase.legendre_coefficient(1) - (0.9 * 0.8 - 0.1 * 0.3)).abs() < 1e-12);
}

#[test]
fn bad_terms_name_the_key_and_the_rule() {
    let term = "[[atmosphere.terms]]\nscattering = 1e-5\nprofile = \"constant\"\n";
    let cases: Vec<(String, &str, &str)> = vec![
        ("[atmosphere]\nterms = []\n".to_owned(), "atmosphere.terms", "1 to 8"),
        (term.repeat(9), "atmosphere.terms", "1 to 8"),
        (
            "[[atmosphere.terms]]\nscattering = -1e-5\nprofile = \"constant\"\n".to_owned(),
            "atmosphere.terms[0].scattering",
            ">= 0",
        ),
        (
            "[[atmosphere.terms]]\nabsorption = [1e-5, nan, 0.0]\nprofile = \"constant\"\n".to_owned(),
            "atmosphere.terms[0].absorption",
            "finite",
        ),
        (
            "[[atmosphere.terms]]\nscattering = { mie = { radius = 1 } }\nprofile = \"constant\"\n".to_owned(),
            "atmosphere.terms[0].scattering.mie",
            "rayleigh or angstrom",
        ),
        (
            "[[atmosphere.terms]]\nscattering = { rayleigh = { cross_section = 1e-31 } }\nprofile = \"constant\"\n"
                .to_owned(),
            "atmosphere.terms[0].scattering.rayleigh.number_density",
            "missing",
        ),
        (
            format!("{term}[[atmosphere.terms]]\nprofile = \"table\"\nprofile_table = [[0.0, 1.0], [0.0, 0.5]]\n"),
            "atmosphere.terms[1].profile_table",
            "increase strictly",
        ),
        (
            format!("{term}phase = \"table\"\nphase_table = [[0.0, 0.0], [180.0, 0.0]]\n"),
            "atmosphere.terms[0].phase_table",
            "integrate",
        ),
        (
            format!("{term}phase = \"table\"\nphase_table = [[0.0, 1.0], [90.0, 1.0]]\n"),
            "atmosphere.terms[0].phase_table",
            "0 to 180",
        ),
        (
            "[[atmosphere.terms]]\nprofile = \"exponential\"\n".to_owned(),
            "atmosphere.terms[0].scale_height",
            "missing",
        ),
        (
            format!("{term}scale_height = 8000.0\n"),
            "atmosphere.terms[0].scale_height",
            "not read by profile = \"constant\"",
        ),
        (
            format!("{term}phase = \"henyey_greenstein\"\ng = 1.0\n"),
            "atmosphere.terms[0].g",
            "between -1 and 1",
        ),
        (format!("{term}g = 0.5\n"), "atmosphere.terms[0].g", "not read"),
        (
            format!("[atmosphere]\nmie_g = 0.7\n{term}"),
            "atmosphere.terms",
            "remove atmosphere.mie_g",
        ),
    ];
    for (body, key, rule) in cases {
        let text = format!("preset = \"earth-noon\"\n{body}");
        let got = message(&text);
        assert!(got.contains(key) && got.contains(rule), "{body}\n→ {got}");
    }
}
