//! The crate's typed errors; the [`Sequencer`](smug_core::Sequencer) implementations wrap
//! them in [`smug_core::Error::Stage`] with the stage name `"sequencer"`.

/// Why a solver refuses an instance.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SequencingError {
    /// The cost matrix has no node, not even the start.
    #[error("the cost matrix is empty: a tour needs at least the start node 0")]
    Empty,
    /// The end node of an open path is not a node other than the start.
    #[error("open path end node {end} is invalid for {n} nodes: it must be in 1..{n}")]
    BadEnd {
        /// The requested end node.
        end: usize,
        /// Number of nodes.
        n: usize,
    },
    /// The clusters of a GTSP do not partition the matrix's nodes.
    #[error("the clusters cover {clustered} nodes but the cost matrix has {n}")]
    ClusterMismatch {
        /// Nodes in the clusters.
        clustered: usize,
        /// Nodes of the matrix.
        n: usize,
    },
    /// The end cluster of an open GTSP tour is not a cluster other than the start's.
    #[error("open tour end cluster {end} is invalid for {m} clusters: it must be in 1..{m}")]
    BadEndCluster {
        /// The requested end cluster.
        end: usize,
        /// Number of clusters.
        m: usize,
    },
    /// The instance has more nodes than the solver accepts.
    #[error("{solver}: {n} nodes exceed its limit of {limit} nodes{hint}")]
    TooManyNodes {
        /// The solver.
        solver: &'static str,
        /// Number of nodes.
        n: usize,
        /// The solver's limit.
        limit: usize,
        /// What to do about it (may be empty).
        hint: &'static str,
    },
    /// Held-Karp's table would not fit the memory limit.
    #[error(
        "held-karp: {n} nodes need a {needed_mib} MiB table, more than the limit of \
         {limit_mib} MiB (max_memory_mib); use local-search or auto"
    )]
    TooMuchMemory {
        /// Number of nodes.
        n: usize,
        /// Size of the table in MiB.
        needed_mib: u64,
        /// The configured limit in MiB.
        limit_mib: u64,
    },
}

impl From<SequencingError> for smug_core::Error {
    fn from(err: SequencingError) -> Self {
        smug_core::Error::stage("sequencer", err)
    }
}

/// Why a solver's parameters are invalid; the message names the parameter.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// The time budget is negative or not finite.
    #[error("time_limit_s = {0} must be a finite number ≥ 0")]
    TimeLimit(f64),
    /// Neither a time nor an iteration budget.
    #[error("time_limit_s = 0 and max_iterations = 0: the search would never stop")]
    NeverStops,
    /// Too few neighbours per node.
    #[error("neighbours = {0} must be at least 3")]
    Neighbours(usize),
    /// A fraction or weight out of its range.
    #[error("{name} = {value} must be in [0, {most}]")]
    OutOfRange {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The largest value allowed.
        most: f64,
    },
    /// A count out of its range.
    #[error("{name} = {value} must be in [{least}, {most}]")]
    CountOutOfRange {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: usize,
        /// The smallest value allowed.
        least: usize,
        /// The largest value allowed.
        most: usize,
    },
}
