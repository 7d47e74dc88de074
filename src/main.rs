//! The `streamline-studio` binary: the editor with no subcommand, the headless
//! command line otherwise.

fn main() {
    std::process::exit(streamline_studio::cli::main());
}
