//! The `.tour` reader: a `TOUR_SECTION` of 1-based node ids ended by -1.

use super::cursor::{parse_dimension, Cursor};
use super::error::TsplibError;

/// Parses the text of a `.tour` file (`TOUR_SECTION` of 1-based ids ended by -1):
/// the order as 0-based indices.
pub fn parse_tour(text: &str, path: &str) -> Result<Vec<usize>, TsplibError> {
    let mut cursor = Cursor::new(text, path);
    let mut dimension = None;
    while let Some((line, key, value)) = cursor.next_entry() {
        match key.as_str() {
            "DIMENSION" => dimension = Some(parse_dimension(&cursor, line, value)?),
            "TOUR_SECTION" => return read_tour_section(&mut cursor, dimension),
            "EOF" => break,
            _ => {}
        }
    }
    Err(cursor.invalid("TOUR_SECTION is missing"))
}

fn read_tour_section(
    cursor: &mut Cursor,
    dimension: Option<usize>,
) -> Result<Vec<usize>, TsplibError> {
    let mut order = Vec::new();
    while let Some(line) = cursor.lines.get(cursor.next).copied() {
        cursor.next += 1;
        let line_no = cursor.next;
        for token in line.split_whitespace() {
            let id: i64 = token
                .parse()
                .map_err(|_| cursor.syntax(line_no, format!("`{token}` is not a node id")))?;
            if id == -1 {
                return check_permutation(cursor, order, dimension);
            }
            let index = usize::try_from(id)
                .ok()
                .filter(|&i| i >= 1)
                .ok_or_else(|| cursor.syntax(line_no, format!("node id {id} is not positive")))?;
            order.push(index - 1);
        }
    }
    Err(cursor.invalid("TOUR_SECTION is not ended by -1"))
}

fn check_permutation(
    cursor: &Cursor,
    order: Vec<usize>,
    dimension: Option<usize>,
) -> Result<Vec<usize>, TsplibError> {
    let n = dimension.unwrap_or(order.len());
    let mut seen = vec![false; n];
    let is_permutation = order.len() == n
        && order
            .iter()
            .all(|&v| v < n && !std::mem::replace(&mut seen[v], true));
    if is_permutation {
        Ok(order)
    } else {
        Err(cursor.invalid(format!("the tour is not a permutation of the {n} nodes")))
    }
}
