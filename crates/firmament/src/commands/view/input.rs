//! The viewer's keyboard map: winit key codes to the core's flight actions and to the viewer's
//! own commands. Plain functions of a key, so the map is tested without a window.
//!
//! Free flight: W/S forward and back, A/D left and right, E/Q up and down, Shift ×10, Ctrl ÷10,
//! the mouse (either button held) looks around, the wheel sets the speed. NeHe lesson 44's keys
//! (N switches), as the lesson lists them: W/S pitch, A/D heading, Z gives the camera a constant
//! forward speed, C a constant backward speed, X stops it (the constant: the altitude's flying
//! speed when pressed). In both: Space pauses the clock, `.`/`,` run it faster or slower,
//! Backspace returns to the scene's own time, G goes to the ground, O to orbit, F1 shows or hides
//! the panel, 1 shows and 2 hides the info text (the lesson's "toggle the info on and off"), F12
//! saves a PNG screenshot (Shift+F12 an EXR), Escape quits.

use super::controller::ControllerKey;
use super::flight::{FlightAction, FlightMode, NeHeVelocity};
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
    /// NeHe mode's Z, C, X: fly on at a constant speed, forward or back, or stop.
    NeHeVelocity(NeHeVelocity),
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
            _ => None,
        },
    })
}

/// The command a key press gives in `mode`, if any (`shift`: a Shift key is down).
pub(crate) fn command(code: KeyCode, shift: bool, mode: FlightMode) -> Option<Command> {
    if mode == FlightMode::NeHe {
        let velocity = match code {
            KeyCode::KeyZ => Some(NeHeVelocity::Forward),
            KeyCode::KeyC => Some(NeHeVelocity::Backward),
            KeyCode::KeyX => Some(NeHeVelocity::Stop),
            _ => None,
        };
        if let Some(velocity) = velocity {
            return Some(Command::NeHeVelocity(velocity));
        }
    }
    Some(match code {
        KeyCode::Space => Command::TogglePause,
        KeyCode::Period | KeyCode::NumpadAdd => Command::Faster,
        KeyCode::Comma | KeyCode::NumpadSubtract => Command::Slower,
        KeyCode::Backspace => Command::ResetTime,
        KeyCode::KeyN => Command::ToggleMode,
        KeyCode::KeyG => Command::GoToGround,
        KeyCode::KeyO => Command::GoToOrbit,
        KeyCode::F1 => Command::TogglePanel,
        KeyCode::Digit1 => Command::ShowInfo(true),
        KeyCode::Digit2 => Command::ShowInfo(false),
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
        // Z/C/X are presses in NeHe mode (commands), nothing held; Q/E nothing to NeHe's camera.
        for key in [KeyCode::KeyZ, KeyCode::KeyC, KeyCode::KeyX] {
            assert_eq!(held_action(key, FlightMode::NeHe), None);
            assert_eq!(held_action(key, FlightMode::Free), None);
        }
        assert_eq!(held_action(KeyCode::KeyQ, FlightMode::NeHe), None);
        assert_eq!(
            held_action(KeyCode::ShiftLeft, FlightMode::NeHe),
            Some(FlightAction::Faster)
        );
    }

    #[test]
    fn commands_follow_the_key_list() {
        for mode in [FlightMode::Free, FlightMode::NeHe] {
            assert_eq!(command(KeyCode::Space, false, mode), Some(Command::TogglePause));
            assert_eq!(
                command(KeyCode::F12, false, mode),
                Some(Command::Screenshot { exr: false })
            );
            assert_eq!(
                command(KeyCode::F12, true, mode),
                Some(Command::Screenshot { exr: true })
            );
            // NeHe lesson 44: "The '1' and '2' keys toggle the info on and off."
            assert_eq!(command(KeyCode::Digit1, false, mode), Some(Command::ShowInfo(true)));
            assert_eq!(command(KeyCode::Digit2, false, mode), Some(Command::ShowInfo(false)));
            assert_eq!(command(KeyCode::KeyW, false, mode), None);
        }
    }

    #[test]
    fn nehe_z_c_x_set_a_constant_speed_forward_back_or_none() {
        // "'Z' gives the camera a constant forward velocity, 'C' a constant backward velocity
        // and 'X' will stop the camera."
        let velocity = |key| match command(key, false, FlightMode::NeHe) {
            Some(Command::NeHeVelocity(v)) => v,
            other => panic!("{key:?} gave {other:?}"),
        };
        assert_eq!(velocity(KeyCode::KeyZ).speed(30.0), 30.0);
        assert_eq!(velocity(KeyCode::KeyC).speed(30.0), -30.0);
        assert_eq!(velocity(KeyCode::KeyX).speed(30.0), 0.0);
        for key in [KeyCode::KeyZ, KeyCode::KeyC, KeyCode::KeyX] {
            assert_eq!(command(key, false, FlightMode::Free), None, "{key:?} in free flight");
        }
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
