//! Where a config key was written: key paths and the source texts (files and `--set`
//! overrides), for errors that name the file and line.

use crate::error::{ConfigError, Origin};
use serde::de::DeserializeOwned;
use std::fmt;
use std::path::{Path, PathBuf};
use toml::de::{DeTable, DeValue};

/// One step of a key path: a table key or an array index.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum KeySegment {
    /// A table key.
    Key(String),
    /// An array index.
    Index(usize),
}

/// A dotted key path such as `planner.params.max_stall` or `targets[2].id`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeyPath(pub Vec<KeySegment>);

impl KeyPath {
    /// A path from a dotted string (no array indices).
    pub fn dotted(path: &str) -> Self {
        KeyPath(
            path.split('.')
                .filter(|s| !s.is_empty())
                .map(|s| KeySegment::Key(s.to_string()))
                .collect(),
        )
    }

    /// This path extended by a key.
    pub fn join(&self, key: &str) -> Self {
        let mut segments = self.0.clone();
        segments.push(KeySegment::Key(key.to_string()));
        KeyPath(segments)
    }

    fn starts_with(&self, prefix: &KeyPath) -> bool {
        self.0.len() >= prefix.0.len() && self.0[..prefix.0.len()] == prefix.0[..]
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.0.iter().enumerate() {
            match segment {
                KeySegment::Key(k) if i == 0 => write!(f, "{k}")?,
                KeySegment::Key(k) => write!(f, ".{k}")?,
                KeySegment::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// The texts a config was assembled from, to say where a key was written.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    /// Files, highest precedence first (the main file, then its includes).
    pub(super) files: Vec<SourceFile>,
    /// `--set` overrides in the order given.
    pub(super) overrides: Vec<(KeyPath, String)>,
    /// Directory of the main config file: relative paths in parameters resolve here.
    pub(super) base_dir: PathBuf,
}

/// One config file's name and text.
#[derive(Clone, Debug)]
pub(super) struct SourceFile {
    pub(super) path: String,
    pub(super) text: String,
}

impl SourceMap {
    /// Directory relative paths in the config resolve against.
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    /// The config files read (the main file and its includes), as named.
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.files.iter().map(|f| Path::new(f.path.as_str()))
    }

    /// Where `key` was written: the override that set it (or created its table), or
    /// the line in the file of highest precedence that holds the longest prefix of it.
    pub fn locate(&self, key: &KeyPath) -> Origin {
        let set_by = |matches: &dyn Fn(&KeyPath) -> bool| {
            self.overrides
                .iter()
                .rev()
                .find(|(k, _)| matches(k))
                .map(|(_, text)| Origin::CommandLine { text: text.clone() })
        };
        if let Some(origin) = set_by(&|k| key.starts_with(k)) {
            return origin;
        }
        let mut best: Option<(usize, Origin)> = None;
        for file in &self.files {
            let Ok(root) = DeTable::parse(&file.text) else {
                continue;
            };
            let (depth, span) = deepest_span(root.get_ref(), &key.0);
            if let Some(span) = span {
                if best.as_ref().is_none_or(|(d, _)| depth > *d) {
                    let line = line_of(&file.text, span.start);
                    best = Some((
                        depth,
                        Origin::File {
                            path: file.path.clone(),
                            line,
                        },
                    ));
                }
            }
        }
        match best {
            Some((depth, origin)) if depth == key.0.len() => origin,
            best => set_by(&|k| k.starts_with(key))
                .or(best.map(|(_, origin)| origin))
                .unwrap_or_else(|| Origin::Unlocated {
                    path: self
                        .files
                        .first()
                        .map_or("<config>".into(), |f| f.path.clone()),
                }),
        }
    }

    /// Deserialises `value`, found at `prefix`, into `T`; errors name the offending
    /// key and where it was written.
    pub fn deserialize<T: DeserializeOwned>(
        &self,
        prefix: &KeyPath,
        value: toml::Value,
    ) -> Result<T, ConfigError> {
        serde_path_to_error::deserialize(value).map_err(|err| {
            let mut key = prefix.clone();
            for segment in err.path().iter() {
                match segment {
                    serde_path_to_error::Segment::Map { key: k } => {
                        key.0.push(KeySegment::Key(k.clone()))
                    }
                    serde_path_to_error::Segment::Seq { index } => {
                        key.0.push(KeySegment::Index(*index))
                    }
                    _ => {}
                }
            }
            let message = err.inner().message().trim().to_string();
            if let Some(field) = unknown_field_name(&message) {
                if key.0.last() != Some(&KeySegment::Key(field.to_string())) {
                    key = key.join(field);
                }
            }
            ConfigError::Key {
                origin: self.locate(&key),
                key: key.to_string(),
                message,
            }
        })
    }

    /// An error about `key` with `message`, located.
    pub fn key_error(&self, key: &KeyPath, message: impl Into<String>) -> ConfigError {
        ConfigError::Key {
            key: key.to_string(),
            origin: self.locate(key),
            message: message.into(),
        }
    }
}

/// The field name in serde's "unknown field `x`, expected …" message.
fn unknown_field_name(message: &str) -> Option<&str> {
    let rest = message.strip_prefix("unknown field `")?;
    rest.split('`').next()
}

/// The span of the deepest key of `path` present in `table`, and how deep it is.
fn deepest_span(
    table: &DeTable<'_>,
    path: &[KeySegment],
) -> (usize, Option<std::ops::Range<usize>>) {
    let mut span = None;
    let mut depth = 0;
    let mut current: Option<&DeValue<'_>> = None;
    for segment in path {
        let next = match (segment, current) {
            (KeySegment::Key(k), None) => find_key(table, k),
            (KeySegment::Key(k), Some(DeValue::Table(t))) => find_key(t, k),
            (KeySegment::Index(i), Some(DeValue::Array(a))) => {
                a.get(*i).map(|v| (v.span(), v.get_ref()))
            }
            _ => None,
        };
        let Some((next_span, value)) = next else {
            break;
        };
        span = Some(next_span);
        depth += 1;
        current = Some(value);
    }
    (depth, span)
}

fn find_key<'a, 'i>(
    table: &'a DeTable<'i>,
    key: &str,
) -> Option<(std::ops::Range<usize>, &'a DeValue<'i>)> {
    table
        .iter()
        .find(|(k, _)| k.get_ref().as_ref() == key)
        .map(|(k, v)| (k.span(), v.get_ref()))
}

pub(super) fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

pub(super) fn column_of(text: &str, offset: usize) -> usize {
    let before = &text[..offset.min(text.len())];
    before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1
}
