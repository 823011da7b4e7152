//! What a sweep runs: every config × every combination of the grid's values × every
//! seed, each run named by a stable hash ([`RunSpec::run_id`]).

use sha2::{Digest, Sha256};
use smug_core::config::apply_override;
use smug_core::{ConfigError, LoadedConfig};
use std::path::{Path, PathBuf};

/// The most runs one sweep expands to (a typo such as `1..1000000000` is an error, not
/// hours of work or an exhausted memory).
pub const MAX_RUNS: usize = 1_000_000;

/// Why a sweep cannot start.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The seeds are not `A..B`, `A,B,C` or one number.
    #[error("seeds `{text}`: {message}")]
    Seeds {
        /// The seeds as given.
        text: String,
        /// What is wrong.
        message: String,
    },
    /// A grid axis is not `KEY=V1,V2,…`.
    #[error("grid `{text}`: {message}")]
    Grid {
        /// The axis as given.
        text: String,
        /// What is wrong.
        message: String,
    },
    /// A config file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    ReadConfig {
        /// The config file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A config does not load with one of the grid's combinations (unknown key, bad
    /// value).
    #[error("{} with {}: {source}", config.display(), overrides_text(overrides))]
    Config {
        /// The config file.
        config: PathBuf,
        /// The combination of the grid's overrides.
        overrides: Vec<String>,
        /// The config's error (it names the key and the override).
        source: Box<ConfigError>,
    },
    /// A stage section of a config with one of the grid's combinations names an
    /// unknown plugin or a parameter its plugin does not read.
    #[error("{} with {}: {source}", config.display(), overrides_text(overrides))]
    Params {
        /// The config file.
        config: PathBuf,
        /// The combination of the grid's overrides.
        overrides: Vec<String>,
        /// The stage's error (it names the key).
        source: Box<smug_core::Error>,
    },
    /// The sweep names no config or no seed.
    #[error("a sweep needs at least one {0}")]
    Empty(&'static str),
    /// The sweep would hold more than [`MAX_RUNS`] runs.
    #[error("{runs} runs are more than one sweep may hold ({MAX_RUNS})")]
    TooManyRuns {
        /// How many runs the sweep expands to.
        runs: u128,
    },
    /// The rows file could not be read or written.
    #[error("{}: {what}: {source}", path.display())]
    Rows {
        /// The rows file.
        path: PathBuf,
        /// `cannot read`, `cannot write`.
        what: &'static str,
        /// Why.
        source: std::io::Error,
    },
}

fn overrides_text(overrides: &[String]) -> String {
    if overrides.is_empty() {
        "no override".into()
    } else {
        overrides.join(" ")
    }
}

/// Parses seeds: `A..B` (both included), `A..=B`, `A,B,C`, or one number.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, SweepError> {
    let bad = |message: String| SweepError::Seeds {
        text: text.to_string(),
        message,
    };
    let number = |s: &str| {
        s.trim()
            .parse::<u64>()
            .map_err(|_| bad(format!("`{}` is not a seed (a whole number ≥ 0)", s.trim())))
    };
    if let Some((first, last)) = text.split_once("..") {
        let (first, last) = (number(first)?, number(last.trim_start_matches('='))?);
        if last < first {
            return Err(bad(format!(
                "the range ends ({last}) before it starts ({first})"
            )));
        }
        if last - first >= MAX_RUNS as u64 {
            return Err(bad(format!("more than {MAX_RUNS} seeds")));
        }
        return Ok((first..=last).collect());
    }
    let seeds = text.split(',').map(number).collect::<Result<Vec<_>, _>>()?;
    if let Some(seed) = first_repeated(&seeds) {
        return Err(bad(format!("seed {seed} is given twice")));
    }
    Ok(seeds)
}

/// The first item that an earlier one equals.
fn first_repeated<T: PartialEq>(items: &[T]) -> Option<&T> {
    (1..items.len())
        .find(|&i| items[..i].contains(&items[i]))
        .map(|i| &items[i])
}

/// One axis of a sweep's grid: a config key and the values it takes (TOML, or bare
/// words taken as strings, as `smug plan --set`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GridAxis {
    /// The dotted key, e.g. `planner.params.max_stall`.
    pub key: String,
    /// Its values as override text.
    pub values: Vec<String>,
}

impl GridAxis {
    /// An axis of `key` over `values`: the key dotted, not `seed` (the sweep's seeds
    /// set it), at least one value, none twice.
    pub fn new(key: &str, values: Vec<String>) -> Result<Self, SweepError> {
        let key = key.trim();
        let text = format!("{key}={}", values.join(","));
        let bad = |message: String| SweepError::Grid {
            text: text.clone(),
            message,
        };
        if key.is_empty() || key.split('.').any(|s| s.trim().is_empty()) {
            return Err(bad(format!("`{key}` is not a dotted key")));
        }
        if key == "seed" {
            return Err(bad("the seed is swept with the seeds, not the grid".into()));
        }
        let values: Vec<String> = values.iter().map(|v| v.trim().to_string()).collect();
        if values.is_empty() || values.iter().any(String::is_empty) {
            return Err(bad("expected KEY=V1,V2,… with no empty value".into()));
        }
        if let Some(value) = first_repeated(&values) {
            return Err(bad(format!("the value `{value}` is given twice")));
        }
        Ok(Self {
            key: key.split('.').map(str::trim).collect::<Vec<_>>().join("."),
            values,
        })
    }
}

/// Parses a grid axis `KEY=V1,V2,…`; commas inside `[…]`, `{…}` or quotes belong to
/// the value (`robot.size=[1,2],[2,3]` is two values).
pub fn parse_grid(text: &str) -> Result<GridAxis, SweepError> {
    let (key, values) = text.split_once('=').ok_or_else(|| SweepError::Grid {
        text: text.to_string(),
        message: "expected KEY=V1,V2,…, e.g. planner.params.max_stall=2,3".into(),
    })?;
    GridAxis::new(key, split_top_level(values))
}

/// `text` split at the commas outside brackets, braces and quotes.
fn split_top_level(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let (mut depth, mut quote) = (0i32, None::<char>);
    for c in text.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        parts.last_mut().expect("starts with one part").push(c);
    }
    parts
}

/// One run of a sweep: a config, its overrides (in the grid's order) and a seed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunSpec {
    /// The config file, as given.
    pub config: PathBuf,
    /// The overrides, each `key=value` with the value written as TOML.
    pub overrides: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// The run's id: see [`run_id`].
    pub run_id: String,
}

impl RunSpec {
    /// The run of `config` (read now, for its id) with `overrides` (written anew as
    /// `key=value` with a TOML value, so `selector.type=idp` and
    /// `selector.type="idp"` are one run) and `seed`.
    pub fn new(config: &Path, overrides: &[String], seed: u64) -> Result<Self, SweepError> {
        let content = read_config(config)?;
        let overrides = canonical_overrides(config, overrides)?;
        Ok(Self {
            run_id: run_id(&content, &overrides, seed),
            config: config.to_path_buf(),
            overrides,
            seed,
        })
    }

    /// Loads the run's config with its overrides and seed, as
    /// [`load_config`](crate::load_config) does.
    pub fn load(&self) -> Result<LoadedConfig, ConfigError> {
        let mut set = self.overrides.clone();
        set.push(format!("seed={}", self.seed));
        LoadedConfig::from_file(&self.config, &set)
    }
}

fn read_config(config: &Path) -> Result<Vec<u8>, SweepError> {
    std::fs::read(config).map_err(|source| SweepError::ReadConfig {
        path: config.to_path_buf(),
        source,
    })
}

/// `overrides` each as `key=value`, the key's segments trimmed and the value written
/// as TOML; a malformed one is the config's error for it.
fn canonical_overrides(config: &Path, overrides: &[String]) -> Result<Vec<String>, SweepError> {
    overrides
        .iter()
        .map(|text| {
            let mut table = toml::Table::new();
            let key = apply_override(&mut table, text).map_err(|source| SweepError::Config {
                config: config.to_path_buf(),
                overrides: overrides.to_vec(),
                source: Box::new(source),
            })?;
            let key = key.to_string();
            let root = toml::Value::Table(table);
            let value = key
                .split('.')
                .try_fold(&root, |value, segment| value.get(segment))
                .expect("the override set its own key");
            Ok(format!("{key}={value}"))
        })
        .collect()
}

/// A run's id: the first 16 hex digits of the SHA-256 of SMUG's version, the SHA-256 of
/// the config file's content, the overrides (in order) and the seed. The same config
/// text, overrides and seed on the same SMUG version are the same run wherever the file
/// lies; another version plans anew.
pub fn run_id(config_content: &[u8], overrides: &[String], seed: u64) -> String {
    let content = hex(&Sha256::digest(config_content));
    let key = serde_json::json!([
        "smug-sweep-run",
        crate::version::VERSION,
        content,
        overrides,
        seed
    ]);
    hex(&Sha256::digest(key.to_string().as_bytes()))[..16].to_string()
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// A sweep: configs × every combination of the grid's values × seeds.
#[derive(Clone, Debug, Default)]
pub struct Sweep {
    /// The config files.
    pub configs: Vec<PathBuf>,
    /// The seeds.
    pub seeds: Vec<u64>,
    /// The grid's axes; runs cover every combination, the first axis slowest.
    pub grid: Vec<GridAxis>,
}

impl Sweep {
    /// Every run, config by config, then combination by combination, then seed by
    /// seed, each once (a run id twice is kept the first time). Checks first that every config loads with every combination (an unknown
    /// key or a bad value is an error naming the config and the override).
    pub fn runs(&self) -> Result<Vec<RunSpec>, SweepError> {
        if self.configs.is_empty() {
            return Err(SweepError::Empty("config"));
        }
        if self.seeds.is_empty() {
            return Err(SweepError::Empty("seed"));
        }
        if let Some(axis) = self
            .grid
            .iter()
            .enumerate()
            .find(|(i, axis)| self.grid[..*i].iter().any(|a| a.key == axis.key))
            .map(|(_, axis)| axis)
        {
            return Err(SweepError::Grid {
                text: format!("{}={}", axis.key, axis.values.join(",")),
                message: format!("`{}` is swept twice", axis.key),
            });
        }
        let combinations = self.combinations()?;
        let mut runs = Vec::new();
        for config in &self.configs {
            let content = read_config(config)?;
            for combination in &combinations {
                let overrides = canonical_overrides(config, combination)?;
                let first = RunSpec {
                    config: config.clone(),
                    run_id: run_id(&content, &overrides, self.seeds[0]),
                    overrides,
                    seed: self.seeds[0],
                };
                let loaded = first.load().map_err(|source| SweepError::Config {
                    config: config.clone(),
                    overrides: first.overrides.clone(),
                    source: Box::new(source),
                })?;
                smug_core::Pipeline::check_params(&loaded).map_err(|source| {
                    SweepError::Params {
                        config: config.clone(),
                        overrides: first.overrides.clone(),
                        source: Box::new(source),
                    }
                })?;
                runs.extend(self.seeds.iter().map(|&seed| RunSpec {
                    run_id: run_id(&content, &first.overrides, seed),
                    seed,
                    ..first.clone()
                }));
            }
        }
        // One config given twice (or two files of one content) is one set of runs.
        let mut seen = std::collections::HashSet::new();
        runs.retain(|run| seen.insert(run.run_id.clone()));
        Ok(runs)
    }

    /// Every combination of the grid's values as overrides, the first axis slowest.
    fn combinations(&self) -> Result<Vec<Vec<String>>, SweepError> {
        let count = self
            .grid
            .iter()
            .map(|a| a.values.len() as u128)
            .product::<u128>()
            * self.configs.len() as u128
            * self.seeds.len() as u128;
        if count > MAX_RUNS as u128 {
            return Err(SweepError::TooManyRuns { runs: count });
        }
        let mut combinations = vec![Vec::new()];
        for axis in &self.grid {
            combinations = combinations
                .iter()
                .flat_map(|done: &Vec<String>| {
                    axis.values.iter().map(move |value| {
                        let mut next = done.clone();
                        next.push(format!("{}={value}", axis.key));
                        next
                    })
                })
                .collect();
        }
        Ok(combinations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_are_ranges_lists_or_one_number() {
        assert_eq!(parse_seeds("1..3").unwrap(), vec![1, 2, 3]);
        assert_eq!(parse_seeds("1..=3").unwrap(), vec![1, 2, 3]);
        assert_eq!(parse_seeds("4, 9,2").unwrap(), vec![4, 9, 2]);
        assert_eq!(parse_seeds("7").unwrap(), vec![7]);
        for (bad, says) in [
            ("3..1", "ends (1) before it starts (3)"),
            ("1..x", "`x` is not a seed"),
            ("-1", "`-1` is not a seed"),
            ("1,2,1", "seed 1 is given twice"),
            ("", "`` is not a seed"),
            ("0..2000000", "more than"),
        ] {
            let err = parse_seeds(bad).unwrap_err().to_string();
            assert!(err.contains(says), "{bad}: {err}");
            assert!(err.starts_with(&format!("seeds `{bad}`")), "{err}");
        }
    }

    #[test]
    fn grid_values_split_at_top_level_commas_only() {
        let axis = parse_grid("robot.size = [1, 2],[2,3], '{a,b}'").unwrap();
        assert_eq!(axis.key, "robot.size");
        assert_eq!(axis.values, ["[1, 2]", "[2,3]", "'{a,b}'"]);
        for (bad, says) in [
            ("planner.params.max_stall", "expected KEY=V1,V2"),
            ("planner..x=1", "is not a dotted key"),
            ("seed=1,2", "seeds, not the grid"),
            ("a.b=1,,2", "no empty value"),
            ("a.b=1,1", "`1` is given twice"),
        ] {
            let err = parse_grid(bad).unwrap_err().to_string();
            assert!(err.contains(says), "{bad}: {err}");
        }
    }

    #[test]
    fn run_ids_change_with_every_input_and_nothing_else() {
        let base = run_id(b"seed = 1", &["a.b=2".into()], 1);
        assert_eq!(base.len(), 16);
        assert_eq!(base, run_id(b"seed = 1", &["a.b=2".into()], 1));
        assert_ne!(base, run_id(b"seed = 2", &["a.b=2".into()], 1));
        assert_ne!(base, run_id(b"seed = 1", &["a.b=3".into()], 1));
        assert_ne!(base, run_id(b"seed = 1", &[], 1));
        assert_ne!(base, run_id(b"seed = 1", &["a.b=2".into()], 2));
    }

    #[test]
    fn overrides_are_written_anew_so_spellings_of_one_value_are_one_run() {
        let config = Path::new("x.toml");
        let written = |text: &str| canonical_overrides(config, &[text.to_string()]).unwrap();
        assert_eq!(
            written("selector.type=idp"),
            written("selector.type = \"idp\"")
        );
        assert_eq!(written(" a . b =2"), ["a.b=2"]);
        assert_eq!(written("a.b=0.5"), ["a.b=0.5"]);
    }
}
