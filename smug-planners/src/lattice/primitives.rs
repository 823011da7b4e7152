//! The lattice and its motion primitives: poses on a square grid of points with
//! `headings` evenly spaced headings, and per heading a few motions to other lattice
//! poses, each one the motion model's own shortest curve (so a path of lattice poses is
//! a path of the space's local motions, checked and costed by the pipeline's stages).

use smug_core::{Bounds2, Pose2, StateSpace};
use std::f64::consts::PI;

/// A lattice pose's index: `((iy · nx) + ix) · headings + k`.
pub type StateId = u32;

/// The grid of lattice points and the headings at each.
#[derive(Clone, Debug)]
pub struct Lattice {
    /// The first point (lower left), metres.
    pub origin: [f64; 2],
    /// Spacing of the points, metres.
    pub cell: f64,
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Headings per point.
    pub headings: usize,
    /// The heading of each bin, radians in `(-π, π]`.
    yaws: Vec<f64>,
}

impl Lattice {
    /// The points `cell` apart inside `bounds` (half a cell in from its edges).
    pub fn new(bounds: Bounds2, cell: f64, headings: usize) -> Self {
        let span = |k: usize| ((bounds.max[k] - bounds.min[k]) / cell).floor().max(0.0) as usize;
        Self {
            origin: [bounds.min[0] + 0.5 * cell, bounds.min[1] + 0.5 * cell],
            cell,
            nx: span(0),
            ny: span(1),
            headings,
            yaws: (0..headings)
                .map(|k| smug_core::pose::wrap_angle(2.0 * PI * k as f64 / headings as f64))
                .collect(),
        }
    }

    /// Lattice poses in all.
    pub fn len(&self) -> usize {
        self.nx * self.ny * self.headings
    }

    /// True when the lattice has no pose (bounds narrower than a cell).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Lattice points in all.
    pub fn points(&self) -> usize {
        self.nx * self.ny
    }

    /// The heading of bin `k`, radians in `(-π, π]`.
    pub fn heading(&self, k: usize) -> f64 {
        self.yaws[k]
    }

    /// The bin nearest to heading `yaw`.
    pub fn heading_bin(&self, yaw: f64) -> usize {
        let h = self.headings as f64;
        let k = (yaw.rem_euclid(2.0 * PI) / (2.0 * PI) * h).round() as usize;
        k % self.headings
    }

    /// The index of point `(ix, iy)` at heading `k`.
    pub fn id(&self, ix: usize, iy: usize, k: usize) -> StateId {
        ((iy * self.nx + ix) * self.headings + k) as StateId
    }

    /// Point column, row and heading bin of a state.
    pub fn decode(&self, id: StateId) -> (usize, usize, usize) {
        let id = id as usize;
        let k = id % self.headings;
        let point = id / self.headings;
        (point % self.nx, point / self.nx, k)
    }

    /// The position of point `(ix, iy)`.
    pub fn position(&self, ix: usize, iy: usize) -> [f64; 2] {
        [
            self.origin[0] + ix as f64 * self.cell,
            self.origin[1] + iy as f64 * self.cell,
        ]
    }

    /// The pose of a state.
    pub fn pose(&self, id: StateId) -> Pose2 {
        let (ix, iy, k) = self.decode(id);
        let [x, y] = self.position(ix, iy);
        Pose2::new(x, y, self.heading(k))
    }

    /// The point `(ix + di, iy + dj)` when it is on the lattice.
    pub fn offset(&self, ix: usize, iy: usize, di: i32, dj: i32) -> Option<(usize, usize)> {
        let x = ix as i64 + di as i64;
        let y = iy as i64 + dj as i64;
        (x >= 0 && y >= 0 && (x as usize) < self.nx && (y as usize) < self.ny)
            .then_some((x as usize, y as usize))
    }

    /// The points within `radius` of `(x, y)`, as (column, row).
    pub fn points_near(&self, x: f64, y: f64, radius: f64) -> Vec<(usize, usize)> {
        let c = self.cell;
        let lo = |v: f64, o: f64| ((v - radius - o) / c).ceil().max(0.0) as usize;
        let hi = |v: f64, o: f64, n: usize| {
            let h = ((v + radius - o) / c).floor();
            if h < 0.0 {
                None
            } else {
                Some((h as usize).min(n.saturating_sub(1)))
            }
        };
        let (Some(x1), Some(y1)) = (
            hi(x, self.origin[0], self.nx),
            hi(y, self.origin[1], self.ny),
        ) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for iy in lo(y, self.origin[1])..=y1 {
            for ix in lo(x, self.origin[0])..=x1 {
                let [px, py] = self.position(ix, iy);
                if (px - x).hypot(py - y) <= radius && ix < self.nx && iy < self.ny {
                    out.push((ix, iy));
                }
            }
        }
        out
    }
}

/// One motion from a lattice pose to another: the model's shortest curve between them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Primitive {
    /// Columns moved.
    pub di: i32,
    /// Rows moved.
    pub dj: i32,
    /// Heading bin at the end.
    pub to_heading: usize,
    /// Driven in reverse gear (the whole curve).
    pub reverse: bool,
    /// Planar length of the curve, metres.
    pub length: f64,
}

/// The primitives of every heading bin.
#[derive(Clone, Debug)]
pub struct Primitives {
    /// Per heading bin, its primitives.
    pub by_heading: Vec<Vec<Primitive>>,
    /// The most primitives of one heading (the stride of the edge cache).
    pub stride: usize,
}

impl Primitives {
    /// Every primitive as the motion it is from the origin: its slot (`k · stride + p`:
    /// primitive `p` of heading `k`), the pose `(0, 0, heading(k))` and its end pose
    /// (a primitive is the same curve from every lattice point, translated).
    pub fn from_origin<'a>(
        &'a self,
        lattice: &'a Lattice,
    ) -> impl Iterator<Item = (usize, Pose2, Pose2)> + 'a {
        self.by_heading
            .iter()
            .enumerate()
            .flat_map(move |(k, prims)| {
                let from = Pose2::new(0.0, 0.0, lattice.heading(k));
                prims.iter().enumerate().map(move |(p, prim)| {
                    let to = Pose2::new(
                        prim.di as f64 * lattice.cell,
                        prim.dj as f64 * lattice.cell,
                        lattice.heading(prim.to_heading),
                    );
                    (k * self.stride + p, from, to)
                })
            })
    }
}

/// Shapes of the primitives: straight ahead, full lock left, full lock right, at a
/// nominal length and twice it.
const TIERS: [f64; 2] = [1.0, 2.0];

/// How the lattice's curves are laid out.
pub struct Layout<'a> {
    /// The motion model.
    pub space: &'a dyn StateSpace,
    /// Its minimum turning radius, metres.
    pub radius: f64,
    /// Whether reverse primitives are made.
    pub reverse: bool,
}

impl Layout<'_> {
    /// The primitives of every heading of `lattice`: for each gear, steering
    /// (straight, left, right) and tier, the lattice pose nearest the ideal end of that
    /// motion whose shortest curve stays close to it (no loops, one gear).
    pub fn primitives(&self, lattice: &Lattice) -> Primitives {
        let step = 2.0 * PI / lattice.headings as f64;
        let nominal = std::f64::consts::SQRT_2 * lattice.cell;
        // Bins per arc: an arc at full lock at least `nominal` long.
        let bins = (nominal / (self.radius * step)).ceil().max(1.0) as usize;
        let mut by_heading = Vec::with_capacity(lattice.headings);
        for k in 0..lattice.headings {
            let mut list: Vec<Primitive> = Vec::new();
            for gear in [false, true] {
                if gear && !self.reverse {
                    continue;
                }
                for tier in TIERS {
                    for steer in [0i32, 1, -1] {
                        let turn_bins = steer * (bins as f64 * tier) as i32;
                        if let Some(p) =
                            self.primitive(lattice, k, gear, steer, turn_bins, tier * nominal)
                        {
                            if !list.iter().any(|q| {
                                q.di == p.di && q.dj == p.dj && q.to_heading == p.to_heading
                            }) {
                                list.push(p);
                            }
                        }
                    }
                }
            }
            by_heading.push(list);
        }
        let stride = by_heading.iter().map(Vec::len).max().unwrap_or(0);
        Primitives { by_heading, stride }
    }

    /// One primitive from heading bin `k`: the ideal end of driving `length` straight
    /// (`steer` 0) or `turn_bins` bins at full lock, snapped to the best nearby point.
    fn primitive(
        &self,
        lattice: &Lattice,
        k: usize,
        reverse: bool,
        steer: i32,
        turn_bins: i32,
        length: f64,
    ) -> Option<Primitive> {
        let h = lattice.headings as i32;
        let step = 2.0 * PI / lattice.headings as f64;
        let sign = if reverse { -1.0 } else { 1.0 };
        let angle = turn_bins.abs() as f64 * step;
        // The ideal end in the start's frame (x ahead, y to the left).
        let (lx, ly, dk) = if steer == 0 {
            (sign * length, 0.0, 0)
        } else {
            let s = steer as f64;
            let dk = if reverse { -turn_bins } else { turn_bins };
            (
                sign * self.radius * angle.sin(),
                s * self.radius * (1.0 - angle.cos()),
                dk,
            )
        };
        let theta = lattice.heading(k);
        let (sin, cos) = theta.sin_cos();
        let wx = lx * cos - ly * sin;
        let wy = lx * sin + ly * cos;
        let to_heading = (k as i32 + dk).rem_euclid(h) as usize;
        let nominal_length = if steer == 0 {
            length
        } else {
            self.radius * angle
        };
        let nominal_turn = if steer == 0 { 0.0 } else { angle };
        let from = Pose2::new(0.0, 0.0, theta);
        let (ci, cj) = (
            (wx / lattice.cell).round() as i32,
            (wy / lattice.cell).round() as i32,
        );
        let mut best: Option<(f64, Primitive)> = None;
        for dj in cj - 1..=cj + 1 {
            for di in ci - 1..=ci + 1 {
                if di == 0 && dj == 0 {
                    continue;
                }
                let to = Pose2::new(
                    di as f64 * lattice.cell,
                    dj as f64 * lattice.cell,
                    lattice.heading(to_heading),
                );
                let extent = self.space.motion_extent(&from, &to);
                if !extent.length.is_finite()
                    || extent.length > 1.3 * nominal_length + lattice.cell
                    || extent.turning > nominal_turn + 0.6
                    || !self.one_gear(&from, &to, reverse)
                {
                    continue;
                }
                let score = (extent.length - nominal_length).abs()
                    + self.radius * (extent.turning - nominal_turn).abs();
                if best.as_ref().is_none_or(|(s, _)| score < *s) {
                    best = Some((
                        score,
                        Primitive {
                            di,
                            dj,
                            to_heading,
                            reverse,
                            length: extent.length,
                        },
                    ));
                }
            }
        }
        best.map(|(_, p)| p)
    }

    /// True when the curve `a → b` is driven in one gear, reverse or not as asked.
    pub fn one_gear(&self, a: &Pose2, b: &Pose2, reverse: bool) -> bool {
        [0.05, 0.25, 0.5, 0.75, 0.95]
            .iter()
            .all(|&t| self.space.is_reversing(a, b, t) == reverse)
    }
}
