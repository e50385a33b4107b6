//! The effects driven by real physics events: a wall hit spreads in the
//! wall's plane; a ball hit converges on the ball, then bursts (X3, X4).

use glam::{DVec3, Vec3};
use rolypoly_fx::{Effects, EffectsConfig, FLASH_SECONDS, ParticleKind};
use rolypoly_physics::{Event, EventKind, World, WorldConfig};

fn weightless_room(balls: usize) -> World {
    let mut cfg = WorldConfig {
        gravity: 0.0,
        ..WorldConfig::default()
    };
    cfg.balls.count = balls;
    cfg.tumblers.placements.clear();
    World::new(cfg, 1).expect("scene builds")
}

/// One step of `world`, then of the effects with its events, as the
/// program ticks them.
fn tick(world: &mut World, fx: &mut Effects, events: &mut Vec<Event>) {
    world.step();
    world.take_events(events);
    fx.consume(events, world);
    fx.update(world.config().solver.dt, world.fireball());
}

/// Steps world and effects together until `want` appears; returns that event.
fn run_until(world: &mut World, fx: &mut Effects, want: fn(&EventKind) -> bool) -> Event {
    let mut events = Vec::new();
    for _ in 0..600 {
        tick(world, fx, &mut events);
        if let Some(e) = events.iter().find(|e| want(&e.kind)) {
            return *e;
        }
    }
    panic!("the event never came");
}

#[test]
fn a_wall_hit_spreads_in_the_wall_plane() {
    let mut world = weightless_room(0);
    let mut fx = Effects::new(EffectsConfig::default(), 1);
    world.launch_fireball(Some((DVec3::new(0.0, 2.0, 0.0), DVec3::NEG_X)));
    let hit = run_until(&mut world, &mut fx, |k| {
        matches!(k, EventKind::FireballSurface { .. })
    });
    world.remove_fireball();
    let (centre, normal) = (hit.point.as_vec3(), hit.normal.as_vec3());
    assert_eq!(normal, Vec3::X, "the left wall faces +x");
    let dt = 1.0 / 120.0;
    let duration = fx.config().wall_hit.duration;
    let mut mean_radius_of_new = Vec::new();
    let mut seen = 0;
    for _ in 0..(duration / dt) as usize {
        fx.update(dt, None);
        let wall: Vec<_> = fx
            .particles()
            .filter(|p| p.kind == ParticleKind::WallHit)
            .collect();
        for p in &wall {
            let off_plane = (p.position() - centre).dot(normal);
            assert!(
                off_plane.abs() < 0.05,
                "a wall-hit cube is {off_plane} m off the wall"
            );
        }
        // The newest cubes show where the ring is now.
        let new: Vec<f32> = wall
            .iter()
            .filter(|p| p.age <= dt as f32 + 1e-6)
            .map(|p| (p.position() - centre).length())
            .collect();
        if !new.is_empty() {
            mean_radius_of_new.push(new.iter().sum::<f32>() / new.len() as f32);
        }
        seen = seen.max(wall.len());
    }
    assert!(seen > 20, "only {seen} cubes");
    let n = mean_radius_of_new.len();
    assert!(n > 10);
    let early = mean_radius_of_new[..n / 4].iter().sum::<f32>() / (n / 4) as f32;
    let late = mean_radius_of_new[3 * n / 4..].iter().sum::<f32>() / (n - 3 * n / 4) as f32;
    assert!(
        late > 1.5 * early,
        "the ring does not spread: {early} m early, {late} m late"
    );
    // After the event and its cubes' lives, nothing is left.
    for _ in 0..120 {
        fx.update(dt, None);
    }
    assert_eq!(fx.stats().live, 0);
    assert_eq!(fx.stats().wall_hits, 0);
}

#[test]
fn a_ball_hit_collapses_onto_the_ball_then_bursts() {
    let mut world = weightless_room(1);
    world
        .balls_mut()
        .set(0, DVec3::new(1.0, 2.0, 0.5), DVec3::ZERO);
    let mut fx = Effects::new(EffectsConfig::default(), 2);
    world.launch_fireball(Some((DVec3::new(-1.0, 2.0, 0.5), DVec3::X)));
    let hit = run_until(&mut world, &mut fx, |k| {
        matches!(k, EventKind::FireballBall { .. })
    });
    world.remove_fireball();
    let centre = Vec3::new(1.0, 2.0, 0.5);
    assert!(
        (hit.point - hit.normal * world.balls().radii()[0])
            .as_vec3()
            .distance(centre)
            < 1e-5
    );
    // The caught ball is drawn shrinking at the centre until the burst.
    let (at, radius, _) = fx
        .captured_balls()
        .next()
        .expect("the ball is held by the collapse");
    assert!(at.distance(centre) < 1e-5 && radius > 0.0);

    let dt = 1.0 / 120.0;
    let cfg = fx.config().ball_hit.clone();
    let mut bursts = 0;
    let mut last_radius = radius;
    for _ in 0..((cfg.duration + cfg.burst_life) / dt) as usize + 2 {
        // Every collapsing cube must be on its way in, and reach the centre
        // when its life ends.
        for p in fx.particles().filter(|p| p.kind == ParticleKind::Collapse) {
            assert_eq!(p.target, centre);
            let left = p.life - p.age;
            let speed = p.origin.distance(p.target) / p.life;
            assert!(
                (p.position().distance(centre) - speed * left).abs() < 1e-3,
                "a cube is off its path"
            );
        }
        fx.update(dt, None);
        if let Some((_, r, _)) = fx.captured_balls().next() {
            assert!(r <= last_radius, "the caught ball grows");
            last_radius = r;
        }
        bursts = bursts.max(
            fx.particles()
                .filter(|p| p.kind == ParticleKind::Burst)
                .count(),
        );
    }
    assert_eq!(bursts, 2, "two particles burst when the collapse ends");
    assert!(
        fx.captured_balls().next().is_none(),
        "the ball vanishes at the burst"
    );
}

#[test]
fn the_trail_follows_the_fireball() {
    let mut world = weightless_room(0);
    let mut fx = Effects::new(EffectsConfig::default(), 3);
    world.launch_fireball(Some((DVec3::new(-3.0, 2.0, 0.0), DVec3::X)));
    for _ in 0..40 {
        world.step();
        world.drain_events().for_each(drop);
        fx.update(world.config().solver.dt, world.fireball());
    }
    let trail: Vec<_> = fx
        .particles()
        .filter(|p| p.kind == ParticleKind::Trail)
        .collect();
    assert!(trail.len() > 5, "only {} trail cubes", trail.len());
    let radius = world.fireball().unwrap().radius as f32;
    for p in &trail {
        let pos = p.position();
        assert!(
            (pos.y - 2.0).abs() < radius && pos.z.abs() < radius,
            "a cube off the path: {pos}"
        );
        assert!(
            pos.x >= -3.0 - radius && pos.x <= world.fireball().unwrap().position.x as f32 + radius
        );
    }
    // Older cubes are smaller and fainter.
    let (old, young) = (trail.first().unwrap(), trail.last().unwrap());
    assert!(old.kind.size(old.progress()) < young.kind.size(young.progress()));
}

#[test]
fn the_same_seed_gives_the_same_particles() {
    let run = || {
        let mut world = weightless_room(0);
        let mut fx = Effects::new(EffectsConfig::default(), 9);
        world.launch_fireball(Some((
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(-1.0, 0.3, 0.2),
        )));
        let mut events = Vec::new();
        for _ in 0..200 {
            tick(&mut world, &mut fx, &mut events);
        }
        fx.particles()
            .map(|p| (p.position().to_array(), p.size()))
            .collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}

#[test]
fn a_hit_flashes_where_it_happened_and_the_flash_fades_out() {
    let mut world = weightless_room(0);
    let mut fx = Effects::new(EffectsConfig::default(), 1);
    assert_eq!(fx.flash(), None, "nothing has been hit");
    world.launch_fireball(Some((DVec3::new(0.0, 2.0, 0.0), DVec3::NEG_X)));
    let hit = run_until(&mut world, &mut fx, |k| {
        matches!(k, EventKind::FireballSurface { .. })
    });
    world.remove_fireball();
    let first = fx.flash().expect("a flash at the hit");
    assert_eq!(first.position, hit.point.as_vec3());
    assert!(first.strength > 0.9, "{first:?}");
    // It only fades, and is gone after FLASH_SECONDS.
    let dt = 1.0 / 120.0;
    let mut last = first.strength;
    for _ in 0..(FLASH_SECONDS / dt as f32) as usize + 2 {
        fx.update(dt, None);
        let now = fx.flash().map_or(0.0, |f| f.strength);
        assert!(now <= last, "{now} after {last}");
        last = now;
    }
    assert_eq!(fx.flash(), None);
}
