//! Clips: frames drawn off-screen written as an animated GIF, an MP4 video
//! (through the program ffmpeg) or a folder of numbered PNGs, with a
//! progress bar (`record` and `replay`).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};

use crate::progress::Progress;
use anyhow::Context;
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};

/// How finely the GIF encoder looks for each frame's 256 colours: 1 is
/// the finest and slowest, 30 the coarsest. At 10 a frame of 640 x 360
/// takes a few hundredths of a second.
const GIF_SPEED: i32 = 10;

/// The kinds of clip, told by the name of the output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ClipKind {
    /// An animated GIF.
    Gif,
    /// An H.264 video, through ffmpeg.
    Mp4,
    /// Numbered PNGs in this folder.
    Pngs,
}

impl ClipKind {
    /// What `out` asks for: `.gif`, `.mp4`, or a folder (a name ending in
    /// `/`, an existing folder, or a name without an extension).
    pub fn of(out: &Path) -> anyhow::Result<ClipKind> {
        let names_folder = out.to_str().is_some_and(|s| s.ends_with('/'))
            || out.is_dir()
            || out.extension().is_none();
        if names_folder {
            return Ok(ClipKind::Pngs);
        }
        let extension = out.extension().and_then(|e| e.to_str()).unwrap_or("");
        match extension.to_ascii_lowercase().as_str() {
            "gif" => Ok(ClipKind::Gif),
            "mp4" => Ok(ClipKind::Mp4),
            _ => anyhow::bail!(
                "cannot write `{}`: a clip is an animated GIF (`.gif`), an MP4 video (`.mp4`) or a folder of PNGs (`DIR/`)",
                out.display()
            ),
        }
    }
}

/// Writes the `count` frames that `frame(k)` draws, `size` each, `fps` a
/// second, as the clip `out` names (see [`ClipKind::of`]), with a
/// progress bar once it takes a while.
pub fn write_clip(
    out: &Path,
    size: (u32, u32),
    fps: u32,
    count: u32,
    mut frame: impl FnMut(u32) -> anyhow::Result<RgbaImage>,
) -> anyhow::Result<()> {
    let kind = ClipKind::of(out)?;
    if kind == ClipKind::Mp4 {
        find_ffmpeg(out)?;
    }
    // A GIF is encoded in memory and written whole at the end, so that a
    // run that fails half way leaves no half a file.
    let mut gif = Vec::new();
    let mut clip = Clip::open(kind.clone(), out, size, fps, &mut gif)?;
    let mut progress = Progress::new(count, "frames");
    for k in 0..count {
        let image = frame(k)?;
        clip.add(k, image)
            .with_context(|| format!("cannot write `{}`", out.display()))?;
        progress.advance();
    }
    progress.finish();
    clip.finish()
        .and_then(|()| match kind {
            ClipKind::Gif => Ok(std::fs::write(out, &gif)?),
            _ => Ok(()),
        })
        .with_context(|| format!("cannot write `{}`", out.display()))
}

/// The frames of a clip of `seconds` at `fps`: one at each 1 / fps from
/// time 0, at least one.
pub fn frame_count(seconds: f64, fps: u32) -> u32 {
    // Both are range-checked: at most an hour at 60 frames a second.
    ((seconds * f64::from(fps)).round() as u32).max(1)
}

/// Fails with a clear error, before any work, where ffmpeg cannot be run.
pub fn find_ffmpeg(out: &Path) -> anyhow::Result<()> {
    match Command::new("ffmpeg")
        .arg("-version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
    {
        Ok(_) => Ok(()),
        Err(e) => anyhow::bail!(
            "cannot write `{}`: an MP4 video is made by the program `ffmpeg`, which could not be run ({e}); install it (Debian and Ubuntu: apt-get install ffmpeg), or record a `.gif` or a folder of PNGs",
            out.display()
        ),
    }
}

/// A clip being written.
enum Clip<'a> {
    /// Encoded into a buffer of the caller's.
    Gif {
        encoder: GifEncoder<&'a mut Vec<u8>>,
        delay: Delay,
    },
    /// Raw frames piped to ffmpeg, which writes the file.
    Mp4 {
        ffmpeg: Child,
        input: ChildStdin,
    },
    Pngs {
        folder: PathBuf,
    },
}

impl<'a> Clip<'a> {
    /// A clip of `kind` into `out`, or for a GIF into `gif`.
    fn open(
        kind: ClipKind,
        out: &Path,
        (width, height): (u32, u32),
        fps: u32,
        gif: &'a mut Vec<u8>,
    ) -> anyhow::Result<Clip<'a>> {
        match kind {
            ClipKind::Gif => {
                let mut encoder = GifEncoder::new_with_speed(gif, GIF_SPEED);
                encoder.set_repeat(Repeat::Infinite)?;
                Ok(Clip::Gif {
                    encoder,
                    delay: Delay::from_numer_denom_ms(1000, fps),
                })
            }
            ClipKind::Mp4 => {
                let mut ffmpeg = Command::new("ffmpeg")
                    .args([
                        "-loglevel",
                        "error",
                        "-y",
                        "-f",
                        "rawvideo",
                        "-pix_fmt",
                        "rgba",
                    ])
                    .args(["-s", &format!("{width}x{height}"), "-r", &fps.to_string()])
                    .args(["-i", "-"])
                    // H.264 in 4:2:0 wants even sides: an odd one gets a
                    // row or column of black.
                    .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
                    .args([
                        "-c:v",
                        "libx264",
                        "-pix_fmt",
                        "yuv420p",
                        "-movflags",
                        "+faststart",
                    ])
                    .arg(out)
                    .stdin(Stdio::piped())
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()
                    .context("cannot start ffmpeg")?;
                let input = ffmpeg.stdin.take().context("cannot write to ffmpeg")?;
                Ok(Clip::Mp4 { ffmpeg, input })
            }
            ClipKind::Pngs => {
                std::fs::create_dir_all(out)
                    .with_context(|| format!("cannot make the folder `{}`", out.display()))?;
                Ok(Clip::Pngs {
                    folder: out.to_path_buf(),
                })
            }
        }
    }

    /// Adds frame number `k`.
    fn add(&mut self, k: u32, image: RgbaImage) -> anyhow::Result<()> {
        match self {
            Clip::Gif { encoder, delay, .. } => {
                encoder.encode_frame(Frame::from_parts(image, 0, 0, *delay))?;
            }
            Clip::Mp4 { input, .. } => input
                .write_all(image.as_raw())
                .context("ffmpeg stopped reading the frames")?,
            Clip::Pngs { folder } => {
                let path = folder.join(format!("frame-{k:05}.png"));
                image
                    .save_with_format(&path, image::ImageFormat::Png)
                    .with_context(|| format!("cannot write `{}`", path.display()))?;
            }
        }
        Ok(())
    }

    fn finish(self) -> anyhow::Result<()> {
        match self {
            // The encoder writes the GIF's trailer when it goes.
            Clip::Gif { encoder, .. } => drop(encoder),
            Clip::Mp4 { ffmpeg, input } => {
                drop(input);
                let output = ffmpeg.wait_with_output().context("ffmpeg did not finish")?;
                if !output.status.success() {
                    let said = String::from_utf8_lossy(&output.stderr);
                    anyhow::bail!(
                        "ffmpeg failed ({}): {}",
                        output.status,
                        said.trim().lines().last().unwrap_or("it said nothing")
                    );
                }
            }
            Clip::Pngs { .. } => {}
        }
        Ok(())
    }
}
