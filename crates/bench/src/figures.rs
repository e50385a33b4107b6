//! The figures in docs/: the physics measured against theory, drawn as SVG.
//! Each is made from simulations run here, so the same code gives the same
//! bytes; `cargo run -p rolypoly-bench --bin figures` writes them, and a
//! test fails when the files in docs/figures/ are not what it would write.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec3;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use rolypoly_physics::{PourConfig, SphereSpec, TumblerPlacement, World, WorldConfig};

/// A figure: its file name in docs/figures/ and its SVG text.
pub struct Figure {
    /// The file name.
    pub name: &'static str,
    /// The SVG.
    pub svg: String,
    /// The figure's numbers as a small table, for figures whose numbers are
    /// worth reading as well as seeing.
    pub table: Option<String>,
}

impl Figure {
    fn drawn(name: &'static str, svg: String) -> Figure {
        Figure {
            name,
            svg,
            table: None,
        }
    }
}

/// Every figure, in the order the docs show them.
pub fn all() -> Result<Vec<Figure>, String> {
    let (heap, heap_table) = angle_of_repose_figure()?;
    Ok(vec![
        Figure::drawn("tumbler-period.svg", tumbler_period()?),
        Figure::drawn("bounce-height.svg", bounce_height()?),
        Figure::drawn("energy.svg", energy()?),
        Figure::drawn("steps-per-second.svg", steps_per_second(STEPS_PER_SECOND)?),
        Figure {
            name: "angle-of-repose.svg",
            svg: heap,
            table: Some(heap_table),
        },
    ])
}

const SIZE: (u32, u32) = (640, 400);

/// Steps per second of each engine at each size, with friction between
/// balls and without, as one run of
/// `cargo bench -p rolypoly-bench --bench versus_rapier -- --csv FILE`
/// wrote them: a bench run
/// takes minutes, so the figure is drawn from its record, not run anew.
const STEPS_PER_SECOND: &str = include_str!("../../../docs/figures/steps-per-second.csv");

fn empty_room() -> WorldConfig {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    config.tumblers.placements.clear();
    config
}

/// The rolling pendulum's period at amplitude `theta0` (radians), for a
/// body of the spheres' mass properties on a round bottom of radius `R`:
/// with `a` the centre of mass below the bottom's centre and `k` the radius
/// of gyration, energy gives `J(θ) θ'² = 2 g a (cos θ - cos θ0)`, where
/// `J = k² + R² + a² - 2 R a cos θ`. With `sin(θ/2) = sin(θ0/2) sin φ` the
/// quarter period is `∫ sqrt(J / (g a)) / sqrt(1 - sin²(θ0/2) sin² φ) dφ`
/// over `φ` from 0 to π/2, taken here by the midpoint rule.
pub fn rolling_pendulum_period(spheres: &[SphereSpec], g: f64, theta0: f64) -> f64 {
    let m: f64 = spheres.iter().map(|s| s.mass).sum();
    let com = spheres.iter().map(|s| s.mass * s.height).sum::<f64>() / m;
    let big_r = spheres[0].radius;
    let a = -com;
    let k2 = spheres
        .iter()
        .map(|s| 0.4 * s.mass * s.radius * s.radius + s.mass * (s.height - com).powi(2))
        .sum::<f64>()
        / m;
    let s = (theta0 / 2.0).sin();
    let n = 2000;
    let h = FRAC_PI_2 / n as f64;
    let quarter: f64 = (0..n)
        .map(|i| {
            let phi = (i as f64 + 0.5) * h;
            let theta = 2.0 * (s * phi.sin()).asin();
            let j = k2 + big_r * big_r + a * a - 2.0 * big_r * a * theta.cos();
            (j / (g * a)).sqrt() / (1.0 - (s * phi.sin()).powi(2)).sqrt() * h
        })
        .sum();
    4.0 * quarter
}

/// A lone undamped tumbler released at `amplitude` degrees: the mean of
/// its first two periods, from the times its axis passes upright.
pub fn simulated_period(amplitude: f64) -> f64 {
    let mut config = empty_room();
    config.tumblers.damping = 0.0;
    config.tumblers.placements = vec![TumblerPlacement {
        x: 0.0,
        z: 0.0,
        tilt_axis: DVec3::X,
        tilt_deg: amplitude,
    }];
    let mut world = World::new(config, 1).expect("a lone tumbler fits the room");
    let dt = world.config().solver.dt;
    let mut crossings = Vec::new();
    let mut prev = world.tumblers()[0].axis().z;
    while crossings.len() < 5 && world.time() < 30.0 {
        world.step();
        let z = world.tumblers()[0].axis().z;
        if (prev < 0.0) != (z < 0.0) {
            crossings.push(world.time() - dt + dt * prev / (prev - z));
        }
        prev = z;
    }
    (crossings[4] - crossings[0]) / 2.0
}

fn tumbler_period() -> Result<String, String> {
    let config = WorldConfig::default();
    let spheres = &config.tumblers.spheres;
    let amplitudes: Vec<f64> = (1..=16).map(|k| 5.0 * k as f64).collect();
    let simulated: Vec<(f64, f64)> = amplitudes
        .iter()
        .map(|&a| (a, simulated_period(a)))
        .collect();
    let theory: Vec<(f64, f64)> = (0..=170)
        .map(|k| {
            let a = 0.5 * k as f64;
            (
                a,
                rolling_pendulum_period(spheres, config.gravity, a.to_radians()),
            )
        })
        .collect();
    let top = simulated
        .iter()
        .chain(&theory)
        .map(|p| p.1)
        .fold(0.0, f64::max)
        * 1.1;
    let small = TAU / (TAU / theory[0].1);
    plot(
        "The tumbler's rocking period against its amplitude",
        ("amplitude (degrees)", 0.0..85.0),
        ("period (s)", 0.0..top),
        &[
            Series::line("rolling pendulum, exact", theory, BLUE),
            Series::dots("simulated", simulated, RED),
            Series::line(
                "small-amplitude limit",
                vec![(0.0, small), (85.0, small)],
                RGBColor(150, 150, 150),
            ),
        ],
        SeriesLabelPosition::LowerRight,
    )
}

/// The height of a ball's first rebound over the height it fell from, on
/// a floor and ball of restitution `e`.
pub fn rebound_ratio(e: f64) -> f64 {
    let mut config = empty_room();
    config.room.restitution = e;
    config.balls.restitution = e;
    config.solver.bounce_threshold = 0.0;
    let mut world = World::new(config, 1).expect("an empty room builds");
    world.throw_ball(DVec3::new(0.0, 1.6, 0.0), DVec3::ZERO);
    let r = world.config().balls.radius;
    let drop = world.balls().positions()[0].y - r;
    let (mut fell, mut top) = (false, 0.0_f64);
    while world.time() < 5.0 {
        world.step();
        let v = world.balls().velocities()[0].y;
        if v > 0.0 {
            fell = true;
            top = top.max(world.balls().positions()[0].y - r);
        } else if fell {
            break;
        }
    }
    top / drop
}

fn bounce_height() -> Result<String, String> {
    let measured: Vec<(f64, f64)> = (1..=10)
        .map(|k| {
            let e = 0.1 * k as f64;
            (e, rebound_ratio(e))
        })
        .collect();
    let theory: Vec<(f64, f64)> = (0..=100)
        .map(|k| (0.01 * k as f64, (0.01 * k as f64).powi(2)))
        .collect();
    plot(
        "Rebound height over drop height against restitution",
        ("restitution e", 0.0..1.05),
        ("rebound / drop", 0.0..1.1),
        &[
            Series::line("e squared", theory, BLUE),
            Series::dots("simulated", measured, RED),
        ],
        SeriesLabelPosition::LowerRight,
    )
}

/// Total energy over time relative to the start, one sample every 0.1 s.
pub fn energy_over_time(config: WorldConfig, seconds: f64) -> Vec<(f64, f64)> {
    let mut world = World::new(config, 1).expect("the scene builds");
    let every = (0.1 / world.config().solver.dt).round() as u64;
    let start = world.energy().total();
    let mut samples = vec![(0.0, 1.0)];
    while world.time() < seconds {
        world.step();
        if world.step_count().is_multiple_of(every) {
            samples.push((world.time(), world.energy().total() / start));
        }
    }
    samples
}

fn energy() -> Result<String, String> {
    // As scenes/elastic-gas.toml: 400 perfectly elastic, frictionless
    // balls without gravity, every impact bouncing.
    let mut gas = WorldConfig {
        gravity: 0.0,
        ..WorldConfig::default()
    };
    gas.room.restitution = 1.0;
    gas.room.friction = 0.0;
    gas.room.rolling_resistance = 0.0;
    gas.balls.count = 400;
    gas.balls.restitution = 1.0;
    gas.balls.friction = 0.0;
    gas.balls.rolling_resistance = 0.0;
    gas.tumblers.placements.clear();
    gas.solver.bounce_threshold = 0.0;
    plot(
        "Total energy over time, as a share of the start",
        ("time (s)", 0.0..10.0),
        ("energy / energy at 0", 0.0..1.1),
        &[
            Series::line(
                "elastic gas (400 balls, e = 1)",
                energy_over_time(gas, 10.0),
                BLUE,
            ),
            Series::line(
                "default scene (settles; what stays is height)",
                energy_over_time(WorldConfig::default(), 10.0),
                RED,
            ),
        ],
        SeriesLabelPosition::LowerRight,
    )
}

/// Steps per second against ball count, each engine, with friction
/// between balls and without, from `csv`
/// (`balls,engine,ball_friction,steps_per_second` lines under a header).
/// Each engine has its colour; a pit with friction between balls is drawn
/// with a solid line, a frictionless one with a dashed line.
fn steps_per_second(csv: &str) -> Result<String, String> {
    /// One engine's steps per second at each size, at one friction.
    struct Runs {
        engine: String,
        friction: f64,
        points: Vec<(f64, f64)>,
    }
    let mut runs: Vec<Runs> = Vec::new();
    for (n, line) in csv.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let [balls, engine, friction, rate] = fields[..] else {
            return Err(format!(
                "steps-per-second.csv:{}: not balls,engine,ball_friction,steps_per_second",
                n + 1
            ));
        };
        let number = |text: &str| {
            text.parse::<f64>()
                .map_err(|_| format!("steps-per-second.csv:{}: `{text}` is not a number", n + 1))
        };
        let friction = number(friction)?;
        let point = (number(balls)?, number(rate)?);
        match runs
            .iter_mut()
            .find(|r| r.engine == engine && r.friction == friction)
        {
            Some(r) => r.points.push(point),
            None => runs.push(Runs {
                engine: engine.to_owned(),
                friction,
                points: vec![point],
            }),
        }
    }
    if runs.is_empty() {
        return Err("steps-per-second.csv holds no runs".into());
    }
    let all = || runs.iter().flat_map(|r| r.points.iter().copied());
    let (x_lo, x_hi) = all().fold((f64::MAX, 0.0_f64), |(lo, hi), p| {
        (lo.min(p.0), hi.max(p.0))
    });
    let (y_lo, y_hi) = all().fold((f64::MAX, 0.0_f64), |(lo, hi), p| {
        (lo.min(p.1), hi.max(p.1))
    });
    let mut engines: Vec<&str> = Vec::new();
    for r in &runs {
        if !engines.contains(&r.engine.as_str()) {
            engines.push(&r.engine);
        }
    }
    let colors = [RED, BLUE, GREEN];
    let color_of = |name: &str| {
        let at = engines.iter().position(|&e| e == name).unwrap_or(0);
        colors[at % colors.len()]
    };
    let series: Vec<Series> = runs
        .iter()
        .map(|r| {
            let color = color_of(&r.engine);
            if r.friction > 0.0 {
                let label = format!("{}, friction {}", r.engine, r.friction);
                Series::measured(&label, r.points.clone(), color)
            } else {
                let label = format!("{}, frictionless", r.engine);
                Series::measured(&label, r.points.clone(), color).dashed()
            }
        })
        .collect();
    plot(
        "Ball pit steps per second (2 threads; the GPU engine on lavapipe)",
        ("balls", (x_lo * 0.8..x_hi * 1.25).log_scale()),
        ("steps per second", (y_lo * 0.5..y_hi * 2.0).log_scale()),
        &series,
        SeriesLabelPosition::UpperRight,
    )
}

/// Coulomb friction between balls at which the heap is poured.
pub const HEAP_FRICTIONS: [f64; 7] = [0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0];

/// Rolling resistance between balls, one curve each.
pub const HEAP_ROLLING_RESISTANCES: [f64; 3] = [0.0, 0.05, 0.1];

/// Balls poured into each heap.
pub const HEAP_BALLS: usize = 800;

/// Seconds the heap is left to settle after the last ball is let go.
const HEAP_SETTLING: f64 = 3.0;

/// A heap poured from a spout, as in the engine's own heap test:
/// `HEAP_BALLS` balls of radius 4 cm, mass 30 g and restitution 0.3, let
/// go 200 a second from a spout of radius 15 cm, 80 cm above the middle of
/// the floor, in a room of 2 x 1.5 x 2 m with no tumblers and no fireball.
/// Between balls Coulomb friction `friction` and rolling resistance
/// `rolling_resistance`; the floor and walls have friction 0.5 and the
/// same rolling resistance.
pub fn heap_config(friction: f64, rolling_resistance: f64) -> WorldConfig {
    let mut config = WorldConfig::default();
    config.tumblers.placements.clear();
    config.fireball.starts_active = false;
    config.room.size = DVec3::new(2.0, 1.5, 2.0);
    config.room.restitution = 0.3;
    config.room.friction = 0.5;
    config.room.rolling_resistance = rolling_resistance;
    config.balls.count = HEAP_BALLS;
    config.balls.radius = 0.04;
    config.balls.mass = 0.03;
    config.balls.restitution = 0.3;
    config.balls.friction = friction;
    config.balls.rolling_resistance = rolling_resistance;
    config.balls.speed_min = 0.0;
    config.balls.speed_max = 0.0;
    config.balls.pour = PourConfig {
        rate: 200.0,
        spout: DVec3::new(0.0, 0.8, 0.0),
        radius: 0.15,
    };
    config
}

/// The longest the spout may take to let every ball go (s).
const HEAP_POUR_LIMIT: f64 = 60.0;

/// The angle of repose in degrees of the heap [`heap_config`] pours, read
/// from the balls in play when every ball has been let go and the heap has
/// settled for `HEAP_SETTLING` seconds; `None` where the balls form no
/// flank, or the spout did not empty within `HEAP_POUR_LIMIT` seconds.
pub fn heap_angle(friction: f64, rolling_resistance: f64) -> Option<f64> {
    let config = heap_config(friction, rolling_resistance);
    let radius = config.balls.radius;
    let settling = (HEAP_SETTLING / config.solver.dt).ceil() as usize;
    let mut world = World::new(config, 1).expect("the heap's room builds");
    while world.balls_to_pour() > 0 {
        if world.time() > HEAP_POUR_LIMIT {
            return None;
        }
        world.step();
        world.drain_events().for_each(drop);
    }
    for _ in 0..settling {
        world.step();
        world.drain_events().for_each(drop);
    }
    let balls = world.balls();
    let in_play: Vec<DVec3> = (balls.positions().iter().zip(balls.alive()))
        .filter_map(|(&p, &alive)| alive.then_some(p))
        .collect();
    rolypoly_physics::angle_of_repose(&in_play, radius, [0.0, 0.0])
}

/// The angle of repose against friction between balls, one curve per
/// rolling resistance, and the same numbers as a table.
fn angle_of_repose_figure() -> Result<(String, String), String> {
    let angles: Vec<Vec<Option<f64>>> = HEAP_ROLLING_RESISTANCES
        .iter()
        .map(|&rolling| {
            HEAP_FRICTIONS
                .iter()
                .map(|&mu| heap_angle(mu, rolling))
                .collect()
        })
        .collect();

    let mut table = format!(
        "angle of repose (degrees) of {HEAP_BALLS} poured balls, '-': no flank\n{:>8}",
        "friction"
    );
    for rolling in HEAP_ROLLING_RESISTANCES {
        table += &format!(" {:>14}", format!("rolling {rolling}"));
    }
    for (k, mu) in HEAP_FRICTIONS.iter().enumerate() {
        table += &format!("\n{mu:>8.2}");
        for row in &angles {
            match row[k] {
                Some(angle) => table += &format!(" {angle:>14.1}"),
                None => table += &format!(" {:>14}", "-"),
            }
        }
    }
    table.push('\n');

    let colors = [BLUE, RGBColor(0, 150, 0), RED];
    let series: Vec<Series> = HEAP_ROLLING_RESISTANCES
        .iter()
        .zip(&angles)
        .zip(colors.iter().cycle())
        .map(|((rolling, row), color)| {
            let points = HEAP_FRICTIONS
                .iter()
                .zip(row)
                .filter_map(|(&mu, angle)| angle.map(|a| (mu, a)))
                .collect();
            Series::measured(&format!("rolling resistance {rolling}"), points, *color)
        })
        .collect();
    let top = 1.25
        * angles
            .iter()
            .flatten()
            .flatten()
            .copied()
            .fold(24.0, f64::max);
    let svg = plot(
        "Angle of repose of a poured heap against friction between balls",
        ("friction between balls", 0.0..1.05),
        ("angle of repose (degrees)", 0.0..top),
        &series,
        SeriesLabelPosition::UpperLeft,
    )?;
    Ok((svg, table))
}

/// What a figure draws of one set of points: a line through them, a dot
/// at each, or both; with its label and colour.
struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    color: RGBColor,
    line: bool,
    dots: bool,
    /// Whether the line is dashed.
    dashed: bool,
}

impl Series {
    fn new(
        label: &str,
        points: Vec<(f64, f64)>,
        color: RGBColor,
        line: bool,
        dots: bool,
    ) -> Series {
        let label = label.to_owned();
        Series {
            label,
            points,
            color,
            line,
            dots,
            dashed: false,
        }
    }
    /// The same with its line dashed.
    fn dashed(self) -> Series {
        Series {
            dashed: true,
            ..self
        }
    }
    /// A curve, such as theory.
    fn line(label: &str, points: Vec<(f64, f64)>, color: RGBColor) -> Series {
        Series::new(label, points, color, true, false)
    }
    /// Dots, such as simulated points over theory.
    fn dots(label: &str, points: Vec<(f64, f64)>, color: RGBColor) -> Series {
        Series::new(label, points, color, false, true)
    }
    /// Dots joined by a line, such as measurements at a few sizes.
    fn measured(label: &str, points: Vec<(f64, f64)>, color: RGBColor) -> Series {
        Series::new(label, points, color, true, true)
    }
}

fn plot<X, Y>(
    title: &str,
    (x_name, x_range): (&str, X),
    (y_name, y_range): (&str, Y),
    series: &[Series],
    legend_at: SeriesLabelPosition,
) -> Result<String, String>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(x_range, y_range)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(x_name)
            .y_desc(y_name)
            .draw()
            .map_err(|e| e.to_string())?;
        for s in series {
            let color = s.color;
            if s.line && s.dashed {
                chart
                    .draw_series(DashedLineSeries::new(
                        s.points.iter().copied(),
                        6,
                        4,
                        color.stroke_width(2),
                    ))
                    .map_err(|e| e.to_string())?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| {
                        plotters::element::DashedPathElement::new(
                            vec![(x, y), (x + 20, y)],
                            6,
                            4,
                            color.stroke_width(2),
                        )
                    });
            } else if s.line {
                chart
                    .draw_series(LineSeries::new(
                        s.points.iter().copied(),
                        color.stroke_width(2),
                    ))
                    .map_err(|e| e.to_string())?
                    .label(s.label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            if s.dots {
                let drawn = chart
                    .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(|e| e.to_string())?;
                // A line drawn with them already stands for them in the legend.
                if !s.line {
                    drawn
                        .label(s.label.as_str())
                        .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
                }
            }
        }
        chart
            .configure_series_labels()
            .position(legend_at)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_per_second_draws_each_engine_with_friction_and_without() {
        let csv = "balls,engine,ball_friction,steps_per_second\n\
                   1000,ours,0.5,500\n1000,theirs,0.5,400\n\
                   10000,ours,0.5,50\n10000,theirs,0.5,40\n\
                   1000,ours,0,1500\n1000,theirs,0,450\n";
        let svg = steps_per_second(csv).expect("the figure draws");
        for label in [
            "ours, friction 0.5",
            "theirs, friction 0.5",
            "ours, frictionless",
            "theirs, frictionless",
        ] {
            assert!(svg.contains(label), "no `{label}` in the legend");
        }
        assert!(steps_per_second("balls,engine,steps_per_second\n1000,ours,500\n").is_err());
        assert!(steps_per_second("balls,engine,ball_friction,steps_per_second\n").is_err());
    }
}
