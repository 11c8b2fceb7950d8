//! Reads arbitrary bytes as a world file (`sitlog-sim`): never a panic. A
//! file that reads is also run: the robot visits every place, looks, grasps
//! what it sees, listens, puts things down; every event must narrate.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_sim::{Hand, Sim, World};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = World::text_of("fuzz.toml", data) else {
        return;
    };
    let Ok(world) = World::parse("fuzz.toml", text) else {
        return;
    };
    let mut sim = Sim::new(&world, 0);
    for place in world.place_names() {
        let _ = sim.navigate(place);
        let seen = sim.see();
        for (object, hand) in seen.objects.iter().zip(Hand::ALL) {
            let _ = sim.grasp(object, hand);
        }
        let _ = sim.hear();
    }
    for hand in Hand::ALL {
        let _ = sim.place(hand);
    }
    sim.wait_for_user(60.0);
    let mut last = 0.0;
    for event in sim.events() {
        assert!(event.time >= last, "time went back: {event:?}");
        last = event.time;
        let _ = event.to_string();
    }
});
