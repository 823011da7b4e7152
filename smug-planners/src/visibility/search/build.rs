//! Building the tangent graph: which corners a point may see, each corner's
//! departures (tangent segments, checked exactly, collinear ones left out), each
//! node's successor along its segment.

use super::*;

impl TangentGraph {
    /// The tangent points `p` on the circles of the corners `q` may see whose segment
    /// to `q` is clear by `need` (`segment_clear` is symmetric, so this serves segments
    /// into and out of `q`): `(corner, unit normal at p, angle relative to the corner,
    /// p)`, in corner and tangent order.
    pub(super) fn clear_tangents(&mut self, q: Pt, need: f64) -> Vec<(u32, Pt, f64, Pt)> {
        let mut tangents = Vec::new();
        for c in self.visible_corners(q, None) {
            let corner = self.grid.corners[c as usize];
            for n in point_tangents(q, corner.at, self.r) {
                let Some(rel) = corner.relative_angle(n) else {
                    continue;
                };
                let p = [corner.at[0] + self.r * n[0], corner.at[1] + self.r * n[1]];
                self.counts.segment_checks += 1;
                if self.grid.segment_clear(q, p, need) {
                    tangents.push((c, n, rel, p));
                }
            }
        }
        tangents
    }

    /// The corners a point may see (a superset of those it sees), without `skip`.
    fn visible_corners(&mut self, s: Pt, skip: Option<u32>) -> Vec<u32> {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.stamp_corner.fill(0);
            self.stamp = 1;
        }
        let mut found = Vec::new();
        let (stamps, stamp, active) = (&mut self.stamp_corner, self.stamp, &self.active);
        self.lines.visible_corners(s, |c| {
            if stamps[c as usize] != stamp && Some(c) != skip && active[c as usize] {
                stamps[c as usize] = stamp;
                found.push(c);
            }
        });
        found
    }

    /// Builds corner `a`'s departures (once).
    pub fn build_corner(&mut self, a: u32) {
        if self.lanes[a as usize].is_some() {
            return;
        }
        let ca = self.grid.corners[a as usize];
        let mut lanes: [Vec<Departure>; 2] = [Vec::new(), Vec::new()];
        for b in self.visible_corners(ca.at, Some(a)) {
            let cb = self.grid.corners[b as usize];
            for (na, nb) in circle_tangents(ca.at, cb.at, self.r) {
                let (Some(rel_a), Some(rel_b)) = (ca.relative_angle(na), cb.relative_angle(nb))
                else {
                    continue;
                };
                if na == nb && self.touches_corner_between(ca.at, cb.at, na) {
                    self.counts.pruned += 1;
                    continue;
                }
                let pa = [ca.at[0] + self.r * na[0], ca.at[1] + self.r * na[1]];
                let pb = [cb.at[0] + self.r * nb[0], cb.at[1] + self.r * nb[1]];
                self.counts.segment_checks += 1;
                if !self.grid.segment_clear(pa, pb, self.r_check) {
                    continue;
                }
                let t = [pb[0] - pa[0], pb[1] - pa[1]];
                lanes[Lane::of(na, t).index()].push(Departure {
                    rel: rel_a,
                    point: pa,
                    to: b,
                    arrive_rel: rel_b,
                    arrive_lane: Lane::of(nb, t),
                    len: dist(pa, pb),
                    to_next: true,
                });
            }
        }
        lanes[0].sort_by(|x, y| x.rel.total_cmp(&y.rel));
        lanes[1].sort_by(|x, y| y.rel.total_cmp(&x.rel));
        for list in &mut lanes {
            let n = list.len();
            for k in 0..n {
                list[k].to_next = k + 1 < n
                    && (!self.big
                        || self.grid.arc_clear(
                            &ca,
                            self.r,
                            list[k].rel,
                            list[k + 1].rel,
                            self.r_check,
                        ));
            }
        }
        let entry = Lanes {
            first: self.nodes.len() as u32,
            ccw: lanes[0].len() as u32,
            cw: lanes[1].len() as u32,
        };
        let count = lanes[0].len() + lanes[1].len();
        let [ccw, cw] = lanes;
        for list in [&ccw, &cw] {
            for (k, d) in list.iter().enumerate() {
                self.slot.push(Slot {
                    point: d.point,
                    cost: f64::INFINITY,
                    chain_cost: if d.to_next {
                        self.r * (list[k + 1].rel - d.rel).abs()
                    } else {
                        f64::INFINITY
                    },
                    succ_cost: f64::INFINITY,
                    query: 0,
                    via: VIA_CHAIN,
                    succ: SUCC_UNSET,
                    arrive_at: d.to,
                });
            }
        }
        self.nodes.extend(ccw);
        self.nodes.extend(cw);
        self.node_corner.extend(std::iter::repeat_n(a, count));
        self.counts.corners_built += 1;
        self.counts.departures += count as u64;
        self.lanes[a as usize] = Some(entry);
    }

    /// True when the outer tangent on side `n` of the circles around the grid vertices
    /// `a` and `b` also touches the quarter circle of a corner between them (its
    /// centre on the segment `a → b`): the path along it is the same through that
    /// corner (a zero arc there), so the graph needs only the pieces. Exact on the
    /// lattice: the vertices between are `a + k·(b − a)/gcd`.
    fn touches_corner_between(&self, a: Pt, b: Pt, n: Pt) -> bool {
        let (dx, dy) = ((b[0] - a[0]) as i64, (b[1] - a[1]) as i64);
        let g = gcd(dx.unsigned_abs(), dy.unsigned_abs()) as i64;
        (1..g).any(|k| {
            let (x, y) = (a[0] as i64 + k * dx / g, a[1] as i64 + k * dy / g);
            self.grid.corner_at(x, y).is_some_and(|m| {
                self.active[m as usize] && self.grid.corners[m as usize].relative_angle(n).is_some()
            })
        })
    }

    /// Builds every corner, and every node's successor along its segment.
    pub fn build_all(&mut self) {
        for a in 0..self.grid.corners.len() as u32 {
            if self.active[a as usize] {
                self.build_corner(a);
            }
        }
        for id in 0..self.nodes.len() as u32 {
            self.successor(id);
        }
    }

    /// Node `id`'s successor along its segment (the first departure at or after its
    /// arrival, in the arrival's lane, whose arc is clear), computed once; building the
    /// corner it arrives at if needed.
    pub(super) fn successor(&mut self, id: u32) -> u32 {
        let i = id as usize;
        if self.slot[i].succ != SUCC_UNSET {
            return self.slot[i].succ;
        }
        let dep = self.nodes[i];
        self.build_corner(dep.to);
        let corner = self.grid.corners[dep.to as usize];
        let (succ, cost) = match self.first_after(dep.to, dep.arrive_lane, dep.arrive_rel) {
            Some((next, rel))
                if !self.big
                    || self
                        .grid
                        .arc_clear(&corner, self.r, dep.arrive_rel, rel, self.r_check) =>
            {
                (next, dep.len + self.r * (rel - dep.arrive_rel).abs())
            }
            _ => (SUCC_NONE, f64::INFINITY),
        };
        self.slot[i].succ = succ;
        self.slot[i].succ_cost = cost;
        succ
    }
}

impl TangentGraph {
    /// Hidden staircase corners still out of the graph.
    pub fn hidden_count(&self) -> usize {
        self.hidden.len()
    }

    /// Activates the hidden corners whose pocket may hold `s` or a goal (a shortest
    /// path touches a hidden corner only from or to a point of its pocket).
    pub(super) fn activate_pockets(&mut self, s: Pt, goals: &[(Pt, f64)]) {
        let r = self.r;
        let corners = &self.grid.corners;
        let wake: Vec<u32> = self
            .hidden
            .iter()
            .filter(|(c, pocket)| {
                let at = corners[*c as usize].at;
                pocket.may_hold(at, s, r) || goals.iter().any(|g| pocket.may_hold(at, g.0, r))
            })
            .map(|&(c, _)| c)
            .collect();
        if wake.is_empty() {
            return;
        }
        self.hidden.retain(|(c, _)| !wake.contains(c));
        for &c in &wake {
            self.active[c as usize] = true;
        }
        for &c in &wake {
            self.activate(c);
        }
    }

    /// Builds the newly active corner `c`, and builds again every built corner it has
    /// a tangent with (tangents are symmetric), so that their lanes hold it; nodes
    /// arriving at a rebuilt corner find their successor again.
    fn activate(&mut self, c: u32) {
        self.lanes[c as usize] = None;
        self.build_corner(c);
        let range = self.lanes(c);
        let ids = range.range(Lane::Ccw).chain(range.range(Lane::Cw));
        let mut others: Vec<u32> = ids.map(|id| self.nodes[id].to).collect();
        others.sort_unstable();
        others.dedup();
        for b in others {
            if self.lanes[b as usize].is_none() {
                continue;
            }
            self.lanes[b as usize] = None;
            self.build_corner(b);
            for slot in &mut self.slot {
                if slot.arrive_at == b {
                    slot.succ = SUCC_UNSET;
                    slot.succ_cost = f64::INFINITY;
                }
            }
        }
    }
}
