//! `propbet hidden`: known effects added to real measurements (validate's props and files, or
//! one stand log with its propeller's file: `propbet hidden log`), and how the diagnosis
//! answers them.

use anyhow::Result;
use clap::{ArgMatches, Args, FromArgMatches, Subcommand};

use propbet_api::commands::validate::{InjectRequest, ValidateRequest};

/// Arguments of `propbet hidden`: validate's flags, or the `log` subcommand. (Parsed by hand:
/// clap's derive gives `None` for an optional group whose struct flattens others.)
#[derive(Debug)]
pub struct HiddenArgs {
    /// One stand log instead of validate's props.
    pub log: Option<HiddenCommand>,
    /// The props, their files and the model, as `propbet validate` takes them.
    pub validate: Option<ValidateRequest>,
    /// What is added.
    pub inject: InjectRequest,
}

impl FromArgMatches for HiddenArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        Self::from_arg_matches_mut(&mut m.clone())
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }

    fn from_arg_matches_mut(m: &mut ArgMatches) -> Result<Self, clap::Error> {
        let log = match m.subcommand_name() {
            Some(_) => Some(HiddenCommand::from_arg_matches_mut(m)?),
            None => None,
        };
        Ok(Self {
            validate: if log.is_none() {
                Some(ValidateRequest::from_arg_matches_mut(m)?)
            } else {
                None
            },
            inject: InjectRequest::from_arg_matches_mut(m)?,
            log,
        })
    }
}

impl Args for HiddenArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        InjectRequest::augment_args(ValidateRequest::augment_args(HiddenCommand::augment_subcommands(cmd)))
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

/// `propbet hidden`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum HiddenCommand {
    /// The same on one set of measured files (a thrust-stand step test) with its propeller's
    /// file, as `compare` takes them: `propbet hidden log --prop P --measured LOG -o OUT`
    Log(Box<HiddenLogArgs>),
}

/// Arguments of `propbet hidden log`.
#[derive(Debug, Args)]
pub struct HiddenLogArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: crate::predict::ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: propbet_api::MeasuredRequest,
    /// What is added.
    #[command(flatten)]
    pub inject: InjectRequest,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: std::path::PathBuf,
}

/// Runs `propbet hidden`.
pub fn run(a: &HiddenArgs) -> Result<bool> {
    let term = crate::output::Terminal::default();
    let validate = match (&a.log, &a.validate) {
        (Some(HiddenCommand::Log(l)), _) => {
            let (model, data) = (l.model.spec()?, l.data.spec()?);
            propbet_api::commands::validate::hidden_log(&model, &data, &l.inject.injections()?, &l.out, &term)?;
            return Ok(true);
        }
        (None, Some(v)) => v,
        (None, None) => unreachable!("clap parses validate's flags without a subcommand"),
    };
    let (spec, props, generic) = validate.spec()?;
    let injections = a.inject.injections()?;
    Ok(propbet_api::commands::validate::hidden(
        &spec,
        &props,
        generic.as_ref(),
        &injections,
        &term,
    )?)
}
