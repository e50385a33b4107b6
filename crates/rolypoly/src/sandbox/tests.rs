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
        s.load(scene.clone(), shipped.name).unwrap();
        assert_eq!(s.scene_name(), shipped.name);
        assert_eq!(s.world().config(), &scene.world);
        assert_eq!(s.world().time(), 0.0);
        assert!(!s.restart_pending());
    }
}
