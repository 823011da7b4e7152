//! Rooms joined by one-cell doors: square rooms on a lattice separated by one-cell
//! walls; a random spanning tree of doors joins every room, and each other pair of
//! adjacent rooms gets a door with probability [`EXTRA_DOOR_CHANCE`]. A door is one
//! passable cell of the wall between two rooms; two rooms share at most one door.

use crate::movingai::MovingAiMap;
use rand::Rng;

/// The chance that two adjacent rooms not joined by the spanning tree get a door.
pub const EXTRA_DOOR_CHANCE: f64 = 0.25;

/// A wall between two adjacent rooms: the rooms (index `row · columns + column`), and
/// where the door may go.
struct Wall {
    rooms: [usize; 2],
    /// The wall's fixed coordinate (a column for a vertical wall, a row otherwise).
    at: usize,
    /// The range of the other coordinate along the shared wall.
    along: (usize, usize),
    vertical: bool,
}

/// A `width` × `height` map of rooms `room` cells across (the last room of a row or
/// column takes what is left, up to `room + 1` cells).
pub(super) fn generate(
    width: usize,
    height: usize,
    room: usize,
    rng: &mut impl Rng,
) -> MovingAiMap {
    let (xs, ys) = (spans(width, room), spans(height, room));
    let mut map = MovingAiMap::filled(width, height, false);
    for &(y0, y1) in &ys {
        for &(x0, x1) in &xs {
            (y0..y1).for_each(|y| (x0..x1).for_each(|x| map.set_passable(x, y, true)));
        }
    }
    let mut walls = walls(&xs, &ys);
    shuffle(&mut walls, rng);
    let mut parent: Vec<usize> = (0..xs.len() * ys.len()).collect();
    for wall in &walls {
        let [a, b] = wall.rooms.map(|r| root(&mut parent, r));
        let joins = a != b;
        if joins {
            parent[a] = b;
        }
        if joins || rng.random_bool(EXTRA_DOOR_CHANCE) {
            let along = rng.random_range(wall.along.0..wall.along.1);
            let (x, y) = if wall.vertical {
                (wall.at, along)
            } else {
                (along, wall.at)
            };
            map.set_passable(x, y, true);
        }
    }
    map
}

/// The interior intervals `[start, end)` of the rooms along a side of `len` cells; the
/// cell after each interval but the last is a wall.
pub(super) fn spans(len: usize, room: usize) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    loop {
        let end = start + room;
        if end + 1 >= len {
            spans.push((start, len));
            return spans;
        }
        spans.push((start, end));
        start = end + 1;
    }
}

/// Every wall between two adjacent rooms, row by row.
fn walls(xs: &[(usize, usize)], ys: &[(usize, usize)]) -> Vec<Wall> {
    let columns = xs.len();
    let mut walls = Vec::new();
    for (j, &y_span) in ys.iter().enumerate() {
        for (i, &x_span) in xs.iter().enumerate() {
            let room = j * columns + i;
            if i + 1 < columns {
                walls.push(Wall {
                    rooms: [room, room + 1],
                    at: x_span.1,
                    along: y_span,
                    vertical: true,
                });
            }
            if j + 1 < ys.len() {
                walls.push(Wall {
                    rooms: [room, room + columns],
                    at: y_span.1,
                    along: x_span,
                    vertical: false,
                });
            }
        }
    }
    walls
}

fn shuffle<T>(items: &mut [T], rng: &mut impl Rng) {
    for i in (1..items.len()).rev() {
        items.swap(i, rng.random_range(0..=i));
    }
}

/// The representative of `room`'s set (union–find with path halving).
fn root(parent: &mut [usize], mut room: usize) -> usize {
    while parent[room] != room {
        parent[room] = parent[parent[room]];
        room = parent[room];
    }
    room
}
