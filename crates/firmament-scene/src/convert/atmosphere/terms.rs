//! `[[atmosphere.terms]]` → the core's medium terms, every key checked.

use firmament_core::CoreError;
use firmament_core::atmosphere::clouds::DualHenyeyGreenstein;
use firmament_core::atmosphere::medium::{
    Density, DensityLayer, DensityProfile, DensityTable, MAX_TERMS, MediumTerm, Phase, PhaseTable,
};
use firmament_core::atmosphere::{Spectrum, Wavelengths};

use crate::checks::{check, non_negative, positive};
use crate::error::SceneError;
use crate::model::{LayerEntry, PhaseName, ProfileName, TermEntry};

/// The terms of `entries`, their spectra at `wavelengths`.
pub(super) fn terms(entries: &[TermEntry], wavelengths: Wavelengths) -> Result<Vec<MediumTerm>, SceneError> {
    check(
        (1..=MAX_TERMS).contains(&entries.len()),
        "atmosphere.terms",
        format!("{} terms", entries.len()),
        &format!("needs 1 to {MAX_TERMS} terms"),
    )?;
    entries
        .iter()
        .enumerate()
        .map(|(i, entry)| term(entry, &format!("atmosphere.terms[{i}]"), wavelengths))
        .collect()
}

fn term(entry: &TermEntry, key: &str, wavelengths: Wavelengths) -> Result<MediumTerm, SceneError> {
    let spectrum = |name: &str, value: &Option<toml::Value>| match value {
        Some(v) => spectrum(&format!("{key}.{name}"), v, wavelengths),
        None => Ok(Spectrum::ZERO),
    };
    Ok(MediumTerm {
        scattering: spectrum("scattering", &entry.scattering)?,
        absorption: spectrum("absorption", &entry.absorption)?,
        density: density(entry, key)?,
        phase: phase(entry, key)?,
    })
}

/// A spectrum in m⁻¹: a number, three numbers, or a formula (see [`TermEntry`]).
fn spectrum(key: &str, value: &toml::Value, wavelengths: Wavelengths) -> Result<Spectrum, SceneError> {
    const RULE: &str = "must be a number, [a, b, c] (m⁻¹ at the model wavelengths), { rayleigh = { cross_section, \
                        number_density } } or { angstrom = { coefficient, exponent } }";
    let values = match value {
        toml::Value::Array(items) if items.len() == 3 => {
            let numbers: Option<Vec<f64>> = items.iter().map(number).collect();
            let numbers = numbers.ok_or_else(|| SceneError::invalid(key, value, RULE))?;
            Spectrum::new(numbers[0], numbers[1], numbers[2])
        }
        toml::Value::Table(table) if table.len() == 1 => {
            let (kind, parameters) = table.iter().next().expect("a table of one entry");
            formula(&format!("{key}.{kind}"), kind, parameters, wavelengths)?
        }
        other => Spectrum::splat(number(other).ok_or_else(|| SceneError::invalid(key, value, RULE))?),
    };
    check(
        values.is_finite() && values.min_element() >= 0.0,
        key,
        format!("{:?}", values.to_array()),
        "every value must be a finite number >= 0 (m⁻¹)",
    )?;
    Ok(values)
}

/// A spectrum from a formula: Rayleigh's λ⁻⁴ or Ångström's power law, at the model wavelengths.
fn formula(key: &str, kind: &str, parameters: &toml::Value, wavelengths: Wavelengths) -> Result<Spectrum, SceneError> {
    let table = parameters
        .as_table()
        .ok_or_else(|| SceneError::invalid(key, parameters, "must be a table of the formula's parameters"))?;
    let get = |name: &str| -> Result<Option<f64>, SceneError> {
        match table.get(name) {
            None => Ok(None),
            Some(v) => number(v)
                .map(Some)
                .ok_or_else(|| SceneError::invalid(format!("{key}.{name}"), v, "must be a number")),
        }
    };
    let known: &[&str] = match kind {
        "rayleigh" => &["cross_section", "number_density", "reference_wavelength"],
        "angstrom" => &["coefficient", "exponent", "reference_wavelength"],
        _ => {
            return Err(SceneError::invalid(
                key,
                parameters,
                "unknown formula: use rayleigh or angstrom",
            ));
        }
    };
    if let Some(stray) = table.keys().find(|k| !known.contains(&k.as_str())) {
        return Err(SceneError::invalid(
            format!("{key}.{stray}"),
            &table[stray],
            format!("unknown key; {kind} takes {}", known.join(", ")),
        ));
    }
    let required = |name: &str| {
        get(name)?.ok_or_else(|| SceneError::WrongType {
            key: format!("{key}.{name}"),
            message: "missing".to_owned(),
        })
    };
    let reference = get("reference_wavelength")?.unwrap_or(550.0);
    positive(&format!("{key}.reference_wavelength"), reference, " nm")?;
    let scale: [f64; 3] = match kind {
        "rayleigh" => {
            let cross_section = required("cross_section")?;
            let number_density = required("number_density")?;
            non_negative(&format!("{key}.cross_section"), cross_section)?;
            non_negative(&format!("{key}.number_density"), number_density)?;
            wavelengths
                .0
                .map(|l| cross_section * number_density * (reference / l).powi(4))
        }
        _ => {
            let coefficient = required("coefficient")?;
            let exponent = required("exponent")?;
            non_negative(&format!("{key}.coefficient"), coefficient)?;
            check(
                exponent.is_finite(),
                &format!("{key}.exponent"),
                exponent,
                "must be finite",
            )?;
            wavelengths.0.map(|l| coefficient * (l / reference).powf(-exponent))
        }
    };
    Ok(Spectrum::from_array(scale))
}

/// The keys each profile and phase function reads, to refuse the others.
const PROFILE_KEYS: [(&str, ProfileName); 6] = [
    ("scale_height", ProfileName::Exponential),
    ("bottom", ProfileName::Tent),
    ("peak", ProfileName::Tent),
    ("top", ProfileName::Tent),
    ("layers", ProfileName::Layers),
    ("profile_table", ProfileName::Table),
];

fn density(entry: &TermEntry, key: &str) -> Result<Density, SceneError> {
    let given = [
        entry.scale_height.is_some(),
        entry.bottom.is_some(),
        entry.peak.is_some(),
        entry.top.is_some(),
        entry.layers.is_some(),
        entry.profile_table.is_some(),
    ];
    for ((name, owner), set) in PROFILE_KEYS.iter().zip(given) {
        check(
            !set || *owner == entry.profile,
            &format!("{key}.{name}"),
            "(given)",
            &format!("is not read by profile = \"{}\"", profile_name(entry.profile)),
        )?;
    }
    let missing = |name: &str| SceneError::WrongType {
        key: format!("{key}.{name}"),
        message: format!("missing: profile = \"{}\" needs it", profile_name(entry.profile)),
    };
    Ok(match entry.profile {
        ProfileName::Exponential => {
            let h = entry.scale_height.ok_or_else(|| missing("scale_height"))?;
            positive(&format!("{key}.scale_height"), h, " metres")?;
            DensityProfile::single(DensityLayer::exponential(h)).into()
        }
        ProfileName::Constant => DensityProfile::single(DensityLayer::constant()).into(),
        ProfileName::Tent => {
            let bottom = entry.bottom.ok_or_else(|| missing("bottom"))?;
            let peak = entry.peak.ok_or_else(|| missing("peak"))?;
            let top = entry.top.ok_or_else(|| missing("top"))?;
            non_negative(&format!("{key}.bottom"), bottom)?;
            check(peak > bottom, &format!("{key}.peak"), peak, "must be above bottom")?;
            check(top > peak, &format!("{key}.top"), top, "must be above peak")?;
            DensityProfile::tent(bottom, peak, top).into()
        }
        ProfileName::Layers => {
            let layers = entry.layers.as_ref().ok_or_else(|| missing("layers"))?;
            let layer = |l: &LayerEntry| DensityLayer {
                width: l.width,
                exp_term: l.exp_term,
                exp_scale: l.exp_scale,
                linear_term: l.linear_term,
                constant_term: l.constant_term,
            };
            let profile = match layers.as_slice() {
                [only] => DensityProfile::single(layer(only)),
                [below, above] => DensityProfile {
                    layers: [layer(below), layer(above)],
                },
                _ => {
                    return Err(SceneError::invalid(
                        format!("{key}.layers"),
                        format!("{} layers", layers.len()),
                        "needs one or two layers",
                    ));
                }
            };
            let finite = profile.layers.iter().all(|l| {
                [l.width, l.exp_term, l.exp_scale, l.linear_term, l.constant_term]
                    .iter()
                    .all(|v| v.is_finite())
            });
            check(finite, &format!("{key}.layers"), "(given)", "every term must be finite")?;
            profile.into()
        }
        ProfileName::Table => {
            let pairs = entry.profile_table.as_ref().ok_or_else(|| missing("profile_table"))?;
            let pairs: Vec<(f64, f64)> = pairs.iter().map(|p| (p[0], p[1])).collect();
            Density::Table(DensityTable::new(&format!("{key}.profile_table"), &pairs).map_err(from_core)?)
        }
    })
}

fn profile_name(profile: ProfileName) -> &'static str {
    match profile {
        ProfileName::Exponential => "exponential",
        ProfileName::Tent => "tent",
        ProfileName::Constant => "constant",
        ProfileName::Layers => "layers",
        ProfileName::Table => "table",
    }
}

fn phase(entry: &TermEntry, key: &str) -> Result<Phase, SceneError> {
    let kind = entry.phase.unwrap_or(PhaseName::Rayleigh);
    let reads = |name: &str| match name {
        "g" => matches!(
            kind,
            PhaseName::CornetteShanks | PhaseName::HenyeyGreenstein | PhaseName::DualHenyeyGreenstein
        ),
        "g_back" | "blend" => kind == PhaseName::DualHenyeyGreenstein,
        _ => kind == PhaseName::Table,
    };
    let given = [
        ("g", entry.g.is_some()),
        ("g_back", entry.g_back.is_some()),
        ("blend", entry.blend.is_some()),
        ("phase_table", entry.phase_table.is_some()),
    ];
    for (name, set) in given {
        check(
            !set || reads(name),
            &format!("{key}.{name}"),
            "(given)",
            "is not read by this term's phase function",
        )?;
    }
    let required = |name: &str, value: Option<f64>| {
        value.ok_or_else(|| SceneError::WrongType {
            key: format!("{key}.{name}"),
            message: "missing: the term's phase function needs it".to_owned(),
        })
    };
    let asymmetry = |name: &str, value: Option<f64>| -> Result<f64, SceneError> {
        let g = required(name, value)?;
        check(
            g > -1.0 && g < 1.0,
            &format!("{key}.{name}"),
            g,
            "must lie strictly between -1 and 1",
        )?;
        Ok(g)
    };
    Ok(match kind {
        PhaseName::Rayleigh => Phase::Rayleigh,
        PhaseName::CornetteShanks => Phase::CornetteShanks {
            g: asymmetry("g", entry.g)?,
        },
        PhaseName::HenyeyGreenstein => Phase::HenyeyGreenstein {
            g: asymmetry("g", entry.g)?,
        },
        PhaseName::DualHenyeyGreenstein => {
            let blend = required("blend", entry.blend)?;
            check(
                (0.0..=1.0).contains(&blend),
                &format!("{key}.blend"),
                blend,
                "must lie in [0, 1]",
            )?;
            Phase::DualHenyeyGreenstein(DualHenyeyGreenstein {
                g_forward: asymmetry("g", entry.g)?,
                g_back: asymmetry("g_back", entry.g_back)?,
                blend,
            })
        }
        PhaseName::Table => {
            let pairs = entry.phase_table.as_ref().ok_or_else(|| SceneError::WrongType {
                key: format!("{key}.phase_table"),
                message: "missing: phase = \"table\" needs it".to_owned(),
            })?;
            let pairs: Vec<(f64, f64)> = pairs.iter().map(|p| (p[0], p[1])).collect();
            Phase::Table(PhaseTable::new(&format!("{key}.phase_table"), &pairs).map_err(from_core)?)
        }
    })
}

/// A TOML number, integer or float.
fn number(value: &toml::Value) -> Option<f64> {
    value.as_float().or_else(|| value.as_integer().map(|i| i as f64))
}

/// A core error about a table, its field already the scene key.
fn from_core(error: CoreError) -> SceneError {
    super::from_core(error, str::to_owned)
}
