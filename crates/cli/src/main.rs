//! The `propbet` binary: parses the command line, runs the command (`propbet_cli::run`) and
//! maps the outcome to an exit code: 0 ok, 1 ran with failures (reported), 2 error.

use std::io::Write as _;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match propbet_cli::parse_args(std::env::args_os()) {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    // An interrupted propbet takes the XFOIL processes and temporary folders it started
    // with it (without a handler the default action still ends propbet).
    let _ = propbet_api::xfoil::interrupt::install();
    match propbet_cli::run(cli) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            // Not a panic when standard error is closed.
            let _ = writeln!(std::io::stderr(), "propbet: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
