//! The viewer's keyboard map: winit key codes to the core's flight actions and to the viewer's
//! own commands. Plain functions of a key, so the map is tested without a window.
//!
//! Free flight: W/S forward and back, A/D left and right, E/Q up and down, Shift ×10, Ctrl ÷10,
//! the mouse (either button held) looks around, the wheel sets the speed. NeHe lesson 44's keys
//! (N switches): W/S pitch, A/D heading, Z/C speed up and down, X stops. In both: Space pauses
//! the clock, `.`/`,` run it faster or slower, Backspace returns to the scene's own time,
//! G goes to the ground, O to orbit, F1 shows or hides the panel, 1/2 hide or show the info
//! text (as in the lesson), F12 saves a PNG screenshot (Shift+F12 an EXR), Escape quits.

use firmament_core::controller::ControllerKey;
use firmament_core::flight::{FlightAction, FlightMode};
use winit::keyboard::KeyCode;

/// What a key press asks of the viewer (beyond the flight keys held down).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Command {
    /// Pause or resume the clock.
    TogglePause,
    /// Run the clock faster.
    Faster,
    /// Run the clock slower.
    Slower,
    /// Back to the scene's own moment.
    ResetTime,
    /// Switch between free flight and NeHe's controls.
    ToggleMode,
    /// Go to a ground view.
    GoToGround,
    /// Go to an orbit view.
    GoToOrbit,
    /// Show or hide the panel.
    TogglePanel,
    /// Show (`true`) or hide the info text.
    ShowInfo(bool),
    /// Save a screenshot: EXR (linear radiance) when `true`, else PNG.
    Screenshot {
        /// EXR instead of PNG.
        exr: bool,
    },
    /// Close the viewer.
    Quit,
}

/// The flight action a held key drives in `mode`, if any.
pub(crate) fn held_action(code: KeyCode, mode: FlightMode) -> Option<FlightAction> {
    let shared = match code {
        KeyCode::ShiftLeft | KeyCode::ShiftRight => Some(FlightAction::Faster),
        KeyCode::ControlLeft | KeyCode::ControlRight => Some(FlightAction::Slower),
        _ => None,
    };
    shared.or(match mode {
        FlightMode::Free => match code {
            KeyCode::KeyW | KeyCode::ArrowUp => Some(FlightAction::Forward),
            KeyCode::KeyS | KeyCode::ArrowDown => Some(FlightAction::Back),
            KeyCode::KeyA | KeyCode::ArrowLeft => Some(FlightAction::Left),
            KeyCode::KeyD | KeyCode::ArrowRight => Some(FlightAction::Right),
            KeyCode::KeyE | KeyCode::PageUp => Some(FlightAction::Up),
            KeyCode::KeyQ | KeyCode::PageDown => Some(FlightAction::Down),
            _ => None,
        },
        FlightMode::NeHe => match code {
            KeyCode::KeyW => Some(FlightAction::NeHe(ControllerKey::PitchUp)),
            KeyCode::KeyS => Some(FlightAction::NeHe(ControllerKey::PitchDown)),
            KeyCode::KeyA => Some(FlightAction::NeHe(ControllerKey::TurnLeft)),
            KeyCode::KeyD => Some(FlightAction::NeHe(ControllerKey::TurnRight)),
            KeyCode::KeyZ => Some(FlightAction::NeHe(ControllerKey::SpeedUp)),
            KeyCode::KeyC => Some(FlightAction::NeHe(ControllerKey::SlowDown)),
            KeyCode::KeyX => Some(FlightAction::NeHe(ControllerKey::Stop)),
            _ => None,
        },
    })
}

/// The command a key press gives, if any (`shift`: a Shift key is down).
pub(crate) fn command(code: KeyCode, shift: bool) -> Option<Command> {
    Some(match code {
        KeyCode::Space => Command::TogglePause,
        KeyCode::Period | KeyCode::NumpadAdd => Command::Faster,
        KeyCode::Comma | KeyCode::NumpadSubtract => Command::Slower,
        KeyCode::Backspace => Command::ResetTime,
        KeyCode::KeyN => Command::ToggleMode,
        KeyCode::KeyG => Command::GoToGround,
        KeyCode::KeyO => Command::GoToOrbit,
        KeyCode::F1 => Command::TogglePanel,
        KeyCode::Digit1 => Command::ShowInfo(false),
        KeyCode::Digit2 => Command::ShowInfo(true),
        KeyCode::F12 => Command::Screenshot { exr: shift },
        KeyCode::Escape => Command::Quit,
        _ => return None,
    })
}

/// The flight actions of every key in `held`, in `mode` (each action once).
pub(crate) fn held_actions<'a>(held: impl IntoIterator<Item = &'a KeyCode>, mode: FlightMode) -> Vec<FlightAction> {
    let mut actions: Vec<FlightAction> = Vec::new();
    for action in held.into_iter().filter_map(|&code| held_action(code, mode)) {
        if !actions.contains(&action) {
            actions.push(action);
        }
    }
    actions
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wasd_flies_in_free_mode_and_steers_in_nehe_mode() {
        assert_eq!(
            held_action(KeyCode::KeyW, FlightMode::Free),
            Some(FlightAction::Forward)
        );
        assert_eq!(held_action(KeyCode::KeyA, FlightMode::Free), Some(FlightAction::Left));
        assert_eq!(held_action(KeyCode::KeyE, FlightMode::Free), Some(FlightAction::Up));
        assert_eq!(held_action(KeyCode::KeyQ, FlightMode::Free), Some(FlightAction::Down));
        assert_eq!(
            held_action(KeyCode::KeyW, FlightMode::NeHe),
            Some(FlightAction::NeHe(ControllerKey::PitchUp))
        );
        assert_eq!(
            held_action(KeyCode::KeyD, FlightMode::NeHe),
            Some(FlightAction::NeHe(ControllerKey::TurnRight))
        );
        assert_eq!(
            held_action(KeyCode::KeyX, FlightMode::NeHe),
            Some(FlightAction::NeHe(ControllerKey::Stop))
        );
        // Z/C/X mean nothing to free flight; Q/E nothing to NeHe's camera.
        assert_eq!(held_action(KeyCode::KeyZ, FlightMode::Free), None);
        assert_eq!(held_action(KeyCode::KeyQ, FlightMode::NeHe), None);
        assert_eq!(
            held_action(KeyCode::ShiftLeft, FlightMode::NeHe),
            Some(FlightAction::Faster)
        );
    }

    #[test]
    fn commands_follow_the_key_list() {
        assert_eq!(command(KeyCode::Space, false), Some(Command::TogglePause));
        assert_eq!(command(KeyCode::F12, false), Some(Command::Screenshot { exr: false }));
        assert_eq!(command(KeyCode::F12, true), Some(Command::Screenshot { exr: true }));
        assert_eq!(command(KeyCode::Digit1, false), Some(Command::ShowInfo(false)));
        assert_eq!(command(KeyCode::Digit2, false), Some(Command::ShowInfo(true)));
        assert_eq!(command(KeyCode::KeyW, false), None);
    }

    #[test]
    fn held_keys_give_each_action_once() {
        let held = [KeyCode::KeyW, KeyCode::ArrowUp, KeyCode::ShiftLeft, KeyCode::KeyZ];
        assert_eq!(
            held_actions(&held, FlightMode::Free),
            vec![FlightAction::Forward, FlightAction::Faster]
        );
    }
}
