//! The sandbox as the panel and the keys drive it, without a window.

use std::time::Duration;

use glam::DVec3;

use super::*;

fn sandbox(seed: u64) -> Sandbox {
    Sandbox::new(Scene::default(), "default.toml", seed).unwrap()
}

/// Frames of `frame` seconds whose steps cost nothing.
fn frames(sandbox: &mut Sandbox, count: usize, frame: f64) -> u32 {
    (0..count)
        .map(|_| sandbox.frame(frame, || Duration::ZERO))
        .sum()
}

/// The mean vertical acceleration of the balls in flight over the next step.
fn free_fall(sandbox: &mut Sandbox) -> f64 {
    let before: Vec<DVec3> = sandbox.world().balls().velocities().to_vec();
    sandbox.playback.set_paused(true);
    sandbox.playback.step_once();
    assert_eq!(frames(sandbox, 1, 0.0), 1);
    let dt = sandbox.world().config().solver.dt;
    let after = sandbox.world().balls().velocities();
    // The one ball thrown into the middle of the room, far from anything.
    let k = after.len() - 1;
    (after[k].y - before[k].y) / dt
}

#[test]
fn changing_gravity_changes_the_next_steps_acceleration() {
    for (seed, gravity) in [(1, 3.0), (2, 0.0), (3, 24.0)] {
        let mut s = sandbox(seed);
        let centre = s.world().room().min.lerp(s.world().room().max, 0.5) + DVec3::Y;
        s.throw(centre, DVec3::X).unwrap();
        s.throw_speed = 0.0;
        let g0 = s.scene().world.gravity;
        assert!((free_fall(&mut s) + g0).abs() < 1e-9);
        let mut scene = s.scene().clone();
        scene.world.gravity = gravity;
        s.set_scene(scene).unwrap();
        assert!(!s.restart_pending());
        let a = free_fall(&mut s);
        assert!((a + gravity).abs() < 1e-9, "gravity {gravity}: {a}");
    }
}

#[test]
fn a_setting_out_of_range_is_refused_whole() {
    let mut s = sandbox(1);
    let mut scene = s.scene().clone();
    scene.world.gravity = 2.0;
    scene.world.balls.restitution = 1.5;
    let error = s.set_scene(scene).unwrap_err().to_string();
    assert!(error.contains("balls.restitution = 1.5"), "{error}");
    assert_eq!(s.scene(), &Scene::default());
    assert_eq!(s.world().config(), &Scene::default().world);
}

#[test]
fn pause_stops_the_step_count_and_a_single_step_advances_it_by_one() {
    for seed in [1, 2] {
        let mut s = sandbox(seed);
        frames(&mut s, 30, 1.0 / 60.0);
        let running = s.world().step_count();
        assert_eq!(running, 60);
        s.playback.set_paused(true);
        frames(&mut s, 60, 1.0 / 60.0);
        assert_eq!(s.world().step_count(), running);
        for n in 1..=3 {
            s.playback.step_once();
            frames(&mut s, 5, 1.0 / 60.0);
            assert_eq!(s.world().step_count(), running + n);
        }
    }
}

#[test]
fn a_quarter_time_scale_runs_a_quarter_of_the_steps_per_second_of_frames() {
    for fps in [24.0, 60.0] {
        let mut s = sandbox(1);
        let per_second = 1.0 / s.world().config().solver.dt;
        s.playback.set_scale(0.25);
        let steps = frames(&mut s, (4.0 * fps) as usize, 1.0 / fps);
        let expected = 4.0 * per_second / 4.0;
        assert!(
            (f64::from(steps) - expected).abs() <= 1.0,
            "{steps} vs {expected}"
        );
        // The step is the scene's, never a larger one.
        assert!((s.world().time() - f64::from(steps) * s.world().config().solver.dt).abs() < 1e-9);
    }
}

#[test]
fn sizes_wait_for_the_restart_which_builds_the_world_anew() {
    let mut s = sandbox(4);
    let mut scene = s.scene().clone();
    scene.world.balls.count = 12;
    scene.world.balls.radius = 0.15;
    scene.world.gravity = 5.0;
    s.set_scene(scene).unwrap();
    assert!(s.restart_pending());
    assert_eq!(s.world().config().gravity, 5.0, "gravity holds at once");
    assert_eq!(s.world().balls().len(), Scene::default().world.balls.count);
    s.restart().unwrap();
    assert!(!s.restart_pending());
    assert_eq!(s.world().balls().len(), 12);
    assert!(s.world().balls().radii().iter().all(|&r| r == 0.15));
    assert_eq!(s.world().config(), &s.scene().world);
}

#[test]
fn throws_stop_at_the_cap_with_a_message_until_the_restart() {
    let mut s = sandbox(5);
    let start = s.world().balls().len();
    let eye = DVec3::new(0.0, 2.0, 3.5);
    for k in 0..MAX_THROWN {
        assert_eq!(s.throw(eye, DVec3::NEG_Z), Ok(start + k));
        if k % 50 == 0 {
            frames(&mut s, 1, 1.0 / 60.0);
        }
    }
    assert_eq!(s.world().balls().len(), start + MAX_THROWN);
    let refused = s.throw(eye, DVec3::NEG_Z).unwrap_err();
    assert!(refused.to_string().contains("press I"), "{refused}");
    s.restart().unwrap();
    assert_eq!((s.world().balls().len(), s.thrown()), (start, 0));
    assert!(s.throw(eye, DVec3::NEG_Z).is_ok());
}

#[test]
fn a_throw_at_a_speed_no_player_can_set_is_refused() {
    let mut s = sandbox(6);
    let balls = s.world().balls().len();
    for speed in [1e300, -1.0, 0.0, THROW_SPEEDS.1 * 1.01] {
        let throw = Input::Throw {
            from: [0.0, 2.0, 1.0],
            direction: [0.0, 0.0, -1.0],
            speed,
        };
        let refused = s.apply(throw).unwrap_err().to_string();
        assert!(refused.starts_with("a ball thrown at"), "{refused}");
    }
    assert_eq!((s.world().balls().len(), s.thrown()), (balls, 0));
}

#[test]
fn a_thrown_ball_leaves_along_the_view_at_the_throw_speed() {
    let mut s = sandbox(6);
    s.throw_speed = 12.0;
    let dir = DVec3::new(0.2, 0.1, -1.0);
    let k = s.throw(DVec3::new(0.0, 2.0, 1.0), dir).unwrap();
    let v = s.world().balls().velocities()[k];
    assert!((v - dir.normalize() * 12.0).length() < 1e-12, "{v}");
}

#[test]
fn a_shipped_scene_loads_at_once_with_its_settings() {
    let mut s = sandbox(7);
    for shipped in SHIPPED_SCENES
        .iter()
        .filter(|s| !s.name.starts_with("ballpit"))
    {
        let scene = scene::parse_scene(shipped.text, shipped.name).unwrap();
        s.load(shipped.text, shipped.name).unwrap();
        assert_eq!(s.scene_name(), shipped.name);
        assert_eq!(s.world().config(), &scene.world);
        assert_eq!(s.world().time(), 0.0);
        assert!(!s.restart_pending());
    }
}

/// A scripted session: every kind of input, at ticks spread over the run,
/// with pauses, single steps and time scales between them.
fn scripted_session(s: &mut Sandbox, rng: &mut rolypoly_physics::Rng) {
    let eye = DVec3::new(0.0, 2.0, 3.5);
    let frame = |s: &mut Sandbox, n: usize| {
        for _ in 0..n {
            s.frame(1.0 / 60.0, || Duration::ZERO);
        }
    };
    frame(s, 20);
    s.start_recording();
    for round in 0..3 {
        s.throw(eye, DVec3::new(rng.range(-0.3, 0.3), -0.2, -1.0))
            .unwrap();
        frame(s, 7);
        s.apply(Input::Fireball {
            from: [0.0, 1.5, 3.0],
            direction: [rng.range(-0.2, 0.2), -0.1, -1.0],
        })
        .unwrap();
        s.playback.set_scale(0.25);
        frame(s, 9);
        s.playback.set_scale(2.0);
        let t = s.world().tumblers()[round].center_of_mass();
        s.apply(Input::Grab {
            tumbler: round,
            point: t.to_array(),
        })
        .unwrap();
        for k in 0..10 {
            let to = t + DVec3::new(0.02 * f64::from(k), 0.0, 0.01 * f64::from(k));
            s.apply(Input::Drag { to: to.to_array() }).unwrap();
            frame(s, 1);
        }
        s.apply(Input::Release).unwrap();
        // The hand takes a ball, swings it up and lets it fly.
        let ball = round % s.world().balls().len().max(1);
        let at = s.world().balls().positions()[ball];
        s.apply(Input::GrabBall { ball }).unwrap();
        for k in 0..8 {
            let to = at + DVec3::new(0.05 * f64::from(k), 0.04 * f64::from(k), 0.0);
            s.apply(Input::Drag { to: to.to_array() }).unwrap();
            frame(s, 1);
        }
        s.apply(Input::Release).unwrap();
        s.playback.set_paused(true);
        s.playback.step_once();
        frame(s, 3);
        s.playback.set_paused(false);
        let mut scene = s.scene().clone();
        scene.world.gravity = rng.range(2.0, 12.0);
        scene.world.balls.restitution = rng.range(0.3, 1.0);
        s.set_scene(scene).unwrap();
        s.apply(Input::Camera {
            position: [0.1, 1.0, 3.0],
            yaw: 0.2,
            pitch: -0.1,
        })
        .unwrap();
        frame(s, 11);
        s.apply(Input::FireballOff).unwrap();
        if round == 1 {
            s.restart().unwrap();
        }
    }
    frame(s, 15);
}

#[test]
fn a_recorded_session_replays_to_the_same_bits() {
    for seed in [11, 12, 13] {
        let mut s = sandbox(seed);
        scripted_session(&mut s, &mut rolypoly_physics::Rng::new(seed));
        let log = s.stop_recording().expect("a recording");
        assert!(log.from_tick > 0 && log.to_tick > log.from_tick);
        assert_eq!(log.end_digest, s.digest());
        // Through the file's text, as `rolypoly replay` reads it.
        let log = ReplayLog::parse(&log.to_text(), "session.replay").unwrap();
        let mut replay = Sandbox::for_replay(&log).unwrap();
        replay.replay_until(log.from_tick);
        assert_eq!(replay.ticks(), log.from_tick);
        replay.replay_until(u64::MAX);
        assert!(!replay.replaying());
        assert_eq!(replay.ticks(), log.to_tick);
        assert_eq!(replay.world().balls(), s.world().balls(), "seed {seed}");
        assert_eq!(replay.world().tumblers(), s.world().tumblers());
        assert_eq!(replay.digest(), log.end_digest);
        assert_eq!(replay.scene(), s.scene());
        assert_eq!(replay.view_pose, s.view_pose);
        // A replay held at its end steps no further until let go.
        replay.tick();
        assert_eq!(replay.ticks(), log.to_tick);
        replay.end_replay();
        replay.tick();
        assert_eq!(replay.ticks(), log.to_tick + 1);
    }
}

#[test]
fn a_replay_without_an_input_ends_elsewhere() {
    let mut s = sandbox(14);
    scripted_session(&mut s, &mut rolypoly_physics::Rng::new(14));
    let mut log = s.stop_recording().unwrap();
    let throw = log
        .inputs
        .iter()
        .position(|t| matches!(t.input, Input::Throw { .. }))
        .unwrap();
    log.inputs.remove(throw);
    let mut replay = Sandbox::for_replay(&log).unwrap();
    replay.replay_until(u64::MAX);
    assert_ne!(replay.digest(), log.end_digest);
}

#[test]
fn a_scene_loaded_while_recording_starts_the_recording_over_from_it() {
    let mut s = sandbox(15);
    s.start_recording();
    frames(&mut s, 10, 1.0 / 60.0);
    let cradle = SHIPPED_SCENES
        .iter()
        .find(|s| s.name == "newtons-cradle.toml")
        .unwrap();
    s.load(cradle.text, cradle.name).unwrap();
    frames(&mut s, 30, 1.0 / 60.0);
    let log = s.stop_recording().unwrap();
    assert_eq!(
        (log.name.as_str(), log.from_tick, log.to_tick),
        (cradle.name, 0, 60)
    );
    let mut replay = Sandbox::for_replay(&log).unwrap();
    replay.replay_until(u64::MAX);
    assert_eq!(replay.digest(), log.end_digest);
}

#[test]
fn a_broken_recording_is_refused_with_its_line() {
    let mut s = sandbox(16);
    s.start_recording();
    s.throw(DVec3::Y, DVec3::X).unwrap();
    frames(&mut s, 5, 1.0 / 60.0);
    let text = s.stop_recording().unwrap().to_text();
    for (broken, says) in [
        (String::new(), "x.replay: the file is empty"),
        ("{}".to_owned(), "x.replay:1: not a rolypoly recording"),
        (
            text.replacen("\"format\":1", "\"format\":9", 1),
            "x.replay:1: a recording of format 9",
        ),
        (
            text.replacen("\"kind\":\"throw\"", "\"kind\":\"jump\"", 1),
            "x.replay:2: unknown variant `jump`",
        ),
        (
            text.replacen("\"tick\":0", "\"tick\":99", 1),
            "x.replay:2: tick 99 is out of order",
        ),
    ] {
        let error = ReplayLog::parse(&broken, "x.replay")
            .unwrap_err()
            .to_string();
        assert!(error.starts_with(says), "{error}");
    }
}

/// Runs `ticks` ticks.
fn run(s: &mut Sandbox, ticks: u64) {
    for _ in 0..ticks {
        s.tick();
    }
}

#[test]
fn going_back_then_playing_on_gives_the_first_run_to_the_bit() {
    for seed in [21, 22, 23] {
        let mut s = sandbox(seed);
        scripted_session(&mut s, &mut rolypoly_physics::Rng::new(seed));
        let (end, digest) = (s.ticks(), s.digest());
        let dt = s.world().config().solver.dt;
        let second = (1.0 / dt).round() as u64;
        // A step back, a second back, and back to the start of the session
        // (which had every kind of input): each played on to the end.
        for back in [1, second, end - s.timeline().0, 7 * second / 3] {
            let reached = s.rewind_to(end - back);
            assert_eq!(reached, end - back, "seed {seed}: went back to {reached}");
            assert_ne!(s.digest(), digest);
            run(&mut s, back);
            assert_eq!(
                s.digest(),
                digest,
                "seed {seed}: {back} ticks back, played on"
            );
        }
        // Scrubbing back and forth within what happened lands on the same run.
        s.rewind_to(end / 2);
        s.rewind_to(end - 3);
        s.rewind_to(end);
        assert_eq!(s.digest(), digest, "seed {seed}: scrubbed");
    }
}

#[test]
fn acting_after_going_back_forgets_the_future_the_first_time_had() {
    let mut s = sandbox(5);
    run(&mut s, 120);
    let eye = DVec3::new(0.0, 1.5, 3.5);
    s.throw(eye, DVec3::new(0.1, -0.1, -1.0)).unwrap();
    run(&mut s, 240);
    let (end, first) = (s.ticks(), s.digest());
    let balls_first = s.world().balls().len();
    s.rewind_to(60);
    // A throw the first time did not have: a new future.
    s.throw(eye, DVec3::new(-0.3, 0.0, -1.0)).unwrap();
    run(&mut s, end - 60);
    assert_ne!(s.digest(), first);
    // Only the new throw happened: the first time's was forgotten.
    assert_eq!(s.world().balls().len(), balls_first);
    assert_eq!(s.timeline().1, end);
    // A camera's move is not an act: the future stays.
    let mut t = sandbox(5);
    run(&mut t, 120);
    t.throw(eye, DVec3::new(0.1, -0.1, -1.0)).unwrap();
    run(&mut t, 240);
    t.rewind_to(100);
    t.apply(Input::Camera {
        position: [0.0, 1.0, 3.0],
        yaw: 0.3,
        pitch: 0.0,
    })
    .unwrap();
    run(&mut t, end - 100);
    assert_eq!(t.digest(), first);
}

#[test]
fn the_history_reaches_thirty_seconds_back_and_no_further() {
    let mut s = sandbox(2);
    let dt = s.world().config().solver.dt;
    let second = (1.0 / dt).round() as u64;
    run(&mut s, 75 * second);
    let (oldest, furthest) = s.timeline();
    assert_eq!(furthest, s.ticks());
    let span = furthest - oldest;
    assert!(
        (30 * second..=31 * second).contains(&span),
        "reaches {} s back",
        span as f64 * dt
    );
    assert!(s.snapshots_kept() <= 32, "{} copies", s.snapshots_kept());
    // Asked to go further back, it goes as far as it reaches.
    assert_eq!(s.rewind_to(0), oldest);
}

#[test]
fn a_change_waits_for_the_restart_exactly_when_the_keys_table_says() {
    use crate::scene::keys::{KEYS, Takes, nearby_change};
    let default = Scene::default();
    for seed in [1, 7] {
        for key in KEYS {
            let Some(scene) = nearby_change(key, &default) else {
                continue;
            };
            let mut sandbox = Sandbox::new(default.clone(), "default.toml", seed).unwrap();
            sandbox.set_scene(scene.clone()).unwrap();
            assert_eq!(
                sandbox.restart_pending(),
                key.takes == Takes::Restart,
                "{}: the table says {:?}",
                key.name,
                key.takes
            );
            if key.takes == Takes::NextStep {
                assert_eq!(sandbox.world().config(), &scene.world, "{}", key.name);
            }
        }
    }
}
