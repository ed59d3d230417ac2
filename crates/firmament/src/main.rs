//! `firmament`: render skies headless to PNG and EXR (the command is the library `firmament_cli`).

fn main() -> std::process::ExitCode {
    firmament_cli::main()
}
