//! The benchmarks' error type.

/// Why a benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// Planning, configuration or plugin error.
    #[error(transparent)]
    Smug(#[from] smug_core::Error),
    /// A TSPLIB / GTSP-LIB file or suite could not be read.
    #[error(transparent)]
    Tsplib(#[from] smug_sequencing::TsplibError),
    /// A bad argument or input (the message says which).
    #[error("{0}")]
    Invalid(String),
    /// A config could not be read.
    #[error(transparent)]
    Config(#[from] smug_core::ConfigError),
    /// A plugin lookup failed.
    #[error(transparent)]
    Registry(#[from] smug_core::RegistryError),
    /// A map file could not be read.
    #[error(transparent)]
    MapFile(#[from] smug_worlds::MapFileError),
    /// A MovingAI map or scenario could not be read or written.
    #[error(transparent)]
    MovingAi(#[from] smug_worlds::MovingAiError),
    /// A grid map could not be generated.
    #[error(transparent)]
    GridGen(#[from] smug_worlds::GridGenError),
    /// A TOML table could not be parsed.
    #[error(transparent)]
    Toml(#[from] toml::de::Error),
    /// A file or folder could not be read or written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The raw numbers could not be written as JSON.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// An error with what was being done (the cause follows it on the error chain).
    #[error("{context}")]
    Context {
        /// What was being done.
        context: String,
        /// The cause.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}

impl BenchError {
    /// A [`BenchError::Invalid`] with this message.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::Invalid(message.into())
    }

    /// `source` with what was being done.
    pub fn context(
        context: impl Into<String>,
        source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
    ) -> Self {
        Self::Context {
            context: context.into(),
            source: source.into(),
        }
    }
}

/// A benchmark's result.
pub type Result<T> = std::result::Result<T, BenchError>;

/// Adds what was being done to an error, as [`BenchError::Context`].
pub trait ResultExt<T> {
    /// The error with `context` before it.
    fn context(self, context: impl Into<String>) -> Result<T>;
    /// The error with the context `f` makes before it (made on error only).
    fn with_context<C: Into<String>>(self, f: impl FnOnce() -> C) -> Result<T>;
}

impl<T, E: Into<Box<dyn std::error::Error + Send + Sync>>> ResultExt<T>
    for std::result::Result<T, E>
{
    fn context(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|e| BenchError::context(context, e))
    }

    fn with_context<C: Into<String>>(self, f: impl FnOnce() -> C) -> Result<T> {
        self.map_err(|e| BenchError::context(f(), e))
    }
}

/// A [`BenchError::Invalid`] from a format string.
macro_rules! invalid {
    ($($arg:tt)*) => { $crate::BenchError::Invalid(format!($($arg)*)) };
}

/// Returns a [`BenchError::Invalid`] from a format string.
macro_rules! bail {
    ($($arg:tt)*) => { return Err($crate::error::invalid!($($arg)*)) };
}

/// Returns a [`BenchError::Invalid`] unless the condition holds.
macro_rules! ensure {
    ($cond:expr, $($arg:tt)*) => {
        if !$cond {
            $crate::error::bail!($($arg)*);
        }
    };
}

pub(crate) use {bail, ensure, invalid};
