//! The TSPLIB reader (instances and tours); small instances are also solved exactly.
#![no_main]

use libfuzzer_sys::fuzz_target;
use smug_core::stages::{Sequencer, TourKind};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = smug_sequencing::tsplib::parse_tour(text, "fuzz.tour");
    let Ok(instance) = smug_sequencing::tsplib::parse_tsplib(text, "fuzz.tsp") else {
        return;
    };
    if instance.costs.len() <= 9 {
        let tour = smug_sequencing::held_karp::HeldKarp::new(Default::default())
            .expect("default limits")
            .solve(&instance.costs, TourKind::Closed)
            .expect("Held-Karp solves every parsed instance");
        let mut order = tour.order.clone();
        order.sort_unstable();
        assert!(
            order.iter().copied().eq(0..instance.costs.len()),
            "a permutation"
        );
    }
});
