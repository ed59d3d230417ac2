//! Colours in scene files: `"#rrggbb"` (sRGB-encoded) or `[r, g, b]` (linear, may exceed 1).

use std::fmt;

use firmament_core::LinearRgb;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

/// A colour as written in a scene file, already decoded to linear RGB.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneColor(pub LinearRgb);

const EXPECTED: &str = r##"a colour: "#rrggbb" (sRGB) or [r, g, b] (linear, each >= 0)"##;

impl SceneColor {
    /// Parses `#rrggbb` (case-insensitive) into a linear colour.
    pub fn from_hex(text: &str) -> Option<Self> {
        let hex = text.strip_prefix('#')?;
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Self(LinearRgb::from_srgb8(byte(0)?, byte(2)?, byte(4)?)))
    }
}

impl<'de> serde::Deserialize<'de> for SceneColor {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ColorVisitor)
    }
}

struct ColorVisitor;

impl<'de> Visitor<'de> for ColorVisitor {
    type Value = SceneColor;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(EXPECTED)
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<SceneColor, E> {
        SceneColor::from_hex(v).ok_or_else(|| E::custom(format!("`{v}` is not {EXPECTED}")))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<SceneColor, A::Error> {
        let mut c = [0.0; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            *slot = seq
                .next_element::<f64>()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        if !c.iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err(de::Error::custom(format!("{c:?} is not {EXPECTED}")));
        }
        Ok(SceneColor(LinearRgb::new(c[0], c[1], c[2])))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_decodes_to_linear() {
        let c = SceneColor::from_hex("#FF8000").expect("valid");
        assert_eq!(c.0.r, 1.0);
        assert!((c.0.g - firmament_core::color::srgb_to_linear(128.0 / 255.0)).abs() < 1e-15);
        assert_eq!(c.0.b, 0.0);
        for bad in ["ff8000", "#ff80", "#ff80001", "#gg0000", "#ff800é"] {
            assert!(SceneColor::from_hex(bad).is_none(), "{bad}");
        }
    }
}
