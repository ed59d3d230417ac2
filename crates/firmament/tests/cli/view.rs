//! `firmament view` under a virtual X server (Xvfb): the window's scene against a headless render
//! of the same scene, and "save scene" round trips. Without Xvfb the tests run
//! `scripts/setup.sh` (which installs it when it can), then fail with a message saying how to
//! install it if there is still none.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{firmament, stderr};

/// A virtual X server on a display of its own, stopped when dropped.
struct Xvfb {
    child: Child,
    display: String,
}

/// Whether an `Xvfb` binary is on the PATH.
fn have_xvfb() -> bool {
    Command::new("sh")
        .args(["-c", "command -v Xvfb"])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Runs the project's setup (which installs Xvfb when it can) if there is no Xvfb yet.
fn ensure_xvfb() {
    static SETUP: std::sync::Once = std::sync::Once::new();
    SETUP.call_once(|| {
        if !have_xvfb() {
            let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/setup.sh");
            let _ = Command::new("bash").arg(script).status();
        }
    });
}

impl Xvfb {
    fn start() -> Self {
        ensure_xvfb();
        // A display number no other test run is likely to hold: from the process id.
        let first = 200 + std::process::id() % 500;
        for number in first..first + 50 {
            let socket = format!("/tmp/.X11-unix/X{number}");
            if Path::new(&socket).exists() || Path::new(&format!("/tmp/.X{number}-lock")).exists() {
                continue;
            }
            let child = Command::new("Xvfb")
                .args([&format!(":{number}"), "-screen", "0", "640x480x24", "-nolisten", "tcp"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap_or_else(|e| {
                    panic!(
                        "cannot start Xvfb ({e}): the viewer tests need a virtual X server; \
                         install it with scripts/setup.sh (Debian/Ubuntu: apt-get install xvfb)"
                    )
                });
            let mut server = Self {
                child,
                display: format!(":{number}"),
            };
            let deadline = Instant::now() + Duration::from_secs(20);
            while Instant::now() < deadline {
                if Path::new(&socket).exists() {
                    return server;
                }
                if let Ok(Some(_)) = server.child.try_wait() {
                    break; // Lost a race for this display: try the next.
                }
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = server.child.kill();
        }
        panic!("Xvfb did not start on any display from :{first}");
    }

    /// Runs `firmament view` on this display in `dir`.
    fn view(&self, dir: &Path, args: &[&str]) -> std::process::Output {
        Command::new(env!("CARGO_BIN_EXE_firmament"))
            .arg("view")
            .args(args)
            .current_dir(dir)
            .env("DISPLAY", &self.display)
            .env_remove("WAYLAND_DISPLAY")
            .env_remove("FIRMAMENT_LOG")
            .output()
            .expect("the firmament binary runs")
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The RGBA bytes of a PNG and its size.
fn png(path: &Path) -> (u32, u32, Vec<u8>) {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8();
    (image.width(), image.height(), image.into_raw())
}

/// The largest difference of any channel of two same-sized images, in 8-bit steps.
fn max_difference(a: &Path, b: &Path) -> u8 {
    let (wa, ha, pa) = png(a);
    let (wb, hb, pb) = png(b);
    assert_eq!((wa, ha), (wb, hb), "{} and {} differ in size", a.display(), b.display());
    pa.iter().zip(&pb).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0)
}

#[test]
fn the_window_shows_what_render_writes_and_a_saved_scene_renders_the_same() {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();

    // The default scene (the gradient sky) and a dated atmosphere scene with the Moon and stars.
    for (preset, extra) in [("default", vec![]), ("earth-night", vec!["--set", "camera.pitch=12"])] {
        let shot = format!("{preset}-view.png");
        let saved = format!("{preset}-saved.toml");
        let mut args = vec![
            "--preset",
            preset,
            "--size",
            "96x54",
            "--frames",
            "3",
            "--paused",
            "--screenshot",
            &shot,
            "--save-scene",
            &saved,
        ];
        args.extend(&extra);
        let out = x.view(d, &args);
        assert!(out.status.success(), "view {preset}: {}", stderr(&out));

        // The same scene rendered headless.
        let headless = format!("{preset}-render.png");
        let mut render = vec![
            "render", "--preset", preset, "--width", "96", "--height", "54", "-o", &headless,
        ];
        render.extend(&extra);
        let out = firmament(d, &render);
        assert!(out.status.success(), "render {preset}: {}", stderr(&out));
        let diff = max_difference(&d.join(&shot), &d.join(&headless));
        assert!(
            diff <= 1,
            "{preset}: the viewer's frame differs from render's by {diff}/255"
        );

        // "save scene" wrote a complete scene that renders what the window showed.
        let resaved = format!("{preset}-resaved.png");
        let out = firmament(d, &["render", &saved, "-o", &resaved]);
        assert!(out.status.success(), "render the saved {preset}: {}", stderr(&out));
        let diff = max_difference(&d.join(&shot), &d.join(&resaved));
        assert!(
            diff <= 1,
            "{preset}: the saved scene renders {diff}/255 away from the window"
        );
    }
}

#[test]
fn bad_input_is_one_clear_message_and_no_window() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    // No display at all.
    let out = Command::new(env!("CARGO_BIN_EXE_firmament"))
        .args(["view", "--frames", "1"])
        .current_dir(d)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .expect("runs");
    assert!(!out.status.success());
    let message = stderr(&out);
    assert!(
        message.contains("no display") && message.contains("firmament render"),
        "{message}"
    );
    assert!(!message.contains("panicked"), "{message}");

    // A display that is not there.
    let out = Command::new(env!("CARGO_BIN_EXE_firmament"))
        .args(["view", "--frames", "1"])
        .current_dir(d)
        .env("DISPLAY", ":4999")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("runs");
    assert!(!out.status.success());
    let message = stderr(&out);
    assert!(message.contains("cannot connect to the display"), "{message}");
    assert!(!message.contains("panicked"), "{message}");

    // A bad scene value, a bad size, a screenshot of an unknown format: before any window.
    for (args, expected) in [
        (vec!["view", "--set", "camera.fov_y=-3"], "camera.fov_y"),
        (vec!["view", "--size", "0x10"], "WxH"),
        (vec!["view", "--screenshot", "shot.bmp"], "shot.bmp"),
        (vec!["view", "--save-scene", "missing/dir/scene.toml"], "missing"),
        (vec!["view", "missing.toml"], "missing.toml"),
    ] {
        let out = firmament(d, &args);
        assert!(!out.status.success(), "{args:?} succeeded");
        let message = stderr(&out);
        assert!(message.contains(expected), "{args:?}: {message}");
        assert!(!message.contains("panicked"), "{args:?}: {message}");
    }
    assert_eq!(std::fs::read_dir(d).expect("dir").count(), 0, "no file written");
}

#[test]
fn a_lost_device_ends_with_one_message_and_a_lost_surface_is_made_anew() {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let view = |fault: &str, shot: &str| {
        Command::new(env!("CARGO_BIN_EXE_firmament"))
            .args([
                "view",
                "--size",
                "64x36",
                "--frames",
                "4",
                "--paused",
                "--screenshot",
                shot,
            ])
            .current_dir(d)
            .env("DISPLAY", &x.display)
            .env("FIRMAMENT_VIEW_INJECT_FAULT", fault)
            .env_remove("WAYLAND_DISPLAY")
            .env_remove("FIRMAMENT_LOG")
            .output()
            .expect("the firmament binary runs")
    };

    // The device destroyed after two frames (and before the first): one error line, no panic,
    // no screenshot.
    for fault in ["device-lost@2", "device-lost@0"] {
        let out = view(fault, "lost.png");
        let message = stderr(&out);
        assert!(!out.status.success(), "{fault}: the viewer went on");
        assert!(!message.contains("panicked"), "{fault}: {message}");
        let errors: Vec<&str> = message.lines().filter(|l| l.starts_with("error")).collect();
        assert_eq!(errors.len(), 1, "{fault}: {message}");
        assert!(errors[0].contains("GPU device was lost"), "{fault}: {message}");
        assert!(!d.join("lost.png").exists(), "{fault}: a screenshot of a lost device");
    }

    // The surface lost once: a new one, and the run completes with its screenshot.
    let out = view("surface-lost@1", "recovered.png");
    let message = stderr(&out);
    assert!(out.status.success(), "surface-lost: {message}");
    assert!(message.contains("making a new one"), "{message}");
    assert!(
        d.join("recovered.png").exists(),
        "no screenshot after the surface came back"
    );
}

#[test]
fn no_adapter_for_the_backend_is_one_clear_message() {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().expect("temp dir");
    // This machine has GL (and maybe Vulkan); Metal and DX12 exist only on their systems.
    let backend = if cfg!(target_os = "macos") { "dx12" } else { "metal" };
    let out = x.view(dir.path(), &["--backend", backend, "--frames", "1"]);
    let message = stderr(&out);
    assert!(!out.status.success(), "--backend {backend} found an adapter: {message}");
    assert!(!message.contains("panicked"), "{message}");
    assert!(
        message.contains("no GPU adapter") && message.contains("firmament render"),
        "{message}"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).expect("dir").count(),
        0,
        "no file written"
    );
}
