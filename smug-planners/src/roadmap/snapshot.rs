//! A roadmap to and from a planner-independent
//! [`RoadmapSnapshot`](super::file::RoadmapSnapshot).

use super::file::{CheckStatus, SavedEdge, SavedVertex};
use super::{pose_key, Roadmap, UnionFind, Validity};
use smug_core::Pose2;

/// Why a saved roadmap cannot be restored.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RestoreError {
    /// The roadmap to restore into already has vertices.
    #[error("the planner's roadmap is not empty")]
    NotEmpty,
    /// A vertex's pose is not finite.
    #[error("vertex {0}: pose is not finite")]
    Pose(usize),
    /// An edge's ends are not two different saved vertices.
    #[error("edge {edge}: ends {a} and {b} of {n} vertices")]
    Ends {
        /// The edge's index.
        edge: usize,
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
        /// Number of vertices.
        n: u32,
    },
    /// An edge's cost is NaN.
    #[error("edge {0}: cost is not a number")]
    Cost(usize),
}

fn status(v: Validity) -> CheckStatus {
    match v {
        Validity::Unknown => CheckStatus::Unchecked,
        Validity::Valid => CheckStatus::Valid,
        Validity::Invalid => CheckStatus::Invalid,
    }
}

fn validity(s: CheckStatus) -> Validity {
    match s {
        CheckStatus::Unchecked => Validity::Unknown,
        CheckStatus::Valid => Validity::Valid,
        CheckStatus::Invalid => Validity::Invalid,
    }
}

impl Roadmap {
    /// Whether each motion and its reverse are separate edges.
    pub fn is_directed(&self) -> bool {
        self.directed
    }

    /// The vertices and edges with their check status and costs, in id order.
    pub fn export(&self) -> (Vec<SavedVertex>, Vec<SavedEdge>) {
        let vertices = self
            .poses
            .iter()
            .zip(&self.vertex_validity)
            .map(|(p, v)| SavedVertex {
                pose: (*p).into(),
                status: status(*v),
            })
            .collect();
        let edges = self
            .edges
            .iter()
            .enumerate()
            .map(|(e, edge)| {
                let back = if self.directed {
                    edge.cost
                } else {
                    let b = edge.b as usize;
                    self.adjacency[b]
                        .iter()
                        .position(|&(_, id)| id as usize == e)
                        .map_or(edge.cost, |k| self.adjacent_costs[b][k])
                };
                SavedEdge {
                    a: edge.a,
                    b: edge.b,
                    cost: edge.cost.to_bits(),
                    cost_back: back.to_bits(),
                    status: status(edge.validity),
                }
            })
            .collect();
        (vertices, edges)
    }

    /// Replaces this (empty) roadmap's graph by the saved `vertices` and `edges`;
    /// invalid ones are kept as removed. Errors name what is inconsistent.
    pub fn restore(
        &mut self,
        vertices: &[SavedVertex],
        edges: &[SavedEdge],
    ) -> Result<(), RestoreError> {
        if !self.poses.is_empty() {
            return Err(RestoreError::NotEmpty);
        }
        for (i, v) in vertices.iter().enumerate() {
            let pose: Pose2 = v.pose.into();
            if !(pose.x.is_finite() && pose.y.is_finite() && pose.yaw.is_finite()) {
                return Err(RestoreError::Pose(i));
            }
            let id = self.poses.len() as u32;
            self.poses.push(pose);
            self.vertex_validity.push(validity(v.status));
            self.adjacency.push(Vec::new());
            self.adjacent_costs.push(Vec::new());
            self.incoming.push(Vec::new());
            if v.status != CheckStatus::Invalid {
                self.grid.insert(id, &pose, &self.poses);
                self.by_pose.insert(pose_key(&pose), id);
            }
        }
        self.components = UnionFind::with_len(self.poses.len());
        let n = self.poses.len() as u32;
        for (i, edge) in edges.iter().enumerate() {
            let (there, back) = (f64::from_bits(edge.cost), f64::from_bits(edge.cost_back));
            if edge.a >= n || edge.b >= n || edge.a == edge.b {
                return Err(RestoreError::Ends {
                    edge: i,
                    a: edge.a,
                    b: edge.b,
                    n,
                });
            }
            if there.is_nan() || back.is_nan() {
                return Err(RestoreError::Cost(i));
            }
            if self.directed {
                self.add_directed_edge(edge.a, edge.b, there);
            } else {
                self.asymmetric_costs |= there != back;
                self.add_edge(edge.a, edge.b, there, back);
            }
            let e = self.edges.len() as u32 - 1;
            let dead_end = [edge.a, edge.b]
                .iter()
                .any(|&v| self.vertex_validity[v as usize] == Validity::Invalid);
            if edge.status == CheckStatus::Invalid || dead_end {
                self.remove_edge(e);
            } else {
                self.set_edge_validity(e, validity(edge.status));
            }
        }
        self.refresh_components();
        Ok(())
    }

    /// Marks edge `e` unchecked again (the world changed near it); removed edges stay
    /// removed (obstacles only ever get added).
    pub fn mark_edge_unknown(&mut self, e: u32) {
        if self.edges[e as usize].validity == Validity::Valid {
            self.set_edge_validity(e, Validity::Unknown);
        }
    }

    /// Number of edges ever added (removed ones included).
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }
}
