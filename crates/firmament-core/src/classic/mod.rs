//! The OpenGL 2.1 fixed-function lighting and fog equations, stated in `f64`: the reference
//! that classic-lighting GPU passes are tested against (seeds 001 and 004).
//!
//! Everything here is in **eye space** (the camera at the origin looking down −z), as the GL
//! specification states the equations. Colours are RGBA in `[0, 1]`-ish GL units (`DVec4`), not
//! physical radiance; they are clamped where GL clamps them.

pub mod fog;
pub mod ground;
pub mod lighting;
pub mod mesh;
pub mod scene;
pub mod shadow;
pub mod sky_light;
