//! Why a command stopped, as its exit code tells.

/// Why a command stopped.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The input cannot be used (a malformed file, an unknown patch, a value out of range): exit 2.
    #[error(transparent)]
    BadInput(anyhow::Error),
    /// The input was fine but the work failed (an output could not be written): exit 1.
    #[error(transparent)]
    Failed(anyhow::Error),
}
