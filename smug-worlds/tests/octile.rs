//! Optimal octile lengths (8-connected, no corner cutting) against hand-built maps and
//! a brute-force relaxation; scenario generation; `.map` / `.scen` writer ↔ reader.

use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::movingai::{
    format_map, format_scenarios, generate_scenarios, octile_distances, octile_length, parse_map,
    parse_scenarios, MovingAiMap, SQRT_2,
};
use std::path::Path;

fn grid(rows: &[&str]) -> MovingAiMap {
    let text = format!(
        "type octile\nheight {}\nwidth {}\nmap\n{}\n",
        rows.len(),
        rows[0].len(),
        rows.join("\n")
    );
    parse_map(&text, Path::new("t.map")).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn known_lengths_on_hand_built_maps() {
    let corridor = grid(&["......."]);
    assert_eq!(octile_length(&corridor, [0, 0], [6, 0]), Some(6.0));
    let open = grid(&["....", "....", "....", "...."]);
    assert!(close(
        octile_length(&open, [0, 0], [3, 3]).unwrap(),
        3.0 * SQRT_2
    ));
    assert!(close(
        octile_length(&open, [0, 3], [3, 1]).unwrap(),
        1.0 + 2.0 * SQRT_2
    ));
    // One blocked side cell forbids the diagonal: around the corner costs 2, not √2.
    let corner = grid(&[".@", ".."]);
    assert_eq!(octile_length(&corner, [0, 0], [1, 1]), Some(2.0));
    let other_corner = grid(&["..", "@."]);
    assert_eq!(octile_length(&other_corner, [0, 0], [1, 1]), Some(2.0));
    // Both side cells blocked: no path at all (no squeezing between diagonal blocks).
    let squeeze = grid(&[".@", "@."]);
    assert_eq!(octile_length(&squeeze, [0, 0], [1, 1]), None);
    // A wall with a gap: around it through the gap.
    let wall = grid(&["...", "@@.", "..."]);
    // No corner cutting on either end of the gap: six straight steps.
    assert_eq!(octile_length(&wall, [0, 0], [0, 2]), Some(6.0));
}

/// Distances by relaxing every legal move until nothing changes (Bellman–Ford),
/// written without the library's move generator.
fn brute_force(m: &MovingAiMap, start: [usize; 2]) -> Vec<f64> {
    let (w, h) = (m.width as i64, m.height as i64);
    let free = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < w && y < h && m.is_passable(x as usize, y as usize)
    };
    let mut d = vec![f64::INFINITY; m.passable.len()];
    if !free(start[0] as i64, start[1] as i64) {
        return d;
    }
    d[start[1] * m.width + start[0]] = 0.0;
    loop {
        let mut changed = false;
        for y in 0..h {
            for x in 0..w {
                for dy in -1..=1i64 {
                    for dx in -1..=1i64 {
                        let (nx, ny) = (x + dx, y + dy);
                        if (dx, dy) == (0, 0) || !free(x, y) || !free(nx, ny) {
                            continue;
                        }
                        let diagonal = dx != 0 && dy != 0;
                        if diagonal && !(free(x + dx, y) && free(x, y + dy)) {
                            continue;
                        }
                        let cost = if diagonal { SQRT_2 } else { 1.0 };
                        let (from, to) = ((y * w + x) as usize, (ny * w + nx) as usize);
                        if d[from] + cost < d[to] - 1e-12 {
                            d[to] = d[from] + cost;
                            changed = true;
                        }
                    }
                }
            }
        }
        if !changed {
            return d;
        }
    }
}

#[test]
fn dijkstra_equals_brute_force_on_tiny_maps() {
    let mut compared = 0;
    for seed in 0..40 {
        let params = GridParams {
            density: 0.1 + 0.02 * (seed % 15) as f64,
            ..GridParams::new(GridFamily::Random, 7 + (seed % 3) as usize, 6, seed)
        };
        let m = generate(&params).unwrap();
        for start in [[0, 0], [3, 2], [6, 5]] {
            let (fast, slow) = (octile_distances(&m, start), brute_force(&m, start));
            for (i, (a, b)) in fast.iter().zip(&slow).enumerate() {
                assert!(
                    a == b || close(*a, *b),
                    "seed {seed} from {start:?}, cell {i}: {a} vs {b}"
                );
                compared += usize::from(a.is_finite());
            }
        }
    }
    assert!(compared > 2000, "{compared} finite distances compared");
}

#[test]
fn scenarios_join_connected_cells_at_their_optimal_length() {
    for family in GridFamily::ALL {
        let m = generate(&GridParams::new(family, 40, 30, 3)).unwrap();
        let scenarios = generate_scenarios(&m, "g.map", 60, 3).unwrap();
        assert_eq!(scenarios.len(), 60);
        assert_eq!(scenarios, generate_scenarios(&m, "g.map", 60, 3).unwrap());
        assert_ne!(scenarios, generate_scenarios(&m, "g.map", 60, 4).unwrap());
        assert!(scenarios.windows(2).all(|w| w[0].bucket <= w[1].bucket));
        for s in &scenarios {
            assert_ne!(s.start, s.goal);
            assert_eq!((s.width, s.height, s.map.as_str()), (40, 30, "g.map"));
            let length = octile_length(&m, s.start, s.goal).unwrap();
            assert!(close(length, s.optimal_length), "{family}: {s:?}");
            assert_eq!(s.bucket, (length / 4.0) as u32);
        }
    }
    let walled = grid(&[".@@", "@@."]);
    let err = generate_scenarios(&walled, "w.map", 1, 1)
        .unwrap_err()
        .to_string();
    assert!(err.contains("no two connected passable cells"), "{err}");
    assert!(generate_scenarios(&walled, "w.map", 0, 1)
        .unwrap()
        .is_empty());
}

#[test]
fn written_maps_and_scenarios_read_back_unchanged() {
    for family in GridFamily::ALL {
        let m = generate(&GridParams::new(family, 23, 17, 5)).unwrap();
        let text = format_map(&m);
        assert_eq!(parse_map(&text, Path::new("g.map")).unwrap(), m, "{family}");
        assert_eq!(
            format_map(&parse_map(&text, Path::new("g.map")).unwrap()),
            text
        );
        let scenarios = generate_scenarios(&m, "g.map", 25, 5).unwrap();
        let scen_text = format_scenarios(&scenarios);
        assert!(scen_text.starts_with("version 1\n"));
        let back = parse_scenarios(&scen_text, Path::new("g.scen")).unwrap();
        assert_eq!(back.len(), scenarios.len());
        for (a, b) in back.iter().zip(&scenarios) {
            assert_eq!(
                (a.bucket, &a.map, a.start, a.goal),
                (b.bucket, &b.map, b.start, b.goal)
            );
            assert!(
                (a.optimal_length - b.optimal_length).abs() <= 5e-9,
                "{a:?} vs {b:?}"
            );
        }
        assert_eq!(format_scenarios(&back), scen_text, "{family}");
    }
}
