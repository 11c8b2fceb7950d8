//! The simulated robot (feature `sim`): written once `sitlog-sim` lands.
