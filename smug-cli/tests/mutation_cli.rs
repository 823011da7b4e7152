//! Mutation test: random edits of the shipped configs, map files and TSPLIB samples
//! (extreme numbers, deleted, doubled or truncated lines, flipped bytes) with a fixed
//! seed. Every run must end within its bound with exit 0, 1 or 2 — never a panic, a
//! signal or a hang. A failing case leaves its input in `target/mutation/`.

mod common;

use common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Values that have broken parsers and solvers before.
const EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "5e-324",
    "-0.0",
    "0",
    "-1",
    "1e18",
    "18446744073709551615",
    "nan",
    "inf",
    "1e-300",
    "1e9",
];

/// Cases per test and the seed: `SMUG_MUTATION_CASES` / `SMUG_MUTATION_SEED` override
/// the CI defaults for longer exploratory runs.
fn cases_and_seed(cases: usize, seed: u64) -> (usize, u64) {
    let var = |name: &str| std::env::var(name).ok().and_then(|v| v.parse().ok());
    (
        var("SMUG_MUTATION_CASES").map_or(cases, |n: u64| n as usize),
        var("SMUG_MUTATION_SEED").unwrap_or(seed),
    )
}

/// A run's wall-time bound: `--deadline 2` plus its grace, world building and start-up.
const BOUND: Duration = Duration::from_secs(20);

/// A mutated copy of `text`: one of five edits at a random place.
fn mutate_text(text: &str, rng: &mut ChaCha8Rng) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let at = rng.random_range(0..lines.len().max(1));
    match rng.random_range(0..5) {
        0 | 1 => replace_a_number(text, rng),
        2 => without_line(&lines, at),
        3 => {
            let mut out: Vec<&str> = lines.clone();
            if let Some(&line) = lines.get(at) {
                out.insert(at, line);
            }
            out.join("\n")
        }
        _ => {
            let cut = rng.random_range(0..=text.len());
            let cut = (0..=cut)
                .rev()
                .find(|&i| text.is_char_boundary(i))
                .unwrap_or(0);
            text[..cut].to_string()
        }
    }
}

fn without_line(lines: &[&str], at: usize) -> String {
    let kept: Vec<&str> = (0..lines.len())
        .filter(|&i| i != at)
        .map(|i| lines[i])
        .collect();
    kept.join("\n")
}

/// Replaces one number of `text` (a run of digits, with its sign, point and exponent)
/// with an extreme value.
fn replace_a_number(text: &str, rng: &mut ChaCha8Rng) -> String {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric()) {
            let start = if i > 0 && bytes[i - 1] == b'-' {
                i - 1
            } else {
                i
            };
            let mut end = i;
            while end < bytes.len()
                && (bytes[end].is_ascii_digit() || b".eE+-".contains(&bytes[end]))
            {
                end += 1;
            }
            spans.push((start, end));
            i = end;
        } else {
            i += 1;
        }
    }
    if spans.is_empty() {
        return text.to_string();
    }
    let (start, end) = spans[rng.random_range(0..spans.len())];
    let value = EXTREMES[rng.random_range(0..EXTREMES.len())];
    format!("{}{value}{}", &text[..start], &text[end..])
}

/// A copy of `bytes` with a few bytes flipped or cut short (binary images).
fn mutate_bytes(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    if rng.random_bool(0.3) {
        out.truncate(rng.random_range(0..=out.len()));
        return out;
    }
    for _ in 0..rng.random_range(1..4) {
        if !out.is_empty() {
            let k = rng.random_range(0..out.len().min(64));
            out[k] = rng.random();
        }
    }
    out
}

/// A fresh case directory with the shipped robot profiles and maps beside the config.
fn case_dir(name: &str) -> PathBuf {
    let dir = workspace().join("target/mutation").join(name);
    std::fs::remove_dir_all(&dir).ok();
    for sub in ["robots", "maps"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        for entry in std::fs::read_dir(workspace().join("configs").join(sub)).unwrap() {
            let path = entry.unwrap().path();
            std::fs::copy(&path, dir.join(sub).join(path.file_name().unwrap())).unwrap();
        }
    }
    dir
}

/// Runs `smug args` and checks it ended in bounds; returns its exit code.
fn run_bounded(case: &Path, args: &[&str]) -> i32 {
    let started = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(args)
        .current_dir(case)
        .output()
        .expect("the smug binary runs");
    let elapsed = started.elapsed();
    let err = stderr(&out);
    let code = out.status.code();
    assert!(
        matches!(code, Some(0..=2)) && !err.contains("panicked"),
        "{}: smug {} ended with {code:?}: {err}",
        case.display(),
        args.join(" ")
    );
    assert!(
        elapsed < BOUND,
        "{}: smug {} took {elapsed:?}",
        case.display(),
        args.join(" ")
    );
    if code != Some(2) {
        std::fs::remove_dir_all(case).ok(); // keep only what may need a look
    }
    code.unwrap()
}

/// `smug plan` on a mutated config or map file, bounded by a deadline and 0.5 GB.
fn plan_case(name: &str, config: &str) -> i32 {
    let case = workspace().join("target/mutation").join(name);
    let config = case.join(config);
    run_bounded(
        &case,
        &[
            "plan",
            config.to_str().unwrap(),
            "--deadline",
            "2",
            "--set",
            "limits.memory_gb=0.5",
            "--out",
            case.join("out").to_str().unwrap(),
        ],
    )
}

#[test]
fn mutated_configs_and_maps_never_panic_or_hang() {
    let (cases, seed) = cases_and_seed(100, 2026);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let configs = [
        "flat-demo.toml",
        "lunar.toml",
        "indoor-disc.toml",
        "flat-dubins.toml",
        "imported-map.toml",
    ];
    let map_files = [
        "random-32x32-d10-s1.yaml",
        "random-32x32-d10-s1.mission.toml",
        "random-32x32-d10-s1.pgm",
    ];
    let mut codes = [0usize; 3];
    for k in 0..cases {
        let name = format!("plan-{k}");
        let dir = case_dir(&name);
        let config = configs[k % configs.len()];
        std::fs::copy(workspace().join("configs").join(config), dir.join(config)).unwrap();
        let (target, config) = if k % 3 == 2 {
            let file = map_files[rng.random_range(0..map_files.len())];
            (dir.join("maps").join(file), "imported-map.toml")
        } else {
            (dir.join(config), config)
        };
        if config == "imported-map.toml" {
            std::fs::copy(workspace().join("configs").join(config), dir.join(config)).unwrap();
        }
        let original = std::fs::read(&target).unwrap();
        let mutated = match std::str::from_utf8(&original) {
            Ok(text) if !target.to_string_lossy().ends_with(".pgm") => {
                mutate_text(text, &mut rng).into_bytes()
            }
            _ => mutate_bytes(&original, &mut rng),
        };
        std::fs::write(&target, mutated).unwrap();
        codes[plan_case(&name, config) as usize] += 1;
    }
    // The edits must reach both sides: some runs still plan, some are refused.
    eprintln!("plan exit codes 0/1/2: {codes:?}");
    assert!(codes[0] > 0 && codes[2] > 0, "exit codes 0/1/2: {codes:?}");
}

#[test]
fn mutated_tsplib_files_never_panic_or_hang() {
    let (cases, seed) = cases_and_seed(200, 2027);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let data = workspace().join("smug-sequencing/tests/data");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&data)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "tsp" || e == "atsp"))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "the TSPLIB samples: {files:?}");
    let mut codes = [0usize; 3];
    for k in 0..cases {
        let source = &files[k % files.len()];
        let case = workspace().join("target/mutation").join(format!("tsp-{k}"));
        std::fs::create_dir_all(&case).unwrap();
        let text = std::fs::read_to_string(source).unwrap();
        let file = case.join(source.file_name().unwrap());
        std::fs::write(&file, mutate_text(&text, &mut rng)).unwrap();
        let code = run_bounded(
            &case,
            &["tsp", file.to_str().unwrap(), "--time-limit", "0.05"],
        );
        codes[code as usize] += 1;
    }
    assert!(codes[0] > 0 && codes[2] > 0, "exit codes 0/1/2: {codes:?}");
}
