//! The states the motion validator checks along each primitive, computed once: a
//! primitive is the same curve from every lattice point (translated copies), so its
//! states from the origin, translated to a lattice point, are those the validator
//! would compute there, without solving the curve again.
//!
//! Only where the two lattice poses lie exactly the primitive's offset apart in `f64`
//! (lattice positions exact in binary, as on maps with round corners): the model then
//! solves the same relative pose, so the same curve, bit for bit. Elsewhere rounding
//! may tip a tie between two curves of one length (mirror images: a different path
//! on the ground), so the motion is checked as asked.

use super::primitives::{Lattice, Primitives};
use smug_core::{MotionValidator, Pose2};

/// Per primitive (`k · stride + p`: primitive `p` of heading `k`), the states the
/// validator checks along it from the pose `(0, 0, heading(k))`, ends included.
pub(crate) struct PrimitiveStates {
    stride: usize,
    states: Vec<Vec<Pose2>>,
    /// Per primitive, its end's offset from its start, metres.
    offsets: Vec<[f64; 2]>,
}

impl PrimitiveStates {
    /// The states of every primitive, as `motions` gives them
    /// ([`MotionValidator::check_states`]); `None` when it does not give them for some
    /// primitive (it checks motions otherwise).
    pub(crate) fn new(
        lattice: &Lattice,
        primitives: &Primitives,
        motions: &dyn MotionValidator,
    ) -> Option<Self> {
        let stride = primitives.stride;
        let mut states = vec![Vec::new(); lattice.headings * stride];
        let mut offsets = vec![[0.0; 2]; lattice.headings * stride];
        for (slot, from, to) in primitives.from_origin(lattice) {
            let along = motions.check_states(&from, &to)?;
            if along.len() < 2 {
                return None;
            }
            states[slot] = along;
            offsets[slot] = [to.x, to.y];
        }
        Some(Self {
            stride,
            states,
            offsets,
        })
    }

    /// Primitive `p` of heading `k` from the lattice pose `a` to the lattice pose `b`:
    /// its states translated to `a`, into `out` (cleared first), the ends `a` and `b`
    /// themselves. False (and `out` untouched) unless `b − a` is exactly the
    /// primitive's offset (see the module's doc).
    pub(crate) fn translated(
        &self,
        k: usize,
        p: usize,
        (a, b): (&Pose2, &Pose2),
        out: &mut Vec<Pose2>,
    ) -> bool {
        let slot = k * self.stride + p;
        let [dx, dy] = self.offsets[slot];
        if b.x - a.x != dx || b.y - a.y != dy {
            return false;
        }
        let relative = &self.states[slot];
        out.clear();
        out.push(*a);
        out.extend(relative[1..relative.len() - 1].iter().map(|s| Pose2 {
            x: a.x + s.x,
            y: a.y + s.y,
            yaw: s.yaw,
        }));
        out.push(*b);
        true
    }
}
