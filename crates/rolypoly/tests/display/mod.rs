//! A virtual X display for the tests that drive the real window: Xvfb on
//! a free display number, the tools found on the path, and children that
//! are killed when a test ends, however it ends.

use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Kills a child process when dropped, whatever happens in the test.
pub struct Guard(pub Child);

impl Drop for Guard {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

pub fn tool(name: &str) -> PathBuf {
    let found = std::env::var_os("PATH")
        .into_iter()
        .flat_map(|p| std::env::split_paths(&p).collect::<Vec<_>>())
        .map(|dir| dir.join(name))
        .find(|p| p.is_file());
    found.unwrap_or_else(|| {
        panic!("`{name}` is needed for the window tests: apt-get install xvfb xdotool")
    })
}

/// A virtual X server, stopped when dropped. Killed, it leaves its lock
/// and socket behind, so those go too: else every run would use up a
/// display number for good.
pub struct XServer {
    server: Guard,
    number: u32,
}

impl Drop for XServer {
    fn drop(&mut self) {
        let _ = self.server.0.kill();
        let _ = self.server.0.wait();
        let _ = std::fs::remove_file(lock_file(self.number));
        let _ = std::fs::remove_file(format!("/tmp/.X11-unix/X{}", self.number));
    }
}

fn lock_file(display: u32) -> PathBuf {
    PathBuf::from(format!("/tmp/.X{display}-lock"))
}

/// Whether a running X server holds display `n`: its lock file names a live
/// process. A lock left by a server that is gone does not count; Xvfb takes
/// such a display over.
fn display_taken(n: u32) -> bool {
    std::fs::read_to_string(lock_file(n))
        .ok()
        .and_then(|pid| pid.trim().parse::<u32>().ok())
        .is_some_and(|pid| PathBuf::from(format!("/proc/{pid}")).exists())
}

/// Starts Xvfb on a free display number and returns it with its server.
pub fn start_display() -> (String, XServer) {
    let xvfb = tool("Xvfb");
    for n in 90..120 {
        if display_taken(n) {
            continue;
        }
        let display = format!(":{n}");
        let child = Command::new(&xvfb)
            .args([
                display.as_str(),
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("Xvfb starts");
        let guard = XServer {
            server: Guard(child),
            number: n,
        };
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            let ok = Command::new(tool("xdotool"))
                .args(["getdisplaygeometry"])
                .env("DISPLAY", &display)
                .output()
                .is_ok_and(|o| o.status.success());
            if ok {
                return (display, guard);
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }
    panic!("could not start Xvfb on any display :90..:119");
}
