//! The figures in docs/figures/ are what the code that draws them draws
//! now: drawn again, byte for byte the same.

use rolypoly_bench::figures;

/// Draws every figure, the poured heaps of angle-of-repose.svg included:
/// their 21 heaps take most of the test's time, some 15 s on two cores.
#[test]
fn the_figures_in_docs_are_current() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/figures");
    for figure in figures::all().expect("the figures draw") {
        let path = format!("{dir}/{}", figure.name);
        let shipped = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            shipped == figure.svg,
            "{path} is not what the code draws now: run `cargo run --release -p rolypoly-bench --bin figures` and look at it"
        );
    }
}

#[test]
fn the_physics_behind_the_figures_holds() {
    // The points lie on the theory they are drawn over.
    let config = rolypoly_physics::WorldConfig::default();
    for amplitude in [10.0, 45.0, 80.0] {
        let theory = figures::rolling_pendulum_period(
            &config.tumblers.spheres,
            config.gravity,
            f64::to_radians(amplitude),
        );
        let simulated = figures::simulated_period(amplitude);
        assert!(
            (simulated - theory).abs() < 0.02 * theory,
            "{amplitude} degrees: {simulated} s against {theory} s"
        );
    }
    for e in [0.3, 0.7, 1.0] {
        let ratio = figures::rebound_ratio(e);
        assert!((ratio - e * e).abs() < 0.01, "e = {e}: {ratio}");
    }
}
