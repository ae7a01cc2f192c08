//! `atmos`: the viewer and the command-line tool (see the library for the work).

use std::process::ExitCode;

fn main() -> ExitCode {
    let Err(err) = atmos::run(std::env::args_os()) else {
        return ExitCode::SUCCESS;
    };
    if let Some(usage) = err.downcast_ref::<clap::Error>() {
        // Help and version to stdout with 0, usage errors to stderr with 2.
        usage.exit();
    }
    if atmos::files::is_broken_pipe(&err) {
        // The reader of stdout has gone (`atmos stability | head -1`): nothing to say.
        return ExitCode::SUCCESS;
    }
    // The chain of causes, each once: some errors already print their source.
    let mut message = err.to_string();
    for cause in err.chain().skip(1).map(ToString::to_string) {
        if !message.contains(&cause) {
            message = format!("{message}: {cause}");
        }
    }
    eprintln!("error: {message}");
    ExitCode::FAILURE
}
