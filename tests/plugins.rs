//! Cross-crate plugin tests: the registry sees every linked plugin crate, and an
//! out-of-tree plugin is selectable by name from a config.

use smug_core::registry::catalogue;
use smug_core::{LoadedConfig, Pipeline};
use std::path::Path;

// Link the built-in plugins (through smug-app) and the out-of-tree examples.
use smug_app as _;
use smug_example_objective as _;
use smug_example_traversability as _;

const CONFIG: &str = r#"
seed = 5

[world]
type = "flat"
[world.params]
size = [6.0, 4.0]
resolution = 0.1
obstacles = [{ min = [3.0, 0.0], max = [6.0, 4.0], height = 0.2 }]
[world.params.mission]
start = { x = 1.0, y = 1.0 }

[traversability]
type = "example-slope"
params = { critical_slope = 0.5 }
"#;

#[test]
fn registries_have_no_duplicates_and_list_the_linked_plugins() {
    let stages = catalogue().expect("no plugin name is registered twice");
    let names: Vec<&str> = stages
        .iter()
        .flat_map(|s| s.plugins.iter().map(|p| p.name))
        .collect();
    for name in [
        "se2",
        "flat",
        "example-slope",
        "uniform",
        "informed",
        "discrete",
        "brute-force",
    ] {
        assert!(names.contains(&name), "{name} is not registered: {names:?}");
    }
}

#[test]
fn a_config_selects_the_out_of_tree_estimator_by_name() {
    let loaded = LoadedConfig::from_text(CONFIG, "example.toml", Path::new("."), &[]).unwrap();
    let pipeline = Pipeline::assemble(&loaded).unwrap();
    let world = pipeline.world.as_ref().unwrap();
    let layer = world
        .traversability
        .as_ref()
        .expect("the estimator filled the layer");
    assert_eq!(layer.geometry, world.elevation.geometry);
    // Flat away from the step: fully traversable; at the 0.2 m step over one cell: not.
    assert_eq!(layer.nearest(1.0, 2.0), Some(1.0));
    assert_eq!(layer.nearest(5.0, 2.0), Some(1.0));
    assert_eq!(layer.nearest(2.95, 2.0), Some(0.0));
    let resolved = &pipeline
        .resolved
        .iter()
        .find(|s| s.key == "traversability")
        .unwrap();
    assert_eq!(resolved.plugin, "example-slope");
    assert_eq!(resolved.params["critical_slope"].as_float(), Some(0.5));
}

#[test]
fn the_out_of_tree_plugin_validates_its_parameters() {
    let text = CONFIG.replace("critical_slope = 0.5", "critical_slop = 0.5");
    let loaded = LoadedConfig::from_text(&text, "example.toml", Path::new("."), &[]).unwrap();
    let err = Pipeline::assemble(&loaded).err().unwrap().to_string();
    assert!(
        err.starts_with("example.toml:15: `traversability.params.critical_slop`: unknown field"),
        "{err}"
    );
    let text = CONFIG.replace("critical_slope = 0.5", "critical_slope = 0.0");
    let loaded = LoadedConfig::from_text(&text, "example.toml", Path::new("."), &[]).unwrap();
    let err = Pipeline::assemble(&loaded).err().unwrap().to_string();
    assert!(err.contains("critical_slope must be > 0"), "{err}");
}

#[test]
fn a_config_plans_with_the_out_of_tree_objective() {
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("../configs/lunar.toml");
    let set = [
        "objective.type=\"example-steepness\"".to_string(),
        "objective.params.penalty=4.0".to_string(),
        "plan.sequencing_costs=\"lazy\"".to_string(),
    ];
    let loaded = LoadedConfig::from_file(&config, &set).unwrap();
    let mut pipeline = Pipeline::assemble(&loaded).unwrap();
    let plan = smug_mission::plan_mission(&mut pipeline, loaded.config.plan).unwrap();
    assert_eq!(plan.metrics.objective, "example-steepness");
    let evaluated = plan.metrics.costs["example-steepness"];
    assert!(
        (evaluated - plan.cost).abs() <= 1e-9 * plan.cost,
        "{evaluated} vs {}",
        plan.cost
    );
    assert!(
        plan.cost >= plan.metrics.length_m,
        "every metre costs at least a metre"
    );
}
