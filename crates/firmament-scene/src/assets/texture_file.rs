//! Image files and embedded images → [`TextureImage`]: decoded with the `image` crate (PNG,
//! JPEG, OpenEXR), converted to 8-bit RGBA as stored (no sRGB decoding; 16-bit channels scaled,
//! floats clamped to `[0, 1]` and scaled) and flipped so that row 0 is the bottom of the picture,
//! `t = 0`, as `glTexImage2D` takes it.

use std::io::Cursor;

use firmament_core::texture::{MAX_TEXTURE_SIDE, TextureImage};
use image::{ImageFormat, ImageReader, Limits};

use super::Budget;

/// The formats the workspace builds the `image` crate with, for messages.
const FORMATS: &str = "PNG, JPEG and OpenEXR";

/// Decodes an encoded image; `hint` is the format to assume when the contents do not tell. The
/// size from the header is checked against [`MAX_TEXTURE_SIDE`] and taken from `budget`'s texels
/// before the pixels are decoded.
pub(super) fn decode(bytes: &[u8], hint: Option<ImageFormat>, budget: &mut Budget) -> Result<TextureImage, String> {
    let guessed = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read the image: {e}"))?
        .format();
    let Some(format) = guessed.or(hint) else {
        return Err(format!(
            "not an image file of a known format (firmament reads {FORMATS})"
        ));
    };
    let failed = |e: image::ImageError| format!("cannot decode the {format:?} image: {e} (firmament reads {FORMATS})");

    // Check the size from the header before decoding the pixels.
    let (width, height) = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(failed)?;
    check_side("width", width)?;
    check_side("height", height)?;
    budget.take_texels(width, height, "the image")?;

    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    // An 8192² RGBA image of 32-bit floats is 1 GiB.
    limits.max_alloc = Some(3 << 29);
    reader.limits(limits);
    let rgba = reader.decode().map_err(failed)?.into_rgba8();
    let (width, height) = rgba.dimensions();
    check_side("width", width)?;
    check_side("height", height)?;

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

/// Checks one side of an image against [`MAX_TEXTURE_SIDE`].
fn check_side(name: &str, side: u32) -> Result<(), String> {
    if side == 0 {
        Err(format!("the image {name} is 0 pixels"))
    } else if side > MAX_TEXTURE_SIDE {
        Err(super::over_limit(
            &format!("the image {name} is {side} pixels"),
            format!("{MAX_TEXTURE_SIDE} pixels on a side"),
            "MAX_TEXTURE_SIDE",
            "scale the image down",
        ))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
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
        let error = decode(b"not an image", Some(ImageFormat::Png), &mut Budget::new()).expect_err("garbage");
        assert!(error.contains("cannot decode the Png image"), "{error}");
        let mut truncated = png(&RgbaImage::new(4, 4));
        truncated.truncate(truncated.len() / 2);
        assert!(decode(&truncated, None, &mut Budget::new()).is_err());
        let wide = png(&RgbaImage::new(MAX_TEXTURE_SIDE + 1, 1));
        let error = decode(&wide, None, &mut Budget::new()).expect_err("too wide");
        assert!(error.contains("width is 8193 pixels"), "{error}");
    }
}
