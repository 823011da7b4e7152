//! Incremental repair of the latest A* search after vertices were added: only the
//! distances the new vertices improve are propagated (the expansion loop and the
//! relaxation of [`AStar::search`], with settled vertices reopened).

use super::{AStar, Marks, Relax, Repair, Roadmap, Settled, Target, Validity};
use smug_core::Objective;

impl AStar {
    /// After [`AStar::search`] from `start` to `goal` found the cheapest path, with
    /// vertices only added since (ids from `fresh_from` on): the cheapest path that
    /// costs less, found by propagating from the new vertices only the distances they
    /// improve (incremental A*: it searches the improvement, not the whole ellipse
    /// again), or [`Repair::NoCheaper`]. The distances stay exact for the next repair.
    /// [`Repair::NoBase`] when the records cannot serve (another query, a removal
    /// since, a Lazy Weighted A* search since): search instead.
    pub fn repair(
        &mut self,
        map: &Roadmap,
        start: u32,
        goal: u32,
        fresh_from: u32,
        objective: &dyn Objective,
    ) -> Repair {
        // The repair relaxes edges into fresh vertices with the costs stored from
        // their side: only right when costs are the same both ways.
        if map.asymmetric_costs || self.settled_for(map, start, goal).is_none() {
            return Repair::NoBase;
        }
        let open = self.prepare(map, goal, objective).open;
        // `prepare` forgets the base when the marks wrap around.
        let Some(base) = self.settled_for(map, start, goal) else {
            return Repair::NoBase;
        };
        let marks = Marks {
            open,
            closed: base.closed,
        };
        let target = Target {
            pose: *map.pose(goal),
            objective,
        };
        // Settled vertices keep their exact distances; a distance lowers only below
        // the known path's cost.
        let rule = Relax::Repair { bound: base.cost };
        for u in fresh_from..map.vertex_count() as u32 {
            if map.vertex_validity(u) == Validity::Invalid {
                continue;
            }
            for (a, e, cost) in map.neighbours_with_costs(u) {
                let settled = self.records[a as usize];
                if a < fresh_from && settled.mark == marks.closed {
                    self.relax(map, (a, e), (u, settled.g + cost), target, marks, rule);
                }
            }
        }
        match self.run(map, goal, target, marks, rule) {
            Some(cost) => {
                self.settled = Some(Settled { cost, ..base });
                Repair::Cheaper(self.trace(start, goal))
            }
            None => Repair::NoCheaper,
        }
    }
}
