//! The error of a command below the binary: the pipeline's, or of making and writing its
//! outputs. Each says what the user gave (a file, a folder, a value) and why, its cause in
//! its own message ("what was done: why"), as the pipeline's errors do.

/// An error of a command's run below the binary.
#[derive(Debug, thiserror::Error)]
pub enum CommandError {
    /// The pipeline's (reading inputs, a stage).
    #[error(transparent)]
    Pipeline(#[from] propbet_model::Error),
    /// A value or setting out of its range.
    #[error(transparent)]
    Settings(#[from] propbet_settings::Error),
    /// Drawing a figure.
    #[error(transparent)]
    Plot(#[from] propbet_plot::PlotError),
    /// Making a table.
    #[error(transparent)]
    Table(#[from] propbet_report::table::Error),
    /// Gathering a table's typed columns.
    #[error(transparent)]
    Columns(#[from] propbet_report::table::columns::Error),
    /// Making a CSV table.
    #[error(transparent)]
    Csv(#[from] csv::Error),
    /// Making a JSON document.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// A refusal or a failure in words (a folder another propbet writes, an input in the
    /// output folder, a value out of range).
    #[error("{0}")]
    Message(String),
    /// A file operation that failed, and what it was.
    #[error("{context}: {cause}")]
    Io {
        /// What was done, naming the file.
        context: String,
        /// The operating system's reason.
        cause: std::io::Error,
    },
    /// An error with what was being done when it happened.
    #[error("{context}: {cause}")]
    Context {
        /// What was being done.
        context: String,
        /// The error.
        cause: Box<CommandError>,
    },
}

impl From<propbet_settings::BadSetting> for CommandError {
    fn from(b: propbet_settings::BadSetting) -> Self {
        CommandError::Settings(b.into())
    }
}

impl CommandError {
    /// A failed file operation: `context` says what was done, naming the file.
    pub fn io(context: impl Into<String>, cause: std::io::Error) -> Self {
        CommandError::Io {
            context: context.into(),
            cause,
        }
    }

    /// `self` with what was being done when it happened.
    pub fn context(self, context: impl Into<String>) -> Self {
        CommandError::Context {
            context: context.into(),
            cause: Box::new(self),
        }
    }
}

/// A command's result below the binary.
pub type CommandResult<T> = std::result::Result<T, CommandError>;

/// Returns a [`CommandError::Message`] made with `format!`.
macro_rules! refuse {
    ($($t:tt)*) => {
        return Err($crate::CommandError::Message(format!($($t)*)))
    };
}
pub(crate) use refuse;

pub use propbet_units::with_causes;
