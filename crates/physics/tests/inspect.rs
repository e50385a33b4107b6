//! What the debug views read of the last step: the contacts the solver
//! pushed at, with impulses that balance the weight they carry, and the
//! broadphase's occupied cells.

mod common;

use common::{build, empty_room};
use glam::DVec3;
use rolypoly_physics::{BallPlacement, ContactKind, World, WorldConfig};

fn resting(position: [f64; 3]) -> BallPlacement {
    BallPlacement::new(DVec3::from_array(position), DVec3::ZERO)
}

fn run(world: &mut World, seconds: f64) {
    for _ in 0..(seconds / world.config().solver.dt).round() as usize {
        world.step();
    }
}

/// A column of `n` balls of radius `r` resting on the floor, one on
/// another, settled for a second.
fn column(n: usize, r: f64, mass: f64) -> World {
    let mut cfg: WorldConfig = empty_room();
    cfg.balls.radius = r;
    cfg.balls.mass = mass;
    cfg.balls.friction = 0.0;
    // Side walls close by, so that the column cannot fall over.
    cfg.balls.placements = (0..n)
        .map(|k| resting([0.0, r + 2.0 * r * k as f64, 0.0]))
        .collect();
    let mut world = build(cfg, 1);
    run(&mut world, 1.0);
    world
}

/// Over a step the solver's impulses carry the weight above each contact.
/// (A lone ball resting on the floor is half held by the exact wall
/// impacts of its flight, which are no solver impulse: columns of two or
/// more.)
#[test]
fn a_resting_column_shows_each_contact_carrying_the_weight_above_it() {
    for (n, r, mass) in [(3, 0.15, 1.0), (2, 0.12, 0.25), (4, 0.1, 0.5)] {
        let world = column(n, r, mass);
        let dt = world.config().solver.dt;
        let g = world.config().gravity;
        let probes = world.contact_probes();
        let floor: Vec<_> = probes
            .iter()
            .filter(|p| p.kind == ContactKind::BallWall)
            .collect();
        assert_eq!(floor.len(), 1, "{n} balls: {probes:#?}");
        let floor = floor[0];
        // The floor carries the whole column over the step.
        let weight = n as f64 * mass * g * dt;
        assert!(
            (floor.impulse - weight).abs() < 0.02 * weight,
            "{n} balls: floor impulse {} against weight {weight}",
            floor.impulse
        );
        assert!((floor.normal - DVec3::Y).length() < 1e-9);
        assert!(floor.point.y.abs() < 1e-3, "{:?}", floor.point);
        assert!(floor.kept, "a contact held for a second is kept");
        let pairs: Vec<_> = probes
            .iter()
            .filter(|p| p.kind == ContactKind::BallBall)
            .collect();
        assert_eq!(pairs.len(), n - 1);
        for p in pairs {
            // The balls above the pair's lower one.
            let [a, b] = p.balls.map(|i| i.expect("two balls"));
            let lower = world.balls().positions()[a]
                .y
                .min(world.balls().positions()[b].y);
            let above = world
                .balls()
                .positions()
                .iter()
                .filter(|q| q.y > lower + r)
                .count();
            let carried = above as f64 * mass * g * dt;
            assert!(
                (p.impulse - carried).abs() < 0.02 * carried,
                "{n} balls: pair impulse {} against {carried}",
                p.impulse
            );
            assert!(p.normal.y.abs() > 0.999 && p.kept);
            // The point lies between the two centres, on the first ball.
            let centre = world.balls().positions()[a];
            assert!((p.point.distance(centre) - r).abs() < 1e-3);
        }
    }
}

#[test]
fn a_ball_landing_makes_a_new_contact_that_is_kept_after() {
    let mut cfg = empty_room();
    cfg.balls.restitution = 0.0;
    cfg.balls.placements = vec![resting([0.5, 0.3, -0.5])];
    let mut world = build(cfg, 1);
    let mut states = Vec::new();
    for _ in 0..240 {
        world.step();
        if let Some(p) = world
            .contact_probes()
            .iter()
            .find(|p| p.kind == ContactKind::BallWall)
        {
            states.push(p.kept);
        }
    }
    assert!(!states.is_empty(), "the ball never touched the floor");
    assert!(!states[0], "the first step on the floor is a new contact");
    assert!(states[1..].iter().all(|&kept| kept), "{states:?}");
}

#[test]
fn every_ball_lies_in_an_occupied_cell_and_no_cell_is_empty() {
    for (count, seed) in [(30, 1), (500, 2), (2000, 3)] {
        let mut cfg = WorldConfig::default();
        cfg.balls.count = count;
        let mut world = build(cfg, seed);
        run(&mut world, 0.2);
        // The grid is built where the balls stand as a step begins.
        let positions = world.balls().positions().to_vec();
        world.step();
        let (cells, edge) = world.occupied_cells();
        assert!(edge > 0.0);
        let inside = |p: DVec3, corner: DVec3| {
            let d = p - corner;
            d.min_element() >= -1e-9 && d.max_element() <= edge + 1e-9
        };
        for p in &positions {
            assert!(cells.iter().any(|&c| inside(*p, c)), "{p} in no cell");
        }
        for c in &cells {
            assert!(
                positions.iter().any(|p| inside(*p, *c)),
                "cell {c} holds no ball"
            );
        }
        let mut unique = cells.clone();
        unique.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
        unique.dedup();
        assert_eq!(unique.len(), cells.len(), "a cell listed twice");
    }
}

#[test]
fn a_standing_tumbler_shows_its_rolling_contact_on_the_floor() {
    let world = build(WorldConfig::default(), 1);
    let rolling: Vec<_> = world
        .contact_probes()
        .into_iter()
        .filter(|p| p.kind == ContactKind::TumblerFloor && p.normal == DVec3::Y)
        .collect();
    assert_eq!(rolling.len(), world.tumblers().len());
    for (p, t) in rolling.iter().zip(world.tumblers()) {
        assert!(p.point.y.abs() < 1e-9 && p.point.distance(t.contact_point()) < 1e-12);
        assert!(p.impulse > 0.0);
    }
}
