//! `smug plan` in the joint mode (`[plan] mode = "joint"`): order and PoIs chosen
//! together by a GTSP sequencer.

mod common;

use common::{assert_bad_input, smug, stderr, stdout, workspace};

/// A config that includes the flat demo and switches it to the joint mode with the
/// sequencer `sequencer`.
fn joint_config(label: &str, sequencer: &str) -> String {
    let dir = workspace()
        .join("target")
        .join(format!("cli-test-joint-{label}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let demo = workspace().join("configs/flat-demo.toml");
    let text = format!(
        "include = {:?}\n\n[plan]\nmode = \"joint\"\n\n[sequencer]\ntype = \"{sequencer}\"\n",
        demo.to_str().unwrap()
    );
    let config = dir.join("joint.toml");
    std::fs::write(&config, text).unwrap();
    config.to_str().unwrap().to_string()
}

#[test]
fn joint_mode_plans_every_target_with_a_gtsp_sequencer() {
    for sequencer in ["gtsp-exact", "gtsp-lns", "auto"] {
        let config = joint_config(sequencer, sequencer);
        let out = workspace()
            .join("target")
            .join(format!("cli-test-joint-out-{sequencer}"));
        let run = smug(&["plan", &config, "--out", out.to_str().unwrap()]);
        assert_eq!(run.status.code(), Some(0), "{sequencer}: {}", stderr(&run));
        assert!(
            stdout(&run).contains("planned 3 targets"),
            "{}",
            stdout(&run)
        );
        let plan: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
        assert_eq!(plan["sequence"].as_array().unwrap().len(), 3);
        assert!(plan["cost"].as_f64().unwrap().is_finite());
    }
}

#[test]
fn joint_mode_with_a_tsp_only_sequencer_is_exit_2_naming_the_gtsp_solvers() {
    let config = joint_config("held-karp", "held-karp");
    let run = smug(&[
        "plan",
        &config,
        "--out",
        "target/cli-test-joint-held-karp-out",
    ]);
    assert_bad_input(&run, &["gtsp-lns", "gtsp-exact"]);
}
