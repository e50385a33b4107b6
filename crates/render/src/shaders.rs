//! The renderer's WGSL shaders, in one place: each file's name, its source
//! (built into the program) and what it draws. The passes take their
//! sources from a [`ShaderSet`]: the shipped ones, or a folder's, checked
//! by naga (wgpu's own front end and validator) before any pipeline is
//! made of them. `rolypoly shaders --export DIR` writes them out, with a
//! README naming what each draws, for reading and editing.

use std::io;
use std::path::{Path, PathBuf};

/// One shipped shader file.
#[derive(Clone, Copy, Debug)]
pub struct ShaderFile {
    /// Its file name, as exported (`scene.wgsl`).
    pub name: &'static str,
    /// Its source.
    pub source: &'static str,
    /// What it draws, a line.
    pub draws: &'static str,
}

/// The lit scene: Blinn-Phong from the point lights, the shadow cube's
/// lookups, the balls traced on squares, the bulb, the shadow faces.
pub const SCENE: ShaderFile = ShaderFile {
    name: "scene.wgsl",
    source: include_str!("../shaders/scene.wgsl"),
    draws: "the lit scene (room, tumblers, balls traced on squares, the bulb): Blinn-Phong's ambient, diffuse and specular terms from the point lights, the shadow cube's filtered lookups, the bounce light; and the six depth faces of the shadow cube",
};

/// The vertex shader put in front of every pass over whole images.
pub const SCREEN: ShaderFile = ShaderFile {
    name: "screen.wgsl",
    source: include_str!("../shaders/screen.wgsl"),
    draws: "one triangle over the whole target: the vertex shader put in front of occlusion.wgsl, bloom.wgsl, tonemap.wgsl, upscale.wgsl and taa.wgsl",
};

/// Contact occlusion.
pub const OCCLUSION: ShaderFile = ShaderFile {
    name: "occlusion.wgsl",
    source: include_str!("../shaders/occlusion.wgsl"),
    draws: "the contact darkening: how much of the sky above each visible point what lies close around it hides (screen-space ambient occlusion), and its blur",
};

/// The bloom chain.
pub const BLOOM: ShaderFile = ShaderFile {
    name: "bloom.wgsl",
    source: include_str!("../shaders/bloom.wgsl"),
    draws: "the bloom: the bright pass, then the chain of half-size images filtered down and back up",
};

/// Tone mapping.
pub const TONEMAP: ShaderFile = ShaderFile {
    name: "tonemap.wgsl",
    source: include_str!("../shaders/tonemap.wgsl"),
    draws: "from the HDR frame to the screen: the occlusion's darkening, the bloom's glow, exposure and the filmic curve",
};

/// The upscale to the output's size.
pub const UPSCALE: ShaderFile = ShaderFile {
    name: "upscale.wgsl",
    source: include_str!("../shaders/upscale.wgsl"),
    draws: "the frame lit at a lower resolution spread over the output's pixels (bilinear)",
};

/// Temporal anti-aliasing with upsampling.
pub const TAA: ShaderFile = ShaderFile {
    name: "taa.wgsl",
    source: include_str!("../shaders/taa.wgsl"),
    draws: "the temporal path: each texel's neighbourhood, the history resolved with this frame, and the sharpened output",
};

/// The debug views' marks.
pub const DEBUG_MARKS: ShaderFile = ShaderFile {
    name: "debug_marks.wgsl",
    source: include_str!("../shaders/debug_marks.wgsl"),
    draws: "the debug views' marks over the finished frame: lines, dots, arrows and spikes, faint where a body hides them",
};

/// Grab mode's cursor.
pub const CURSOR: ShaderFile = ShaderFile {
    name: "cursor.wgsl",
    source: include_str!("../shaders/cursor.wgsl"),
    draws: "grab mode's arrow cursor over the finished frame",
};

/// The views of the frame drawn by a pass of their own.
pub const FRAME_VIEWS: ShaderFile = ShaderFile {
    name: "frame_views.wgsl",
    source: include_str!("../shaders/frame_views.wgsl"),
    draws: "the frame's views with a pass of their own: the shadow cube unfolded, the pixels whose multisamples disagree, the temporal history's weight",
};

/// Every shipped shader, in the order a frame uses them.
pub const SHIPPED: [ShaderFile; 10] = [
    SCENE,
    SCREEN,
    OCCLUSION,
    BLOOM,
    TONEMAP,
    UPSCALE,
    TAA,
    DEBUG_MARKS,
    CURSOR,
    FRAME_VIEWS,
];

/// The README written beside the exported files.
pub const EXPORT_README: &str = "README.md";

/// Why the shaders could not be exported: names the file.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The folder could not be made, or a file written.
    #[error("cannot write `{path}`")]
    Write {
        /// The folder or file.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// The folder's own folder is not there.
    #[error("cannot make `{dir}`: the folder `{parent}` does not exist")]
    NoParent {
        /// The folder asked for.
        dir: PathBuf,
        /// Its parent.
        parent: PathBuf,
    },
    /// A file of that name is there and is not the shipped one: an edit
    /// that the export would lose.
    #[error(
        "`{path}` is there and differs from the shipped one (an edit?): export into another folder, or move it away first"
    )]
    WouldOverwrite {
        /// The file.
        path: PathBuf,
    },
}

/// The README of an export: what each file draws.
pub fn export_readme() -> String {
    let mut text = String::from(
        "# The renderer's shaders\n\nThe WGSL files the renderer draws every frame with, as shipped. Each:\n\n",
    );
    for file in SHIPPED {
        text.push_str(&format!("- `{}`: {}.\n", file.name, file.draws));
    }
    text.push_str(
        "\nThe GPU physics engine's compute shaders are not among them: they step the balls, not the picture.\n",
    );
    text
}

/// Writes every shipped shader and the README into `dir`, made if need be
/// (its parent must be there). A file already there is left as it is if
/// it is the shipped one, and refused if it differs, before anything is
/// written: nothing edited is lost. Returns the files written.
pub fn export(dir: &Path) -> Result<Vec<PathBuf>, ExportError> {
    let readme = export_readme();
    let files: Vec<(PathBuf, &str)> = SHIPPED
        .iter()
        .map(|f| (dir.join(f.name), f.source))
        .chain([(dir.join(EXPORT_README), readme.as_str())])
        .collect();
    for (path, text) in &files {
        match std::fs::read(path) {
            Ok(there) if there != text.as_bytes() => {
                return Err(ExportError::WouldOverwrite { path: path.clone() });
            }
            _ => {}
        }
    }
    if !dir.is_dir() {
        let parent = dir.parent().filter(|p| !p.as_os_str().is_empty());
        if let Some(parent) = parent.filter(|p| !p.is_dir()) {
            return Err(ExportError::NoParent {
                dir: dir.to_path_buf(),
                parent: parent.to_path_buf(),
            });
        }
        std::fs::create_dir(dir).map_err(|source| ExportError::Write {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    for (path, text) in &files {
        std::fs::write(path, text).map_err(|source| ExportError::Write {
            path: path.clone(),
            source,
        })?;
    }
    Ok(files.into_iter().map(|(path, _)| path).collect())
}

/// The shaders a renderer draws with: the shipped ones, or those of a
/// folder (`--shaders DIR`), one source for each of [`SHIPPED`].
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderSet {
    sources: Vec<String>,
}

/// Why a folder's shaders cannot be drawn with: names the folder or file.
#[derive(Debug, thiserror::Error)]
pub enum ShaderError {
    /// The folder is not there.
    #[error(
        "--shaders `{dir}`: no such folder (`shaders --export DIR` writes the shipped ones into one)"
    )]
    NoFolder {
        /// The folder.
        dir: PathBuf,
    },
    /// A file is missing or cannot be read.
    #[error(
        "cannot read the shader `{path}` (the folder needs every file `shaders --export` writes)"
    )]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// A file is not WGSL that wgpu would take.
    #[error("{path}:{line}:{column}: {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// Its line, from 1.
        line: u32,
        /// Its column, from 1.
        column: u32,
        /// naga's message.
        message: String,
    },
}

impl ShaderSet {
    /// The shaders built into the program.
    pub fn shipped() -> ShaderSet {
        ShaderSet {
            sources: SHIPPED.iter().map(|f| f.source.to_owned()).collect(),
        }
    }

    /// The shaders of `dir`, a file for each of [`SHIPPED`], each parsed
    /// and validated as wgpu does: the first that fails is named, with its
    /// line and column.
    pub fn load(dir: &Path) -> Result<ShaderSet, ShaderError> {
        if !dir.is_dir() {
            return Err(ShaderError::NoFolder {
                dir: dir.to_path_buf(),
            });
        }
        let mut sources = Vec::with_capacity(SHIPPED.len());
        for file in SHIPPED {
            let path = dir.join(file.name);
            let source = std::fs::read_to_string(&path)
                .map_err(|source| ShaderError::Unreadable { path, source })?;
            sources.push(source);
        }
        let set = ShaderSet { sources };
        let screen = set.source(&SCREEN);
        for file in SHIPPED {
            // A pass over whole images is compiled after screen.wgsl.
            let prelude = if SCREEN_PASSES.iter().any(|p| p.name == file.name) {
                screen
            } else {
                ""
            };
            check(&dir.join(file.name), set.source(&file), prelude)?;
        }
        Ok(set)
    }

    /// The source of `file`.
    pub fn source(&self, file: &ShaderFile) -> &str {
        let k = SHIPPED
            .iter()
            .position(|f| f.name == file.name)
            .expect("a shipped shader");
        &self.sources[k]
    }

    /// The source of a pass over whole images: screen.wgsl, then `file`.
    pub fn screen_pass(&self, file: &ShaderFile) -> String {
        screen_pass(self.source(&SCREEN), self.source(file))
    }
}

/// The passes over whole images, compiled after screen.wgsl.
const SCREEN_PASSES: [ShaderFile; 6] = [OCCLUSION, BLOOM, TONEMAP, UPSCALE, TAA, FRAME_VIEWS];

/// `source` after the shared vertex shader `screen`.
fn screen_pass(screen: &str, source: &str) -> String {
    format!("{screen}\n{source}")
}

/// Parses and validates `source` (of the file at `path`) as wgpu does,
/// after `prelude` where it is compiled after one; a place in the prelude
/// is named as screen.wgsl's.
fn check(path: &Path, source: &str, prelude: &str) -> Result<(), ShaderError> {
    let whole = if prelude.is_empty() {
        source.to_owned()
    } else {
        screen_pass(prelude, source)
    };
    // The lines before the file's own in what is compiled.
    let before = if prelude.is_empty() {
        0
    } else {
        prelude.matches('\n').count() as u32 + 1
    };
    let invalid = |location: Option<naga::SourceLocation>, message: String| {
        let (line, column) = location.map_or((1, 1), |l| (l.line_number, l.line_position));
        let (path, line) = if line > before {
            (path.to_path_buf(), line - before)
        } else {
            (path.with_file_name(SCREEN.name), line)
        };
        ShaderError::Invalid {
            path,
            line,
            column,
            message,
        }
    };
    let module = naga::front::wgsl::parse_str(&whole)
        .map_err(|e| invalid(e.location(&whole), e.message().to_owned()))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| invalid(e.location(&whole), e.as_inner().to_string()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_wgsl_file_of_the_renderer_is_shipped_once_and_named_by_its_file() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".wgsl"))
            .collect();
        on_disk.sort();
        let mut shipped: Vec<String> = SHIPPED.iter().map(|f| f.name.to_owned()).collect();
        shipped.sort();
        assert_eq!(shipped, on_disk);
        for file in SHIPPED {
            let source = std::fs::read_to_string(folder.join(file.name)).unwrap();
            assert_eq!(file.source, source, "{}", file.name);
            assert!(export_readme().contains(&format!("`{}`", file.name)));
        }
    }

    #[test]
    fn a_folder_of_the_exported_shaders_is_the_shipped_set_and_a_broken_file_is_named_by_line() {
        let dir = std::env::temp_dir().join(format!("rolypoly-load-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        export(&dir).unwrap();
        assert_eq!(ShaderSet::load(&dir).unwrap(), ShaderSet::shipped());
        // A mistake on the fourth line of a pass after screen.wgsl: its own
        // line, not the compiled whole's.
        let mut lines: Vec<&str> = TONEMAP.source.lines().collect();
        lines.insert(3, "let = oops;");
        std::fs::write(dir.join(TONEMAP.name), lines.join("\n")).unwrap();
        let error = ShaderSet::load(&dir).unwrap_err();
        let ShaderError::Invalid {
            path, line, column, ..
        } = &error
        else {
            panic!("{error}");
        };
        assert_eq!(path, &dir.join("tonemap.wgsl"));
        assert_eq!((*line, *column), (4, 1), "{error}");
        // A type error, found by validation rather than parsing.
        std::fs::write(dir.join(TONEMAP.name), TONEMAP.source).unwrap();
        let scene = SCENE.source.replacen(
            "fn ",
            "fn broken() -> f32 { return vec3<f32>(1.0); }\nfn ",
            1,
        );
        std::fs::write(dir.join(SCENE.name), &scene).unwrap();
        let error = ShaderSet::load(&dir).unwrap_err().to_string();
        assert!(error.contains("scene.wgsl:"), "{error}");
        // A file missing, and no folder at all.
        std::fs::remove_file(dir.join(CURSOR.name)).unwrap();
        let error = ShaderSet::load(&dir).unwrap_err().to_string();
        assert!(error.contains("cursor.wgsl"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
        let error = ShaderSet::load(&dir).unwrap_err().to_string();
        assert!(error.contains("no such folder"), "{error}");
    }

    #[test]
    fn an_export_writes_every_file_again_unchanged_and_refuses_to_lose_an_edit() {
        let dir = std::env::temp_dir().join(format!("rolypoly-shaders-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let written = export(&dir).unwrap();
        assert_eq!(written.len(), SHIPPED.len() + 1);
        for file in SHIPPED {
            assert_eq!(
                std::fs::read_to_string(dir.join(file.name)).unwrap(),
                file.source
            );
        }
        // Again into the same folder: the same files, nothing refused.
        export(&dir).unwrap();
        // An edited file is kept, and named.
        let edited = dir.join(SCENE.name);
        std::fs::write(&edited, "// my own\n").unwrap();
        let error = export(&dir).unwrap_err();
        assert!(error.to_string().contains("scene.wgsl"), "{error}");
        assert_eq!(std::fs::read_to_string(&edited).unwrap(), "// my own\n");
        std::fs::remove_dir_all(&dir).unwrap();
        // A folder in a folder that is not there: one error naming it.
        let lost = dir.join("no").join("such");
        let error = export(&lost).unwrap_err().to_string();
        assert!(
            error.contains("does not exist") && error.contains("no"),
            "{error}"
        );
        assert!(!dir.exists());
    }
}
