//! `kinegen`: see [`kinegen_cli`]. Errors go to stderr, one line per problem, exit 2.

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    // clap prints usage errors itself and exits with status 2.
    let cli = kinegen_cli::Cli::parse();
    match kinegen_cli::run(&cli) {
        Ok(text) => {
            let mut out = std::io::stdout().lock();
            // A closed pipe (`kinegen show ur5 | head`) is not an error worth a panic.
            let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
            ExitCode::SUCCESS
        }
        Err(e) => {
            for line in e.to_string().lines() {
                eprintln!("kinegen: error: {line}");
            }
            ExitCode::from(2)
        }
    }
}
