//! Faults the viewer's tests inject to check its recovery paths under a real window:
//! `FIRMAMENT_VIEW_INJECT_FAULT=device-lost@N` destroys the GPU device after N frames shown,
//! `surface-lost@N` reports the window's surface lost once after N frames (the path a driver's
//! `Lost` takes). Not a command-line flag on purpose: it is for tests, not users.

use anyhow::{Result, bail};

/// The environment variable that names a fault to inject.
pub(crate) const INJECT_FAULT_VAR: &str = "FIRMAMENT_VIEW_INJECT_FAULT";

/// A fault to inject, after this many frames shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum InjectedFault {
    /// Destroy the device (`wgpu::Device::destroy`): the viewer must end with one message.
    DeviceLost(u64),
    /// Report the surface lost once: the viewer must make a new one and go on.
    SurfaceLost(u64),
}

impl InjectedFault {
    /// The fault `FIRMAMENT_VIEW_INJECT_FAULT` names, if it is set.
    pub(crate) fn from_env() -> Result<Option<Self>> {
        match std::env::var(INJECT_FAULT_VAR) {
            Ok(text) if !text.is_empty() => Self::parse(&text).map(Some),
            _ => Ok(None),
        }
    }

    /// Parses `device-lost@N` or `surface-lost@N`.
    fn parse(text: &str) -> Result<Self> {
        let rule = "expected device-lost@N or surface-lost@N (N: frames shown before the fault)";
        let Some((kind, frames)) = text.split_once('@') else {
            bail!("{INJECT_FAULT_VAR}={text}: {rule}");
        };
        let Ok(frames) = frames.parse::<u64>() else {
            bail!("{INJECT_FAULT_VAR}={text}: {rule}");
        };
        Ok(match kind {
            "device-lost" => Self::DeviceLost(frames),
            "surface-lost" => Self::SurfaceLost(frames),
            _ => bail!("{INJECT_FAULT_VAR}={text}: {rule}"),
        })
    }

    /// The frames shown before the fault.
    pub(crate) fn after_frames(self) -> u64 {
        match self {
            Self::DeviceLost(n) | Self::SurfaceLost(n) => n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faults_parse_and_bad_ones_name_the_variable() {
        assert_eq!(
            InjectedFault::parse("device-lost@2").unwrap(),
            InjectedFault::DeviceLost(2)
        );
        assert_eq!(
            InjectedFault::parse("surface-lost@0").unwrap(),
            InjectedFault::SurfaceLost(0)
        );
        for bad in ["device-lost", "surface-lost@x", "gpu-on-fire@1"] {
            let message = InjectedFault::parse(bad).unwrap_err().to_string();
            assert!(message.contains(INJECT_FAULT_VAR), "{message}");
        }
    }
}
