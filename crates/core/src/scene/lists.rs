//! The keys that hold lists: their entries' schema, read with serde, and
//! how they are laid over the scene. Inside a list entry every key is
//! required unless said otherwise: a half-given sphere or placement makes
//! no sense.

use glam::DVec3;
use rolypoly_physics::{BallPlacement, SphereSpec, TumblerPlacement};
use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeValue, ValueDeserializer};

use super::keys::List;
use super::read::Reader;
use super::{Scene, SceneError};

type Vec3 = [f64; 3];

/// One `[[balls.placement]]`: a position is required; a ball left without
/// a velocity starts at rest.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileBallPlacement {
    position: Spanned<Vec3>,
    velocity: Option<Spanned<Vec3>>,
    spin: Option<Spanned<Vec3>>,
    color: Option<Spanned<Vec3>>,
    radius: Option<Spanned<f64>>,
    mass: Option<Spanned<f64>>,
}

/// One of `tumblers.spheres`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSphere {
    height: Spanned<f64>,
    radius: Spanned<f64>,
    mass: Spanned<f64>,
}

/// One `[[tumblers.placement]]`: upright about x unless tilted.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileTumblerPlacement {
    x: Spanned<f64>,
    z: Spanned<f64>,
    tilt_axis: Option<Spanned<Vec3>>,
    tilt_deg: Option<Spanned<f64>>,
}

fn rgb(c: Vec3) -> rolypoly_physics::Rgb {
    c.map(|x| x as f32)
}

impl Reader<'_> {
    /// The list `name` from `value`, replacing the scene's list whole.
    pub(super) fn list(
        &mut self,
        list: List,
        name: &str,
        value: &Spanned<DeValue>,
        scene: &mut Scene,
    ) -> Result<(), SceneError> {
        self.note(name, value.span());
        let world = &mut scene.world;
        match list {
            List::BallPlacements => {
                let entries: Vec<FileBallPlacement> = self.entries(name, value)?;
                world.balls.placements = entries
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| self.ball_placement(&format!("{name}[{i}]"), p))
                    .collect();
            }
            List::TumblerColors => {
                let colors: Vec<Spanned<Vec3>> = self.entries(name, value)?;
                world.tumblers.colors = colors
                    .into_iter()
                    .enumerate()
                    .map(|(i, color)| {
                        self.note(&format!("{name}[{i}]"), color.span());
                        rgb(color.into_inner())
                    })
                    .collect();
            }
            List::TumblerSpheres => {
                let spheres: Vec<FileSphere> = self.entries(name, value)?;
                world.tumblers.spheres = spheres
                    .into_iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let key = format!("{name}[{i}]");
                        self.note(&key, s.height.span());
                        SphereSpec {
                            height: self.take(&format!("{key}.height"), s.height),
                            radius: self.take(&format!("{key}.radius"), s.radius),
                            mass: self.take(&format!("{key}.mass"), s.mass),
                        }
                    })
                    .collect();
            }
            List::TumblerPlacements => {
                let entries: Vec<FileTumblerPlacement> = self.entries(name, value)?;
                world.tumblers.placements = entries
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| self.tumbler_placement(&format!("{name}[{i}]"), p))
                    .collect();
            }
        }
        Ok(())
    }

    /// The entries of the list `name`, each read by its schema.
    fn entries<T: for<'de> Deserialize<'de>>(
        &self,
        name: &str,
        value: &Spanned<DeValue>,
    ) -> Result<Vec<T>, SceneError> {
        Vec::<T>::deserialize(ValueDeserializer::from(value.clone()))
            .map_err(|e| self.syntax(&e, Some(name)))
    }

    /// A value of a list entry, its line and text noted under `key`.
    fn take<T>(&mut self, key: &str, value: Spanned<T>) -> T {
        self.note_written(key, value.span());
        value.into_inner()
    }

    /// [`Self::take`] for a key an entry may leave out.
    fn take_or<T>(&mut self, key: &str, value: Option<Spanned<T>>, default: T) -> T {
        value.map_or(default, |v| self.take(key, v))
    }

    fn ball_placement(&mut self, key: &str, p: FileBallPlacement) -> BallPlacement {
        self.note(key, p.position.span());
        let at = |name: &str| format!("{key}.{name}");
        let position = DVec3::from_array(self.take(&at("position"), p.position));
        let velocity = DVec3::from_array(self.take_or(&at("velocity"), p.velocity, [0.0; 3]));
        let mut placement = BallPlacement::new(position, velocity);
        placement.spin = DVec3::from_array(self.take_or(&at("spin"), p.spin, [0.0; 3]));
        placement.color = p.color.map(|c| rgb(self.take(&at("color"), c)));
        placement.radius = p.radius.map(|r| self.take(&at("radius"), r));
        placement.mass = p.mass.map(|m| self.take(&at("mass"), m));
        placement
    }

    fn tumbler_placement(&mut self, key: &str, p: FileTumblerPlacement) -> TumblerPlacement {
        self.note(key, p.x.span());
        let at = |name: &str| format!("{key}.{name}");
        TumblerPlacement {
            x: self.take(&at("x"), p.x),
            z: self.take(&at("z"), p.z),
            tilt_axis: DVec3::from_array(self.take_or(
                &at("tilt_axis"),
                p.tilt_axis,
                [1.0, 0.0, 0.0],
            )),
            tilt_deg: self.take_or(&at("tilt_deg"), p.tilt_deg, 0.0),
        }
    }
}
