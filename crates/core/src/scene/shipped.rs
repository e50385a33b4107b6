//! The scenes that ship in `scenes/`, built into the binary so that the
//! window's scene list works wherever the program is run from.

/// A shipped scene: its file name and text.
#[derive(Clone, Copy, Debug)]
pub struct ShippedScene {
    /// Its file name in `scenes/`.
    pub name: &'static str,
    /// Its file's text.
    pub text: &'static str,
}

macro_rules! shipped {
    ($($name:literal),* $(,)?) => {
        [$(ShippedScene {
            name: $name,
            text: include_str!(concat!("../../../../scenes/", $name)),
        }),*]
    };
}

/// Every file in `scenes/`, the default first (a test checks that none is
/// missing).
pub const SHIPPED_SCENES: [ShippedScene; 10] = shipped![
    "default.toml",
    "newtons-cradle.toml",
    "billiards-break.toml",
    "unequal-masses.toml",
    "elastic-gas.toml",
    "tumbler-crowd.toml",
    "heap.toml",
    "ballpit-10k.toml",
    "ballpit-100k.toml",
    "ballpit-1m.toml",
];

impl ShippedScene {
    /// The first line of its header comment, without the `#`: what it shows.
    pub fn summary(&self) -> &'static str {
        self.text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix('#'))
            .map_or("", str::trim)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_in_scenes_is_shipped_and_loads() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        files.sort();
        let mut shipped: Vec<String> = SHIPPED_SCENES.iter().map(|s| s.name.to_owned()).collect();
        shipped.sort();
        assert_eq!(shipped, files);
        for scene in SHIPPED_SCENES {
            crate::scene::parse_scene(scene.text, scene.name).unwrap();
            assert!(!scene.summary().is_empty(), "{}", scene.name);
        }
    }
}
