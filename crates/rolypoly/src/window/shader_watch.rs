//! `--shaders DIR` in the window: the folder is watched, and a saved WGSL
//! file has the whole set loaded and checked again (naga, as wgpu checks
//! it), so that the window can draw with it from the next frame, or keep
//! its last good shaders and say what is wrong.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

use anyhow::Context as _;
use notify::{RecursiveMode, Watcher as _};
use rolypoly_render::shaders::{ShaderError, ShaderSet};

/// How long the folder must be quiet after a change before it is read: an
/// editor's save is often several writes (truncate, write, rename), and
/// the set is read once they are done, not half-way.
pub const SETTLE: Duration = Duration::from_millis(30);

/// A watched shader folder.
pub struct ShaderWatch {
    dir: PathBuf,
    /// Kept alive: dropping it stops the watching.
    _watcher: notify::RecommendedWatcher,
    /// Each change with when the watcher saw it (not when a frame read it).
    changes: Receiver<(Instant, notify::Result<notify::Event>)>,
    /// When the last change not yet read was seen.
    changed_at: Option<Instant>,
    /// When the first change not yet read was seen: what a reload's
    /// latency counts from.
    first_change: Option<Instant>,
}

/// A reload: the shaders as they are now, or why they cannot be drawn
/// with, and when the file was saved.
pub struct Reload {
    pub shaders: Result<ShaderSet, ShaderError>,
    pub saved_at: Instant,
}

impl ShaderWatch {
    /// Starts watching `dir`.
    pub fn new(dir: &Path) -> anyhow::Result<ShaderWatch> {
        let (send, changes) = channel();
        let mut watcher = notify::recommended_watcher(move |event| {
            let _ = send.send((Instant::now(), event));
        })
        .with_context(|| format!("cannot watch the shader folder `{}`", dir.display()))?;
        watcher
            .watch(dir, RecursiveMode::NonRecursive)
            .with_context(|| format!("cannot watch the shader folder `{}`", dir.display()))?;
        Ok(ShaderWatch {
            dir: dir.to_path_buf(),
            _watcher: watcher,
            changes,
            changed_at: None,
            first_change: None,
        })
    }

    /// The folder watched.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The shaders read anew if a WGSL file changed and the folder has
    /// been quiet for [`SETTLE`] since; None otherwise. Never waits.
    pub fn poll(&mut self) -> Option<Reload> {
        while let Ok((seen, event)) = self.changes.try_recv() {
            // A watcher's own error (events lost) is a reason to read the
            // folder again, as a change is.
            let touches_wgsl = event.as_ref().map_or(true, |e| {
                !matches!(e.kind, notify::EventKind::Access(_))
                    && e.paths
                        .iter()
                        .any(|p| p.extension().is_some_and(|x| x == "wgsl"))
            });
            if touches_wgsl {
                self.changed_at = Some(seen);
                self.first_change.get_or_insert(seen);
            }
        }
        let quiet = self.changed_at?.elapsed() >= SETTLE;
        if !quiet {
            return None;
        }
        self.changed_at = None;
        let saved_at = self.first_change.take().unwrap_or_else(Instant::now);
        Some(Reload {
            shaders: ShaderSet::load(&self.dir),
            saved_at,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Polls until a reload comes, for at most five seconds.
    fn next_reload(watch: &mut ShaderWatch) -> Reload {
        let deadline = Instant::now() + Duration::from_secs(5);
        loop {
            if let Some(reload) = watch.poll() {
                return reload;
            }
            assert!(Instant::now() < deadline, "no reload after the save");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    #[test]
    fn a_saved_shader_is_read_again_once_and_a_broken_one_is_named() {
        let dir = std::env::temp_dir().join(format!("rolypoly-watch-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        rolypoly_render::shaders::export(&dir).unwrap();
        let mut watch = ShaderWatch::new(&dir).unwrap();
        assert!(watch.poll().is_none(), "nothing changed yet");

        // A file that is not a shader is not a reason to read them again.
        std::fs::write(dir.join("notes.txt"), "try 64").unwrap();
        std::thread::sleep(SETTLE * 4);
        assert!(watch.poll().is_none());

        let scene = dir.join("scene.wgsl");
        let source = std::fs::read_to_string(&scene).unwrap();
        std::fs::write(&scene, format!("{source}\nfn oops( {{\n")).unwrap();
        let broken = next_reload(&mut watch);
        let error = broken.shaders.expect_err("a syntax error").to_string();
        assert!(error.contains("scene.wgsl:"), "{error}");
        assert!(broken.saved_at.elapsed() >= SETTLE);
        // One save, one reload.
        std::thread::sleep(SETTLE * 4);
        assert!(watch.poll().is_none());

        std::fs::write(&scene, &source).unwrap();
        let fixed = next_reload(&mut watch);
        assert_eq!(fixed.shaders.unwrap(), ShaderSet::shipped());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
