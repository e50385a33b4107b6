//! `simulate --series`: the run's totals as CSV, held to the physics they
//! plot, and its bad input refused.

use glam::DVec3;
use std::path::PathBuf;
use std::process::{Command, Output};

fn rolypoly(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .output()
        .expect("the rolypoly binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("series");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

/// A series: its header's names and its rows of numbers.
struct Series {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Series {
    fn column(&self, name: &str) -> Vec<f64> {
        let k = self
            .columns
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.columns));
        self.rows.iter().map(|row| row[k]).collect()
    }
}

/// Runs `simulate` with `args` and `--series`, and reads the file back.
fn series(name: &str, args: &[&str]) -> Series {
    let path = scratch(name);
    let path_text = path.to_str().expect("a UTF-8 path");
    let mut all = vec!["simulate", "--series", path_text];
    all.extend_from_slice(args);
    let output = rolypoly(&all);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(&path).expect("the series is written");
    let mut lines = text.lines();
    let columns: Vec<String> = lines
        .next()
        .expect("a header")
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|line| {
            let row: Vec<f64> = line
                .split(',')
                .map(|v| v.parse().expect("a number"))
                .collect();
            assert_eq!(row.len(), columns.len(), "{line}");
            row
        })
        .collect();
    Series { columns, rows }
}

#[test]
fn the_columns_are_documented_and_a_line_is_written_every_n_steps_and_at_the_last() {
    let run = series(
        "every.csv",
        &["--steps", "25", "--series-every", "10", "--seed", "3"],
    );
    let mut expected: Vec<String> = [
        "step",
        "time",
        "kinetic_translational",
        "kinetic_rotational",
        "potential",
        "total",
        "momentum_x",
        "momentum_y",
        "momentum_z",
        "surface_impulse_x",
        "surface_impulse_y",
        "surface_impulse_z",
        "tumbler_impulse_x",
        "tumbler_impulse_y",
        "tumbler_impulse_z",
        "guard_impulse_x",
        "guard_impulse_y",
        "guard_impulse_z",
        "gravity_impulse_y",
        "poured_momentum_y",
        "contacts",
        "impacts",
        "surface_impacts",
    ]
    .iter()
    .map(|c| (*c).to_owned())
    .collect();
    expected.extend((0..5).map(|k| format!("tumbler_{k}_tilt")));
    assert_eq!(run.columns, expected);
    assert_eq!(run.column("step"), [0.0, 10.0, 20.0, 25.0]);
    let using =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/using.md"))
            .expect("docs/using.md");
    let fixed = expected.len() - 5;
    for column in expected
        .iter()
        .take(fixed)
        .chain(["tumbler_K_tilt".to_owned()].iter())
    {
        assert!(
            using.contains(&format!("`{column}`")),
            "docs/using.md does not name the column {column}"
        );
    }
}

#[test]
fn the_parts_add_up_and_the_default_rooms_energy_never_rises() {
    for seed in ["1", "4"] {
        let run = series("default.csv", &["--seconds", "3", "--seed", seed]);
        let parts: Vec<f64> = run.rows.iter().map(|r| r[2] + r[3] + r[4]).collect();
        for (sum, total) in parts.iter().zip(run.column("total")) {
            assert!((sum - total).abs() <= 1e-12 * total.abs(), "{sum} {total}");
        }
        let total = run.column("total");
        for pair in total.windows(2) {
            assert!(
                pair[1] <= pair[0] + 1e-9 * pair[0].abs(),
                "seed {seed}: the energy rose from {} J to {} J",
                pair[0],
                pair[1]
            );
        }
        // Balls fall and land: energy leaves, and the impacts are counted.
        assert!(total[total.len() - 1] < 0.9 * total[0], "seed {seed}");
        assert!(
            run.column("impacts").iter().sum::<f64>() > 30.0,
            "seed {seed}"
        );
        assert!(
            run.column("contacts").iter().any(|&c| c > 0.0),
            "seed {seed}"
        );
    }
}

/// Per step from the second line on: the change of the balls' momentum
/// less what the step's impulses gave (the surfaces', the tumblers' and the
/// energy guard's), and the surfaces' impulse alone.
fn momentum_balance(run: &Series) -> Vec<(DVec3, DVec3)> {
    let vectors = |name: &str| -> Vec<DVec3> {
        let [x, y, z] = ["x", "y", "z"].map(|axis| run.column(&format!("{name}_{axis}")));
        (0..x.len()).map(|k| DVec3::new(x[k], y[k], z[k])).collect()
    };
    let momentum = vectors("momentum");
    let (surfaces, tumblers, guard) = (
        vectors("surface_impulse"),
        vectors("tumbler_impulse"),
        vectors("guard_impulse"),
    );
    let poured = run.column("poured_momentum_y");
    (1..momentum.len())
        .map(|k| {
            // Gravity's is held to its own law by the callers.
            let given = surfaces[k] + tumblers[k] + guard[k] + DVec3::Y * poured[k];
            (momentum[k] - momentum[k - 1] - given, surfaces[k])
        })
        .collect()
}

/// The largest length among `vectors`.
fn largest(vectors: impl Iterator<Item = DVec3>) -> f64 {
    vectors.map(DVec3::length).fold(0.0, f64::max)
}

#[test]
fn an_elastic_gas_keeps_its_energy_and_only_its_walls_change_its_momentum() {
    let gas = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/elastic-gas.toml");
    for seed in ["2", "7"] {
        let run = series(
            "gas.csv",
            &["--scene", gas, "--seconds", "10", "--seed", seed],
        );
        let total = run.column("total");
        let start = total[0];
        for (k, e) in total.iter().enumerate() {
            assert!(
                (e - start).abs() <= 1e-3 * start,
                "seed {seed}: {e} J at line {k} from {start} J"
            );
        }
        // No gravity: each step's change of the balls' momentum is what the
        // walls gave them; the balls' impacts on one another keep its sum.
        let balance = momentum_balance(&run);
        let scale = largest(balance.iter().map(|(_, walls)| *walls));
        assert!(scale > 0.0, "seed {seed}: the walls gave nothing");
        for (k, (gap, _)) in balance.iter().enumerate() {
            assert!(
                gap.length() <= 1e-9 * scale,
                "seed {seed}, step {}: the momentum moved {gap} beyond its impulses (scale {scale})",
                k + 1
            );
        }
        let turned = balance
            .iter()
            .filter(|(_, w)| w.length() > 1e-3 * scale)
            .count();
        assert!(turned > 10, "seed {seed}: only {turned} steps met a wall");
    }
}

#[test]
fn with_gravity_the_momentum_also_gains_m_g_dt() {
    // The elastic gas with gravity: 400 balls of about 0.25 kg each (their
    // masses vary with their sizes; the physics crate's own test holds
    // gravity's impulse to their sum).
    let gas = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/elastic-gas.toml");
    let text = std::fs::read_to_string(gas).expect("the elastic gas scene");
    let heavy = scratch("heavy-gas.toml");
    std::fs::write(&heavy, text.replace("gravity = 0.0", "gravity = 9.81")).unwrap();
    for seed in ["3", "8"] {
        let run = series(
            "heavy.csv",
            &[
                "--scene",
                heavy.to_str().unwrap(),
                "--seconds",
                "3",
                "--seed",
                seed,
            ],
        );
        let (time, gravity) = (run.column("time"), run.column("gravity_impulse_y"));
        let balance = momentum_balance(&run);
        let scale = largest(balance.iter().map(|(_, walls)| *walls));
        for (k, (gap, _)) in balance.iter().enumerate() {
            // Gravity's impulse a step is the balls' weight times the step.
            let mass = -gravity[k + 1] / (9.81 * (time[k + 1] - time[k]));
            assert!(
                (mass - 100.0).abs() < 5.0,
                "seed {seed}, step {}: gravity's impulse is of {mass} kg",
                k + 1
            );
            let weight = DVec3::new(0.0, gravity[k + 1], 0.0);
            assert!(
                (*gap - weight).length() <= 1e-9 * scale,
                "seed {seed}, step {}: {gap} beyond the impulses, gravity gives {weight}",
                k + 1
            );
        }
    }
}

#[test]
fn the_gpu_engine_writes_the_same_columns() {
    let run = series(
        "gpu.csv",
        &["--engine", "gpu", "--steps", "20", "--series-every", "5"],
    );
    assert_eq!(run.column("step"), [0.0, 5.0, 10.0, 15.0, 20.0]);
    let total = run.column("total");
    assert!(total.iter().all(|e| e.is_finite() && *e > 0.0));
    // It counts no impulses: unknown, not zero.
    assert!(run.column("surface_impulse_y").iter().all(|v| v.is_nan()));
}

#[test]
fn bad_series_flags_are_one_clear_error_and_write_nothing() {
    let missing = scratch("no-such-folder/out.csv");
    let missing = missing.to_str().unwrap();
    let cases: [(&[&str], &str); 3] = [
        (
            &["simulate", "--steps", "1", "--series", missing],
            "out.csv",
        ),
        (
            &[
                "simulate",
                "--steps",
                "1",
                "--series",
                "x.csv",
                "--series-every",
                "0",
            ],
            "--series-every",
        ),
        (
            &["simulate", "--steps", "1", "--series-every", "2"],
            "--series",
        ),
    ];
    for (args, named) in cases {
        let output = rolypoly(args);
        let err = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?}");
        assert!(err.contains(named), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(output.stdout.is_empty(), "{args:?}");
    }
    assert!(!std::path::Path::new("x.csv").exists());
}
