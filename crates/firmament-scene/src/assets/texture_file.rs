//! Image files and embedded images → [`TextureImage`]: decoded with the `image` crate (PNG,
//! JPEG, OpenEXR), converted to 8-bit RGBA as stored (no sRGB decoding; 16-bit channels scaled,
//! floats clamped to `[0, 1]` and scaled) and flipped so that row 0 is the bottom of the picture,
//! `t = 0`, as `glTexImage2D` takes it. Without the crate's `image-files` feature there is no
//! decoder: naming an image file is an error that says so.

#[cfg(feature = "image-files")]
use std::io::Cursor;
use std::path::Path;

use firmament_core::texture::TextureImage;
#[cfg(feature = "image-files")]
use image::{ImageFormat, ImageReader, Limits};

use super::limits::Budget;

/// The format a file's name or a media type suggests, for contents that do not say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FormatHint {
    /// PNG.
    Png,
    /// JPEG.
    Jpeg,
    /// OpenEXR.
    Exr,
}

impl FormatHint {
    /// From a file name's extension.
    pub(crate) fn from_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "png" => Some(Self::Png),
            "jpg" | "jpeg" => Some(Self::Jpeg),
            "exr" => Some(Self::Exr),
            _ => None,
        }
    }

    /// From a media type (`image/png`).
    pub(crate) fn from_mime_type(media_type: &str) -> Option<Self> {
        match media_type.trim().to_ascii_lowercase().as_str() {
            "image/png" => Some(Self::Png),
            "image/jpeg" | "image/jpg" => Some(Self::Jpeg),
            "image/x-exr" | "image/aces" => Some(Self::Exr),
            _ => None,
        }
    }

    #[cfg(feature = "image-files")]
    fn image_format(self) -> ImageFormat {
        match self {
            Self::Png => ImageFormat::Png,
            Self::Jpeg => ImageFormat::Jpeg,
            Self::Exr => ImageFormat::OpenExr,
        }
    }
}

/// Without a decoder: every image is an error naming the feature that brings one.
#[cfg(not(feature = "image-files"))]
pub(super) fn decode(_bytes: &[u8], _hint: Option<FormatHint>, _budget: &mut Budget) -> Result<TextureImage, String> {
    Err(
        "firmament-scene was built without its `image-files` feature, so it cannot read image files \
         (enable the feature to read PNG, JPEG and OpenEXR)"
            .to_owned(),
    )
}

/// Without the `image` crate nothing is decoded, so nothing needs resampling; nearest texel.
#[cfg(not(feature = "image-files"))]
pub(super) fn resampled(texture: &TextureImage, side: u32) -> TextureImage {
    let pick = |i: u32, n: u32| ((u64::from(i) * u64::from(n)) / u64::from(side.max(1))) as u32;
    let texels = (0..side)
        .flat_map(|t| (0..side).map(move |s| (s, t)))
        .map(|(s, t)| {
            texture
                .texel(pick(s, texture.width), pick(t, texture.height))
                .unwrap_or_default()
        })
        .collect();
    TextureImage {
        width: side,
        height: side,
        texels,
    }
}

/// The formats the workspace builds the `image` crate with, for messages.
#[cfg(feature = "image-files")]
const FORMATS: &str = "PNG, JPEG and OpenEXR";

/// Decodes an encoded image; `hint` is the format to assume when the contents do not tell. The
/// size from the header is checked against the budget's longest side
/// ([`MAX_TEXTURE_SIDE`](firmament_core::texture::MAX_TEXTURE_SIDE) or a confinement's) and taken from `budget`'s texels
/// before the pixels are decoded.
#[cfg(feature = "image-files")]
pub(super) fn decode(bytes: &[u8], hint: Option<FormatHint>, budget: &mut Budget) -> Result<TextureImage, String> {
    let guessed = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read the image: {e}"))?
        .format();
    let Some(format) = guessed.or(hint.map(FormatHint::image_format)) else {
        return Err(format!(
            "not an image file of a known format (firmament reads {FORMATS})"
        ));
    };
    let failed = |e: image::ImageError| format!("cannot decode the {format:?} image: {e} (firmament reads {FORMATS})");

    // Check the size from the header before decoding the pixels.
    let (width, height) = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(failed)?;
    budget.check_texture_side("width", width)?;
    budget.check_texture_side("height", height)?;
    budget.take_texels(width, height, "the image")?;

    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = Limits::default();
    limits.max_image_width = Some(budget.limits.max_texture_side);
    limits.max_image_height = Some(budget.limits.max_texture_side);
    // An 8192² RGBA image of 32-bit floats is 1 GiB.
    limits.max_alloc = Some(3 << 29);
    reader.limits(limits);
    let rgba = reader.decode().map_err(failed)?.into_rgba8();
    let (width, height) = rgba.dimensions();
    budget.check_texture_side("width", width)?;
    budget.check_texture_side("height", height)?;

    let row_bytes = width as usize * 4;
    let texels: Vec<[u8; 4]> = rgba
        .as_raw()
        .chunks_exact(row_bytes)
        .rev()
        .flat_map(|row| row.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]))
        .collect();
    let texture = TextureImage { width, height, texels };
    texture.validate().map_err(|e| format!("bad image: {e}"))?;
    Ok(texture)
}

/// `texture` resampled to `side` × `side` texels (Catmull-Rom; rows keep their order).
#[cfg(feature = "image-files")]
pub(super) fn resampled(texture: &TextureImage, side: u32) -> TextureImage {
    if texture.width == side && texture.height == side {
        return texture.clone();
    }
    let picture = image::RgbaImage::from_fn(texture.width, texture.height, |s, t| {
        image::Rgba(texture.texel(s, t).unwrap_or_default())
    });
    let scaled = image::imageops::resize(&picture, side, side, image::imageops::FilterType::CatmullRom);
    TextureImage {
        width: side,
        height: side,
        texels: scaled.pixels().map(|p| p.0).collect(),
    }
}

#[cfg(all(test, feature = "image-files"))]
mod tests {
    use firmament_core::texture::MAX_TEXTURE_SIDE;
    use image::{Rgba, RgbaImage};

    use super::*;

    fn png(image: &RgbaImage) -> Vec<u8> {
        let mut bytes = Vec::new();
        image
            .write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)
            .expect("encodes");
        bytes
    }

    #[test]
    fn rows_are_flipped() {
        // Top row red, bottom row blue, in file order (row 0 at the top).
        let image = RgbaImage::from_fn(2, 3, |x, y| match y {
            0 => Rgba([255, 0, 0, 255]),
            2 => Rgba([0, 0, 255, 128]),
            _ => Rgba([0, x as u8, 0, 255]),
        });
        let texture = decode(&png(&image), None, &mut Budget::new()).expect("decodes");
        assert_eq!((texture.width, texture.height), (2, 3));
        assert_eq!(texture.texel(0, 0), Some([0, 0, 255, 128]));
        assert_eq!(texture.texel(1, 1), Some([0, 1, 0, 255]));
        assert_eq!(texture.texel(1, 2), Some([255, 0, 0, 255]));
    }

    #[test]
    fn resampling_keeps_a_flat_image_flat_and_rows_in_order() {
        let image = RgbaImage::from_fn(4, 6, |_, y| if y < 3 { Rgba([200; 4]) } else { Rgba([0, 0, 0, 255]) });
        let texture = decode(&png(&image), None, &mut Budget::new()).expect("decodes");
        let scaled = resampled(&texture, 16);
        assert_eq!((scaled.width, scaled.height), (16, 16));
        // Row 0 is the bottom of the picture, which is black; the top is grey.
        assert_eq!(scaled.texel(5, 0), Some([0, 0, 0, 255]));
        assert_eq!(scaled.texel(5, 15), Some([200; 4]));
    }

    #[test]
    fn bad_images_are_errors() {
        let error = decode(b"not an image", None, &mut Budget::new()).expect_err("garbage");
        assert!(error.contains("not an image file of a known format"), "{error}");
        let error = decode(b"not an image", Some(FormatHint::Png), &mut Budget::new()).expect_err("garbage");
        assert!(error.contains("cannot decode the Png image"), "{error}");
        let mut truncated = png(&RgbaImage::new(4, 4));
        truncated.truncate(truncated.len() / 2);
        assert!(decode(&truncated, None, &mut Budget::new()).is_err());
        let wide = png(&RgbaImage::new(MAX_TEXTURE_SIDE + 1, 1));
        let error = decode(&wide, None, &mut Budget::new()).expect_err("too wide");
        assert!(error.contains("width is 8193 pixels"), "{error}");
    }
}
