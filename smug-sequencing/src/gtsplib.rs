//! A GTSP-LIB reader: TSPLIB files (read by [`crate::tsplib`]) with `GTSP_SETS: m` and a
//! `GTSP_SET_SECTION` of `m` records `set node node … -1` (1-based ids; a record may wrap
//! across lines). Set `k` becomes cluster `k − 1`, node `k` index `k − 1`.
//!
//! Tolerated quirks of the published files: `TYPE: GTSP (M.~Hofmeister)` (or `TSP …`
//! with sets), `GTSP_SET_SECTION:` with a colon.

use crate::tsplib::{file_stem, parse_with, read_text, Cursor, ProblemType, TsplibError};
use smug_core::{Clusters, CostMatrix};
use std::path::Path;

/// A GTSP-LIB instance: the TSPLIB instance and its clusters.
#[derive(Clone, Debug, PartialEq)]
pub struct GtspInstance {
    /// `NAME` (the file stem if absent).
    pub name: String,
    /// `TYPE` (GTSP reads as [`ProblemType::Tsp`]).
    pub problem: ProblemType,
    /// `COMMENT` lines, joined.
    pub comment: String,
    /// How the weights were given, e.g. `EUC_2D`.
    pub weights: String,
    /// Costs between nodes, diagonal 0.
    pub costs: CostMatrix,
    /// The sets, set `k` of the file as cluster `k − 1`.
    pub clusters: Clusters,
}

/// Reads a `.gtsp` file.
pub fn read_gtsplib(path: impl AsRef<Path>) -> Result<GtspInstance, TsplibError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    let mut instance = parse_gtsplib(&text, &path.display().to_string())?;
    if instance.name.is_empty() {
        instance.name = file_stem(path);
    }
    Ok(instance)
}

/// A node id of a set record and the line it is on.
type Member = (usize, usize);

/// The set keys as the parser meets them.
#[derive(Default)]
struct Sets {
    count: Option<usize>,
    records: Option<Vec<Vec<Member>>>,
}

/// Parses the text of a `.gtsp` file; `path` is only used in errors.
pub fn parse_gtsplib(text: &str, path: &str) -> Result<GtspInstance, TsplibError> {
    let mut sets = Sets::default();
    let instance = parse_with(text, path, &mut |cursor, line, key, value| match key {
        "GTSP_SETS" => {
            sets.count = Some(parse_count(cursor, line, value)?);
            Ok(true)
        }
        "GTSP_SET_SECTION" => {
            let m = sets
                .count
                .ok_or_else(|| cursor.syntax(line, "GTSP_SET_SECTION before GTSP_SETS"))?;
            sets.records = Some(read_sets(cursor, m)?);
            Ok(true)
        }
        _ => Ok(false),
    })?;
    let invalid = |message: String| TsplibError::Invalid {
        path: path.to_string(),
        message,
    };
    let records = match (sets.count, sets.records) {
        (None, _) => return Err(invalid("GTSP_SETS is missing: not a GTSP-LIB file".into())),
        (Some(_), None) => return Err(invalid("GTSP_SET_SECTION is missing".into())),
        (Some(_), Some(records)) => records,
    };
    let clusters = clusters_of(path, instance.costs.len(), records)?;
    Ok(GtspInstance {
        name: instance.name,
        problem: instance.problem,
        comment: instance.comment,
        weights: instance.weights,
        costs: instance.costs,
        clusters,
    })
}

fn parse_count(cursor: &Cursor, line: usize, value: &str) -> Result<usize, TsplibError> {
    value
        .parse::<usize>()
        .ok()
        .filter(|&m| (1..=crate::tsplib::MAX_DIMENSION).contains(&m))
        .ok_or_else(|| {
            cursor.syntax(
                line,
                format!(
                    "GTSP_SETS `{value}` is not an integer in 1..={} (no more sets than nodes)",
                    crate::tsplib::MAX_DIMENSION
                ),
            )
        })
}

/// `m` records `id node … -1`, ids 1..=m each once; returned by id.
fn read_sets(cursor: &mut Cursor, m: usize) -> Result<Vec<Vec<Member>>, TsplibError> {
    let mut records: Vec<Option<Vec<Member>>> = vec![None; m];
    let mut current: Option<(usize, Vec<Member>)> = None;
    let mut done = 0;
    while done < m {
        let ended = |cursor: &Cursor, done: usize| {
            cursor.invalid(format!(
                "GTSP_SET_SECTION: the file ends after {done} of {m} sets"
            ))
        };
        let Some((line, tokens)) = cursor.next_tokens() else {
            return Err(ended(cursor, done));
        };
        for token in tokens {
            if token.eq_ignore_ascii_case("EOF") {
                return Err(ended(cursor, done));
            }
            let value: i64 = token.parse().map_err(|_| {
                cursor.syntax(
                    line,
                    format!("GTSP_SET_SECTION: `{token}` is not an integer id"),
                )
            })?;
            match current.take() {
                None => {
                    let id = usize::try_from(value)
                        .ok()
                        .filter(|id| (1..=m).contains(id))
                        .ok_or_else(|| {
                            cursor.syntax(line, format!("set id {value} is not in 1..={m}"))
                        })?;
                    if records[id - 1].is_some() {
                        return Err(cursor.syntax(line, format!("set {id} appears twice")));
                    }
                    current = Some((id, Vec::new()));
                }
                Some((id, members)) if value == -1 => {
                    if members.is_empty() {
                        return Err(cursor.syntax(line, format!("set {id} is empty")));
                    }
                    records[id - 1] = Some(members);
                    done += 1;
                    if done == m {
                        break;
                    }
                }
                Some((id, mut members)) => {
                    let node =
                        usize::try_from(value)
                            .ok()
                            .filter(|&v| v >= 1)
                            .ok_or_else(|| {
                                cursor.syntax(
                                    line,
                                    format!("set {id}: node id {value} is not positive"),
                                )
                            })?;
                    members.push((node - 1, line));
                    current = Some((id, members));
                }
            }
        }
    }
    // m records with distinct ids in 1..=m cover every set.
    Ok(records.into_iter().map(Option::unwrap_or_default).collect())
}

/// The clusters of `n` nodes: every node in exactly one set.
fn clusters_of(path: &str, n: usize, records: Vec<Vec<Member>>) -> Result<Clusters, TsplibError> {
    let syntax = |line: usize, message: String| TsplibError::Syntax {
        path: path.to_string(),
        line,
        message,
    };
    let mut owner = vec![None; n];
    for (c, members) in records.iter().enumerate() {
        for &(v, line) in members {
            let slot = owner.get_mut(v).ok_or_else(|| {
                syntax(
                    line,
                    format!("set {}: node {} is not in 1..={n}", c + 1, v + 1),
                )
            })?;
            if let Some(other) = slot.replace(c) {
                return Err(syntax(
                    line,
                    format!("node {} is in sets {} and {}", v + 1, other + 1, c + 1),
                ));
            }
        }
    }
    if let Some(v) = owner.iter().position(Option::is_none) {
        return Err(TsplibError::Invalid {
            path: path.to_string(),
            message: format!("node {} is in no set of GTSP_SET_SECTION", v + 1),
        });
    }
    let members = records
        .into_iter()
        .map(|set| set.into_iter().map(|(v, _)| v).collect())
        .collect();
    Clusters::new(n, members).map_err(|e| TsplibError::Invalid {
        path: path.to_string(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "NAME : 3tiny6\nTYPE : GTSP (test)\nDIMENSION : 6\nGTSP_SETS : 3\n\
        EDGE_WEIGHT_TYPE : EUC_2D\nNODE_COORD_SECTION\n1 0 0\n2 3 4\n3 6 8\n4 0 5\n5 1 1\n\
        6 9 9\n";

    fn parse(sets: &str) -> Result<GtspInstance, TsplibError> {
        parse_gtsplib(&format!("{HEADER}{sets}EOF\n"), "t.gtsp")
    }

    #[test]
    fn reads_sets_as_clusters() {
        let instance = parse("GTSP_SET_SECTION:\n2 2 3 -1\n1 1\n 5 -1 3 4 6 -1\n").unwrap();
        assert_eq!(instance.name, "3tiny6");
        assert_eq!(instance.costs.get(0, 1), 5.0);
        assert_eq!(instance.clusters.len(), 3);
        assert_eq!(instance.clusters.members(0), &[0, 4]);
        assert_eq!(instance.clusters.members(1), &[1, 2]);
        assert_eq!(instance.clusters.of(5), 2);
    }

    #[test]
    fn a_set_count_beyond_any_dimension_is_refused_before_allocating() {
        // Found by `cargo fuzz run gtsplib`: 18446744073709551615 sets aborted on allocation.
        let text = HEADER.replace("GTSP_SETS : 3", "GTSP_SETS : 18446744073709551615");
        let err = parse_gtsplib(&format!("{text}GTSP_SET_SECTION\n1 1 -1\nEOF\n"), "t.gtsp")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("GTSP_SETS `18446744073709551615` is not an integer in 1..=20000"),
            "{err}"
        );
    }

    #[test]
    fn malformed_sets_name_the_line() {
        let err = |sets: &str| parse(sets).unwrap_err().to_string();
        assert_eq!(
            err("GTSP_SET_SECTION\n1 1 5 -1\n2 2 3 -1\n3 4 7 -1\n"),
            "t.gtsp:16: set 3: node 7 is not in 1..=6"
        );
        assert_eq!(
            err("GTSP_SET_SECTION\n1 1 5 -1\n2 2 3 -1\n3 4 5 6 -1\n"),
            "t.gtsp:16: node 5 is in sets 1 and 3"
        );
        assert_eq!(
            err("GTSP_SET_SECTION\n1 1 5 -1\n2 2 3 -1\n3 4 -1\n"),
            "t.gtsp: node 6 is in no set of GTSP_SET_SECTION"
        );
        assert_eq!(
            err("GTSP_SET_SECTION\n1 1 5 -1\n4 2 3 -1\n"),
            "t.gtsp:15: set id 4 is not in 1..=3"
        );
        assert_eq!(
            err("GTSP_SET_SECTION\n1 1 5 -1\n1 2 3 -1\n"),
            "t.gtsp:15: set 1 appears twice"
        );
        assert!(err("GTSP_SET_SECTION\n1 1 5 -1\n2 x -1\n").contains(":15: GTSP_SET_SECTION: `x`"));
        assert!(err("GTSP_SET_SECTION\n1 1 5 -1\n").contains("ends after 1 of 3 sets"));
        assert!(err("").contains("GTSP_SET_SECTION is missing"));
        let plain = "NAME: p\nTYPE: TSP\nDIMENSION: 1\nEDGE_WEIGHT_TYPE: EUC_2D\n\
                     NODE_COORD_SECTION\n1 0 0\n";
        assert!(parse_gtsplib(plain, "p.tsp")
            .unwrap_err()
            .to_string()
            .contains("GTSP_SETS is missing"));
        let early = "NAME: p\nGTSP_SET_SECTION\n";
        assert_eq!(
            parse_gtsplib(early, "e").unwrap_err().to_string(),
            "e:2: GTSP_SET_SECTION before GTSP_SETS"
        );
    }
}
