//! The plugin registry: plugins register themselves with `inventory`, one entry type
//! per stage; lookup tables are built once, reject duplicate names, and name the known
//! plugins when asked for an unknown one.

use crate::config::KeyPath;
use crate::config::PluginSection;
use crate::context::BuildContext;
use crate::error::{RegistryError, Result};
use crate::stages::Sampler;
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// A pipeline stage: its config section name and the type its plugins build.
pub trait Stage: Sized + 'static {
    /// Config section and display name, e.g. `"sampler"`.
    const NAME: &'static str;
    /// What the stage does, one line.
    const SUMMARY: &'static str;
    /// What a plugin of this stage builds (usually `dyn Trait`).
    type Object: ?Sized + 'static;
    /// The stage's lookup table, built once from every linked plugin.
    fn registry() -> std::result::Result<&'static Registry<Self>, RegistryError>;
}

/// A built stage object and its fully resolved parameters (defaults filled in).
pub struct Built<S: Stage> {
    /// The object.
    pub object: Box<S::Object>,
    /// The parameters it was built with.
    pub params: toml::Table,
}

/// A registered plugin. Create entries with [`register_plugin!`](crate::register_plugin).
pub struct Plugin<S: Stage> {
    /// Name used in `type = "…"`.
    pub name: &'static str,
    /// One-line description for `smug plugins`.
    pub summary: &'static str,
    /// The parameters' defaults, for `smug plugins`.
    pub default_params: fn() -> toml::Table,
    /// Builds the stage object from its config section.
    pub build: fn(&PluginSection, &BuildContext) -> Result<Built<S>>,
    /// Checks the section's parameters as `build` reads them (unknown keys, wrong
    /// types), without building anything.
    pub check_params: fn(&PluginSection, &BuildContext) -> Result<()>,
}

/// One stage's plugins by name.
pub struct Registry<S: Stage> {
    plugins: BTreeMap<&'static str, &'static Plugin<S>>,
}

impl<S: Stage> Registry<S> {
    /// A table of `plugins`; two plugins with one name are an error.
    pub fn new(
        plugins: impl IntoIterator<Item = &'static Plugin<S>>,
    ) -> std::result::Result<Self, RegistryError> {
        let mut table = BTreeMap::new();
        for plugin in plugins {
            if table.insert(plugin.name, plugin).is_some() {
                return Err(RegistryError::Duplicate {
                    stage: S::NAME,
                    name: plugin.name.to_string(),
                });
            }
        }
        Ok(Self { plugins: table })
    }

    /// The plugin called `name`, or an error listing every known name.
    pub fn get(&self, name: &str) -> std::result::Result<&'static Plugin<S>, RegistryError> {
        self.plugins
            .get(name)
            .copied()
            .ok_or_else(|| RegistryError::Unknown {
                stage: S::NAME,
                name: name.to_string(),
                known: self.names().iter().map(|n| n.to_string()).collect(),
            })
    }

    /// Every registered name, sorted.
    pub fn names(&self) -> Vec<&'static str> {
        self.plugins.keys().copied().collect()
    }

    /// Every plugin, sorted by name.
    pub fn plugins(&self) -> impl Iterator<Item = &'static Plugin<S>> + '_ {
        self.plugins.values().copied()
    }
}

/// Serialises plugin parameters into a TOML table (for listings and `smug check`).
pub fn params_table<P: Serialize>(params: &P) -> toml::Table {
    match toml::Value::try_from(params) {
        Ok(toml::Value::Table(table)) => table,
        _ => toml::Table::new(),
    }
}

macro_rules! define_stage {
    ($(#[$doc:meta])* $marker:ident, $name:expr, $summary:literal, $object:ty) => {
        $(#[$doc])*
        pub enum $marker {}

        impl Stage for $marker {
            const NAME: &'static str = $name;
            const SUMMARY: &'static str = $summary;
            type Object = $object;

            fn registry() -> std::result::Result<&'static Registry<Self>, RegistryError> {
                static TABLE: OnceLock<std::result::Result<Registry<$marker>, RegistryError>> =
                    OnceLock::new();
                TABLE
                    .get_or_init(|| Registry::new(inventory::iter::<Plugin<$marker>>))
                    .as_ref()
                    .map_err(Clone::clone)
            }
        }

        inventory::collect!(Plugin<$marker>);
    };
}

macro_rules! define_stages {
    ($($(#[$doc:meta])* $key:ident: $marker:ident = $summary:literal, $object:ty, $default:expr;)*) => {
        $(define_stage!(
            #[doc = concat!("The `", stringify!($key), "` stage: ", $summary, ".")]
            $marker, stringify!($key), $summary, $object
        );)*

        /// Every stage's config key, in pipeline order.
        pub const STAGE_KEYS: &[&str] = &[$(stringify!($key)),*];

        /// Checks that every stage section of `config` names a registered plugin whose
        /// parameters read (unknown keys, wrong types: errors name the key), without
        /// building anything.
        pub fn check_sections(
            config: &crate::config::PipelineConfig,
            ctx: &BuildContext,
        ) -> Result<()> {
            for section in config.sections() {
                match section.key.as_str() {
                    $(stringify!($key) => ctx.check_params::<$marker>(section)?,)*
                    _ => {}
                }
            }
            Ok(())
        }

        /// Every stage with its registered plugins, in pipeline order.
        pub fn catalogue() -> std::result::Result<Vec<StageInfo>, RegistryError> {
            Ok(vec![$(stage_info::<$marker>()?),*])
        }
    };
}

stage_table!(define_stages);

/// A plugin as listed by `smug plugins`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PluginInfo {
    /// Name used in `type = "…"`.
    pub name: &'static str,
    /// One line.
    pub summary: &'static str,
    /// Parameters and their defaults.
    pub params: toml::Table,
}

/// One stage and its plugins, as listed by `smug plugins`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StageInfo {
    /// Stage name (config section).
    pub stage: &'static str,
    /// What the stage does.
    pub summary: &'static str,
    /// Its plugins, sorted by name.
    pub plugins: Vec<PluginInfo>,
}

fn stage_info<S: Stage>() -> std::result::Result<StageInfo, RegistryError> {
    Ok(StageInfo {
        stage: S::NAME,
        summary: S::SUMMARY,
        plugins: S::registry()?
            .plugins()
            .map(|p| PluginInfo {
                name: p.name,
                summary: p.summary,
                params: (p.default_params)(),
            })
            .collect(),
    })
}

/// Building stages by name through the registry (beside it: the context only
/// carries what builders use).
impl BuildContext {
    /// A new sampler built from the config's `[sampler]` section.
    pub fn new_sampler(&self) -> Result<Box<dyn Sampler>> {
        let section = self
            .sampler
            .as_ref()
            .ok_or_else(|| self.missing(SamplerStage::NAME))?;
        Ok(self.build::<SamplerStage>(section)?.object)
    }

    /// Builds `section` with the plugin it names; an unknown name is an error that
    /// lists the known ones and points at the `type` line.
    pub fn build<S: Stage>(&self, section: &PluginSection) -> Result<Built<S>> {
        let plugin = self.plugin::<S>(section)?;
        let mut ctx = self.clone();
        ctx.building = section.key.clone();
        (plugin.build)(section, &ctx)
    }

    /// Checks `section`'s plugin name and parameters without building it.
    pub fn check_params<S: Stage>(&self, section: &PluginSection) -> Result<()> {
        (self.plugin::<S>(section)?.check_params)(section, self)
    }

    /// The plugin `section` names; an unknown name is an error that lists the known
    /// ones and points at the `type` line.
    fn plugin<S: Stage>(&self, section: &PluginSection) -> Result<&'static Plugin<S>> {
        S::registry()?.get(&section.kind).map_err(|err| {
            let key = KeyPath::dotted(&section.key).join("type");
            self.sources.key_error(&key, err.to_string()).into()
        })
    }
}

/// Registers a plugin for a stage. The parameters type must implement
/// `Deserialize + Serialize + Default` and should carry `#[serde(deny_unknown_fields)]`;
/// the builder is a non-capturing closure `|params, ctx| -> Result<Box<Object>>`.
///
/// ```ignore
/// smug_core::register_plugin!(
///     smug_core::registry::SamplerStage,
///     name = "uniform",
///     summary = "uniform SE(2) samples within the map bounds",
///     params = UniformParams,
///     build = |params, ctx| Ok(Box::new(Uniform::new(params, ctx.rng("sampler")))),
/// );
/// ```
#[macro_export]
macro_rules! register_plugin {
    ($stage:ty, name = $name:expr, summary = $summary:expr, params = $params:ty, build = $build:expr $(,)?) => {
        const _: () = {
            fn __smug_default_params() -> $crate::toml::Table {
                $crate::registry::params_table(&<$params as ::core::default::Default>::default())
            }

            fn __smug_check_params(
                section: &$crate::config::PluginSection,
                ctx: &$crate::context::BuildContext,
            ) -> $crate::Result<()> {
                ctx.params::<$params>(section).map(|_| ())
            }

            fn __smug_build(
                section: &$crate::config::PluginSection,
                ctx: &$crate::context::BuildContext,
            ) -> $crate::Result<$crate::registry::Built<$stage>> {
                let params: $params = ctx.params(section)?;
                let resolved = $crate::registry::params_table(&params);
                let builder: fn(
                    $params,
                    &$crate::context::BuildContext,
                ) -> $crate::Result<
                    ::std::boxed::Box<<$stage as $crate::registry::Stage>::Object>,
                > = $build;
                Ok($crate::registry::Built {
                    object: builder(params, ctx)?,
                    params: resolved,
                })
            }

            $crate::inventory::submit! {
                $crate::registry::Plugin::<$stage> {
                    name: $name,
                    summary: $summary,
                    default_params: __smug_default_params,
                    build: __smug_build,
                    check_params: __smug_check_params,
                }
            }
        };
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_params() -> toml::Table {
        toml::Table::new()
    }

    fn no_check(_: &PluginSection, _: &BuildContext) -> Result<()> {
        Ok(())
    }

    fn never_built(_: &PluginSection, _: &BuildContext) -> Result<Built<SequencerStage>> {
        Err(crate::Error::InvalidInput("test plugin".into()))
    }

    static FIRST: Plugin<SequencerStage> = Plugin {
        name: "twin",
        summary: "first",
        default_params: no_params,
        build: never_built,
        check_params: no_check,
    };
    static SECOND: Plugin<SequencerStage> = Plugin {
        name: "twin",
        summary: "second",
        default_params: no_params,
        build: never_built,
        check_params: no_check,
    };
    static OTHER: Plugin<SequencerStage> = Plugin {
        name: "other",
        summary: "other",
        default_params: no_params,
        build: never_built,
        check_params: no_check,
    };

    #[test]
    fn duplicate_names_are_rejected() {
        let err = Registry::new([&FIRST, &OTHER, &SECOND]).err().unwrap();
        assert_eq!(
            err,
            RegistryError::Duplicate {
                stage: "sequencer",
                name: "twin".into()
            }
        );
        assert_eq!(
            err.to_string(),
            "sequencer plugin `twin` is registered twice"
        );
    }

    #[test]
    fn unknown_names_list_the_known_ones() {
        let registry = Registry::new([&FIRST, &OTHER]).unwrap();
        assert_eq!(registry.get("twin").unwrap().summary, "first");
        let message = registry.get("twn").err().unwrap().to_string();
        assert_eq!(
            message,
            "unknown sequencer plugin `twn`; known sequencer plugins: other, twin"
        );
    }

    #[test]
    fn the_global_tables_hold_the_core_space_and_objective() {
        let spaces = SpaceStage::registry().unwrap();
        assert!(spaces.names().contains(&"se2"));
        let params = (spaces.get("se2").unwrap().default_params)();
        assert_eq!(params["rotation_weight"].as_float(), Some(0.5));
        let objectives = ObjectiveStage::registry().unwrap();
        let params = (objectives.get("path-length").unwrap().default_params)();
        assert_eq!(params["rotation_weight"].as_float(), Some(0.5));
        assert!(catalogue().unwrap().iter().any(|s| s.stage == "planner"));
    }
}
