//! The command's error type: bad input (exit code 2) or a failure while running (exit code 1).

use thiserror::Error;

/// Why a command failed. Every message is one line: it names the problem and, for bad input,
/// the expected form.
#[derive(Debug, Error)]
pub enum CliError {
    /// The input is malformed or describes something that cannot be simulated (exit code 2).
    #[error("{0}")]
    Input(String),
    /// The input was fine but the work failed: an integrator gave up, a file could not be
    /// written (exit code 1).
    #[error("{0}")]
    Runtime(String),
}

impl CliError {
    /// Returns a bad-input error with the message `message`.
    pub fn input(message: impl Into<String>) -> Self {
        CliError::Input(message.into())
    }

    /// Returns a run-time error with the message `message`.
    pub fn runtime(message: impl Into<String>) -> Self {
        CliError::Runtime(message.into())
    }

    /// Returns the process exit code: 2 for bad input, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Input(_) => 2,
            CliError::Runtime(_) => 1,
        }
    }
}

impl From<rotorflow::scene::SceneError> for CliError {
    /// A bad scene is bad input (exit code 2), a failed run a run-time error (exit code 1),
    /// with the same message.
    fn from(e: rotorflow::scene::SceneError) -> Self {
        use rotorflow::scene::SceneError;
        match e {
            SceneError::Invalid(message) => CliError::Input(message),
            SceneError::Failed(message) => CliError::Runtime(message),
        }
    }
}

/// The result type of the command's functions.
pub type CliResult<T> = Result<T, CliError>;
