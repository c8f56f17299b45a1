//! The `curvemesh` binary, what `cargo install --path xtask` installs: the same command as
//! `cargo xtask` ([`xtask::entry`]), naming itself `curvemesh` in help and usage lines.

fn main() -> std::process::ExitCode {
    xtask::entry::main(xtask::entry::CURVEMESH)
}
