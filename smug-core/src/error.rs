//! Typed errors of the framework. Plugin crates wrap theirs in [`Error::Stage`].

use crate::mission::MissionError;
use std::fmt;

/// Where a configuration key came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A line of a config file.
    File {
        /// The file.
        path: String,
        /// 1-based line number.
        line: usize,
    },
    /// A `--set` override on the command line.
    CommandLine {
        /// The override as given, `key=value`.
        text: String,
    },
    /// A file, line unknown.
    Unlocated {
        /// The file (or `<config>`).
        path: String,
    },
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::File { path, line } => write!(f, "{path}:{line}"),
            Origin::CommandLine { text } => write!(f, "--set {text}"),
            Origin::Unlocated { path } => write!(f, "{path}"),
        }
    }
}

/// Errors in configuration files and command-line overrides.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// A file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// A file is not valid TOML.
    #[error("{path}:{line}:{column}: TOML syntax error: {message}")]
    Syntax {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A key is unknown, missing, of the wrong type or has a bad value.
    #[error("{origin}: `{key}`: {message}")]
    Key {
        /// Dotted path of the key, e.g. `planner.params.max_stall`.
        key: String,
        /// Where it was written.
        origin: Origin,
        /// What is wrong.
        message: String,
    },
    /// A `--set` override is malformed.
    #[error("--set {text}: {message}")]
    Override {
        /// The override as given.
        text: String,
        /// What is wrong.
        message: String,
    },
    /// Includes form a cycle or nest too deep.
    #[error("{path}: {message}")]
    Include {
        /// The including file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

/// Errors of the plugin registry.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RegistryError {
    /// No plugin of that name is registered for the stage.
    #[error(
        "unknown {stage} plugin `{name}`; known {stage} plugins: {}",
        list_or_none(known)
    )]
    Unknown {
        /// Stage name.
        stage: &'static str,
        /// The name asked for.
        name: String,
        /// Every registered name, sorted.
        known: Vec<String>,
    },
    /// Two plugins of a stage share a name.
    #[error("{stage} plugin `{name}` is registered twice")]
    Duplicate {
        /// Stage name.
        stage: &'static str,
        /// The duplicated name.
        name: String,
    },
}

fn list_or_none(names: &[String]) -> String {
    if names.is_empty() {
        "(none registered)".to_string()
    } else {
        names.join(", ")
    }
}

/// The error type of every SMUG library crate's public API.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad configuration.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// Plugin lookup failed.
    #[error(transparent)]
    Registry(#[from] RegistryError),
    /// A mission is malformed.
    #[error("invalid mission: {0}")]
    Mission(#[from] MissionError),
    /// A plugin parameter has a value outside its domain.
    #[error("{stage}: {message}")]
    InvalidParam {
        /// Stage (config section) the parameter belongs to.
        stage: String,
        /// What is wrong.
        message: String,
    },
    /// Input data is unusable (start in collision, malformed map, …).
    #[error("{0}")]
    InvalidInput(String),
    /// A stage needs another stage the pipeline has not built.
    #[error("{stage} needs a {needed}; add a [{needed}] section to the config")]
    MissingStage {
        /// The stage being built.
        stage: String,
        /// The stage it needs.
        needed: &'static str,
    },
    /// A file could not be read or written.
    #[error("{context}: {source}")]
    Io {
        /// Which file and what was attempted.
        context: String,
        /// Why it failed.
        source: std::io::Error,
    },
    /// The run's deadline ([`crate::deadline`]) passed before a complete plan was found.
    #[error("the deadline of {seconds} s passed during {during} before a complete plan was found")]
    DeadlinePassed {
        /// The deadline, in seconds from the start of the run.
        seconds: f64,
        /// What was running when it passed.
        during: String,
    },
    /// A plugin's own typed error.
    #[error("{stage}: {source}")]
    Stage {
        /// Plugin or stage name.
        stage: String,
        /// The plugin's error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}

impl Error {
    /// A parameter error for the config section `stage`.
    pub fn invalid_param(stage: impl Into<String>, message: impl Into<String>) -> Self {
        Error::InvalidParam {
            stage: stage.into(),
            message: message.into(),
        }
    }

    /// Wraps a plugin's typed error.
    pub fn stage(
        stage: impl Into<String>,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        Error::Stage {
            stage: stage.into(),
            source: Box::new(source),
        }
    }

    /// An I/O error with context.
    pub fn io(context: impl Into<String>, source: std::io::Error) -> Self {
        Error::Io {
            context: context.into(),
            source,
        }
    }
}

/// `Result` with [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
