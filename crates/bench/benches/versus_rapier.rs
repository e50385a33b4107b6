//! The rolypoly engine against Rapier on the same ball pit, in one process.
//!
//! `cargo bench -p rolypoly-bench --bench versus_rapier` runs pits of 1k,
//! 10k and 100k balls twice: first with Coulomb friction 0.5 between balls
//! (the headline table), then frictionless between balls; the walls'
//! friction is 0.5 in both, and neither engine has rolling resistance.
//! `cargo bench -p rolypoly-bench --bench versus_rapier -- 1000 5000` picks
//! the sizes and `-- 10000 10s` the simulated time too (3 s unless told);
//! the flags after `--` need the bench named, or every bench target of the
//! crate, the library's test harness too, is handed them. Each pit is
//! simulated for the same time by both engines from the same start, in
//! turns of half a simulated second, on the same threads (all of the
//! machine's, or `RAYON_NUM_THREADS`; Rapier is built with its `parallel`
//! feature); only `step` calls are timed. Quality is measured after every
//! turn (untimed) and at the end. The share of balls at rest is also
//! measured at 10 s of simulated time: within the run where it lasts that
//! long, else by running pits of up to 10 000 balls on, untimed, after it
//! (a 100 000-ball pit would keep Rapier minutes more). The ratio of the
//! speeds is also printed turn by turn (lowest, median, highest), to show
//! how much the machine moved it. After the 10k and 100k pits it says
//! whether the engine's targets for them were met, and with friction
//! whether both engines had 99 % of the balls at rest at 10 s.
//!
//! The GPU engine (`rolypoly-gpu`, on the adapter named at the top) runs as
//! a third column, in the same turns; its turns are timed to the end of
//! the GPU's work. Rapier sits out pits of more than 100 000 balls. After
//! each pit the GPU's time a step is split by stage, by timestamp queries
//! where the adapter has them.

use glam::DVec3;
use rolypoly_bench::gpu_pit::GpuPit;
use rolypoly_bench::ours::OurPit;
use rolypoly_bench::pit::{FRICTION, Pit, PitEngine};
use rolypoly_bench::quality::{Quality, measure};
use rolypoly_bench::rapier_pit::RapierPit;
use rolypoly_physics::{World, WorldConfig};
use std::time::Instant;

/// Simulated time of every pit run unless an argument such as `10s` says otherwise.
const SECONDS: f64 = 3.0;

/// When the share of balls at rest is measured besides the end (s).
const REST_AT: f64 = 10.0;

/// The largest pit run on past its end, untimed, to measure rest at
/// [`REST_AT`] when the run is shorter.
const REST_AT_MOST_BALLS: usize = 10_000;

/// At least this share of balls at rest at [`REST_AT`] with friction, in
/// both engines.
const RESTING_TARGET: f64 = 0.99;

struct Run {
    steps_per_second: f64,
    /// Worst over the run (penetration, escapes).
    worst: Quality,
    /// At the end (energy, rest).
    end: Quality,
    /// At [`REST_AT`], where measured.
    rest_at: Option<Quality>,
    /// Seconds spent in `step` in each turn.
    turns: Vec<f64>,
}

/// One engine's share of a run: its time in `step` turn by turn, the worst
/// quality seen and the quality after its last turn.
struct Timing<'a> {
    engine: &'a mut dyn PitEngine,
    turns: Vec<f64>,
    worst: Quality,
    last: Quality,
    rest_at: Option<Quality>,
}

impl Timing<'_> {
    /// Steps `steps` times, timing only the steps (to the end of the
    /// work they queued), then measures quality.
    fn advance(&mut self, pit: &Pit, steps: usize, read: &mut (Vec<DVec3>, Vec<DVec3>)) {
        let start = Instant::now();
        for _ in 0..steps {
            self.engine.step();
        }
        self.engine.finish();
        self.turns.push(start.elapsed().as_secs_f64());
        self.engine.read(&mut read.0, &mut read.1);
        self.last = measure(pit, &read.0, &read.1);
        self.worst = self.worst.worst(self.last);
    }
}

/// Runs both engines on `pit` for `seconds`, in turn, half a simulated
/// second each: the machine's speed wanders over a run, and taking turns
/// lets both engines meet the same wander, so that the ratio of their
/// speeds holds from run to run better than either speed does. With
/// `rest_at` (seconds) the quality at that time is kept too: a turn ends
/// there when the run lasts that long, else both engines are stepped on
/// to it after the run, untimed.
fn run_in_turn(
    engines: Vec<&mut dyn PitEngine>,
    pit: &Pit,
    seconds: f64,
    rest_at: Option<f64>,
) -> Vec<Run> {
    let steps = ((seconds / pit.dt).round() as usize).max(1);
    let turn = ((0.5 / pit.dt).round() as usize).max(1);
    let rest_at = rest_at.map(|t| ((t / pit.dt).round() as usize).max(1));
    let mut read = (Vec::new(), Vec::new());
    let mut timings: Vec<Timing> = engines
        .into_iter()
        .map(|engine| Timing {
            engine,
            turns: Vec::new(),
            worst: Quality::default(),
            last: Quality::default(),
            rest_at: None,
        })
        .collect();
    let mut done = 0;
    while done < steps {
        let mut now = turn.min(steps - done);
        if let Some(at) = rest_at.filter(|&at| at > done) {
            now = now.min(at - done);
        }
        for t in &mut timings {
            t.advance(pit, now, &mut read);
        }
        done += now;
        if rest_at == Some(done) {
            for t in &mut timings {
                t.rest_at = Some(t.last);
            }
        }
    }
    if let Some(at) = rest_at.filter(|&at| at > steps) {
        for t in &mut timings {
            for _ in steps..at {
                t.engine.step();
            }
            t.engine.read(&mut read.0, &mut read.1);
            t.rest_at = Some(measure(pit, &read.0, &read.1));
        }
    }
    // The last turn ends the run: its quality is the end's.
    timings
        .into_iter()
        .map(|t| Run {
            steps_per_second: steps as f64 / t.turns.iter().sum::<f64>(),
            worst: t.worst,
            end: t.last,
            rest_at: t.rest_at,
            turns: t.turns,
        })
        .collect()
}

/// The ratio of the engines' speeds in each turn: lowest, median and
/// highest. A turn's ratio moves with the machine's speed while the two
/// take it, so the spread says how far to trust the run's ratio.
fn ratio_by_turn(ours: &Run, rapier: &Run) -> Option<[f64; 3]> {
    let mut ratios: Vec<f64> = (ours.turns.iter().zip(&rapier.turns))
        .map(|(&o, &r)| r / o)
        .filter(|r| r.is_finite())
        .collect();
    ratios.sort_by(f64::total_cmp);
    let (&lowest, &highest) = (ratios.first()?, ratios.last()?);
    Some([lowest, ratios[ratios.len() / 2], highest])
}

/// The share of `balls` that `q` counted at rest.
fn resting_share(q: &Quality, balls: usize) -> f64 {
    q.resting as f64 / balls as f64
}

fn print_header() {
    println!(
        "{:>7} {:<14} {:>9} {:>13} {:>7} {:>13} {:>8} {:>12} {:>8} {:>9} {:>10}",
        "balls",
        "engine",
        "steps/s",
        "ball-steps/s",
        "ratio",
        "overlap (mm)",
        "escapes",
        "KE end (J)",
        "at rest",
        "resting",
        format!("at {REST_AT} s"),
    );
}

fn print_row(balls: usize, name: &str, r: &Run, ratio: Option<f64>) {
    let ratio = ratio.map_or("-".into(), |x| format!("{x:.2}"));
    let rest_at = match &r.rest_at {
        Some(q) => format!("{:.1}%", 100.0 * resting_share(q, balls)),
        None => "-".into(),
    };
    println!(
        "{:>7} {:<14} {:>9.1} {:>13.3e} {:>7} {:>13.2} {:>8} {:>12.3} {:>8} {:>8.1}% {:>10}",
        balls,
        name,
        r.steps_per_second,
        r.steps_per_second * balls as f64,
        ratio,
        r.worst.max_penetration * 1e3,
        r.worst.escapes,
        r.end.kinetic_energy,
        if r.end.at_rest() { "yes" } else { "no" },
        100.0 * resting_share(&r.end, balls),
        rest_at,
    );
}

/// The target this engine is held to for a pit of `balls` with
/// `friction` between balls, and whether this run met it: at 10 000 balls,
/// frictionless ten times Rapier's steps per second with no deeper overlap,
/// with friction six times with at most a fifth of Rapier's overlap, and no
/// escapes; at 100 000 balls 60 steps per second.
fn target_for(balls: usize, friction: f64, ours: &Run, rapier: &Run, ratio: f64) -> Option<String> {
    let verdict = |met: bool| if met { "met" } else { "NOT met" };
    match balls {
        10_000 => {
            let (times, overlap_share, overlap) = if friction > 0.0 {
                (6.0, 0.2, "at most a fifth of its overlap")
            } else {
                (10.0, 1.0, "no deeper overlap")
            };
            let met = ratio >= times
                && ours.worst.max_penetration <= overlap_share * rapier.worst.max_penetration
                && ours.worst.escapes == 0;
            Some(format!(
                "target: at least {times}x Rapier, {overlap}, no escapes: {}",
                verdict(met)
            ))
        }
        100_000 => Some(format!(
            "target: at least 60 steps/s: {} ({:.1})",
            verdict(ours.steps_per_second >= 60.0),
            ours.steps_per_second
        )),
        _ => None,
    }
}

/// The targets the GPU engine is held to on an H100-class GPU: 100 000
/// balls at 600 steps per second and a million at 60, with at most 10 mm
/// of overlap, no escapes and the balls at rest at 10 s; and whether this
/// run, on `adapter`, met them.
fn gpu_target_for(balls: usize, gpu: &Run, adapter: &str) -> Option<String> {
    let speed = match balls {
        100_000 => 600.0,
        1_000_000 => 60.0,
        _ => return None,
    };
    let met = gpu.steps_per_second >= speed
        && gpu.worst.max_penetration <= 0.010
        && gpu.worst.escapes == 0
        && gpu
            .rest_at
            .as_ref()
            .is_none_or(|q| resting_share(q, balls) >= RESTING_TARGET);
    Some(format!(
        "GPU target (on an H100-class GPU): at least {speed} steps/s, overlap at most 10 mm, \
         no escapes: {} on {adapter} ({:.1})",
        if met { "met" } else { "NOT met" },
        gpu.steps_per_second
    ))
}

/// The largest pit Rapier runs: beyond, it would take hours.
const RAPIER_MOST_BALLS: usize = 100_000;

/// With friction between balls, whether both engines had at least
/// [`RESTING_TARGET`] of the balls at rest at [`REST_AT`], where measured.
fn rest_target(balls: usize, ours: &Run, rapier: &Run) -> Option<String> {
    let (ours, rapier) = (ours.rest_at.as_ref()?, rapier.rest_at.as_ref()?);
    let met = [ours, rapier]
        .iter()
        .all(|q| resting_share(q, balls) >= RESTING_TARGET);
    Some(format!(
        "target: at least {:.0} % of the balls at rest at {REST_AT} s in both engines: {}",
        100.0 * RESTING_TARGET,
        if met { "met" } else { "NOT met" }
    ))
}

/// Step time of the default scene with the fireball flying (ours only).
fn default_scene_with_fireball() -> Result<f64, String> {
    let mut world = World::new(WorldConfig::default(), 1).map_err(|e| e.to_string())?;
    world.launch_fireball(None);
    for _ in 0..60 {
        world.step();
        world.drain_events().for_each(drop);
    }
    let steps = 1200;
    let start = Instant::now();
    for _ in 0..steps {
        world.step();
        world.drain_events().for_each(drop);
    }
    Ok(start.elapsed().as_secs_f64() / steps as f64)
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    // `--csv FILE`: the steps per second of each engine at each size and
    // friction between balls (both tables), for the figure in docs/figures/.
    let csv = match args.iter().position(|a| a == "--csv") {
        None => None,
        Some(at) if at + 1 < args.len() => {
            let path = args.remove(at + 1);
            args.remove(at);
            Some(path)
        }
        Some(_) => {
            eprintln!("versus_rapier: --csv needs a file name");
            std::process::exit(2);
        }
    };
    // `--cpu-only`: the CPU engine alone (a thread sweep runs it so);
    // `--friction-only`: the headline table, without the frictionless one.
    let mut flag = |name: &str| match args.iter().position(|a| a == name) {
        Some(at) => {
            args.remove(at);
            true
        }
        None => false,
    };
    let cpu_only = flag("--cpu-only");
    let friction_only = flag("--friction-only");
    if let Some(unknown) = args.iter().find(|a| a.starts_with("--") && *a != "--bench") {
        eprintln!(
            "versus_rapier: unknown option '{unknown}' (known: --csv FILE, --cpu-only, --friction-only)"
        );
        std::process::exit(2);
    }
    let mut rows = String::from("balls,engine,ball_friction,steps_per_second\n");
    let seconds = match args
        .iter()
        .find(|a| a.ends_with('s') && !a.starts_with('-'))
    {
        None => SECONDS,
        Some(a) => match a.trim_end_matches('s').parse::<f64>() {
            Ok(t) if t.is_finite() && t > 0.0 => t,
            _ => {
                eprintln!("versus_rapier: '{a}' is not a positive number of seconds");
                std::process::exit(2);
            }
        },
    };
    let sizes: Vec<usize> = args
        .iter()
        .filter(|a| !a.starts_with('-') && !a.ends_with('s'))
        .map(|a| match a.parse() {
            Ok(n) => n,
            Err(_) => {
                eprintln!("versus_rapier: '{a}' is not a ball count");
                std::process::exit(2);
            }
        })
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1_000, 10_000, 100_000]
    } else {
        sizes
    };
    println!(
        "pit: balls of radius 0.1 m, mass 1 kg, restitution 0.8, wall friction 0.5, \
         no rolling resistance, dt 1/60 s, {seconds} s simulated; threads, for both CPU engines: {}",
        rayon_threads()
    );
    let compute = match rolypoly_gpu::Compute::headless() {
        _ if cpu_only => {
            println!("GPU engine and Rapier: not run (--cpu-only)");
            None
        }
        Ok(compute) => {
            println!("GPU engine on {}", compute.adapter);
            Some(compute)
        }
        Err(e) => {
            println!("GPU engine: none ({e})");
            None
        }
    };
    println!(
        "overlap: deepest over the run; at rest: every ball slower than {} cm/s at the end; \
         resting: the share of balls that are, at the end and at {REST_AT} s \
         (pits of up to {REST_AT_MOST_BALLS} balls run on untimed to it; '-': not measured)",
        100.0 * rolypoly_bench::quality::REST_SPEED
    );
    let tables = [
        (FRICTION, format!("friction {FRICTION} between balls")),
        (0.0, "frictionless between balls".to_string()),
    ];
    let tables = if friction_only {
        &tables[..1]
    } else {
        &tables[..]
    };
    for (friction, title) in tables {
        let friction = *friction;
        println!();
        println!("{title}:");
        print_header();
        for &n in &sizes {
            let pit = Pit::new(n, 7).with_ball_friction(friction);
            let mut ours = match OurPit::new(&pit) {
                Ok(p) => p,
                Err(e) => {
                    eprintln!("versus_rapier: {n} balls: {e}");
                    std::process::exit(1);
                }
            };
            let mut gpu = match compute.as_ref().map(|c| GpuPit::new(&pit, c)).transpose() {
                Ok(gpu) => gpu,
                Err(e) => {
                    println!("{n:>7} rolypoly-gpu: {e}");
                    None
                }
            };
            let mut rapier = (n <= RAPIER_MOST_BALLS && !cpu_only).then(|| RapierPit::new(&pit));
            let rapier_name = RapierPit::NAME;
            let rest_at = (seconds >= REST_AT || n <= REST_AT_MOST_BALLS).then_some(REST_AT);
            let mut engines: Vec<&mut dyn PitEngine> = vec![&mut ours];
            if let Some(gpu) = gpu.as_mut() {
                engines.push(gpu);
            }
            if let Some(rapier) = rapier.as_mut() {
                engines.push(rapier);
            }
            let runs = run_in_turn(engines, &pit, seconds, rest_at);
            let our_run = &runs[0];
            let gpu_run = gpu.as_ref().map(|_| &runs[1]);
            let rapier_run = rapier.as_ref().and_then(|_| runs.last());
            let retaken = ours.world().retakes();
            let over_rapier =
                |run: &Run| rapier_run.map(|r| run.steps_per_second / r.steps_per_second);
            print_row(n, "rolypoly", our_run, over_rapier(our_run));
            rows += &format!("{n},rolypoly,{friction},{:.2}\n", our_run.steps_per_second);
            if let Some(gpu_run) = gpu_run {
                print_row(n, "rolypoly-gpu", gpu_run, over_rapier(gpu_run));
                rows += &format!(
                    "{n},rolypoly-gpu,{friction},{:.2}\n",
                    gpu_run.steps_per_second
                );
            }
            if let Some(rapier_run) = rapier_run {
                print_row(n, rapier_name, rapier_run, Some(1.0));
                rows += &format!(
                    "{n},{rapier_name},{friction},{:.2}\n",
                    rapier_run.steps_per_second
                );
            }
            if let (Some(gpu_run), Some(compute), Some(gpu)) = (gpu_run, &compute, gpu.as_ref()) {
                println!(
                    "{:>7} rolypoly-gpu over rolypoly: {:.2}; dispatches a step: {}",
                    "",
                    gpu_run.steps_per_second / our_run.steps_per_second,
                    gpu.dispatches_per_step()
                );
                if let Some(target) = gpu_target_for(n, gpu_run, &compute.adapter) {
                    println!("{:>7} {target}", "");
                }
            }
            if let Some(gpu) = gpu.as_mut() {
                match gpu.profile(10) {
                    Ok(Some(stages)) => {
                        let total: f64 = stages.iter().sum();
                        let parts: Vec<String> = rolypoly_gpu::Stage::ALL
                            .iter()
                            .zip(stages)
                            .map(|(s, t)| {
                                format!(
                                    "{} {:.2} ms ({:.0} %)",
                                    s.name(),
                                    1e3 * t,
                                    100.0 * t / total
                                )
                            })
                            .collect();
                        println!(
                            "{:>7} GPU time a step, by timestamps: {:.2} ms: {}",
                            "",
                            1e3 * total,
                            parts.join(", ")
                        );
                    }
                    Ok(None) => println!(
                        "{:>7} GPU time by stage: the adapter writes no timestamps",
                        ""
                    ),
                    Err(e) => println!("{:>7} GPU time by stage: {e}", ""),
                }
            }
            let Some(rapier_run) = rapier_run else {
                continue;
            };
            let ratio = our_run.steps_per_second / rapier_run.steps_per_second;
            if let Some([lowest, median, highest]) = ratio_by_turn(our_run, rapier_run) {
                println!(
                    "{:>7} ratio turn by turn ({} turns): lowest {lowest:.2}, median {median:.2}, \
                     highest {highest:.2}",
                    "",
                    our_run.turns.len()
                );
            }
            println!(
                "{:>7} rolypoly steps retaken with less warm start: {retaken}",
                ""
            );
            if let Some(target) = target_for(n, friction, our_run, rapier_run, ratio) {
                println!("{:>7} {target}", "");
            }
            if friction > 0.0
                && let Some(target) = rest_target(n, our_run, rapier_run)
            {
                println!("{:>7} {target}", "");
            }
        }
    }
    if let Some(path) = csv {
        match std::fs::write(&path, &rows) {
            Ok(()) => println!("wrote {path}"),
            Err(e) => {
                eprintln!("versus_rapier: cannot write `{path}`: {e}");
                std::process::exit(1);
            }
        }
    }
    match default_scene_with_fireball() {
        Ok(t) => println!(
            "default scene (30 balls, 5 tumblers) with the fireball: {:.1} us/step",
            t * 1e6
        ),
        Err(e) => eprintln!("versus_rapier: default scene: {e}"),
    }
}

fn rayon_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}
