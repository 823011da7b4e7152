//! The GTSP-LIB reader; small instances are also solved by the exact GTSP solver.
#![no_main]

use libfuzzer_sys::fuzz_target;
use smug_core::stages::{Sequencer, TourKind};
use smug_sequencing::{GtspExact, GtspExactParams};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(instance) = smug_sequencing::gtsplib::parse_gtsplib(text, "fuzz.gtsp") else {
        return;
    };
    if instance.costs.len() <= 12 {
        let solver = GtspExact::new(GtspExactParams::default()).expect("default limits");
        if let Ok(tour) =
            solver.solve_clusters(&instance.costs, &instance.clusters, TourKind::Closed)
        {
            assert!(tour.order.len() <= instance.costs.len());
        }
    }
});
