//! The room's sound as the program makes it: `rolypoly sound` and
//! `record`'s sound track, the same samples every time, never clipping in
//! the loudest scenes shipped.

#[path = "../../sound/tests/spectrum/mod.rs"]
mod spectrum;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rolypoly::scene::{Overrides, load_scene_with};
use rolypoly::simulation::Simulation;
use rolypoly::sound::{Recording, StandIns, ticks_heard};
use rolypoly_physics::World;
use rolypoly_sound::{CEILING, Listener, to_pcm};
use spectrum::spectral_peak;

fn rolypoly(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .output()
        .expect("the rolypoly binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sound");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The samples of a 16-bit stereo WAV file at 48 kHz.
fn samples(path: &Path) -> Vec<i16> {
    let mut reader = hound::WavReader::open(path).expect("a WAV file");
    let spec = reader.spec();
    assert_eq!(
        (spec.channels, spec.sample_rate, spec.bits_per_sample),
        (2, 48_000, 16)
    );
    reader
        .samples::<i16>()
        .map(|s| s.expect("a sample"))
        .collect()
}

fn sound_of(scene: Option<&str>, seed: &str, seconds: &str, out: &Path) -> Vec<i16> {
    let mut args = vec!["sound", "--seconds", seconds, "--seed", seed, "--fireball"];
    if let Some(scene) = scene {
        args.extend(["--scene", scene]);
    }
    args.extend(["--out", out.to_str().expect("UTF-8 path")]);
    let output = rolypoly(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    samples(out)
}

#[test]
fn sound_writes_the_run_the_same_every_time() {
    for (seed, seconds) in [("1", "1.5"), ("5", "2")] {
        let first = sound_of(None, seed, seconds, &scratch(&format!("a{seed}.wav")));
        let again = sound_of(None, seed, seconds, &scratch(&format!("b{seed}.wav")));
        let expected = (seconds.parse::<f64>().unwrap() * 48_000.0).round() as usize * 2;
        assert_eq!(
            first.len(),
            expected,
            "seed {seed}: two channels, 48 000 frames a second"
        );
        assert!(first == again, "seed {seed}: a rerun differs");
        assert!(
            first.iter().any(|&s| s.unsigned_abs() > 300),
            "seed {seed}: the room is heard"
        );
    }
}

/// A scene of two balls of `radius` and `mass` meeting head-on in the air,
/// without gravity, written to a file named `name`.
fn head_on_scene(name: &str, radius: f64, mass: f64) -> PathBuf {
    let path = scratch(name);
    let ball = |x: f64, v: f64| {
        format!("[[balls.placement]]\nposition = [{x}, 2.5, 0.0]\nvelocity = [{v}, 0.0, 0.0]\n\n")
    };
    let text = format!(
        "gravity = 0.0\n\n[balls]\ncount = 0\nradius = {radius}\nmass = {mass}\n\n\
         [tumblers]\nplacement = []\n\n{}{}",
        ball(-0.5, 3.0),
        ball(0.5, -3.0)
    );
    std::fs::write(&path, text).expect("the scene is written");
    path
}

#[test]
fn on_the_gpu_engine_a_ball_of_half_the_radius_rings_an_octave_higher_as_on_the_cpu() {
    let pitch = |engine: &str, radius: f64, mass: f64| {
        let scene = head_on_scene(&format!("head-on-{radius}.toml"), radius, mass);
        let out = scratch(&format!("head-on-{engine}-{radius}.wav"));
        let output = rolypoly(&[
            "--scene",
            scene.to_str().unwrap(),
            "--engine",
            engine,
            "sound",
            "--seconds",
            "0.6",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{engine}: {}", stderr(&output));
        let stereo = samples(&out);
        let mono: Vec<f32> = stereo
            .chunks(2)
            .map(|f| (f32::from(f[0]) + f32::from(f[1])) / 2.0)
            .collect();
        assert!(
            mono.iter().any(|s| s.abs() > 100.0),
            "{engine}, radius {radius}: the impact is heard"
        );
        spectral_peak(&mono, 100.0, 23_000.0)
    };
    for (radius, mass) in [(0.12, 0.25), (0.08, 0.5)] {
        let gpu = (
            pitch("gpu", radius, mass),
            pitch("gpu", radius / 2.0, mass / 8.0),
        );
        let cpu = (
            pitch("cpu", radius, mass),
            pitch("cpu", radius / 2.0, mass / 8.0),
        );
        let ratio = gpu.1 / gpu.0;
        assert!(
            (ratio - 2.0).abs() < 0.04,
            "radius {radius}: {:.0} Hz and {:.0} Hz on the GPU, ratio {ratio:.4}",
            gpu.0,
            gpu.1
        );
        for (g, c) in [gpu.0, gpu.1].into_iter().zip([cpu.0, cpu.1]) {
            assert!(
                (g / c - 1.0).abs() < 0.01,
                "{g:.0} Hz on the GPU, {c:.0} on the CPU"
            );
        }
    }
}

/// The live sound of 0.6 s of `scene` on `engine`, as the window hears
/// it (the GPU engine's balls through their stand-ins), as mono samples.
fn live_sound(scene: &Path, engine: rolypoly::engine::Engine) -> Vec<f32> {
    let overrides = Overrides {
        engine: Some(engine),
        ..Overrides::default()
    };
    let scene = load_scene_with(Some(scene), &overrides).expect("the scene loads");
    let world = World::new(scene.world.clone(), 1).unwrap();
    let mut sim = Simulation::new(world, scene.effects, 1);
    if engine == rolypoly::engine::Engine::Gpu {
        rolypoly_gpu::set_program_gpu_timeout(std::time::Duration::from_secs(600));
        let compute = rolypoly_gpu::Compute::headless().expect("an adapter");
        sim.move_balls_to_compute(&compute).unwrap();
    }
    let ear = Listener {
        position: glam::DVec3::new(0.0, 2.5, 3.0),
        forward: glam::DVec3::NEG_Z,
    };
    let mut track = rolypoly_sound::Soundtrack::new(&scene.sound, &sim.world);
    let mut stand_ins = StandIns::default();
    let mut mono = Vec::new();
    for _ in 0..(0.6 / scene.world.solver.dt).round() as u64 {
        sim.step().unwrap();
        match engine {
            rolypoly::engine::Engine::Cpu => track.hear_step(&sim.world, sim.last_events(), &ear),
            rolypoly::engine::Engine::Gpu => {
                let balls = stand_ins.after_step(&sim).unwrap();
                track.hear_step_among(&sim.world, balls, sim.last_events(), &ear);
            }
        }
        mono.extend(track.take_frames().iter().map(|f| (f[0] + f[1]) / 2.0));
    }
    mono
}

#[test]
fn the_windows_live_sound_rings_the_gpu_engines_balls_as_the_cpu_engines() {
    use rolypoly::engine::Engine;
    for (radius, mass) in [(0.12, 0.25), (0.06, 0.25 / 8.0)] {
        let scene = head_on_scene(&format!("live-head-on-{radius}.toml"), radius, mass);
        let gpu = live_sound(&scene, Engine::Gpu);
        let cpu = live_sound(&scene, Engine::Cpu);
        let loudest = |s: &[f32]| s.iter().fold(0.0f32, |m, x| m.max(x.abs()));
        let (gpu_peak, cpu_peak) = (loudest(&gpu), loudest(&cpu));
        assert!(cpu_peak > 1e-3, "radius {radius}: heard on the CPU engine");
        // Heard as loud (their masses and sizes), from about where they met.
        assert!(
            (gpu_peak / cpu_peak - 1.0).abs() < 0.1,
            "radius {radius}: loudest {gpu_peak} on the GPU engine, {cpu_peak} on the CPU"
        );
        let (g, c) = (
            spectral_peak(&gpu, 100.0, 23_000.0),
            spectral_peak(&cpu, 100.0, 23_000.0),
        );
        assert!(
            (g / c - 1.0).abs() < 0.01,
            "radius {radius}: {g:.0} Hz on the GPU engine, {c:.0} on the CPU"
        );
    }
}

#[test]
fn sound_refuses_what_it_cannot_do_cleanly() {
    for (args, says) in [
        (vec!["sound", "--out", "a.mp3"], "name the file `.wav`"),
        (
            vec!["sound", "--out", "no-such-folder/a.wav"],
            "does not exist",
        ),
        (vec!["sound", "--seconds", "0", "--out", "a.wav"], "0"),
    ] {
        let output = rolypoly(&args);
        let err = stderr(&output);
        assert!(!output.status.success(), "{args:?}");
        assert!(
            err.contains(says) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn a_scene_that_turns_the_sound_off_is_silent() {
    let scene = scratch("quiet.toml");
    std::fs::write(&scene, "[sound]\nenabled = false\n").unwrap();
    let quiet = sound_of(
        Some(scene.to_str().unwrap()),
        "1",
        "1",
        &scratch("quiet.wav"),
    );
    assert_eq!(quiet.len(), 96_000);
    assert!(quiet.iter().all(|&s| s == 0));
    let scene = scratch("soft.toml");
    std::fs::write(&scene, "[sound]\nvolume = 0.25\nballs = \"steel\"\n").unwrap();
    let soft = sound_of(
        Some(scene.to_str().unwrap()),
        "1",
        "1",
        &scratch("soft.wav"),
    );
    let loud = sound_of(None, "1", "1", &scratch("loud.wav"));
    assert!(soft != loud, "the keys change the sound");
    let bad = scratch("bad.toml");
    std::fs::write(&bad, "[sound]\nballs = \"cheese\"\n").unwrap();
    let output = rolypoly(&["sound", "--scene", bad.to_str().unwrap(), "--out", "x.wav"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("sound.balls"),
        "{}",
        stderr(&output)
    );
}

/// The loudest sample of `seconds` of the shipped scene `file`, on the
/// CPU engine, heard from the overview: before the limiter and after.
fn loudest(file: &str, seconds: f64) -> (f32, i16) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(file);
    let overrides = Overrides {
        engine: Some(rolypoly::engine::Engine::Cpu),
        ..Overrides::default()
    };
    let scene = load_scene_with(Some(&path), &overrides).expect("a shipped scene");
    let world = World::new(scene.world.clone(), 1).unwrap();
    let mut sim = Simulation::new(world, scene.effects, 1);
    let camera = rolypoly::frames::chosen_camera(None, sim.world.config());
    let ear = rolypoly::sound::listener_of(&camera);
    let mut recording = Recording::new(&scene.sound, &sim, ear);
    let steps = (seconds / scene.world.solver.dt).round() as u64;
    ticks_heard(&mut sim, steps, &mut recording).unwrap();
    let frames = recording.frames();
    let peak = frames
        .iter()
        .flat_map(|f| [to_pcm(f[0]), to_pcm(f[1])])
        .map(|s| s.saturating_abs())
        .max()
        .unwrap();
    let after = frames
        .iter()
        .fold(0.0f32, |m, f| m.max(f[0].abs()).max(f[1].abs()));
    assert!(
        after <= CEILING + 1e-6,
        "{file}: {after} past the limiter's ceiling"
    );
    (after, peak)
}

#[test]
fn the_billiards_break_and_the_pits_landing_never_reach_full_scale() {
    for (file, seconds) in [("billiards-break.toml", 3.0), ("ballpit-10k.toml", 1.5)] {
        let (after, peak) = loudest(file, seconds);
        assert!(peak < i16::MAX, "{file}: a sample at full scale");
        assert!(after > 0.01, "{file}: heard ({after})");
    }
}

#[test]
fn the_listener_faces_where_the_camera_looks() {
    let camera =
        rolypoly::frames::chosen_camera(Some([1.0, 2.0, 3.0, 1.0, 2.0, 0.0]), &Default::default());
    let Listener { position, forward } = rolypoly::sound::listener_of(&camera);
    assert_eq!(position, glam::DVec3::new(1.0, 2.0, 3.0));
    assert!((forward.normalize() - -glam::DVec3::Z).length() < 1e-9);
}

/// Records half a second, ten tiny frames a second, with `more` flags.
fn record(more: &[&str]) {
    let mut args = vec![
        "record",
        "--seconds",
        "0.5",
        "--fps",
        "10",
        "--size",
        "32x18",
    ];
    args.extend(more);
    let output = rolypoly(&args);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn record_carries_the_same_sound_as_sound() {
    let wav = scratch("recorded.wav");
    let clip = scratch("clip.gif");
    record(&[
        "--fireball",
        "--seed",
        "3",
        "--audio",
        wav.to_str().unwrap(),
        "--out",
        clip.to_str().unwrap(),
    ]);
    let alone = sound_of(None, "3", "0.5", &scratch("alone.wav"));
    assert!(samples(&wav) == alone, "record's sound is sound's");

    if Command::new("ffmpeg").arg("-version").output().is_err() {
        eprintln!("ffmpeg is not installed: the MP4's sound is not checked");
        return;
    }
    let mp4 = scratch("clip.mp4");
    record(&["--out", mp4.to_str().unwrap()]);
    let probe = Command::new("ffprobe")
        .args([
            "-v",
            "error",
            "-show_entries",
            "stream=codec_type,codec_name,sample_rate,channels",
        ])
        .args(["-of", "csv=p=0", mp4.to_str().unwrap()])
        .output()
        .expect("ffprobe comes with ffmpeg");
    let streams = String::from_utf8_lossy(&probe.stdout);
    assert!(streams.contains("aac,audio,48000,2"), "{streams}");
    assert!(streams.contains("h264,video"), "{streams}");
    let folder = mp4.parent().unwrap();
    let left: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".clip.mp4"))
        .collect();
    assert!(left.is_empty(), "working files left behind");
}
