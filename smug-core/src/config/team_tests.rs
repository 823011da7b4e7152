//! Team configs: robots layered above the shared keys, bad teams named by key.

use super::team::TeamUnit;
use super::LoadedConfig;
use crate::error::ConfigError;
use crate::stages::TeamObjective;
use std::path::Path;

const TEAM: &str = r#"seed = 2
[planner]
type = "lazy-prm-star"
[team]
objective = "makespan"
[[team.robots]]
name = "a"
start = { x = 1.0, y = 2.0 }
robot = { length = 2.0 }
[[team.robots]]
name = "b"
start = { x = 3.0, y = 2.0, yaw = 1.0 }
end = { x = 4.0, y = 2.0 }
planner = { type = "other" }
[[team.targets]]
id = "t1"
robots = ["b"]
"#;

fn load(text: &str) -> Result<LoadedConfig, ConfigError> {
    LoadedConfig::from_text(text, "team.toml", Path::new("."), &[])
}

#[test]
fn members_layer_their_sections_above_the_shared_ones() {
    let loaded = load(TEAM).unwrap();
    let team = loaded.config.team.as_ref().unwrap();
    assert_eq!(team.objective, TeamObjective::Makespan);
    assert_eq!(team.unit, TeamUnit::Time);
    assert_eq!(team.robots[1].end.unwrap().x, 4.0);
    let a = loaded.member(0).unwrap().unwrap();
    assert_eq!(a.config.robot.length, 2.0);
    assert_eq!(a.config.seed, 2);
    assert!(a.config.team.is_none());
    assert_eq!(a.config.planner.unwrap().kind, "lazy-prm-star");
    let b = loaded.member(1).unwrap().unwrap();
    assert_eq!(b.config.planner.unwrap().kind, "other");
    assert!(loaded.member(2).is_none());
}

#[test]
fn bad_teams_name_the_key() {
    let err = |text: &str| load(text).unwrap_err().to_string();
    let none = err("[team]\nobjective = \"sum\"\n");
    assert!(none.contains("`team.robots`: a team needs"), "{none}");
    let twice = err(&TEAM.replace("name = \"b\"", "name = \"a\""));
    assert!(
        twice.contains("`team.robots[1].name`: robot name `a` is used twice"),
        "{twice}"
    );
    let unknown = err(&TEAM.replace("robots = [\"b\"]", "robots = [\"c\"]"));
    assert!(
        unknown.contains("`team.targets[0].robots`: target `t1` is restricted to robot `c`"),
        "{unknown}"
    );
    let bad_key = load(&TEAM.replace("length = 2.0", "lenght = 2.0"))
        .unwrap()
        .member(0)
        .unwrap()
        .unwrap_err()
        .to_string();
    assert!(
        bad_key.contains("`team.robots[0].robot.lenght`: robot `a`: unknown field"),
        "{bad_key}"
    );
}
