//! One outcome for every planning command: solved, or no solution and why; errors are
//! [`AppError`](crate::AppError)s beside it.

use smug_mission::{CutOff, NoTargetLeft, Unreachable};

/// What a planning command found; `W` says why there is no solution (a
/// [`NoSolution`], or a `NoPlan` with the report plan.json gets).
#[derive(Debug)]
pub enum Outcome<T, W = NoSolution> {
    /// A solution (the CLI's exit 0).
    Solved(T),
    /// The pipeline ran but found no solution (the CLI's exit 1; Python's `NoSolution`).
    NoSolution {
        /// Why.
        why: W,
    },
}

/// Why there is no solution.
#[derive(Debug)]
pub enum NoSolution {
    /// Some targets cannot be reached (the message names them).
    Unreachable(String),
    /// A replan has no target left to visit.
    NoTargetLeft(String),
    /// The run's deadline passed before a complete plan was found.
    DeadlinePassed(String),
}

impl std::fmt::Display for NoSolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Unreachable(why) | Self::NoTargetLeft(why) | Self::DeadlinePassed(why) => {
                f.write_str(why)
            }
        }
    }
}

impl<T> Outcome<T> {
    /// Sorts a library result: unreachable targets, no target left and a passed
    /// deadline are no solution; other errors stay errors.
    pub fn of(result: smug_core::Result<T>) -> smug_core::Result<Self> {
        match result {
            Ok(value) => Ok(Self::Solved(value)),
            Err(err) => match NoSolution::of(&err) {
                Some(why) => Ok(Self::NoSolution { why }),
                None => Err(err),
            },
        }
    }
}

impl<T, W> Outcome<T, W> {
    /// The solution, if any.
    pub fn solved(self) -> Option<T> {
        match self {
            Self::Solved(value) => Some(value),
            Self::NoSolution { .. } => None,
        }
    }

    /// The same outcome with the reason for no solution mapped by `f`.
    pub fn map_no_solution<V>(self, f: impl FnOnce(W) -> V) -> Outcome<T, V> {
        match self {
            Self::Solved(value) => Outcome::Solved(value),
            Self::NoSolution { why } => Outcome::NoSolution { why: f(why) },
        }
    }
}

impl NoSolution {
    /// The no-solution reading of a library error, if it is one.
    pub fn of(err: &smug_core::Error) -> Option<Self> {
        match err {
            smug_core::Error::Stage { source, .. }
                if source.is::<Unreachable>() || source.is::<CutOff>() =>
            {
                Some(Self::Unreachable(source.to_string()))
            }
            smug_core::Error::Stage { source, .. } if source.is::<NoTargetLeft>() => {
                Some(Self::NoTargetLeft(source.to_string()))
            }
            smug_core::Error::DeadlinePassed { .. } => Some(Self::DeadlinePassed(err.to_string())),
            _ => None,
        }
    }
}

/// The error and its causes on one line; a cause whose text the message already holds
/// (library errors print their sources) is not repeated.
pub fn one_line(err: &(dyn std::error::Error + 'static)) -> String {
    let mut message = String::new();
    let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(err);
    while let Some(err) = cause {
        let text = err.to_string();
        if !message.contains(&text) {
            if !message.is_empty() {
                message.push_str(": ");
            }
            message.push_str(&text);
        }
        cause = err.source();
    }
    message.replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unreachable_targets_and_a_passed_deadline_are_no_solution() {
        let unreachable = smug_core::Error::stage(
            "sequencing",
            Unreachable {
                targets: vec!["t1".into()],
                why: Vec::new(),
                legs: Vec::new(),
            },
        );
        let outcome = Outcome::<()>::of(Err(unreachable)).unwrap();
        let Outcome::NoSolution { why } = outcome else {
            panic!("expected no solution");
        };
        assert!(matches!(why, NoSolution::Unreachable(_)));
        assert_eq!(why.to_string(), "no safe path reaches target(s) `t1`");
        let deadline = smug_core::Error::DeadlinePassed {
            seconds: 1.0,
            during: "sequencing".into(),
        };
        let outcome = Outcome::<()>::of(Err(deadline)).unwrap();
        assert!(matches!(
            outcome,
            Outcome::NoSolution {
                why: NoSolution::DeadlinePassed(_)
            }
        ));
        let other = smug_core::Error::InvalidInput("bad".into());
        assert!(Outcome::<()>::of(Err(other)).is_err());
        assert_eq!(Outcome::of(Ok(3)).unwrap().solved(), Some(3));
    }

    #[test]
    fn one_line_does_not_repeat_causes_the_message_holds() {
        let err = smug_core::Error::stage("world", std::io::Error::other("gone"));
        assert_eq!(one_line(&err), "world: gone");
    }
}
