//! Typed pipeline configuration: TOML files with includes and `--set` overrides.
//!
//! Every error names the key and where it was written (file and line, or the
//! override), whether it comes from the pipeline's own keys or a plugin's parameters.

mod schema;
mod source;
mod team;
#[cfg(test)]
mod team_tests;

pub use schema::{OutputConfig, PipelineConfig, PluginSection, RobotConfig};
pub use source::{KeyPath, KeySegment, SourceMap};
pub use team::{team_key, TargetRestriction, TeamConfig, TeamMemberConfig, TeamUnit};

use crate::error::ConfigError;
use source::{column_of, line_of, SourceFile};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A loaded, merged, overridden and typed config with the sources it came from.
#[derive(Clone, Debug)]
pub struct LoadedConfig {
    /// The typed config.
    pub config: PipelineConfig,
    /// The merged TOML (after includes and overrides).
    pub table: toml::Table,
    /// Where each key was written, for error messages.
    pub sources: Arc<SourceMap>,
}

/// How deep includes may nest.
const MAX_INCLUDE_DEPTH: usize = 8;

impl LoadedConfig {
    /// The files this config makes a run read: the config files, and every string
    /// value that names an existing file (relative to the main file's directory or as
    /// given): maps, missions, layers. Outputs must never overwrite them.
    pub fn input_files(&self) -> Vec<PathBuf> {
        fn strings<'a>(value: &'a toml::Value, out: &mut Vec<&'a str>) {
            match value {
                toml::Value::String(s) => out.push(s),
                toml::Value::Array(items) => items.iter().for_each(|v| strings(v, out)),
                toml::Value::Table(table) => table.values().for_each(|v| strings(v, out)),
                _ => {}
            }
        }
        let mut values = Vec::new();
        self.table.values().for_each(|v| strings(v, &mut values));
        let base = self.sources.base_dir();
        let mut files: Vec<PathBuf> = self.sources.files().map(Path::to_path_buf).collect();
        for value in values {
            for candidate in [base.join(value), PathBuf::from(value)] {
                if candidate.is_file() {
                    files.push(candidate);
                }
            }
        }
        files
    }

    /// Loads `path` (with its includes) and applies `overrides` (`key=value` each).
    pub fn from_file(path: &Path, overrides: &[String]) -> Result<Self, ConfigError> {
        let mut files = Vec::new();
        let table = read_layered(path, &mut Vec::new(), &mut files)?;
        files.reverse();
        let base_dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Self::finish(table, files, base_dir, overrides)
    }

    /// Loads a config from text; includes resolve against `base_dir`.
    pub fn from_text(
        text: &str,
        name: &str,
        base_dir: &Path,
        overrides: &[String],
    ) -> Result<Self, ConfigError> {
        let mut files = Vec::new();
        let table = layer_text(text, name, base_dir, &mut Vec::new(), &mut files)?;
        files.reverse();
        Self::finish(table, files, base_dir.to_path_buf(), overrides)
    }

    fn finish(
        mut table: toml::Table,
        files: Vec<SourceFile>,
        base_dir: PathBuf,
        overrides: &[String],
    ) -> Result<Self, ConfigError> {
        let mut sources = SourceMap {
            files,
            overrides: Vec::new(),
            base_dir,
        };
        for text in overrides {
            let key = apply_override(&mut table, text)?;
            sources.overrides.push((key, text.clone()));
        }
        let mut config: PipelineConfig =
            sources.deserialize(&KeyPath::default(), toml::Value::Table(table.clone()))?;
        config.assign_section_keys();
        if let Some((field, message)) = config.robot.invalid_field() {
            return Err(sources.key_error(&KeyPath::dotted("robot").join(field), message));
        }
        if let Some((field, message)) = config.plan.invalid_field() {
            return Err(sources.key_error(&KeyPath::dotted("plan").join(field), message));
        }
        if let Some((field, message)) = config.limits.invalid_field() {
            return Err(sources.key_error(&KeyPath::dotted("limits").join(field), message));
        }
        if let Some((key, message)) = config.team.as_ref().and_then(|t| t.invalid_field()) {
            return Err(sources.key_error(&key, message));
        }
        Ok(Self {
            config,
            table,
            sources: Arc::new(sources),
        })
    }
}

impl LoadedConfig {
    /// The whole config of team robot `k`: the shared keys (without `[team]`), its
    /// includes above them, its inline sections above those; typed and checked like a
    /// config file (errors name the robot's key). `None` without a `[team]` or robot `k`.
    pub fn member(&self, k: usize) -> Option<Result<LoadedConfig, ConfigError>> {
        let member = self.config.team.as_ref()?.robots.get(k)?;
        Some(self.member_config(k, member))
    }

    fn member_config(
        &self,
        k: usize,
        member: &team::TeamMemberConfig,
    ) -> Result<LoadedConfig, ConfigError> {
        let mut table = self.table.clone();
        table.remove("team");
        let base_dir = self.sources.base_dir().to_path_buf();
        let mut files: Vec<SourceFile> = Vec::new();
        for include in &member.include {
            let layer = read_layered(&base_dir.join(include), &mut Vec::new(), &mut files)?;
            merge_tables(&mut table, layer);
        }
        merge_tables(&mut table, member.sections.clone());
        files.reverse();
        // The robot's own keys (in the main file, under team.robots[k]) come first.
        let mut main = self.sources.files.iter().cloned();
        let mut all: Vec<SourceFile> = main.next().into_iter().collect();
        all.extend(files);
        all.extend(main);
        LoadedConfig::finish(table, all, base_dir, &[]).map_err(|err| match err {
            ConfigError::Key { key, message, .. } => {
                let key = format!("team.robots[{k}].{key}");
                let mut path = KeyPath::dotted("team.robots");
                path.0.push(KeySegment::Index(k));
                ConfigError::Key {
                    origin: self.sources.locate(&path),
                    key,
                    message: format!("robot `{}`: {message}", member.name),
                }
            }
            other => other,
        })
    }
}

fn read_layered(
    path: &Path,
    stack: &mut Vec<PathBuf>,
    files: &mut Vec<SourceFile>,
) -> Result<toml::Table, ConfigError> {
    let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
        path: path.display().to_string(),
        source,
    })?;
    let canonical = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    if stack.contains(&canonical) {
        return Err(ConfigError::Include {
            path: path.display().to_string(),
            message: "includes itself (include cycle)".into(),
        });
    }
    stack.push(canonical);
    let base_dir = path.parent().unwrap_or(Path::new("."));
    let table = layer_text(&text, &path.display().to_string(), base_dir, stack, files);
    stack.pop();
    table
}

/// Parses `text`, merges its includes beneath it and records the files.
fn layer_text(
    text: &str,
    name: &str,
    base_dir: &Path,
    stack: &mut Vec<PathBuf>,
    files: &mut Vec<SourceFile>,
) -> Result<toml::Table, ConfigError> {
    let mut own = parse_table(text, name)?;
    let includes = take_includes(&mut own, text, name)?;
    if !includes.is_empty() && stack.len() >= MAX_INCLUDE_DEPTH {
        return Err(ConfigError::Include {
            path: name.to_string(),
            message: format!("includes nest deeper than {MAX_INCLUDE_DEPTH} levels"),
        });
    }
    let mut merged = toml::Table::new();
    for include in includes {
        let layer = read_layered(&base_dir.join(include), stack, files)?;
        merge_tables(&mut merged, layer);
    }
    merge_tables(&mut merged, own);
    files.push(SourceFile {
        path: name.to_string(),
        text: text.to_string(),
    });
    Ok(merged)
}

fn parse_table(text: &str, name: &str) -> Result<toml::Table, ConfigError> {
    text.parse::<toml::Table>().map_err(|err| {
        let offset = err.span().map_or(0, |s| s.start);
        ConfigError::Syntax {
            path: name.to_string(),
            line: line_of(text, offset),
            column: column_of(text, offset),
            message: err.message().trim().to_string(),
        }
    })
}

/// Removes the top-level `include` key (a path or a list of paths).
fn take_includes(
    table: &mut toml::Table,
    text: &str,
    name: &str,
) -> Result<Vec<String>, ConfigError> {
    let bad = |message: &str| {
        let sources = SourceMap {
            files: vec![SourceFile {
                path: name.to_string(),
                text: text.to_string(),
            }],
            overrides: Vec::new(),
            base_dir: PathBuf::new(),
        };
        sources.key_error(&KeyPath::dotted("include"), message)
    };
    match table.remove("include") {
        None => Ok(Vec::new()),
        Some(toml::Value::String(path)) => Ok(vec![path]),
        Some(toml::Value::Array(items)) => items
            .into_iter()
            .map(|item| match item {
                toml::Value::String(path) => Ok(path),
                _ => Err(bad("include must be a path or a list of paths")),
            })
            .collect(),
        Some(_) => Err(bad("include must be a path or a list of paths")),
    }
}

/// Deep-merges `top` over `base`. A plugin section whose `type` changes is replaced
/// whole, so one plugin's parameters never leak into another's.
fn merge_tables(base: &mut toml::Table, top: toml::Table) {
    for (key, value) in top {
        match (base.get_mut(&key), value) {
            (Some(toml::Value::Table(old)), toml::Value::Table(new))
                if old.get("type").is_none()
                    || new.get("type").is_none()
                    || old.get("type") == new.get("type") =>
            {
                merge_tables(old, new);
            }
            (_, value) => {
                base.insert(key, value);
            }
        }
    }
}

/// Applies `key.path=value` to `table`; the value is TOML, or a bare word taken as a string.
pub fn apply_override(table: &mut toml::Table, text: &str) -> Result<KeyPath, ConfigError> {
    let bad = |message: String| ConfigError::Override {
        text: text.to_string(),
        message,
    };
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| bad("expected KEY=VALUE, e.g. planner.params.max_stall=5".into()))?;
    let segments: Vec<&str> = key.trim().split('.').map(str::trim).collect();
    if segments.iter().any(|s| s.is_empty()) {
        return Err(bad(format!("`{}` is not a dotted key", key.trim())));
    }
    let value = value.trim();
    let value = parse_override_value(value)
        .ok_or_else(|| bad(format!("`{value}` is neither a TOML value nor a bare word")))?;
    let (leaf, parents) = segments.split_last().expect("split yields one segment");
    let mut current = table;
    for (depth, segment) in parents.iter().enumerate() {
        let entry = current
            .entry(segment.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        current = match entry {
            toml::Value::Table(t) => t,
            _ => {
                return Err(bad(format!(
                    "`{}` is not a table",
                    segments[..=depth].join(".")
                )))
            }
        };
    }
    // A new plugin type starts from its own defaults, as with includes.
    if *leaf == "type" && current.get("type").is_some_and(|old| *old != value) {
        current.remove("params");
    }
    current.insert(leaf.to_string(), value);
    Ok(KeyPath::dotted(&segments.join(".")))
}

/// A `--set` value: a TOML value, else a bare word as a string; `None` for neither.
fn parse_override_value(text: &str) -> Option<toml::Value> {
    if let Ok(mut doc) = format!("v = {text}").parse::<toml::Table>() {
        if let Some(value) = doc.remove("v") {
            return Some(value);
        }
    }
    let is_bare_word = !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | '.' | '/' | ':' | '+'));
    is_bare_word.then(|| toml::Value::String(text.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Origin;

    const CONFIG: &str = r#"seed = 3

[robot]
length = 1.0

[planner]
type = "lazy-prm-star"

[planner.params]
max_stall = 3
"#;

    fn load(text: &str, overrides: &[&str]) -> Result<LoadedConfig, ConfigError> {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        LoadedConfig::from_text(text, "test.toml", Path::new("."), &overrides)
    }

    #[test]
    fn loads_sections_and_defaults() {
        let loaded = load(CONFIG, &[]).unwrap();
        let c = &loaded.config;
        assert_eq!(c.seed, 3);
        assert_eq!(c.robot.length, 1.0);
        assert_eq!(c.robot.width, RobotConfig::default().width);
        let planner = c.planner.as_ref().unwrap();
        assert_eq!(planner.key, "planner");
        assert_eq!(planner.params["max_stall"].as_integer(), Some(3));
        assert!(c.sampler.is_none());
    }

    #[test]
    fn misspelt_top_level_key_names_key_and_line() {
        let text = format!("{CONFIG}\n[samplr]\ntype = \"uniform\"\n");
        let err = load(&text, &[]).unwrap_err().to_string();
        assert!(
            err.starts_with("test.toml:12: `samplr`: unknown field `samplr`"),
            "{err}"
        );
    }

    #[test]
    fn wrong_type_names_key_and_line() {
        let err = load(&CONFIG.replace("length = 1.0", "length = \"long\""), &[])
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("test.toml:4: `robot.length`: invalid type"),
            "{err}"
        );
    }

    #[test]
    fn bad_robot_value_is_located() {
        let err = load(&CONFIG.replace("length = 1.0", "length = -1.0"), &[])
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("test.toml:4: `robot.length`: must be"),
            "{err}"
        );
    }

    #[test]
    fn syntax_errors_have_line_and_column() {
        let err = load("seed = 3\n[robot\n", &[]).unwrap_err();
        assert!(matches!(err, ConfigError::Syntax { line: 2, .. }), "{err}");
    }

    #[test]
    fn overrides_set_values_and_bare_words() {
        let loaded = load(
            CONFIG,
            &["planner.params.max_stall=5", "selector.type=dp", "seed = 9"],
        )
        .unwrap();
        let c = &loaded.config;
        assert_eq!(c.seed, 9);
        assert_eq!(c.selector.as_ref().unwrap().kind, "dp");
        assert_eq!(
            c.planner.as_ref().unwrap().params["max_stall"].as_integer(),
            Some(5)
        );
        let quoted = load(CONFIG, &["selector.type=\"idp\""]).unwrap();
        assert_eq!(quoted.config.selector.unwrap().kind, "idp");
        let switched = load(CONFIG, &["planner.type=other"]).unwrap();
        assert!(
            switched.config.planner.unwrap().params.is_empty(),
            "params of the old type leak"
        );
    }

    #[test]
    fn override_of_unknown_key_is_an_error_naming_it() {
        let err = load(CONFIG, &["robot.lenght=2"]).unwrap_err().to_string();
        assert!(
            err.starts_with("--set robot.lenght=2: `robot.lenght`: unknown field"),
            "{err}"
        );
    }

    #[test]
    fn malformed_overrides_are_rejected() {
        assert!(matches!(
            load(CONFIG, &["seed"]),
            Err(ConfigError::Override { .. })
        ));
        assert!(matches!(
            load(CONFIG, &["seed.x=1"]),
            Err(ConfigError::Override { .. })
        ));
        assert!(matches!(
            load(CONFIG, &["a..b=1"]),
            Err(ConfigError::Override { .. })
        ));
        assert!(matches!(
            load(CONFIG, &["seed=[1,"]),
            Err(ConfigError::Override { .. })
        ));
    }

    #[test]
    fn locates_plugin_params() {
        let loaded = load(CONFIG, &[]).unwrap();
        let origin = loaded
            .sources
            .locate(&KeyPath::dotted("planner.params.max_stall"));
        assert_eq!(
            origin,
            Origin::File {
                path: "test.toml".into(),
                line: 10
            }
        );
        let origin = loaded
            .sources
            .locate(&KeyPath::dotted("planner.params.missing"));
        assert_eq!(
            origin,
            Origin::File {
                path: "test.toml".into(),
                line: 9
            }
        );
    }

    #[test]
    fn includes_merge_beneath_and_replace_sections_of_another_type() {
        let dir = std::env::temp_dir().join(format!("smug-config-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("robot.toml"),
            "[robot]\nlength = 2.0\nwidth = 0.7\n[planner]\ntype = \"other\"\nparams = { x = 1 }\n",
        )
        .unwrap();
        std::fs::write(
            dir.join("main.toml"),
            format!("include = \"robot.toml\"\n{CONFIG}"),
        )
        .unwrap();
        let loaded = LoadedConfig::from_file(&dir.join("main.toml"), &[]).unwrap();
        let c = &loaded.config;
        assert_eq!(c.robot.length, 1.0, "the including file wins");
        assert_eq!(c.robot.width, 0.7, "included keys fill in");
        let planner = c.planner.as_ref().unwrap();
        assert!(
            planner.params.get("x").is_none(),
            "params of another plugin type leak"
        );
        let origin = loaded.sources.locate(&KeyPath::dotted("robot.width"));
        assert!(
            matches!(origin, Origin::File { ref path, line: 3 } if path.ends_with("robot.toml")),
            "{origin:?}"
        );

        std::fs::write(dir.join("loop.toml"), "include = \"loop.toml\"\n").unwrap();
        let err = LoadedConfig::from_file(&dir.join("loop.toml"), &[]).unwrap_err();
        assert!(matches!(err, ConfigError::Include { .. }), "{err}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
