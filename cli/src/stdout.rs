//! A command's output on standard output, where a reader that stopped early is no failure.

use super::error::CliError;

/// Writes a command's output to standard output through `write`; a reader that stopped early
/// (`glint … | head`) is not a failure. `what` names the output in an error.
pub(crate) fn write_stdout(
    what: &str,
    write: impl FnOnce(&mut dyn std::io::Write) -> anyhow::Result<()>,
) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match write(&mut out).and_then(|()| std::io::Write::flush(&mut out).map_err(Into::into)) {
        Err(e)
            if e.downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) =>
        {
            Ok(())
        }
        other => other.map_err(|e| CliError::Failed(e.context(format!("writing {what}")))),
    }
}
