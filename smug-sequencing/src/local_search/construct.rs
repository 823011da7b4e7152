//! Construction heuristics: the starting tour of the local search.

use super::neighbours::Neighbours;
use crate::costs::Dist;
use serde::{Deserialize, Serialize};

/// How the local search builds its first tour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Construction {
    /// Greedy matching of the cheapest candidate legs into fragments, joined by nearest
    /// neighbour (typically 15–20% above optimal on Euclidean instances).
    #[default]
    Greedy,
    /// From the start, always to the nearest unvisited node (typically ~25% above).
    NearestNeighbour,
}

/// A cycle through all nodes; with `fixed = Some((end, 0))` it contains the leg end → 0.
pub(crate) fn construct(
    method: Construction,
    dist: &Dist,
    neighbours: &Neighbours,
    fixed: Option<(usize, usize)>,
) -> Vec<usize> {
    match method {
        Construction::Greedy => greedy(dist, neighbours, fixed),
        Construction::NearestNeighbour => nearest_neighbour(dist, fixed),
    }
}

/// Nearest neighbour from node 0; an open path's end node is kept for last.
fn nearest_neighbour(dist: &Dist, fixed: Option<(usize, usize)>) -> Vec<usize> {
    let n = dist.len();
    let reserved = fixed.map(|(end, _)| end);
    let mut visited = vec![false; n];
    visited[0] = true;
    if let Some(end) = reserved {
        visited[end] = true;
    }
    let mut order = vec![0];
    let mut current = 0;
    while let Some(next) = (0..n)
        .filter(|&j| !visited[j])
        .min_by(|&a, &b| dist.d(current, a).total_cmp(&dist.d(current, b)))
    {
        visited[next] = true;
        order.push(next);
        current = next;
    }
    order.extend(reserved);
    order
}

/// Fragments under construction: degrees, links and a union-find over fragments.
struct Fragments {
    symmetric: bool,
    succ: Vec<Option<usize>>,
    pred: Vec<Option<usize>>,
    root: Vec<usize>,
}

impl Fragments {
    fn new(n: usize, symmetric: bool) -> Self {
        Self {
            symmetric,
            succ: vec![None; n],
            pred: vec![None; n],
            root: (0..n).collect(),
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.root[i] != i {
            self.root[i] = self.root[self.root[i]];
            i = self.root[i];
        }
        i
    }

    /// Links `i → j` if both have a free slot and they are in different fragments.
    /// Symmetric fragments are undirected: a node's two slots are interchangeable.
    fn try_link(&mut self, i: usize, j: usize) -> bool {
        let (ri, rj) = (self.find(i), self.find(j));
        if ri == rj {
            return false;
        }
        if self.symmetric {
            let (Some(si), Some(sj)) = (self.free_slot(i), self.free_slot(j)) else {
                return false;
            };
            self.fill_slot(i, si, j);
            self.fill_slot(j, sj, i);
        } else {
            if self.succ[i].is_some() || self.pred[j].is_some() {
                return false;
            }
            self.succ[i] = Some(j);
            self.pred[j] = Some(i);
        }
        self.root[ri] = rj;
        true
    }

    fn free_slot(&self, i: usize) -> Option<bool> {
        if self.succ[i].is_none() {
            Some(true)
        } else if self.pred[i].is_none() {
            Some(false)
        } else {
            None
        }
    }

    fn fill_slot(&mut self, i: usize, succ_slot: bool, j: usize) {
        if succ_slot {
            self.succ[i] = Some(j);
        } else {
            self.pred[i] = Some(j);
        }
    }

    /// Links of `i` (one or two; undirected for symmetric fragments).
    fn links(&self, i: usize) -> impl Iterator<Item = usize> {
        self.succ[i].into_iter().chain(self.pred[i])
    }

    /// Walks each fragment from one of its ends: the node sequences, in direction of the
    /// links for asymmetric fragments.
    fn paths(&self) -> Vec<Vec<usize>> {
        let n = self.succ.len();
        let mut seen = vec![false; n];
        let mut paths = Vec::new();
        for start in 0..n {
            let is_end = if self.symmetric {
                self.links(start).count() < 2
            } else {
                self.pred[start].is_none()
            };
            if seen[start] || !is_end {
                continue;
            }
            let mut path = vec![start];
            seen[start] = true;
            let mut current = start;
            while let Some(next) = self.forward_link(current, &seen) {
                seen[next] = true;
                path.push(next);
                current = next;
            }
            paths.push(path);
        }
        paths
    }

    fn forward_link(&self, i: usize, seen: &[bool]) -> Option<usize> {
        if self.symmetric {
            self.links(i).find(|&j| !seen[j])
        } else {
            self.succ[i].filter(|&j| !seen[j])
        }
    }
}

/// Greedy edge matching on the candidate legs, then fragments joined nearest-end first.
fn greedy(dist: &Dist, neighbours: &Neighbours, fixed: Option<(usize, usize)>) -> Vec<usize> {
    let n = dist.len();
    let symmetric = dist.is_symmetric();
    let mut legs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| neighbours.out_of(i).iter().map(move |&j| (i, j)))
        .filter(|&(i, j)| !symmetric || i < j || !neighbours.out_of(j).contains(&i))
        .collect();
    legs.sort_by(|&(a, b), &(c, d)| {
        dist.d(a, b)
            .total_cmp(&dist.d(c, d))
            .then((a, b).cmp(&(c, d)))
    });
    let mut fragments = Fragments::new(n, symmetric);
    if let Some((end, start)) = fixed {
        fragments.try_link(end, start);
    }
    for (i, j) in legs {
        fragments.try_link(i, j);
    }
    join_paths(dist, fragments.paths(), symmetric)
}

/// Chains fragments: from the end of the current chain to the nearest fragment end
/// (a symmetric fragment may be entered from either end).
fn join_paths(dist: &Dist, mut paths: Vec<Vec<usize>>, symmetric: bool) -> Vec<usize> {
    let mut order = paths.swap_remove(0);
    while !paths.is_empty() {
        let tail = order[order.len() - 1];
        let entry_cost = |path: &Vec<usize>, reversed: bool| {
            let first = if reversed {
                path[path.len() - 1]
            } else {
                path[0]
            };
            dist.d(tail, first)
        };
        let (index, reversed) = (0..paths.len())
            .flat_map(|k| {
                let both = if symmetric { 2 } else { 1 };
                (0..both).map(move |r| (k, r == 1))
            })
            .min_by(|&(a, ra), &(b, rb)| {
                entry_cost(&paths[a], ra).total_cmp(&entry_cost(&paths[b], rb))
            })
            .unwrap_or((0, false));
        let mut next = paths.swap_remove(index);
        if reversed {
            next.reverse();
        }
        order.extend(next);
    }
    order
}
