//! The polar engines a user chooses between: XFOIL, NeuralFoil, or XFOIL with NeuralFoil
//! filling what it leaves out.

/// Which program makes the polars.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Engine {
    /// XFOIL.
    #[default]
    Xfoil,
    /// NeuralFoil's networks.
    NeuralFoil,
    /// XFOIL, with what it leaves out (unconverged angles, polars it could not make) from
    /// NeuralFoil.
    Auto,
}

impl Engine {
    /// Every engine.
    pub const ALL: [Engine; 3] = [Engine::Xfoil, Engine::NeuralFoil, Engine::Auto];

    /// The name the command line and a case use.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Xfoil => "xfoil",
            Engine::NeuralFoil => "neuralfoil",
            Engine::Auto => "auto",
        }
    }

    /// The engine of a name.
    pub fn parse(name: &str) -> Option<Engine> {
        Engine::ALL.into_iter().find(|e| e.name() == name)
    }
}
