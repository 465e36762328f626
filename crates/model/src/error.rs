//! The pipeline's error: what failed, with the file or setting it concerns.

use std::path::PathBuf;

use thiserror::Error;

/// A stage or an input that failed.
#[derive(Debug, Error)]
pub enum Error {
    /// A file could not be read.
    #[error("{}: cannot read: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why (in the message, not a `source`: the error chain would print it twice).
        reason: std::io::Error,
    },
    /// A file's content is wrong (the parser's message, with its line where it has one).
    #[error("{}: {message}", path.display())]
    Input {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A value as written does not read (a list, a unit, a quantity, a colour, a path where a
    /// folder is wanted: `FLAG 'TEXT': PROBLEM`), or a declared setting's value is outside what
    /// it allows ([`propbet_settings::Error`]).
    #[error(transparent)]
    Settings(#[from] propbet_settings::Error),
    /// A number outside what its flag allows (the flag named in the text).
    #[error("{0}")]
    Range(String),
    /// Settings that cannot go together, or a setting missing that another needs.
    #[error("{0}")]
    Conflict(String),
    /// Nothing to work on: no operating point, no measured point, no polar, no propeller.
    #[error("{0}")]
    Nothing(String),
    /// The points cannot make what a target asks for (a hover model without static points,
    /// curves over J without advance ratios).
    #[error("{0}")]
    Unsuited(String),
    /// An error of something named: a flag's value, a stage of a run, an exported file.
    #[error("{what}: {cause}")]
    About {
        /// What it concerns (`--airfoil e63x`, `polars stage`).
        what: String,
        /// The error (in the message, not a `source`: the chain would print it twice).
        cause: Box<Error>,
    },
    /// A mesh does not read.
    #[error(transparent)]
    Mesh(#[from] propbet_geometry::MeshError),
    /// A point cloud does not read.
    #[error(transparent)]
    Cloud(#[from] propbet_geometry::cloud::CloudError),
    /// Airfoil coordinates do not make an airfoil.
    #[error(transparent)]
    Airfoil(#[from] propbet_polar::AirfoilError),
    /// A rotor cannot be made of a blade.
    #[error(transparent)]
    Rotor(#[from] propbet_bemt::RotorError),
    /// An APC PE0 file does not read.
    #[error(transparent)]
    Pe0(#[from] propbet_qprop::apc::ReadPe0Error),
    /// NeuralFoil's weights cannot be used.
    #[error(transparent)]
    Weights(#[from] propbet_neuralfoil::WeightsError),
    /// The diagnosis cannot run on these data.
    #[error(transparent)]
    Diagnose(#[from] propbet_diagnose::DiagnoseError),
    /// An effect failed while predicting.
    #[error(transparent)]
    Effect(#[from] propbet_effects::EffectError),
    /// XFOIL or the polar cache could not be set up.
    #[error(transparent)]
    Polar(#[from] propbet_polar::PolarError),
    /// The XFOIL executable could not be found.
    #[error(transparent)]
    FindXfoil(#[from] xfoil_runner::FindXfoilError),
    /// The XFOIL executable could not be started.
    #[error(transparent)]
    Xfoil(#[from] xfoil_runner::XfoilError),
}

impl From<propbet_settings::BadSetting> for Error {
    fn from(b: propbet_settings::BadSetting) -> Self {
        Error::Settings(b.into())
    }
}

impl Error {
    /// A value that does not read: `FLAG 'TEXT': PROBLEM`.
    pub fn value(flag: &str, text: &str, problem: impl std::fmt::Display) -> Self {
        Error::Settings(propbet_settings::Error::value(flag, text, problem))
    }

    /// `cause`, about `what`.
    pub fn about(what: impl std::fmt::Display, cause: impl Into<Error>) -> Self {
        Error::About {
            what: what.to_string(),
            cause: Box::new(cause.into()),
        }
    }

    /// A file's content error.
    pub fn input(path: impl Into<PathBuf>, message: impl std::fmt::Display) -> Self {
        Error::Input {
            path: path.into(),
            message: message.to_string(),
        }
    }
}

/// The pipeline's result.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `Err(Error::Range(format!(...)))`: a number outside what its flag allows.
#[macro_export]
macro_rules! out_of_range {
    ($($t:tt)*) => { return Err($crate::Error::Range(format!($($t)*))) };
}

/// `Err(Error::Conflict(format!(...)))`: settings that cannot go together.
#[macro_export]
macro_rules! conflict {
    ($($t:tt)*) => { return Err($crate::Error::Conflict(format!($($t)*))) };
}

/// `Err(Error::Nothing(format!(...)))`: nothing to work on.
#[macro_export]
macro_rules! nothing {
    ($($t:tt)*) => { return Err($crate::Error::Nothing(format!($($t)*))) };
}

/// `Err(Error::Unsuited(format!(...)))`: points that cannot make what a target asks for.
#[macro_export]
macro_rules! unsuited {
    ($($t:tt)*) => { return Err($crate::Error::Unsuited(format!($($t)*))) };
}

/// The largest input file read [bytes]: a scan of tens of millions of triangles is well
/// below; a device or a file that never ends is not read past it.
pub(crate) const INPUT_LIMIT: u64 = 4 << 30;

/// Reads an input file's bytes, naming it in the error. Only a regular file (or a link to
/// one) is read: a FIFO would block for ever and a device like /dev/zero never ends; a file
/// growing past [`INPUT_LIMIT`] as it is read is refused.
pub fn read_bytes(path: &std::path::Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let read_error = |reason| Error::Read {
        path: path.to_path_buf(),
        reason,
    };
    let meta = std::fs::metadata(path).map_err(read_error)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a directory"
        } else {
            "a pipe, socket or device"
        };
        return Err(Error::input(path, format!("is {what}, not a file propbet can read")));
    }
    let too_big = || {
        Error::input(
            path,
            format!("is larger than {} GiB, the most propbet reads", INPUT_LIMIT >> 30),
        )
    };
    if meta.len() > INPUT_LIMIT {
        return Err(too_big());
    }
    // Opened without blocking, then read to at most the limit: the file may have been
    // replaced by a FIFO since the check, or grow while it is read.
    let file = {
        use std::os::unix::fs::OpenOptionsExt;
        std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32)
            .open(path)
            .map_err(read_error)?
    };
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(INPUT_LIMIT + 1).read_to_end(&mut bytes).map_err(read_error)?;
    if bytes.len() as u64 > INPUT_LIMIT {
        return Err(too_big());
    }
    Ok(bytes)
}

/// Reads a file as text, naming it in the error.
pub fn read_text(path: &std::path::Path) -> Result<String> {
    let bytes = read_bytes(path)?;
    String::from_utf8(bytes)
        .map_err(|e| Error::input(path, format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to())))
}

/// Where the UTF-8 of `bytes` first fails.
fn e_at(bytes: &[u8]) -> usize {
    std::str::from_utf8(bytes).err().map_or(0, |e| e.valid_up_to())
}

/// A text file whose first line is a free-text title (prop files, airfoil coordinates): the
/// title may be Latin-1 (older tools write it so) and is decoded as such; the rest must be UTF-8.
pub fn read_titled_text(path: &std::path::Path) -> Result<String> {
    let bytes = read_bytes(path)?;
    match String::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let bytes = e.into_bytes();
            let not_text = || Error::input(path, format!("not UTF-8 text (byte {})", e_at(&bytes)));
            // A title: a first line ended by a newline, of printable bytes (no NUL or other
            // control bytes: those make a binary file, not a Latin-1 title).
            let nl = bytes.iter().position(|&b| b == b'\n').ok_or_else(not_text)?;
            let (title, rest) = bytes.split_at(nl);
            if title.iter().any(|&b| b < 0x20 && b != b'\t' && b != b'\r' || b == 0x7f) {
                return Err(not_text());
            }
            let rest = std::str::from_utf8(rest)
                .map_err(|e| Error::input(path, format!("not UTF-8 text (byte {})", nl + e.valid_up_to())))?;
            Ok(title.iter().map(|&b| char::from(b)).collect::<String>() + rest)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_of_mistake_has_its_variant_and_names_what_it_concerns() {
        let e: Error = propbet_settings::values::parse_list("--rpm", "1,,2")
            .unwrap_err()
            .into();
        assert!(
            matches!(e, Error::Settings(propbet_settings::Error::Value { .. })),
            "{e:?}"
        );
        assert_eq!(e.to_string(), "--rpm '1,,2': empty item");
        assert!(matches!(
            propbet_settings::values::parse_length_unit("furlong"),
            Err(propbet_settings::Error::Value { .. })
        ));
        let e: Error = propbet_settings::check_ncrit_effect(&[25.0], 5.0).unwrap_err().into();
        assert!(
            matches!(e, Error::Settings(propbet_settings::Error::Setting(_))),
            "{e:?}"
        );
        assert!(e.to_string().starts_with("--ncrit-effect 25: "), "{e}");
        assert!(matches!(
            propbet_settings::check_ncrit_effect(&[5.0], 5.0),
            Err(propbet_settings::Error::Conflict(_))
        ));
        let e = Error::about("polars stage", Error::Nothing("no polar".into()));
        assert_eq!(e.to_string(), "polars stage: no polar");
        assert!(
            std::error::Error::source(&e).is_none(),
            "the cause is in the message, not the chain"
        );
    }

    #[test]
    fn a_latin1_title_is_read_the_rest_must_be_utf8() {
        let dir = tempfile::tempdir().unwrap();
        let ok = dir.path().join("h.dat");
        std::fs::write(&ok, b"H\xe9lice 10\xb0\n1.0 0.0\n").unwrap();
        assert_eq!(read_titled_text(&ok).unwrap(), "Hélice 10°\n1.0 0.0\n");
        let bad = dir.path().join("b.dat");
        std::fs::write(&bad, b"title\n1.0 \xff0.0\n").unwrap();
        let e = read_titled_text(&bad).unwrap_err().to_string();
        assert!(e.contains("b.dat") && e.contains("not UTF-8 text (byte 10)"), "{e}");
        // Binary, not a title: no newline, control bytes.
        let bin = dir.path().join("x.qprop");
        std::fs::write(&bin, [0xff, 0xfe, 0x00, 0x80]).unwrap();
        assert!(read_titled_text(&bin)
            .unwrap_err()
            .to_string()
            .contains("not UTF-8 text (byte 0)"));
        std::fs::write(&bin, b"\xff\x00\x01\n1 2\n").unwrap();
        assert!(read_titled_text(&bin)
            .unwrap_err()
            .to_string()
            .contains("not UTF-8 text"));
    }
}
