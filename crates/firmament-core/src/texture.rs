//! Texture images for classic objects, laid out the way `glTexImage2D` takes them.
//!
//! # Conventions
//! Texels are 8-bit RGBA used **as stored**: fixed-function GL multiplies the lit colour by the
//! texel's bytes / 255 with no sRGB decoding, and so do we (`GL_MODULATE`). Row 0 is `t = 0`, the
//! *bottom* of the picture (OpenGL's texture origin), so a loader flips an image file's rows.

use glam::DVec4;

use crate::error::CoreError;

/// Texture filtering, for both magnification and minification (no mipmaps).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TextureFilter {
    /// `GL_NEAREST`.
    Nearest,
    /// `GL_LINEAR`.
    #[default]
    Linear,
}

/// The largest texture side accepted, texels (what every wgpu adapter supports, `max_texture_dimension_2d` ≥ 8192).
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// An RGBA8 image, bottom row first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureImage {
    /// Width, texels, 1 to [`MAX_TEXTURE_SIDE`].
    pub width: u32,
    /// Height, texels, 1 to [`MAX_TEXTURE_SIDE`].
    pub height: u32,
    /// `width × height` texels, row by row from `t = 0` (bottom), each row from `s = 0` (left).
    pub texels: Vec<[u8; 4]>,
}

impl TextureImage {
    /// A checkerboard of `squares × squares` squares on `size × size` texels, `first` in the
    /// square at `(s, t) = (0, 0)`, alternating with `second`.
    ///
    /// # Errors
    /// [`CoreError::Invalid`] when `size` is not in `1..=MAX_TEXTURE_SIDE` or `squares` not in
    /// `1..=size`.
    pub fn checkerboard(size: u32, squares: u32, first: [u8; 4], second: [u8; 4]) -> Result<Self, CoreError> {
        if !(1..=MAX_TEXTURE_SIDE).contains(&size) {
            return Err(CoreError::Invalid {
                field: "checkerboard.size",
                value: size.to_string(),
                rule: "must be in 1..=8192 texels",
            });
        }
        if !(1..=size).contains(&squares) {
            return Err(CoreError::Invalid {
                field: "checkerboard.squares",
                value: squares.to_string(),
                rule: "must be in 1..=size",
            });
        }
        // Square index of texel k along a side: ⌊k·squares / size⌋ (exact in u64).
        let square = |k: u32| u64::from(k) * u64::from(squares) / u64::from(size);
        let texels = (0..size)
            .flat_map(|t| (0..size).map(move |s| (s, t)))
            .map(|(s, t)| {
                if (square(s) + square(t)).is_multiple_of(2) {
                    first
                } else {
                    second
                }
            })
            .collect();
        Ok(Self {
            width: size,
            height: size,
            texels,
        })
    }

    /// Checks the size rules and that there are `width × height` texels.
    ///
    /// # Errors
    /// [`CoreError::Invalid`] naming `texture.width`, `texture.height` or `texture.texels`.
    pub fn validate(&self) -> Result<(), CoreError> {
        for (field, side) in [("texture.width", self.width), ("texture.height", self.height)] {
            if !(1..=MAX_TEXTURE_SIDE).contains(&side) {
                return Err(CoreError::Invalid {
                    field,
                    value: side.to_string(),
                    rule: "must be in 1..=8192 texels",
                });
            }
        }
        if self.texels.len() as u64 != u64::from(self.width) * u64::from(self.height) {
            return Err(CoreError::Invalid {
                field: "texture.texels",
                value: format!("{} texels for {}×{}", self.texels.len(), self.width, self.height),
                rule: "needs width × height texels",
            });
        }
        Ok(())
    }

    /// The texel at column `s`, row `t` (row 0 at the bottom); `None` outside the image.
    pub fn texel(&self, s: u32, t: u32) -> Option<[u8; 4]> {
        (s < self.width && t < self.height).then(|| self.texels[(t as usize) * (self.width as usize) + s as usize])
    }

    /// The texel at integer coordinates wrapped with `GL_REPEAT`, as RGBA in `[0, 1]`.
    fn repeat_texel(&self, i: i64, j: i64) -> DVec4 {
        let i = i.rem_euclid(i64::from(self.width)) as usize;
        let j = j.rem_euclid(i64::from(self.height)) as usize;
        let [r, g, b, a] = self.texels[j * self.width as usize + i];
        DVec4::new(f64::from(r), f64::from(g), f64::from(b), f64::from(a)) / 255.0
    }

    /// GL's texture lookup at `(s, t)` with `GL_REPEAT` wrapping and no mipmaps (OpenGL 2.1
    /// §3.8.8, equations 3.21–3.22): `GL_NEAREST` takes texel `(⌊u⌋, ⌊v⌋)` with `u = s·width`,
    /// `v = t·height`; `GL_LINEAR` blends the four texels around `(u − ½, v − ½)` bilinearly.
    pub fn sample(&self, s: f64, t: f64, filter: TextureFilter) -> DVec4 {
        let (u, v) = (s * f64::from(self.width), t * f64::from(self.height));
        match filter {
            TextureFilter::Nearest => self.repeat_texel(u.floor() as i64, v.floor() as i64),
            TextureFilter::Linear => {
                let (x, y) = (u - 0.5, v - 0.5);
                let (i0, j0) = (x.floor(), y.floor());
                let (a, b) = (x - i0, y - j0);
                let (i0, j0) = (i0 as i64, j0 as i64);
                self.repeat_texel(i0, j0) * ((1.0 - a) * (1.0 - b))
                    + self.repeat_texel(i0 + 1, j0) * (a * (1.0 - b))
                    + self.repeat_texel(i0, j0 + 1) * ((1.0 - a) * b)
                    + self.repeat_texel(i0 + 1, j0 + 1) * (a * b)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checkerboard_alternates_from_the_lower_left() {
        let (a, b) = ([255, 255, 255, 255], [0, 0, 0, 255]);
        let image = TextureImage::checkerboard(8, 4, a, b).expect("valid");
        assert_eq!(image.validate(), Ok(()));
        assert_eq!(image.texel(0, 0), Some(a));
        assert_eq!(image.texel(1, 1), Some(a));
        assert_eq!(image.texel(2, 0), Some(b));
        assert_eq!(image.texel(2, 2), Some(a));
        assert_eq!(image.texel(7, 0), Some(b));
        assert_eq!(image.texel(8, 0), None);
        assert!(TextureImage::checkerboard(0, 1, a, b).is_err());
        assert!(TextureImage::checkerboard(4, 5, a, b).is_err());
    }

    #[test]
    fn gl_sampling_repeats_and_blends() {
        let image = TextureImage {
            width: 2,
            height: 1,
            texels: vec![[0, 0, 0, 255], [255, 51, 0, 255]],
        };
        // Nearest: s in [0.5, 1) is texel 1; s = 1.25 wraps to texel 0.
        assert_eq!(image.sample(0.75, 0.5, TextureFilter::Nearest).x, 1.0);
        assert_eq!(image.sample(1.25, 0.5, TextureFilter::Nearest).x, 0.0);
        // Linear: at s = 0.5 (between the texel centres 0.25 and 0.75) half of each.
        let mid = image.sample(0.5, 0.5, TextureFilter::Linear);
        assert!((mid - DVec4::new(0.5, 0.1, 0.0, 1.0)).length() < 1e-12, "{mid}");
        // At s = 0 the blend wraps to the last texel: half of texel 1 and half of texel 0.
        assert!((image.sample(0.0, 0.5, TextureFilter::Linear).x - 0.5).abs() < 1e-12);
    }
}
