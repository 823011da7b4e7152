//! The ROS 2 side of plan.mcap: CDR encoding ([`cdr`]), the messages ([`msgs`]) and
//! their schema texts ([`schema`]). Small and ours: no ROS install, no code generator.

pub mod cdr;
pub mod msgs;
pub mod schema;
