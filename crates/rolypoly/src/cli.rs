//! The command line (A1-A3): global scene options and the subcommands.

use std::path::{Path, PathBuf};
use std::time::Duration;

use clap::{Args, Parser, Subcommand};

use crate::engine::Engine;
use crate::frames::{FrameOptions, Frames};
use crate::scene::Overrides;
use rolypoly_render::{DebugViews, FrameView, LightConfig, QualityChoice};

/// Help section of the options shared by every command.
const SCENE_HEADING: &str = "Scene options";

/// rolypoly: a 3D toy room where roly-poly tumblers rock, balls bounce and a
/// fireball tears through.
///
/// Without a subcommand it opens the window on the scene. Every constant of a
/// scene comes from a TOML scene file that overrides the built-in default
/// (see scenes/default.toml for the format).
#[derive(Debug, Parser)]
#[command(
    name = "rolypoly",
    version,
    about,
    long_about,
    propagate_version = true
)]
pub struct Cli {
    #[command(flatten)]
    pub scene: SceneArgs,

    #[command(flatten)]
    pub window: WindowArgs,

    #[command(flatten)]
    pub gpu: GpuArgs,

    #[command(subcommand)]
    pub command: Option<Command>,
}

impl WindowArgs {
    /// The window as these flags open it, on a scene of `seed` from
    /// `scene_file` (if one was given).
    pub fn options(&self, seed: u64, scene_file: Option<&Path>) -> crate::window::WindowOptions {
        crate::window::WindowOptions {
            size: self.window_size,
            fullscreen: self.fullscreen,
            vsync: !self.no_vsync,
            msaa: self.msaa,
            temporal: match (self.temporal, self.no_temporal) {
                (true, _) => Some(true),
                (_, true) => Some(false),
                _ => None,
            },
            quality: self.quality,
            log_events: self.log_events,
            seed,
            screenshot_dir: self.screenshot_dir.clone(),
            move_speed: self.move_speed,
            look_speed: self.look_speed.to_radians(),
            scene_file: scene_file.map(Path::to_path_buf),
            replay_digest: None,
            replay_from: None,
            shaders: self.shaders.clone(),
            view: self.view.unwrap_or(FrameView::Final),
        }
    }
}

/// Help section of the options on the graphics adapter.
const GPU_HEADING: &str = "GPU options";

/// How the program treats the graphics adapter, on every command and the
/// window.
#[derive(Debug, Args)]
pub struct GpuArgs {
    /// Longest wait for the GPU, in seconds (decimals allowed, such as
    /// 0.001; at most 86400): a frame, the GPU engine's step or a read-back
    /// that takes longer ends the program with an error naming what was
    /// waited for and the adapter, instead of hanging.
    #[arg(
        long,
        value_name = "SECONDS",
        default_value = "30",
        value_parser = parse_gpu_timeout,
        global = true,
        allow_negative_numbers = true,
        help_heading = GPU_HEADING
    )]
    pub gpu_timeout: Duration,
}

/// Help section of the window's options.
const WINDOW_HEADING: &str = "Window options (no subcommand)";

/// How the window opens and behaves.
#[derive(Debug, Args)]
pub struct WindowArgs {
    /// Window size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = parse_size, help_heading = WINDOW_HEADING)]
    pub window_size: (u32, u32),

    /// Open full screen.
    #[arg(long, help_heading = WINDOW_HEADING)]
    pub fullscreen: bool,

    /// Draw as fast as possible instead of at the display's rate (to measure).
    #[arg(long, help_heading = WINDOW_HEADING)]
    pub no_vsync: bool,

    /// How finely the window draws: high, medium, low, or auto, which
    /// lowers the render scale, then steps down, while frames are slower
    /// than the target (--fps) (default: the scene's render.quality, auto
    /// unless it says otherwise).
    #[arg(long, value_name = "LEVEL", value_parser = parse_quality, help_heading = WINDOW_HEADING)]
    pub quality: Option<QualityChoice>,

    /// The frames a second auto quality holds the window to, by its render
    /// scale first (default: the scene's render.target_fps; 0 there: the
    /// display's rate with a GPU, 30 on a software renderer).
    #[arg(long, value_name = "FPS", value_parser = parse_fps, help_heading = WINDOW_HEADING)]
    pub fps: Option<f64>,

    /// Multisample anti-aliasing in the window at every quality level: 4 or
    /// 1 (off) (default: the level's own).
    #[arg(long = "window-msaa", value_name = "N", value_parser = parse_msaa, help_heading = WINDOW_HEADING)]
    pub msaa: Option<u32>,

    /// Temporal anti-aliasing with upsampling in the window: frames
    /// jittered and resolved against the ones before them at the window's
    /// resolution, in place of multisampling (default: on with a GPU; off
    /// on a software renderer, where its two passes at the window's
    /// resolution cost more than the frame rate allows).
    #[arg(long, conflicts_with = "no_temporal", help_heading = WINDOW_HEADING)]
    pub temporal: bool,

    /// Draw the window without temporal anti-aliasing, whatever the adapter.
    #[arg(long, help_heading = WINDOW_HEADING)]
    pub no_temporal: bool,

    /// Print every change of state (keys, modes, grabs, screenshots) as one
    /// JSON object per line on standard output.
    #[arg(long, help_heading = WINDOW_HEADING)]
    pub log_events: bool,

    /// Folder that the F12 key writes screenshots into.
    #[arg(long, value_name = "DIR", default_value = ".", help_heading = WINDOW_HEADING)]
    pub screenshot_dir: PathBuf,

    #[command(flatten, next_help_heading = WINDOW_HEADING)]
    pub effects: LightEffectArgs,

    /// Walking speed of W/A/S/D in m/s (0.1 ..= 50).
    #[arg(long, value_name = "M/S", default_value_t = 2.5, value_parser = parse_speed, help_heading = WINDOW_HEADING)]
    pub move_speed: f32,

    /// Mouse-look sensitivity in degrees per pixel (0.01 ..= 5).
    #[arg(long, value_name = "DEG", default_value_t = 0.15, value_parser = parse_look, help_heading = WINDOW_HEADING)]
    pub look_speed: f32,

    /// The view of the frame the window opens on (V and Shift+V change
    /// it): final, albedo, normals, depth, shadow-cube, ... (`render --view
    /// list` prints them all).
    #[arg(long, value_name = "NAME", help_heading = WINDOW_HEADING)]
    pub view: Option<FrameView>,

    /// Draw the window with the renderer's shaders from this folder
    /// (`shaders --export DIR` writes them there), watched: a saved file is
    /// drawn with from the next frame, or its error shown while the last
    /// good shaders draw on.
    #[arg(long, value_name = "DIR", help_heading = WINDOW_HEADING)]
    pub shaders: Option<PathBuf>,
}

fn parse_bounded(text: &str, lo: f32, hi: f32) -> Result<f32, String> {
    let v: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        // As written: `1e300` rather than `inf`, or all 300 digits.
        Err(format!(
            "{} is out of range: allowed {lo} ..= {hi}",
            text.trim()
        ))
    }
}

fn parse_speed(text: &str) -> Result<f32, String> {
    parse_bounded(text, 0.1, 50.0)
}

fn parse_look(text: &str) -> Result<f32, String> {
    parse_bounded(text, 0.01, 5.0)
}

/// Switches that turn the light's effects off, each on unless switched off
/// here or by the scene file's `[light]`.
#[derive(Clone, Copy, Debug, Default, Args)]
pub struct LightEffectArgs {
    /// Without the glow around the bulb, the fireball and its particles
    /// (the scene's light.bloom).
    #[arg(long)]
    pub no_bloom: bool,

    /// Without the fireball's light on the room and the flash of its hits
    /// (light.fireball_light).
    #[arg(long)]
    pub no_fireball_light: bool,

    /// Without the light bounced off the walls, floor and ceiling
    /// (light.indirect).
    #[arg(long)]
    pub no_indirect: bool,

    /// Without the darkening where things touch (light.occlusion).
    #[arg(long)]
    pub no_occlusion: bool,
}

impl FrameArgs {
    /// The options these flags choose.
    pub fn options(&self) -> FrameOptions {
        FrameOptions {
            quality: self.quality,
            msaa: self.msaa,
            camera: self.camera,
            no_shadows: self.no_shadows,
            shadow_size: self.shadow_size,
            shadow_taps: self.shadow_taps,
            tumbler_obj: self.tumbler_obj.clone(),
            shaders: self.shaders.clone(),
            show: self.show,
            scale: self.scale,
            temporal: self.temporal,
            view: match self.view {
                Some(ViewChoice::Show(view)) => Some(view),
                _ => None,
            },
        }
    }

    /// Whether `--view list` asked for the list of views instead of frames.
    pub fn lists_views(&self) -> bool {
        self.view == Some(ViewChoice::List)
    }

    /// Frames of `size` of the scene `config`, drawn as these flags say at
    /// the scene's `quality` unless they say otherwise, with the debug
    /// views' legend where `--legend` asks for it.
    pub fn frames(
        &self,
        config: &rolypoly_physics::WorldConfig,
        quality: QualityChoice,
        size: (u32, u32),
    ) -> anyhow::Result<Frames> {
        let mut frames = Frames::new(config, quality, &self.options(), size)?;
        if self.legend {
            let legend = crate::legend::OffscreenLegend::new(frames.gpu());
            frames.set_overlay(Box::new(legend));
        }
        Ok(frames)
    }
}

impl LightEffectArgs {
    /// The scene's light with the effects switched off here turned off.
    pub fn apply(&self, light: &LightConfig) -> LightConfig {
        LightConfig {
            bloom: light.bloom && !self.no_bloom,
            fireball_light: light.fireball_light && !self.no_fireball_light,
            indirect: light.indirect && !self.no_indirect,
            occlusion: light.occlusion && !self.no_occlusion,
            ..*light
        }
    }
}

/// Options that choose and adjust the scene; accepted before or after the
/// subcommand.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// Scene file (TOML) whose keys override the built-in default scene.
    #[arg(long, value_name = "FILE", global = true, help_heading = SCENE_HEADING)]
    pub scene: Option<PathBuf>,

    /// Seed of the random start (ball positions and velocities); the same
    /// seed gives the same run, step for step.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        global = true,
        help_heading = SCENE_HEADING
    )]
    pub seed: u64,

    /// Number of balls (overrides balls.count of the scene; 0 ..= 1000000).
    #[arg(long, value_name = "N", global = true, help_heading = SCENE_HEADING)]
    pub balls: Option<usize>,

    /// Gravity in m/s^2 (overrides gravity of the scene; 0 ..= 100).
    #[arg(
        long,
        value_name = "G",
        global = true,
        help_heading = SCENE_HEADING,
        allow_negative_numbers = true
    )]
    pub gravity: Option<f64>,

    /// Which engine steps the balls: cpu or gpu (overrides solver.engine
    /// of the scene).
    #[arg(long, value_name = "ENGINE", global = true, value_parser = parse_engine, help_heading = SCENE_HEADING)]
    pub engine: Option<Engine>,
}

impl SceneArgs {
    /// The command-line settings that override the scene file.
    pub fn overrides(&self) -> Overrides {
        Overrides {
            balls: self.balls,
            gravity: self.gravity,
            engine: self.engine,
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate a scene without a window and print a summary, or
    /// write a JSON Lines trace of every body, the energy and the events.
    Simulate(SimulateArgs),
    /// Simulate a scene to a moment and write that frame to a PNG, with the
    /// renderer the window uses, without a window.
    Render(RenderArgs),
    /// Simulate a scene and write its frames as a clip: an animated GIF, an
    /// MP4 video or a folder of PNGs, with the renderer the window uses,
    /// without a window.
    Record(RecordArgs),
    /// Play a recording of the inputs made with R in the window: in the
    /// window, or with --out off-screen into a clip as `record` makes. The
    /// state at its end is checked against the recording's, bit for bit.
    Replay(ReplayArgs),
    /// Write the tumbler's mesh, made from the scene's six collision
    /// spheres, as a Wavefront OBJ file (the shipped assets/tumbler.obj is
    /// made this way from the default scene).
    MakeTumblerObj(MakeTumblerObjArgs),
    /// Simulate a scene and write its sound, synthesized from the impacts
    /// and heard from the camera, to a WAV file (16-bit stereo, 48 kHz),
    /// without drawing and without an audio device.
    Sound(SoundArgs),
    /// Write the renderer's WGSL shaders as shipped into a folder, with a
    /// README naming what each draws, to read them or edit them. A file
    /// already there that differs (an edit) is refused, never overwritten.
    Shaders(ShadersArgs),
}

#[derive(Debug, Args)]
pub struct ShadersArgs {
    /// The folder to write them into (made if need be, in a folder that is).
    #[arg(long, value_name = "DIR")]
    pub export: PathBuf,
}

#[derive(Debug, Args)]
pub struct SoundArgs {
    /// Length of the sound, in simulated seconds (more than 0, at most 3600).
    #[arg(long, value_name = "S", default_value_t = 3.0, value_parser = parse_clip_seconds)]
    pub seconds: f64,

    /// Where the listener stands and looks: the camera as `render` takes it,
    /// eye then target (`ex,ey,ez,tx,ty,tz`); the overview if not given.
    #[arg(long, value_name = "EYE,TARGET", value_parser = parse_camera, allow_hyphen_values = true)]
    pub camera: Option<[f32; 6]>,

    /// Launch the fireball at the start, as F does.
    #[arg(long)]
    pub fireball: bool,

    /// The WAV file to write.
    #[arg(long, value_name = "FILE.wav")]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Simulated time of the frame, in seconds.
    #[arg(long, value_name = "S", default_value_t = 0.0, value_parser = parse_seconds)]
    pub time: f64,

    /// Frame size in pixels, WIDTHxHEIGHT (each 1 ..= 8192).
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),

    #[command(flatten)]
    pub frame: FrameArgs,

    #[command(flatten)]
    pub truth: ReferenceArgs,

    /// The PNG file to write (needed unless `--view list` asks only for
    /// the views).
    #[arg(
        long = "out",
        value_name = "FILE.png",
        required_unless_present = "view"
    )]
    pub out_file: Option<PathBuf>,
}

impl RenderArgs {
    /// The PNG file to write.
    pub fn out(&self) -> anyhow::Result<&Path> {
        self.out_file
            .as_deref()
            .ok_or_else(|| anyhow::anyhow!("render needs --out FILE.png: the PNG file to write"))
    }
}

/// The path-traced reference of a frame, and the real-time frame measured
/// against it.
#[derive(Debug, Args)]
pub struct ReferenceArgs {
    /// Path-trace the frame instead: the same scene at the same moment lit
    /// as light really goes, on the CPU's threads.
    #[arg(long, conflicts_with = "compare")]
    pub reference: bool,

    /// Write the real-time frame to --out, the path-traced reference beside
    /// it (NAME-reference.png) and FLIP's error map of the one against the
    /// other (NAME-flip.png), and print the mean error.
    #[arg(long)]
    pub compare: bool,

    /// The reference's samples a pixel, 1 ..= 65536 (default: 64).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub spp: Option<u32>,

    /// The seed of the reference's samples, apart from the scene's --seed
    /// (default: 1).
    #[arg(long, value_name = "S")]
    pub reference_seed: Option<u64>,

    /// Also write the reference's linear radiance to this OpenEXR file.
    #[arg(long, value_name = "FILE.exr")]
    pub hdr: Option<PathBuf>,

    /// Measure the frame made here (real-time, or with --reference
    /// path-traced) against this reference picture of the same scene,
    /// moment and size, written before by --reference: writes FLIP's error
    /// map beside --out (NAME-flip.png) and prints the mean error.
    #[arg(long, value_name = "FILE.png", conflicts_with = "compare")]
    pub against: Option<PathBuf>,
}

impl ReferenceArgs {
    /// The reference's samples a pixel when --spp does not say.
    pub const DEFAULT_SPP: u32 = 64;
    /// The reference's seed when --reference-seed does not say.
    pub const DEFAULT_SEED: u64 = 1;

    /// Whether a reference is traced.
    pub fn traced(&self) -> bool {
        self.reference || self.compare
    }
}

#[derive(Debug, Args)]
pub struct RecordArgs {
    /// Length of the clip, in simulated seconds (more than 0, at most 3600).
    #[arg(long, value_name = "S", default_value_t = 3.0, value_parser = parse_clip_seconds)]
    pub seconds: f64,

    #[command(flatten)]
    pub clip: ClipArgs,

    #[command(flatten)]
    pub frame: FrameArgs,

    /// Where the clip goes: FILE.gif (an animated GIF), FILE.mp4 (H.264,
    /// through the program ffmpeg, with the run's sound as AAC unless the
    /// scene's sound.enabled is false) or DIR/ (numbered PNGs, the folder
    /// made if need be).
    #[arg(long, value_name = "FILE.gif|FILE.mp4|DIR/")]
    pub out: PathBuf,

    /// Also write the run's sound alone to this WAV file.
    #[arg(long, value_name = "FILE.wav")]
    pub audio: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The recording: a `.replay` file that R writes beside the screenshots.
    #[arg(value_name = "LOG")]
    pub log: PathBuf,

    #[command(flatten)]
    pub clip: ClipArgs,

    #[command(flatten)]
    pub frame: FrameArgs,

    /// Draw the replay off-screen into FILE.gif, FILE.mp4 or DIR/ (as
    /// `record` does) instead of playing it in the window. The camera is
    /// the one recorded, unless --camera says otherwise.
    #[arg(long, value_name = "FILE.gif|FILE.mp4|DIR/")]
    pub out: Option<PathBuf>,
}

/// The rate and size of the frames of a clip (`record`, `replay --out`).
#[derive(Debug, Args)]
pub struct ClipArgs {
    /// Frames per simulated second (1 ..= 60). A GIF keeps its delays in
    /// hundredths of a second, so it plays 30 as 33.
    #[arg(long, value_name = "N", default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=60))]
    pub fps: u32,

    /// Frame size in pixels, WIDTHxHEIGHT (each 1 ..= 8192).
    #[arg(long, value_name = "WxH", default_value = "640x360", value_parser = parse_size)]
    pub size: (u32, u32),
}

/// How the frames of `render`, `record` and `replay` are drawn.
#[derive(Debug, Args)]
pub struct FrameArgs {
    /// How finely frames are drawn: high, medium or low; auto draws as
    /// high, so that pictures do not depend on the machine (default: the
    /// scene's render.quality).
    #[arg(long, value_name = "LEVEL", value_parser = parse_quality)]
    pub quality: Option<QualityChoice>,

    /// Multisample anti-aliasing: 4 or 1 (off) (default: the quality
    /// level's).
    #[arg(long, value_name = "N", value_parser = parse_msaa)]
    pub msaa: Option<u32>,

    /// Light the scene at this share of the frame's width and height,
    /// 0.33 ..= 1, and spread it over the frame (default: the quality
    /// level's).
    #[arg(long, value_name = "S", value_parser = parse_scale)]
    pub scale: Option<f32>,

    /// Temporal anti-aliasing with upsampling: each frame jittered and
    /// resolved against the frames before it at the frame's resolution.
    /// `render` draws the 16 moments before its own first, 1/60 s apart.
    /// It takes the place of multisampling.
    #[arg(long, conflicts_with = "msaa")]
    pub temporal: bool,

    /// Draw one pass of the frame instead of the finished picture: final,
    /// albedo, normals, depth, shadow-cube, shadow, ambient, diffuse,
    /// specular, bounce, occlusion, bloom, motion, history or msaa-edges;
    /// `list` prints each with what it shows.
    #[arg(long, value_name = "NAME", value_parser = parse_view)]
    pub view: Option<ViewChoice>,

    /// Camera position and the point it looks at: EX,EY,EZ,TX,TY,TZ in metres
    /// (default: the whole room from outside its front wall).
    #[arg(long, value_name = "EYE,TARGET", value_parser = parse_camera, allow_hyphen_values = true)]
    pub camera: Option<[f32; 6]>,

    /// Draw without the point light's shadows.
    #[arg(long)]
    pub no_shadows: bool,

    #[command(flatten)]
    pub effects: LightEffectArgs,

    /// Size of each of the six shadow faces, in texels (16 ..= 4096)
    /// (default: the quality level's).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub shadow_size: Option<u32>,

    /// Shadow filter taps along each side of its square, 1 ..= 8 (1: hard
    /// edges) (default: the quality level's).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=8))]
    pub shadow_taps: Option<u32>,

    /// Use this OBJ file as the tumbler's mesh instead of the built-in one.
    #[arg(long, value_name = "FILE")]
    pub tumbler_obj: Option<PathBuf>,

    /// Draw with the renderer's shaders from this folder instead of the
    /// shipped ones (`shaders --export DIR` writes them there to edit);
    /// each is checked first, an error naming its file, line and column.
    #[arg(long, value_name = "DIR")]
    pub shaders: Option<PathBuf>,

    /// Launch the fireball from the scene's spawn point at time 0.
    #[arg(long)]
    pub fireball: bool,

    /// Draw debug views of what happens inside the step, a comma-separated
    /// list of: contacts, impulses, velocities, grid, rest, com.
    #[arg(long, value_name = "LIST", value_parser = parse_show)]
    pub show: Option<DebugViews>,

    /// Draw the legend of the debug views --show names in the frame: what
    /// each colour and mark means (the window shows it while any view is
    /// on).
    #[arg(long, requires = "show")]
    pub legend: bool,
}

#[derive(Debug, Args)]
pub struct MakeTumblerObjArgs {
    /// The OBJ file to write.
    #[arg(long, value_name = "FILE.obj")]
    pub out: PathBuf,
}

/// Debug views by name, comma-separated.
/// What `--view` asks for: one view of the frame, or their list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewChoice {
    /// Draw this view.
    Show(FrameView),
    /// Print every view's name and what it shows.
    List,
}

fn parse_view(text: &str) -> Result<ViewChoice, String> {
    if text == "list" {
        return Ok(ViewChoice::List);
    }
    text.parse()
        .map(ViewChoice::Show)
        .map_err(|e: rolypoly_render::UnknownView| e.to_string())
}

fn parse_show(text: &str) -> Result<DebugViews, String> {
    DebugViews::parse(text)
}

/// A render scale: a share of each side, from the least the window
/// lowers it to up to the whole.
fn parse_scale(text: &str) -> Result<f32, String> {
    let (least, most) = (rolypoly_render::MIN_SCALE, rolypoly_render::MAX_SCALE);
    match text.parse::<f32>() {
        Ok(scale) if (least..=most).contains(&scale) => Ok(scale),
        _ => Err(format!(
            "`{text}` is not a render scale: give the share of each side the scene is lit at, {least} ..= {most}"
        )),
    }
}

/// A frame rate for the window to hold: more than 0, at most 1000.
fn parse_fps(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(fps) if fps > 0.0 && fps <= 1000.0 => Ok(fps),
        _ => Err(format!(
            "`{text}` is not a frame rate: give frames a second, more than 0 and at most 1000"
        )),
    }
}

/// An engine by name.
fn parse_engine(text: &str) -> Result<Engine, String> {
    Engine::from_name(text.trim()).ok_or_else(|| {
        format!(
            "`{text}` is not an engine: use one of {}",
            Engine::NAMES.join(", ")
        )
    })
}

fn parse_quality(text: &str) -> Result<QualityChoice, String> {
    QualityChoice::from_name(text.trim()).ok_or_else(|| {
        format!(
            "`{text}` is not a quality level: use one of {}",
            QualityChoice::NAMES.join(", ")
        )
    })
}

/// 1 or 4 samples per pixel.
fn parse_msaa(text: &str) -> Result<u32, String> {
    match text.trim() {
        "1" => Ok(1),
        "4" => Ok(4),
        _ => Err(format!("`{text}` is not allowed: use 1 or 4")),
    }
}

/// `WIDTHxHEIGHT`, each side 1 ..= 8192.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{text}` is not WIDTHxHEIGHT (for example 1280x720)"))?;
    let side = |s: &str| -> Result<u32, String> {
        let n: u32 = s
            .trim()
            .parse()
            .map_err(|_| format!("`{s}` is not a whole number of pixels"))?;
        if (1..=8192).contains(&n) {
            Ok(n)
        } else {
            Err(format!(
                "{n} is out of range: each side is allowed 1 ..= 8192"
            ))
        }
    };
    Ok((side(w)?, side(h)?))
}

/// Six comma-separated finite numbers.
fn parse_camera(text: &str) -> Result<[f32; 6], String> {
    let numbers: Vec<f32> = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f32>()
                .map_err(|_| format!("`{s}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    let values: [f32; 6] = numbers
        .try_into()
        .map_err(|v: Vec<f32>| format!("expected 6 numbers EX,EY,EZ,TX,TY,TZ, got {}", v.len()))?;
    if values.iter().any(|v| !v.is_finite()) {
        return Err("camera numbers must be finite".into());
    }
    if values[..3] == values[3..] {
        return Err("the camera must look at a point other than its own position".into());
    }
    Ok(values)
}

#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub length: Length,

    /// Write a JSON Lines trace to FILE (`-` for standard output): a scene
    /// line, then a state line at step 0, every K steps and at the last step.
    #[arg(long, value_name = "FILE|-")]
    pub trace: Option<PathBuf>,

    /// Write a state line every K steps (K >= 1); each line carries all
    /// events since the previous one.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    pub every: u64,

    /// Launch the fireball from the scene's spawn point before the first step.
    #[arg(long)]
    pub fireball: bool,

    /// Write the run's totals to FILE as CSV: a line at step 0, then every
    /// N steps (`--series-every`) and at the last step, with the energy in
    /// its parts, the momentum, the contacts and impacts, and each
    /// tumbler's tilt (the columns in docs/using.md).
    #[arg(long, value_name = "FILE.csv")]
    pub series: Option<PathBuf>,

    /// Write a series line every N steps (N >= 1).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        requires = "series",
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    pub series_every: u64,
}

/// How long to simulate: exactly one of the two.
#[derive(Debug, Args)]
#[group(required = true, multiple = false)]
pub struct Length {
    /// Number of fixed time steps to simulate.
    #[arg(long, value_name = "N")]
    pub steps: Option<u64>,

    /// Simulated seconds, rounded to the nearest whole number of steps.
    #[arg(long, value_name = "S", value_parser = parse_seconds)]
    pub seconds: Option<f64>,
}

/// A length of simulated time: finite and not negative.
fn parse_seconds(text: &str) -> Result<f64, String> {
    let seconds: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    if seconds.is_finite() && (0.0..=1e9).contains(&seconds) {
        Ok(seconds)
    } else {
        // As written: `1e308` rather than all its 309 digits.
        Err(format!("{text} is out of range: allowed 0 ..= 1000000000"))
    }
}

/// The longest clip, in simulated seconds: an hour.
pub const MAX_CLIP_SECONDS: f64 = 3600.0;

/// The longest bound on a wait for the GPU: a day.
pub const MAX_GPU_TIMEOUT_SECONDS: f64 = 86_400.0;

/// A number of seconds more than nothing and at most `most`.
fn parse_positive_seconds(text: &str, most: f64) -> Result<f64, String> {
    let seconds: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    if seconds.is_finite() && seconds > 0.0 && seconds <= most {
        Ok(seconds)
    } else {
        Err(format!(
            "{text} is out of range: allowed more than 0, at most {most}"
        ))
    }
}

/// The length of a clip: more than nothing, at most an hour.
fn parse_clip_seconds(text: &str) -> Result<f64, String> {
    parse_positive_seconds(text, MAX_CLIP_SECONDS)
}

/// The bound on every wait for the GPU: more than nothing, at most a day.
fn parse_gpu_timeout(text: &str) -> Result<Duration, String> {
    parse_positive_seconds(text, MAX_GPU_TIMEOUT_SECONDS).map(Duration::from_secs_f64)
}

pub use rolypoly_core::steps_for;

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn scene_options_go_before_or_after_the_subcommand() {
        let cli =
            Cli::try_parse_from(["rolypoly", "--seed", "7", "simulate", "--steps", "3"]).unwrap();
        assert_eq!(cli.scene.seed, 7);
        let cli =
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "3", "--seed", "8"]).unwrap();
        assert_eq!(cli.scene.seed, 8);
    }

    #[test]
    fn steps_and_seconds_are_exclusive_and_one_is_required() {
        assert!(Cli::try_parse_from(["rolypoly", "simulate"]).is_err());
        assert!(
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "3", "--seconds", "1"])
                .is_err()
        );
        assert!(Cli::try_parse_from(["rolypoly", "simulate", "--seconds", "-1"]).is_err());
        assert!(
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "1", "--every", "0"]).is_err()
        );
    }

    #[test]
    fn a_number_out_of_range_is_named_as_written() {
        assert_eq!(
            parse_seconds("1e308").unwrap_err(),
            "1e308 is out of range: allowed 0 ..= 1000000000"
        );
        assert_eq!(
            parse_look(" 1e300").unwrap_err(),
            "1e300 is out of range: allowed 0.01 ..= 5"
        );
        assert_eq!(
            parse_speed("0.05").unwrap_err(),
            "0.05 is out of range: allowed 0.1 ..= 50"
        );
    }

    #[test]
    fn a_target_frame_rate_is_more_than_nothing_and_at_most_a_thousand() {
        let cli = Cli::try_parse_from(["rolypoly", "--fps", "60"]).unwrap();
        assert_eq!(cli.window.fps, Some(60.0));
        assert_eq!(Cli::try_parse_from(["rolypoly"]).unwrap().window.fps, None);
        for bad in ["0", "-5", "1001", "fast", "NaN", "inf"] {
            let flag = format!("--fps={bad}");
            let error = Cli::try_parse_from(["rolypoly", flag.as_str()])
                .unwrap_err()
                .to_string();
            assert!(error.contains("is not a frame rate"), "{bad}: {error}");
        }
    }

    #[test]
    fn quality_levels_are_read_by_name_and_others_named_in_the_error() {
        let cli = Cli::try_parse_from(["rolypoly", "--quality", "low"]).unwrap();
        assert_eq!(cli.window.quality, QualityChoice::from_name("low"));
        let cli = Cli::try_parse_from([
            "rolypoly",
            "render",
            "--out",
            "a.png",
            "--quality",
            "medium",
        ])
        .unwrap();
        let Some(Command::Render(args)) = cli.command else {
            panic!("render")
        };
        assert_eq!(args.frame.quality, QualityChoice::from_name("medium"));
        assert_eq!(args.frame.msaa, None);
        let error = parse_quality("ultra").unwrap_err();
        assert!(
            error.contains("ultra") && error.contains("high, medium, low, auto"),
            "{error}"
        );
    }

    /// `--scale` takes a share from the window's least scale up to 1, and
    /// `--temporal` takes the place of `--msaa`; the window's two temporal
    /// flags exclude each other, and neither leaves the adapter's default.
    #[test]
    fn scales_and_the_temporal_path_are_checked() {
        let render = |extra: &[&str]| {
            let mut args = vec!["rolypoly", "render", "--out", "a.png"];
            args.extend_from_slice(extra);
            Cli::try_parse_from(args)
        };
        let cli = render(&["--scale", "0.5", "--temporal"]).unwrap();
        let Some(Command::Render(args)) = cli.command else {
            panic!("render")
        };
        assert_eq!((args.frame.scale, args.frame.temporal), (Some(0.5), true));
        for bad in ["0.2", "1.5", "0", "half", "NaN"] {
            let error = render(&["--scale", bad]).unwrap_err().to_string();
            assert!(error.contains("is not a render scale"), "{bad}: {error}");
        }
        let error = render(&["--temporal", "--msaa", "4"])
            .unwrap_err()
            .to_string();
        assert!(error.contains("cannot be used with"), "{error}");
        assert!(Cli::try_parse_from(["rolypoly", "--temporal", "--no-temporal"]).is_err());
        let window = |args: &[&str]| {
            Cli::try_parse_from(args)
                .unwrap()
                .window
                .options(1, None)
                .temporal
        };
        assert_eq!(window(&["rolypoly"]), None);
        assert_eq!(window(&["rolypoly", "--temporal"]), Some(true));
        assert_eq!(window(&["rolypoly", "--no-temporal"]), Some(false));
    }

    #[test]
    fn seconds_round_to_steps() {
        assert_eq!(steps_for(10.0, 1.0 / 120.0), 1200);
        assert_eq!(steps_for(0.0, 1.0 / 120.0), 0);
    }
}
