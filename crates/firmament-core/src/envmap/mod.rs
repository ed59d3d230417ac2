//! Environment maps: the full sphere of directions around a point, as an equirectangular
//! (latitude-longitude) image or six cube faces, in `f64`.
//!
//! [`projection`] maps directions to pixels and back (and gives each pixel's solid angle);
//! [`sun_disc`] spreads a sun's disc, seen through the air, over those pixels energy-exactly,
//! since a disc's radiance does not fit the GPU's half-float target.
//!
//! # Frames
//!
//! Directions are in firmament's world frame, East-North-Up (`x` east, `y` north, `z` up). The
//! equirectangular map has the zenith on its top row and the nadir on its bottom row; its columns
//! run with the compass azimuth (clockwise from north, seen from above): **west** on the left and
//! right edges (the seam), **north** a quarter of the way across, **east** in the middle,
//! **south** at three quarters. That is the layout Blender (world `+X` east, `+Y` north), three.js
//! and Unity (`+X` east, `+Y` up, `+Z` south and north respectively) read without a rotation.
//!
//! The cube faces follow the OpenGL / Khronos cube-map convention in the **Y-up** frame
//! `x` = east, `y` = up, `z` = south ([`enu_to_y_up`]): faces `+X` (east), `−X` (west), `+Y`
//! (up), `−Y` (down), `+Z` (south), `−Z` (north), each image's top row first; [`cross`] lays
//! them out in one image as a horizontal cross.

pub mod cross;
pub mod projection;
pub mod sun_disc;

pub use cross::{CROSS_CELLS, cross_face, cross_position};
pub use projection::{
    CubeFace, cube_direction, cube_position, cube_texel_solid_angle, enu_to_y_up, equirect_direction,
    equirect_pixel_solid_angle, equirect_position, y_up_to_enu,
};
pub use sun_disc::{DiscSample, SunAtEye, sun_at_eye};
