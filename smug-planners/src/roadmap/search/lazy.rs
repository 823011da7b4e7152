//! Lazy Weighted A* (Cohen, Phillips & Likhachev 2014): elements are checked only when
//! the vertex they lead to is about to be expanded. Relaxes as [`AStar::search`] does.

use super::NO_PARENT;
use super::{AStar, Evaluator, GraphPath, Marks, Open, Relax, Roadmap, Target, Validity};
use smug_core::Objective;
use std::collections::BinaryHeap;

impl AStar {
    /// Lazy Weighted A* (Cohen, Phillips & Likhachev 2014): one search that checks an
    /// element only when the vertex it leads to is about to be expanded. Returns the
    /// cheapest valid path over the live edges (every element on it checked), or `None`
    /// (also when every valid path costs more than `bound`, as in [`AStar::search`]).
    pub fn search_lazy(
        &mut self,
        map: &mut Roadmap,
        start: u32,
        goal: u32,
        objective: &dyn Objective,
        evaluator: &mut dyn Evaluator,
        bound: f64,
    ) -> Option<GraphPath> {
        let marks = self.prepare(map, goal, objective);
        self.settled = None;
        let target = Target {
            pose: *map.pose(goal),
            objective,
        };
        let mut open = std::mem::take(&mut self.lazy_heap);
        open.clear();
        let h0 = self.heuristic(map, start, &target.pose, objective);
        open.push(Open {
            f: h0,
            g: 0.0,
            v: start,
            parent: NO_PARENT,
        });
        let mut found = None;
        while let Some(Open { g, v, parent, .. }) = open.pop() {
            if self.records[v as usize].mark == marks.closed {
                continue;
            }
            let (_, e) = parent;
            let reachable = (e == u32::MAX
                || map.edge(e).validity != Validity::Invalid && evaluator.edge(map, e))
                && evaluator.vertex(map, v);
            if !reachable {
                continue;
            }
            let record = &mut self.records[v as usize];
            (record.mark, record.g, record.parent) = (marks.closed, g, parent);
            if v == goal {
                found = Some(self.trace(start, goal));
                break;
            }
            self.expansions += 1;
            self.push_lazy_successors(&mut open, map, (v, g), target, marks, bound);
        }
        self.lazy_heap = open;
        found
    }

    /// Pushes every neighbour of `v` (reached at cost `g`) that is not closed, not
    /// already reached as cheaply through a checked-valid edge, and estimated within
    /// `bound` (the relaxation rule of [`AStar::search`]); its record takes the cost
    /// only when the edge is known valid.
    fn push_lazy_successors(
        &mut self,
        open: &mut BinaryHeap<Open>,
        map: &Roadmap,
        (v, g): (u32, f64),
        target: Target,
        marks: Marks,
        bound: f64,
    ) {
        for (w, e, cost) in map.neighbours_with_costs(v) {
            let candidate = g + cost;
            let rule = Relax::Search { bound };
            let Some(h) = self.admit(map, w, candidate, target, marks, rule) else {
                continue;
            };
            if map.edge_known_valid(e) {
                let record = &mut self.records[w as usize];
                (record.mark, record.g) = (marks.open, candidate);
            }
            open.push(Open {
                f: candidate + h,
                g: candidate,
                v: w,
                parent: (v, e),
            });
        }
    }
}
