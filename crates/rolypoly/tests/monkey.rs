//! A monkey at the window: the real binary under a virtual X display,
//! driven for minutes by seeded random input (keys, held Shift, mouse
//! moves, clicks and drags, the wheel, clicks in the panel, which switch
//! scenes and move sliders, resizes down to 1 x 1, rewinds). The program
//! must not panic or hang (it logs its frame rate every second), must quit
//! cleanly when asked, and its memory after the warm-up must stay within
//! [`GROWTH_BOUND_MB`] of what it was then.
//!
//! Two minutes by default (continuous integration runs that); longer on
//! demand: `cargo test -p rolypoly --test monkey -- --minutes 10 --seed 7`.
//! Needs `Xvfb` and `xdotool`, as the window test does.

mod display;

use display::{Guard, start_display, tool};
use serde_json::Value;
use std::io::{BufRead, BufReader, Read};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

/// How long the program may go without logging a frame before it counts
/// as hung (seconds): a frame of the largest shipped scene on a software
/// renderer in a debug build takes a few.
const HANG_SECONDS: u64 = 60;
/// The warm-up, before memory is first read (seconds).
const WARM_UP_SECONDS: u64 = 15;
/// How much the resident memory may grow after the warm-up (MB): the
/// largest shipped scene (100 000 balls) with its 30 s of rewind, and the
/// renderer's buffers for it.
const GROWTH_BOUND_MB: f64 = 1500.0;
/// The window's size between resizes.
const SIZE: (u32, u32) = (640, 360);

/// What the monkey can do, and how often (weights).
const KEYS: [&str; 23] = [
    "w",
    "a",
    "s",
    "d",
    "f",
    "b",
    "p",
    "period",
    "comma",
    "BackSpace",
    "bracketleft",
    "bracketright",
    "g",
    "i",
    "o",
    "1",
    "2",
    "3",
    "4",
    "5",
    "6",
    "h",
    "Tab",
];

/// A small seeded generator (xorshift), the same run for the same seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
}

struct Options {
    minutes: f64,
    seed: u64,
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .map(|v| {
                v.parse::<f64>()
                    .unwrap_or_else(|_| panic!("{name} takes a number, not `{v}`"))
            })
    };
    Options {
        minutes: value("--minutes").unwrap_or(2.0),
        seed: value("--seed").map_or(1, |s| s as u64),
    }
}

struct Monkey {
    display: String,
    window: String,
    rng: Rng,
    counts: std::collections::BTreeMap<&'static str, u32>,
}

impl Monkey {
    /// Runs xdotool; a failure (the window resized away, say) is no error
    /// of the program's.
    fn xdotool(&self, args: &[&str]) {
        let _ = Command::new(tool("xdotool"))
            .args(args)
            .env("DISPLAY", &self.display)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status();
    }

    fn point(&mut self) -> (String, String) {
        let (w, h) = SIZE;
        (
            self.rng.below(u64::from(w)).to_string(),
            self.rng.below(u64::from(h)).to_string(),
        )
    }

    /// One random act, and a short pause.
    fn act(&mut self) {
        let w = self.window.clone();
        let what = match self.rng.below(100) {
            0..=39 => {
                let key = KEYS[self.rng.below(KEYS.len() as u64) as usize];
                self.xdotool(&["key", "--window", &w, key]);
                "key"
            }
            40..=44 => {
                self.xdotool(&["keydown", "--window", &w, "Shift_L"]);
                std::thread::sleep(Duration::from_millis(self.rng.below(400)));
                self.xdotool(&["keyup", "--window", &w, "Shift_L"]);
                "held shift"
            }
            45..=59 => {
                let (x, y) = self.point();
                self.xdotool(&["mousemove", "--window", &w, &x, &y]);
                "move"
            }
            60..=69 => {
                let (x, y) = self.point();
                self.xdotool(&["mousemove", "--window", &w, &x, &y, "click", "1"]);
                "click"
            }
            70..=77 => {
                let (x, y) = self.point();
                self.xdotool(&["mousemove", "--window", &w, &x, &y, "mousedown", "1"]);
                for _ in 0..4 {
                    let (x, y) = self.point();
                    self.xdotool(&["mousemove", "--window", &w, &x, &y]);
                }
                self.xdotool(&["mouseup", "1"]);
                "drag"
            }
            78..=81 => {
                let button = if self.rng.below(2) == 0 { "4" } else { "5" };
                self.xdotool(&["click", "--repeat", "3", button]);
                "wheel"
            }
            82..=91 => {
                // Somewhere in the panel, on the right (open or not).
                let (w_px, h_px) = SIZE;
                let x = (w_px * 3 / 5 + self.rng.below(u64::from(w_px) * 2 / 5) as u32).to_string();
                let y = self.rng.below(u64::from(h_px)).to_string();
                self.xdotool(&["mousemove", "--window", &w, &x, &y, "click", "1"]);
                "panel click"
            }
            92..=95 => {
                let sizes = [(1, 1), (2, 200), (300, 1), (160, 90), (1000, 700)];
                let (sw, sh) = sizes[self.rng.below(sizes.len() as u64) as usize];
                self.xdotool(&["windowsize", &w, &sw.to_string(), &sh.to_string()]);
                std::thread::sleep(Duration::from_millis(300));
                let (w0, h0) = SIZE;
                self.xdotool(&["windowsize", &w, &w0.to_string(), &h0.to_string()]);
                "resize"
            }
            _ => {
                let key = if self.rng.below(2) == 0 {
                    "comma"
                } else {
                    "BackSpace"
                };
                self.xdotool(&["key", "--window", &w, "--repeat", "5", key]);
                "rewind"
            }
        };
        *self.counts.entry(what).or_default() += 1;
        std::thread::sleep(Duration::from_millis(20 + self.rng.below(80)));
    }
}

/// The resident memory of process `pid` (MB).
fn resident_mb(pid: u32) -> Option<f64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// What the program logged: when it last drew (its frame rate, logged
/// once a second), and how many of each event of interest.
struct Logged {
    last_frame: Instant,
    counts: std::collections::BTreeMap<String, u32>,
}

impl Logged {
    /// Takes every line the program has logged so far.
    fn drain(&mut self, lines: &Receiver<Value>) {
        while let Ok(v) = lines.try_recv() {
            let event = v["event"].as_str().unwrap_or("").to_owned();
            if event == "frame_rate" {
                self.last_frame = Instant::now();
            }
            if [
                "frame_rate",
                "scene",
                "rewound",
                "resized",
                "grabbed",
                "orbit",
                "quality",
            ]
            .contains(&event.as_str())
            {
                *self.counts.entry(event).or_default() += 1;
            }
        }
    }
}

fn main() {
    let options = options();
    let (display, _xvfb) = start_display();
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("monkey");
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch).expect("scratch folder");
    let mut child = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args([
            "--log-events",
            "--window-size",
            "640x360",
            "--seed",
            "1",
            "--screenshot-dir",
        ])
        .arg(&scratch)
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", &scratch)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("rolypoly starts");
    let pid = child.id();
    let stdout = child.stdout.take().expect("stdout");
    let mut stderr = child.stderr.take().expect("stderr");
    let errors = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });
    let mut app = Guard(child);
    let (send, lines) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if let Ok(v) = serde_json::from_str::<Value>(&line) {
                let _ = send.send(v);
            }
        }
    });
    // The window opens and logs it.
    let opened = Instant::now();
    loop {
        if let Ok(v) = lines.recv_timeout(Duration::from_millis(200))
            && v["event"] == "ready"
        {
            break;
        }
        assert!(
            opened.elapsed() < Duration::from_secs(60),
            "the window never opened"
        );
    }
    let found = Command::new(tool("xdotool"))
        .args(["search", "--sync", "--name", "^rolypoly$"])
        .env("DISPLAY", &display)
        .output()
        .expect("xdotool search");
    let window = String::from_utf8_lossy(&found.stdout)
        .lines()
        .next()
        .expect("the window exists")
        .to_owned();
    let mut monkey = Monkey {
        display,
        window: window.clone(),
        rng: Rng(options.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1),
        counts: Default::default(),
    };
    monkey.xdotool(&["windowfocus", "--sync", &window]);

    let start = Instant::now();
    let total = Duration::from_secs_f64(options.minutes * 60.0);
    let mut logged = Logged {
        last_frame: Instant::now(),
        counts: Default::default(),
    };
    let mut baseline: Option<f64> = None;
    let mut peak = 0.0f64;
    let mut acts = 0u64;
    while start.elapsed() < total {
        monkey.act();
        acts += 1;
        logged.drain(&lines);
        if let Ok(Some(status)) = app.0.try_wait() {
            let text = errors.join().unwrap_or_default();
            panic!("the program ended on its own ({status}) after {acts} acts:\n{text}");
        }
        assert!(
            logged.last_frame.elapsed() < Duration::from_secs(HANG_SECONDS),
            "no frame for {HANG_SECONDS} s after {acts} acts: hung"
        );
        if start.elapsed() > Duration::from_secs(WARM_UP_SECONDS) {
            let now = resident_mb(pid).unwrap_or(0.0);
            let base = *baseline.get_or_insert(now);
            peak = peak.max(now);
            assert!(
                now - base <= GROWTH_BOUND_MB,
                "memory grew from {base:.0} MB to {now:.0} MB after {acts} acts"
            );
        }
    }
    // Asked to quit, it quits cleanly: Esc frees the mouse, Esc again quits.
    monkey.xdotool(&["windowsize", &window, "640", "360"]);
    monkey.xdotool(&["windowfocus", "--sync", &window]);
    let quit_asked = Instant::now();
    let status = loop {
        monkey.xdotool(&["key", "--window", &window, "Escape"]);
        if let Ok(Some(status)) = app.0.try_wait() {
            break status;
        }
        std::thread::sleep(Duration::from_millis(500));
        assert!(
            quit_asked.elapsed() < Duration::from_secs(HANG_SECONDS),
            "it did not quit when asked"
        );
    };
    let text = errors.join().unwrap_or_default();
    assert!(status.success(), "it quit with {status}:\n{text}");
    assert!(!text.contains("panicked"), "it panicked:\n{text}");
    let base = baseline.unwrap_or(0.0);
    println!(
        "monkey, seed {}: {acts} acts in {:.0} s ({:?}); logged {:?}; memory {base:.0} MB after the warm-up, at most {peak:.0} MB (+{:.0} MB, bound +{GROWTH_BOUND_MB:.0}); quit cleanly",
        options.seed,
        start.elapsed().as_secs_f64(),
        monkey.counts,
        logged.counts,
        peak - base
    );
}
