//! The sky a frame draws apart from the physical atmosphere: the keyframed gradient sky and its
//! day/night cycle, the sun's diurnal path for a time of day, and the night sky (stars, Moon).

pub mod gradient;
pub mod night;
pub mod sun;
pub mod time_of_day;
