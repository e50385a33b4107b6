//! Which engine steps the balls: the CPU engine (the reference) or the GPU
//! engine (`rolypoly-gpu`), chosen per run by `solver.engine` or
//! `--engine`.

/// The engine that steps the balls.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// The CPU engine, which every analytic check is held to.
    #[default]
    Cpu,
    /// The GPU engine: compute shaders on the graphics adapter.
    Gpu,
}

impl Engine {
    /// The names a scene file and the command line use, in order.
    pub const NAMES: [&'static str; 2] = ["cpu", "gpu"];

    /// Its name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The engine named `name`, if any.
    pub fn from_name(name: &str) -> Option<Engine> {
        match name {
            "cpu" => Some(Engine::Cpu),
            "gpu" => Some(Engine::Gpu),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_engine_is_read_back_by_its_name() {
        for engine in [Engine::Cpu, Engine::Gpu] {
            assert_eq!(Engine::from_name(engine.name()), Some(engine));
        }
        assert_eq!(Engine::from_name("GPU"), None);
    }
}
