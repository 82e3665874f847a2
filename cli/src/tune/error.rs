//! Why a request to the tuning server fails, and the HTTP status each reason is answered with.

use thiserror::Error;

/// A request that could not be done; the message is one line for the page to show.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum TuneError {
    /// What was asked is not valid: a path, a value out of range, a pixel off the model, a
    /// malformed request (HTTP 400). Nothing is written.
    #[error("{0}")]
    Bad(String),
    /// What was asked no longer fits the file: it was changed elsewhere (HTTP 409). Nothing is
    /// written.
    #[error("{0}")]
    Conflict(String),
    /// The work failed: a frame could not be rendered or the file not written (HTTP 500).
    #[error("{0}")]
    Failed(String),
}

impl TuneError {
    /// The HTTP status the error is answered with.
    #[must_use]
    pub fn status(&self) -> u16 {
        match self {
            TuneError::Bad(_) => 400,
            TuneError::Conflict(_) => 409,
            TuneError::Failed(_) => 500,
        }
    }
}
