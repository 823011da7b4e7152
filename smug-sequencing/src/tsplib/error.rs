//! The TSPLIB readers' error.

/// Why a TSPLIB file cannot be used. Line numbers are 1-based.
#[derive(Debug, thiserror::Error)]
pub enum TsplibError {
    /// The file could not be read.
    #[error("{path}: cannot read: {error}")]
    Io {
        /// The file.
        path: String,
        /// Why (part of the message, so not also a `source()`).
        error: std::io::Error,
    },
    /// A line is malformed.
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file as a whole is unusable (a required key is missing, …).
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}
