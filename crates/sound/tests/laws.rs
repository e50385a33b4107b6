//! The sound checked against the physics it comes from: each impact heard
//! once at its moment, pitch against size, loudness against speed and side,
//! silence after rest, and the same samples on every run.

mod spectrum;

use glam::DVec3;
use rolypoly_physics::{BallPlacement, Event, EventKind, TumblerPlacement, World, WorldConfig};
use rolypoly_sound::{
    CEILING, Listener, SAMPLE_RATE, SPEED_OF_SOUND, SoundConfig, Soundtrack, to_pcm,
};
use spectrum::spectral_peak;

const RATE: f64 = SAMPLE_RATE as f64;

/// A room with only the balls placed: no random balls, no tumblers.
fn room_with(balls: &[(DVec3, DVec3)]) -> WorldConfig {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 0;
    cfg.tumblers.placements.clear();
    cfg.balls.placements = balls
        .iter()
        .map(|&(p, v)| BallPlacement::new(p, v))
        .collect();
    cfg
}

/// A listener standing at `position` and looking along -z.
fn ear_at(position: DVec3) -> Listener {
    Listener {
        position,
        forward: -DVec3::Z,
    }
}

/// What a run of `steps` sounds like, and each impact with the moment it
/// is heard at the listener.
struct Heard {
    frames: Vec<[f32; 2]>,
    impacts: Vec<(f64, Event)>,
    sound: Soundtrack,
}

fn hear(world: &mut World, ear: &Listener, config: &SoundConfig, steps: usize) -> Heard {
    let mut sound = Soundtrack::new(config, world);
    let mut events = Vec::new();
    let mut impacts = Vec::new();
    let dt = world.config().solver.dt;
    for _ in 0..steps {
        let start = world.time();
        world.step();
        world.take_events(&mut events);
        for e in &events {
            let travel = (e.point - ear.position).length() / SPEED_OF_SOUND;
            impacts.push((start + e.within_step + travel, *e));
        }
        sound.hear_step(world, &events, ear);
        assert!((world.time() - start - dt).abs() < 1e-12);
    }
    Heard {
        frames: sound.take_frames(),
        impacts,
        sound,
    }
}

fn mono(frames: &[[f32; 2]]) -> Vec<f32> {
    frames.iter().map(|f| f[0] + f[1]).collect()
}

/// Onsets: a sample louder than `floor` and than 8 times (18 dB) the
/// loudest of the 10 ms before it (less the last 0.25 ms, where a pulse
/// already rises); then 20 ms before the next may be found.
fn onsets(signal: &[f32], floor: f32) -> Vec<f64> {
    let (window, skip, refractory) = (480, 12, 960);
    let mut found = Vec::new();
    let mut n = window + skip;
    while n < signal.len() {
        let x = signal[n].abs();
        let before = signal[n - window - skip..n - skip]
            .iter()
            .fold(0.0f32, |m, s| m.max(s.abs()));
        if x > floor && x > 8.0 * before {
            found.push(n as f64 / RATE);
            n += refractory;
        } else {
            n += 1;
        }
    }
    found
}

/// The impacts that must be heard: those faster than this (m/s).
const LOUD: f64 = 1.5;

#[test]
fn each_loud_impact_is_heard_once_at_its_moment() {
    // Balls thrown up at different speeds from the same height land in
    // turn; a dead floor (e = 0.3) keeps their rebounds few.
    for (seed, spread) in [(1u64, 0.0), (2, 0.7), (3, -0.5)] {
        let throws = [0.0, 3.0, 6.0, 4.5];
        let balls: Vec<_> = throws
            .iter()
            .enumerate()
            .map(|(k, &up)| {
                let x = -2.4 + 1.6 * k as f64 + spread;
                (DVec3::new(x, 1.0, spread), DVec3::new(0.0, up, 0.0))
            })
            .collect();
        let mut cfg = room_with(&balls);
        cfg.room.restitution = 0.3;
        let mut world = World::new(cfg, seed).unwrap();
        let ear = ear_at(DVec3::new(0.5 - spread, 1.6, 3.0 + spread));
        let heard = hear(&mut world, &ear, &SoundConfig::default(), 360);
        // A body's ring builds in a sample; the slope shows the new
        // strike over the boards' slow low ringing of the one before.
        let signal: Vec<f32> = mono(&heard.frames)
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        let peak = signal.iter().fold(0.0f32, |m, s| m.max(s.abs()));
        let found = onsets(&signal, 0.05 * peak);
        let loud: Vec<f64> = heard
            .impacts
            .iter()
            .filter(|(_, e)| e.speed > LOUD)
            .map(|&(t, _)| t)
            .collect();
        assert!(loud.len() >= 6, "seed {seed}: {} loud impacts", loud.len());
        for &t in &loud {
            let near = found.iter().filter(|&&o| (o - t).abs() < 0.002).count();
            assert_eq!(
                near, 1,
                "seed {seed}: impact at {t:.4} s heard {near} times; onsets {found:?}"
            );
        }
        for &o in &found {
            assert!(
                heard.impacts.iter().any(|&(t, _)| (o - t).abs() < 0.002),
                "seed {seed}: an onset at {o:.4} s with no impact; impacts {:?}",
                heard.impacts.iter().map(|x| x.0).collect::<Vec<_>>()
            );
        }
    }
}

/// The sound of one ball of `radius` dropped onto the floor, from its
/// impact on.
fn one_drop(
    radius: f64,
    mass: f64,
    speed: f64,
    ear: &Listener,
    config: &SoundConfig,
) -> Vec<[f32; 2]> {
    let start = DVec3::new(0.0, radius + 0.01, 0.0);
    let mut cfg = room_with(&[(start, DVec3::new(0.0, -speed, 0.0))]);
    cfg.balls.radius = radius;
    cfg.balls.mass = mass;
    let mut world = World::new(cfg, 1).unwrap();
    let heard = hear(&mut world, ear, config, 48);
    let first = heard.impacts.first().expect("the ball lands").0;
    heard.frames[(first * RATE) as usize - 48..].to_vec()
}

/// The sound of two balls of `radius` meeting head-on in mid-air, from
/// their impact on: the balls alone, no floor.
fn mid_air(radius: f64, mass: f64, ear: &Listener) -> Vec<f32> {
    let mut cfg = room_with(&[
        (DVec3::new(-0.5, 2.5, 0.0), DVec3::new(3.0, 0.0, 0.0)),
        (DVec3::new(0.5, 2.5, 0.0), DVec3::new(-3.0, 0.0, 0.0)),
    ]);
    cfg.balls.radius = radius;
    cfg.balls.mass = mass;
    let mut world = World::new(cfg, 1).unwrap();
    let heard = hear(&mut world, ear, &SoundConfig::default(), 60);
    assert_eq!(heard.impacts.len(), 1, "one impact, in the air");
    let first = heard.impacts[0].0;
    mono(&heard.frames[(first * RATE) as usize - 48..])
}

#[test]
fn a_ball_of_half_the_radius_rings_an_octave_higher() {
    let ear = ear_at(DVec3::new(0.0, 1.6, 2.0));
    for (radius, mass) in [(0.12, 0.25), (0.08, 0.5), (0.06, 0.1)] {
        let big = mid_air(radius, mass, &ear);
        let small = mid_air(radius / 2.0, mass / 8.0, &ear);
        let (f_big, f_small) = (
            spectral_peak(&big, 100.0, 23_000.0),
            spectral_peak(&small, 100.0, 23_000.0),
        );
        let ratio = f_small / f_big;
        assert!(
            (ratio - 2.0).abs() < 0.04,
            "radius {radius}: {f_big:.0} Hz and {f_small:.0} Hz, ratio {ratio:.4}"
        );
    }
}

fn peak(frames: &[[f32; 2]], channel: usize) -> f32 {
    frames.iter().fold(0.0, |m, f| m.max(f[channel].abs()))
}

fn energy(frames: &[[f32; 2]], channel: usize) -> f64 {
    frames.iter().map(|f| (f[channel] as f64).powi(2)).sum()
}

#[test]
fn a_harder_hit_is_louder() {
    let ear = ear_at(DVec3::new(0.0, 1.2, 2.0));
    // Quiet enough that the limiter never acts: the law is the synthesis'.
    let config = SoundConfig {
        volume: 0.02,
        ..SoundConfig::default()
    };
    for (radius, mass) in [(0.12, 0.25), (0.05, 1.0)] {
        let mut last = 0.0;
        for speed in [0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0] {
            let frames = one_drop(radius, mass, speed, &ear, &config);
            let loudest = peak(&frames, 0).max(peak(&frames, 1));
            assert!(loudest < CEILING, "{loudest} reached the limiter");
            assert!(
                loudest > last,
                "radius {radius}: {speed} m/s peaks at {loudest}, no louder than {last}"
            );
            last = loudest;
        }
    }
}

#[test]
fn a_hit_on_the_left_is_heard_on_the_left() {
    for (distance, facing) in [
        (2.0, -DVec3::Z),
        (3.5, DVec3::X),
        (1.5, DVec3::new(1.0, 0.0, 1.0)),
    ] {
        let facing: DVec3 = facing.normalize();
        let ear = Listener {
            position: DVec3::new(0.5, 1.0, 0.5),
            forward: facing,
        };
        // 45 degrees to the left of where the listener looks.
        let left = facing.cross(DVec3::Y).normalize() * -1.0;
        let towards = (facing + left).normalize();
        let spot = ear.position + towards * distance;
        let mut cfg = room_with(&[(DVec3::new(spot.x, 0.13, spot.z), DVec3::new(0.0, -3.0, 0.0))]);
        cfg.balls.radius = 0.12;
        let mut world = World::new(cfg, 1).unwrap();
        let heard = hear(&mut world, &ear, &SoundConfig::default(), 60);
        let ratio_db = 10.0 * (energy(&heard.frames, 0) / energy(&heard.frames, 1)).log10();
        assert!(
            ratio_db >= 6.0,
            "facing {facing}: left {ratio_db:.1} dB over right"
        );
    }
}

#[test]
fn once_everything_rests_the_room_falls_silent_within_a_second() {
    // The default room, tumblers and all, with fewer balls.
    for seed in [1u64, 4, 9] {
        let mut cfg = WorldConfig::default();
        cfg.balls.count = 8;
        let mut world = World::new(cfg, seed).unwrap();
        let ear = ear_at(DVec3::new(0.0, 1.6, 3.5));
        let mut sound = Soundtrack::new(&SoundConfig::default(), &world);
        let mut events = Vec::new();
        let mut rested = None;
        let mut frames = Vec::new();
        for step in 0..120 * 40 {
            world.step();
            world.take_events(&mut events);
            sound.hear_step(&world, &events, &ear);
            frames.extend(sound.take_frames());
            let moving = world
                .balls()
                .velocities()
                .iter()
                .any(|v| v.length() > 0.005)
                || world.tumblers().iter().any(|t| {
                    t.linear_velocity().length() > 0.005 || t.angular_velocity().length() > 0.02
                });
            match (rested, moving) {
                (None, false) => rested = Some(step),
                (Some(_), true) => rested = None,
                (Some(at), false) if step >= at + 120 + 12 => break,
                _ => {}
            }
        }
        let at = rested.expect("the balls come to rest within 40 s");
        let later = &frames[(at + 120) * 400..];
        let loudest = peak(later, 0).max(peak(later, 1));
        assert!(
            20.0 * loudest.log10() < -60.0,
            "seed {seed}: {:.1} dBFS a second after rest",
            20.0 * loudest.log10()
        );
    }
}

fn pcm_of(threads: usize, seconds: usize) -> Vec<i16> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut cfg = WorldConfig::default();
        cfg.balls.count = 600;
        cfg.balls.radius = 0.08;
        let mut world = World::new(cfg, 7).unwrap();
        world.launch_fireball(None);
        let ear = ear_at(DVec3::new(1.0, 1.6, 3.5));
        let heard = hear(&mut world, &ear, &SoundConfig::default(), 120 * seconds);
        heard
            .frames
            .iter()
            .flat_map(|f| [to_pcm(f[0]), to_pcm(f[1])])
            .collect()
    })
}

#[test]
fn the_same_run_gives_the_same_samples_on_any_thread_count() {
    let one = pcm_of(1, 2);
    assert!(one.iter().any(|&s| s.abs() > 1000), "the run is heard");
    assert_eq!(one, pcm_of(2, 2), "one thread and two");
    assert_eq!(one, pcm_of(2, 2), "a rerun");
}

/// The energy of `signal` at `frequency` (Goertzel's single bin).
fn tone(signal: &[f32], frequency: f64) -> f64 {
    let w = std::f64::consts::TAU * frequency / RATE;
    let (mut s1, mut s2) = (0.0, 0.0);
    for &x in signal {
        let s = x as f64 + 2.0 * w.cos() * s1 - s2;
        s2 = s1;
        s1 = s;
    }
    s1 * s1 + s2 * s2 - 2.0 * w.cos() * s1 * s2
}

#[test]
fn the_tumblers_bells_chime_only_while_they_rock() {
    for tilt in [0.0, 25.0, 40.0] {
        let mut cfg = WorldConfig::default();
        cfg.balls.count = 0;
        cfg.tumblers.placements = (0..3)
            .map(|k| TumblerPlacement {
                x: -2.0 + 2.0 * k as f64,
                z: 0.0,
                tilt_axis: DVec3::new(1.0, 0.0, 0.3 * k as f64),
                tilt_deg: tilt,
            })
            .collect();
        let mut world = World::new(cfg, 3).unwrap();
        let ear = ear_at(DVec3::new(0.0, 1.6, 3.5));
        let mut sound = Soundtrack::new(&SoundConfig::default(), &world);
        let mut events = Vec::new();
        let mut signal = Vec::new();
        let mut last_rocking_chimes = 0;
        for _ in 0..120 * 12 {
            world.step();
            world.take_events(&mut events);
            sound.hear_step(&world, &events, &ear);
            signal.extend(mono(&sound.take_frames()));
            let rocking = world
                .tumblers()
                .iter()
                .any(|t| t.angular_velocity().length() > 0.05);
            if rocking {
                last_rocking_chimes = sound.chimes();
            }
        }
        let still = world.tumblers().iter().all(|t| t.tilt() < 0.05);
        assert!(still, "tilt {tilt}: the tumblers settle within 12 s");
        assert_eq!(
            sound.chimes(),
            last_rocking_chimes,
            "tilt {tilt}: a chime after they stopped"
        );
        let bell = tone(&signal, 2093.0).sqrt() / signal.len() as f64;
        if tilt == 0.0 {
            assert_eq!(sound.chimes(), 0, "upright tumblers do not chime");
        } else {
            // Each starts leaning, swings through upright and past the
            // bell's angle on the other side.
            assert!(
                sound.chimes() >= 3,
                "tilt {tilt}: {} chimes",
                sound.chimes()
            );
            assert!(
                bell > 1e-6,
                "tilt {tilt}: the bell's note is heard ({bell:e})"
            );
        }
    }
}

#[test]
fn impacts_between_balls_strike_both() {
    // Two balls meet head-on in the air: both ring, then fall silent.
    let mut cfg = room_with(&[
        (DVec3::new(-0.5, 2.0, 0.0), DVec3::new(3.0, 0.0, 0.0)),
        (DVec3::new(0.5, 2.0, 0.0), DVec3::new(-3.0, 0.0, 0.0)),
    ]);
    cfg.balls.radius = 0.1;
    let mut world = World::new(cfg, 1).unwrap();
    let ear = ear_at(DVec3::new(0.0, 1.6, 3.0));
    let heard = hear(&mut world, &ear, &SoundConfig::default(), 30);
    assert!(
        heard
            .impacts
            .iter()
            .any(|(_, e)| matches!(e.kind, EventKind::BallBall { .. }))
    );
    assert_eq!(heard.sound.strikes(), (2, 0), "one strike a ball");
    // Rung out within the quarter second.
    assert_eq!(heard.sound.voices(), 0);
}
