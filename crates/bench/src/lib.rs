pub mod pit;
pub mod rapier_pit;
