//! Spectral values in scene files: one number for all three model wavelengths, or `[a, b, c]`
//! for each in the order of `atmosphere.wavelengths` (680, 550, 440 nm unless changed).

use std::fmt;

use firmament_core::atmosphere::Spectrum;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

/// A value per model wavelength, as written in a scene file. Parsing accepts any number
/// (NaN and negatives included); the rules are checked by validation, which names the key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneSpectrum(pub [f64; 3]);

impl SceneSpectrum {
    /// The core spectrum.
    pub fn spectrum(self) -> Spectrum {
        Spectrum::from_array(self.0)
    }

    /// True when every value is finite and >= 0.
    pub(crate) fn is_finite_non_negative(self) -> bool {
        self.0.iter().all(|v| v.is_finite() && *v >= 0.0)
    }
}

impl fmt::Display for SceneSpectrum {
    /// `[a, b, c]`, small and large values in exponent form (`5.802e-6`) as scene files write them.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [a, b, c] = self.0.map(Number);
        write!(f, "[{a}, {b}, {c}]")
    }
}

/// A number as a person would write it in a scene file: plain between 0.001 and 10⁷, else with
/// an exponent.
struct Number(f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-3..1e7).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

const EXPECTED: &str = "a number or [a, b, c] (one value per model wavelength)";

impl<'de> serde::Deserialize<'de> for SceneSpectrum {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(SpectrumVisitor)
    }
}

struct SpectrumVisitor;

impl<'de> Visitor<'de> for SpectrumVisitor {
    type Value = SceneSpectrum;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(EXPECTED)
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<SceneSpectrum, E> {
        Ok(SceneSpectrum([v; 3]))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<SceneSpectrum, E> {
        // Scene values are far below 2^53; the conversion is exact for them.
        self.visit_f64(v as f64)
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<SceneSpectrum, E> {
        self.visit_f64(v as f64)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<SceneSpectrum, A::Error> {
        let mut values = [0.0; 3];
        for (i, slot) in values.iter_mut().enumerate() {
            *slot = seq
                .next_element::<f64>()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(SceneSpectrum(values))
    }
}
