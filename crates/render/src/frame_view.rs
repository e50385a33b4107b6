//! The views of the frame's own passes: what the renderer draws over the
//! whole output instead of the finished picture, to show one pass or one
//! term of the light alone (as engines that teach show their buffers).
//!
//! Each view is drawn by one of three places, the fewest passes it needs:
//! the scene shader writes a term or a surface's property in place of its
//! lit colour (`frame_view` in scene.wgsl), tone mapping shows that as data
//! or in its own curve, or reads the occlusion or the bloom's chain
//! (tonemap.wgsl), and one extra pass draws what lies in no frame target
//! of its own (frame_views.wgsl: the shadow cube, the multisampled edges,
//! the temporal history).

use crate::view::Light;

/// A view of the frame: the finished picture, or one of its passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FrameView {
    /// The frame as it is shown.
    #[default]
    Final,
    /// The surfaces' colour and texture before any light.
    Albedo,
    /// World normals, encoded as n / 2 + 1/2.
    Normals,
    /// Linear distance from the camera, near white to far black.
    Depth,
    /// The light's six depth faces, unfolded as a cross.
    ShadowCube,
    /// The share of the ceiling light that reaches each pixel.
    Shadow,
    /// Blinn-Phong's ambient term alone.
    Ambient,
    /// Blinn-Phong's diffuse term alone (both lights, shadowed).
    Diffuse,
    /// Blinn-Phong's specular term alone (both lights, shadowed).
    Specular,
    /// The light bounced once off the room's surfaces, alone.
    Bounce,
    /// The contact darkening's factor.
    Occlusion,
    /// The bloom's chain of glow images.
    Bloom,
    /// How far each surface moved on screen since the last frame.
    Motion,
    /// How much of the temporal path's history each pixel keeps.
    History,
    /// The pixels whose multisamples disagree.
    MsaaEdges,
}

/// Where a view's pixels come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Drawn {
    /// The finished frame.
    Final,
    /// The scene shader writes mode `code` (scene.wgsl's `VIEW_*`) and tone
    /// mapping shows it as `finish`.
    Scene { code: u32, finish: Finish },
    /// Tone mapping shows one of its inputs (tonemap.wgsl's `SHOW_*`).
    Tonemap(Finish),
    /// The extra pass draws it over the frame (frame_views.wgsl).
    Extra,
}

/// The constants a view builds the pipelines with: what the scene shader
/// writes (scene.wgsl's `FRAME_VIEW`: 0 the lit colour, else a pass's
/// `VIEW_*`) and how tone mapping shows it (tonemap.wgsl's `SHOW`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ViewCodes {
    pub scene: u32,
    pub show: u32,
}

impl ViewCodes {
    /// The finished frame's: the lit colour, tone-mapped as the frame.
    pub const FINAL: ViewCodes = ViewCodes {
        scene: 0,
        show: Finish::Frame as u32,
    };
}

/// How tone mapping shows what it reads (tonemap.wgsl's `SHOW_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Finish {
    /// As the frame: occlusion, glow, exposure and the filmic curve.
    Frame = 0,
    /// As data: each value written as the picture's value, unchanged.
    Data = 1,
    /// Exposure and the filmic curve, without occlusion or glow.
    Curve = 2,
    /// The occlusion's factor as grey.
    Occlusion = 3,
    /// The bloom chain's levels side by side.
    Bloom = 4,
}

/// Above this many pixels of motion a frame the motion view is at full
/// brightness (scene.wgsl's `motion_color` reads it from the globals).
pub const MOTION_FULL_PIXELS: f32 = 16.0;

/// Where each of the light's six faces (+X, -X, +Y, -Y, +Z, -Z) lies in
/// the shadow cube's unfolded cross, four faces wide and three high:
/// (column, row) from the top left.
pub const SHADOW_CROSS: [(u32, u32); 6] = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];

/// What a caption needs to know of the frame beside the view.
#[derive(Clone, Copy, Debug)]
pub struct FrameFacts {
    /// Samples a pixel that can be read (1: no multisampling, or samples
    /// the adapter cannot read).
    pub msaa: u32,
    /// Whether the light casts shadows.
    pub shadows: bool,
    /// Whether the frame takes the temporal path.
    pub temporal: bool,
    /// Whether the glow is on.
    pub bloom: bool,
    /// Whether the contact darkening is on.
    pub occlusion: bool,
    /// Whether the bounce light is on.
    pub bounce: bool,
    /// The depth view's range: white at the first distance, black at the
    /// second (m).
    pub depth_range: (f32, f32),
}

impl FrameFacts {
    /// The facts of a frame drawn with `msaa`, `shadows` and `temporal`,
    /// lighting as `light` says, its depth running to `farthest`.
    pub fn new(msaa: u32, shadows: bool, temporal: bool, light: &Light, farthest: f32) -> Self {
        FrameFacts {
            msaa,
            shadows,
            temporal,
            bloom: light.bloom.is_some(),
            occlusion: light.occlusion,
            bounce: light.indirect,
            depth_range: (0.0, farthest),
        }
    }
}

/// A name that is no view's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownView(pub String);

impl std::fmt::Display for UnknownView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<_> = FrameView::ALL.iter().map(|v| v.name()).collect();
        write!(
            f,
            "no frame view is called '{}'; the views are: {}",
            self.0,
            names.join(", ")
        )
    }
}

impl std::error::Error for UnknownView {}

impl std::str::FromStr for FrameView {
    type Err = UnknownView;

    fn from_str(name: &str) -> Result<FrameView, UnknownView> {
        FrameView::ALL
            .iter()
            .copied()
            .find(|v| v.name() == name)
            .ok_or_else(|| UnknownView(name.to_string()))
    }
}

impl std::fmt::Display for FrameView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FrameView {
    /// Every view, in the order V steps through them.
    pub const ALL: [FrameView; 15] = [
        FrameView::Final,
        FrameView::Albedo,
        FrameView::Normals,
        FrameView::Depth,
        FrameView::ShadowCube,
        FrameView::Shadow,
        FrameView::Ambient,
        FrameView::Diffuse,
        FrameView::Specular,
        FrameView::Bounce,
        FrameView::Occlusion,
        FrameView::Bloom,
        FrameView::Motion,
        FrameView::History,
        FrameView::MsaaEdges,
    ];

    /// The name flags and keys know it by.
    pub fn name(self) -> &'static str {
        match self {
            FrameView::Final => "final",
            FrameView::Albedo => "albedo",
            FrameView::Normals => "normals",
            FrameView::Depth => "depth",
            FrameView::ShadowCube => "shadow-cube",
            FrameView::Shadow => "shadow",
            FrameView::Ambient => "ambient",
            FrameView::Diffuse => "diffuse",
            FrameView::Specular => "specular",
            FrameView::Bounce => "bounce",
            FrameView::Occlusion => "occlusion",
            FrameView::Bloom => "bloom",
            FrameView::Motion => "motion",
            FrameView::History => "history",
            FrameView::MsaaEdges => "msaa-edges",
        }
    }

    /// A line on what it shows and what its colours mean.
    pub fn about(self) -> &'static str {
        match self {
            FrameView::Final => "the frame as it is shown",
            FrameView::Albedo => "the surfaces' colour and texture before any light",
            FrameView::Normals => "world normals as colour, n / 2 + 1/2: +x red, +y green, +z blue",
            FrameView::Depth => "distance from the camera, near white to far black",
            FrameView::ShadowCube => {
                "the light's six depth faces as an unfolded cross, near dark to far light"
            }
            FrameView::Shadow => {
                "the share of the ceiling light reaching each pixel, as the shadow filter gives it: white lit, black in shadow"
            }
            FrameView::Ambient => {
                "Blinn-Phong's ambient term alone, the even light in the surface's colour"
            }
            FrameView::Diffuse => "Blinn-Phong's diffuse term alone, base * max(n.l, 0), shadowed",
            FrameView::Specular => "Blinn-Phong's specular term alone, k * max(n.h, 0)^s, shadowed",
            FrameView::Bounce => "the light bounced once off the room's surfaces, alone",
            FrameView::Occlusion => {
                "the contact darkening's factor: white open, darker where surfaces meet"
            }
            FrameView::Bloom => {
                "the bloom chain's glow images: the largest on the left, each smaller one on the right"
            }
            FrameView::Motion => {
                "each surface's motion on screen since the last frame: hue for direction, brightness for length"
            }
            FrameView::History => {
                "the temporal path's weight of history per pixel: black none, white settled"
            }
            FrameView::MsaaEdges => "the pixels whose multisamples disagree, in white",
        }
    }

    /// The view after this one (V), round to the first.
    pub fn next(self) -> FrameView {
        let at = FrameView::ALL.iter().position(|&v| v == self).unwrap_or(0);
        FrameView::ALL[(at + 1) % FrameView::ALL.len()]
    }

    /// The view before this one (Shift+V), round to the last.
    pub fn previous(self) -> FrameView {
        let at = FrameView::ALL.iter().position(|&v| v == self).unwrap_or(0);
        FrameView::ALL[(at + FrameView::ALL.len() - 1) % FrameView::ALL.len()]
    }

    /// Every name with its line, one a line (`render --view list`).
    pub fn list() -> String {
        FrameView::ALL
            .iter()
            .map(|v| format!("{:<12} {}\n", v.name(), v.about()))
            .collect()
    }

    /// Why the view shows nothing in a frame of `facts`, where a level or a
    /// flag turned its pass off.
    pub fn missing(self, facts: &FrameFacts) -> Option<&'static str> {
        match self {
            FrameView::ShadowCube | FrameView::Shadow if !facts.shadows => {
                Some("shadows are off (--no-shadows or the level): no shadow faces are drawn")
            }
            FrameView::Bounce if !facts.bounce => {
                Some("the bounce light is off (--no-bounce or the level)")
            }
            FrameView::Occlusion if !facts.occlusion => {
                Some("the contact darkening is off (--no-occlusion or the level)")
            }
            FrameView::Bloom if !facts.bloom => Some("the bloom is off (--no-bloom or the level)"),
            FrameView::History if !facts.temporal => {
                Some("the temporal path is off: there is no history (--temporal turns it on)")
            }
            FrameView::MsaaEdges if facts.msaa <= 1 => {
                Some("multisampling is off, or its samples cannot be read on this adapter (OpenGL)")
            }
            _ => None,
        }
    }

    /// The caption drawn with the view: its name, what its colours mean,
    /// and a scale where one applies, or why it is empty.
    pub fn caption(self, facts: &FrameFacts) -> String {
        let mut caption = format!("{}: {}", self.name(), self.about());
        match self {
            FrameView::Depth => {
                let (near, far) = facts.depth_range;
                caption += &format!(" (white {near:.1} m, black {far:.1} m)");
            }
            FrameView::Motion => {
                caption += &format!(
                    " (full brightness at {MOTION_FULL_PIXELS:.0} pixels a frame; black still)"
                );
            }
            FrameView::Ambient if facts.bounce => {
                caption += " (not in this frame: the bounce light takes its place)";
            }
            _ => {}
        }
        if let Some(why) = self.missing(facts) {
            caption += &format!(" - empty here: {why}");
        }
        caption
    }

    /// What the pipelines are built to draw for it: views of one code draw
    /// alike but for the pass over the frame that [`Drawn::Extra`] adds.
    pub(crate) fn codes(self) -> ViewCodes {
        match self.drawn() {
            Drawn::Scene { code, finish } => ViewCodes {
                scene: code,
                show: finish as u32,
            },
            Drawn::Tonemap(finish) => ViewCodes {
                scene: 0,
                show: finish as u32,
            },
            Drawn::Final | Drawn::Extra => ViewCodes::FINAL,
        }
    }

    /// Where its pixels come from.
    pub(crate) fn drawn(self) -> Drawn {
        let scene = |code, finish| Drawn::Scene { code, finish };
        match self {
            FrameView::Final => Drawn::Final,
            FrameView::Albedo => scene(1, Finish::Data),
            FrameView::Normals => scene(2, Finish::Data),
            FrameView::Depth => scene(3, Finish::Data),
            FrameView::Shadow => scene(4, Finish::Data),
            FrameView::Ambient => scene(5, Finish::Curve),
            FrameView::Diffuse => scene(6, Finish::Curve),
            FrameView::Specular => scene(7, Finish::Curve),
            FrameView::Bounce => scene(8, Finish::Curve),
            FrameView::Motion => scene(9, Finish::Data),
            FrameView::Occlusion => Drawn::Tonemap(Finish::Occlusion),
            FrameView::Bloom => Drawn::Tonemap(Finish::Bloom),
            FrameView::ShadowCube | FrameView::History | FrameView::MsaaEdges => Drawn::Extra,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_view_is_found_by_its_own_name_and_no_two_share_one() {
        for view in FrameView::ALL {
            assert_eq!(view.name().parse::<FrameView>(), Ok(view));
        }
        let mut names: Vec<_> = FrameView::ALL.iter().map(|v| v.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), FrameView::ALL.len());
    }

    #[test]
    fn an_unknown_name_is_refused_with_the_list() {
        let error = "nosuch".parse::<FrameView>().unwrap_err().to_string();
        assert!(error.contains("'nosuch'"), "{error}");
        for view in FrameView::ALL {
            assert!(error.contains(view.name()), "{error}");
        }
    }

    #[test]
    fn next_and_previous_walk_the_whole_list_and_undo_each_other() {
        let mut view = FrameView::Final;
        for _ in 0..FrameView::ALL.len() {
            assert_eq!(view.next().previous(), view);
            view = view.next();
        }
        assert_eq!(view, FrameView::Final);
        assert_eq!(FrameView::Final.previous(), FrameView::MsaaEdges);
    }

    #[test]
    fn a_view_whose_pass_is_off_says_so() {
        let facts = FrameFacts {
            msaa: 1,
            shadows: false,
            temporal: false,
            bloom: false,
            occlusion: false,
            bounce: false,
            depth_range: (0.0, 9.0),
        };
        for view in [
            FrameView::ShadowCube,
            FrameView::Shadow,
            FrameView::Bounce,
            FrameView::Occlusion,
            FrameView::Bloom,
            FrameView::History,
            FrameView::MsaaEdges,
        ] {
            assert!(view.caption(&facts).contains("empty here"), "{view}");
        }
        let on = FrameFacts {
            msaa: 4,
            shadows: true,
            temporal: true,
            bloom: true,
            occlusion: true,
            bounce: true,
            ..facts
        };
        for view in FrameView::ALL {
            assert!(!view.caption(&on).contains("empty here"), "{view}");
        }
        assert!(FrameView::Depth.caption(&facts).contains("9.0 m"));
    }
}
