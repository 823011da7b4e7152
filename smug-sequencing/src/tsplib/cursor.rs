//! The lines of a TSPLIB file with a cursor, and the `DIMENSION` key both the
//! instance and the tour readers take.

use super::error::TsplibError;

/// A number of a section and the line it is on.
pub(crate) type Located = (f64, usize);

/// The lines of a file with a cursor; errors carry the file and line.
pub(crate) struct Cursor<'a> {
    path: &'a str,
    pub(crate) lines: Vec<&'a str>,
    pub(crate) next: usize,
}

impl<'a> Cursor<'a> {
    pub(crate) fn new(text: &'a str, path: &'a str) -> Self {
        Self {
            path,
            lines: text.lines().collect(),
            next: 0,
        }
    }

    pub(crate) fn syntax(&self, line: usize, message: impl Into<String>) -> TsplibError {
        TsplibError::Syntax {
            path: self.path.to_string(),
            line,
            message: message.into(),
        }
    }

    pub(crate) fn invalid(&self, message: impl Into<String>) -> TsplibError {
        TsplibError::Invalid {
            path: self.path.to_string(),
            message: message.into(),
        }
    }

    /// The next non-blank line and its number, as `(KEY, value)`.
    pub(crate) fn next_entry(&mut self) -> Option<(usize, String, &'a str)> {
        while let Some(line) = self.lines.get(self.next).copied() {
            self.next += 1;
            let line = line.trim();
            if line.is_empty() {
                continue;
            }
            let (key, value) = match line.split_once(':') {
                Some((key, value)) => (key.trim(), value.trim()),
                None => match line.split_once(char::is_whitespace) {
                    Some((key, value)) => (key, value.trim()),
                    None => (line, ""),
                },
            };
            return Some((self.next, key.to_ascii_uppercase(), value));
        }
        None
    }

    /// The whitespace-separated tokens of the next line and its number, `None` at the end.
    pub(crate) fn next_tokens(&mut self) -> Option<(usize, std::str::SplitWhitespace<'a>)> {
        let line = self.lines.get(self.next).copied()?;
        self.next += 1;
        Some((self.next, line.split_whitespace()))
    }

    /// The next `count` numbers, which may span any number of lines. `what` names the
    /// section in errors.
    pub(crate) fn numbers(
        &mut self,
        count: usize,
        what: &str,
    ) -> Result<Vec<Located>, TsplibError> {
        let mut out = Vec::with_capacity(count.min(1 << 20));
        let start_line = self.next;
        while out.len() < count {
            let Some(line) = self.lines.get(self.next).copied() else {
                return Err(self.syntax(
                    self.next.max(start_line),
                    format!(
                        "{what}: the file ends after {} of {count} numbers",
                        out.len()
                    ),
                ));
            };
            self.next += 1;
            let line_no = self.next;
            for token in line.split_whitespace() {
                if out.len() == count {
                    return Err(self.syntax(
                        line_no,
                        format!("{what}: unexpected `{token}` after the {count} expected numbers"),
                    ));
                }
                let value = token
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        self.syntax(
                            line_no,
                            format!(
                                "{what}: `{token}` is not a number (found {} of {count})",
                                out.len()
                            ),
                        )
                    })?;
                out.push((value, line_no));
            }
        }
        Ok(out)
    }
}

/// Largest `DIMENSION` accepted: the matrix is dense (20 000 nodes take 3.2 GB).
pub const MAX_DIMENSION: usize = 20_000;

/// `DIMENSION`'s value: a positive integer up to [`MAX_DIMENSION`].
pub(crate) fn parse_dimension(
    cursor: &Cursor,
    line: usize,
    value: &str,
) -> Result<usize, TsplibError> {
    let n = value
        .parse::<usize>()
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| {
            cursor.syntax(
                line,
                format!("DIMENSION `{value}` is not a positive integer"),
            )
        })?;
    if n > MAX_DIMENSION {
        return Err(cursor.syntax(
            line,
            format!("DIMENSION {n} is above the {MAX_DIMENSION} nodes a dense matrix allows here"),
        ));
    }
    Ok(n)
}
