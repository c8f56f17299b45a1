//! The `xtask` binary, run as `cargo xtask` (the alias in `.cargo/config.toml`); everything is
//! in the library ([`xtask::entry`]), shared with the `curvemesh` binary.

fn main() -> std::process::ExitCode {
    xtask::entry::main(xtask::entry::CARGO_XTASK)
}
