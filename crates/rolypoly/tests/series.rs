//! `simulate --series`: the run's totals as CSV, held to the physics they
//! plot, and its bad input refused.

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
    for column in expected
        .iter()
        .take(12)
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

#[test]
fn an_elastic_gas_keeps_its_energy_and_its_momentum_but_at_the_walls() {
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
        // No gravity and no friction: the balls' impacts on each other
        // pass momentum between them and keep its sum, so a step without
        // an impact on a wall leaves it where it was, to rounding; the
        // walls are what turn it.
        let (px, py, pz) = (
            run.column("momentum_x"),
            run.column("momentum_y"),
            run.column("momentum_z"),
        );
        let walls = run.column("surface_impacts");
        let changes: Vec<(f64, bool)> = (1..run.rows.len())
            .map(|k| {
                let change = ((px[k] - px[k - 1]).powi(2)
                    + (py[k] - py[k - 1]).powi(2)
                    + (pz[k] - pz[k - 1]).powi(2))
                .sqrt();
                (change, walls[k] > 0.0)
            })
            .collect();
        // The scale: the largest turn a step's wall impacts gave.
        let scale = changes
            .iter()
            .filter(|(_, wall)| *wall)
            .map(|(c, _)| *c)
            .fold(0.0, f64::max);
        let (mut quiet, mut turned) = (0, 0);
        for (k, (change, wall)) in changes.iter().enumerate() {
            if !wall {
                quiet += 1;
                assert!(
                    *change <= 1e-9 * scale,
                    "seed {seed}, step {}: momentum moved {change} with no wall hit (scale {scale})",
                    k + 1
                );
            } else if *change > 1e-3 * scale {
                turned += 1;
            }
        }
        assert!(quiet > 10 && turned > 10, "seed {seed}: {quiet} {turned}");
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
