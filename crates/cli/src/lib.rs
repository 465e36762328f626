//! The `propbet` command line: flags parsed into the typed API's requests, its commands run with
//! the terminal as their console ([`Terminal`]), and how it went: exit 0 done, 1 done with
//! problems it reported, 2 an error. A library so that the Python package (`crates/python`)
//! prints to the same terminal and runs `propbet` itself (`execute`).

use clap::{Parser, Subcommand};

/// `eprintln!` that does not panic when standard error is closed (`propbet ... 2>&- `, or a
/// pipe whose reader has gone): a message nobody can read is not a reason to abort. Defined
/// before the modules, so it replaces the standard macro in all of them.
/// On a terminal, a sentence longer than a terminal line (160 characters) is wrapped at 100
/// columns (`output::for_terminal`); a table row is data and stays whole; into a pipe or a
/// file every message stays one line.
macro_rules! eprintln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let tty = std::io::IsTerminal::is_terminal(&std::io::stderr());
        let _ = writeln!(std::io::stderr(), "{}", $crate::output::for_terminal(&format!($($t)*), tty));
    }};
}

/// `println!` that does not panic when standard output is closed (`propbet ... | head -1`).
macro_rules! println {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let tty = std::io::IsTerminal::is_terminal(&std::io::stdout());
        let _ = writeln!(std::io::stdout(), "{}", $crate::output::for_terminal(&format!($($t)*), tty));
    }};
}

mod argv;
mod compare;
mod compare_props;
mod diagnose;
mod engine;
mod export;
mod hidden;
mod motor_fit;
mod motor_flags;
mod output;
mod polar;
mod powered;
mod predict;
mod prop;
mod run;
mod scan;
mod serve;
mod synth;
mod validate;

pub use output::Terminal;

/// Propeller performance from geometry, and why it disagrees with the thrust stand.
#[derive(Debug, Parser)]
#[command(name = "propbet", version, about, after_help = EXIT, max_term_width = 100)]
pub struct Cli {
    /// Worker threads for sweeps (default: all cores).
    #[arg(long, global = true)]
    threads: Option<usize>,
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// The exit codes, as every help page states them.
const EXIT: &str = "Exit status: 0 done; 1 done, with problems it reports (unfit stations, XFOIL faults, \
dropped rows, unconverged points); 2 error (bad input or arguments: a message naming the file, line or value).";

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// The main job: a case directory (case.toml) from scan to report — scan, polars (XFOIL or
    /// NeuralFoil), sweeps, comparison with the measurements, diagnosis, one HTML report.
    #[command(after_help = concat!(
        "Example:\n  propbet run props/apcsp_10x7 -o run_apc\n\n",
        "Exit status: 0 done; 1 done, with problems it reports; 2 error (the output folder keeps INCOMPLETE.txt)."
    ))]
    Run(Box<run::RunArgs>),
    /// Blade geometry from a scan (STL mesh or PLY / COLMAP / XYZ cloud): sections, airfoil
    /// fits, geometry CSV, geom.txt, QPROP prop file, airfoil files and plots.
    #[command(after_help = concat!(
        "Example:\n  propbet scan props/apcsf_10x4.7/apcsf_10x4.7.stl --units mm -o scan_apc\n\n",
        "Exit status: 0 done; 1 done, with stations it could not measure or fit, which it reports; 2 error."
    ))]
    Scan(Box<scan::ScanArgs>),
    /// Polars of every station of a blade at its operating Re and Mach, reduced to a QPROP file.
    #[command(after_help = concat!(
        "Example:\n  propbet polars --geometry props/apcsf_10x4.7/apcsf_10x4.7_geometry.qprop \\\n",
        "    --airfoil props/airfoils/e63.dat --rpm 4000,6000 --j 0:0.6:0.1 --out-prop apc.qprop --out-polars apc.json\n\n",
        "Exit status: 0 done; 1 done, with unfit stations or XFOIL faults it reports; 2 error."
    ))]
    Polars(Box<propbet_api::PolarsRequest>),
    /// Polars of one section from XFOIL at given Reynolds numbers, with their QPROP fit.
    #[command(after_help = concat!(
        "Example:\n  propbet polar --airfoil naca4412 --re 5e4,1e5 -o naca4412.csv\n\n",
        "Exit status: 0 done; 1 done, with XFOIL faults it reports; 2 error."
    ))]
    Polar(Box<polar::PolarArgs>),
    /// Predict thrust, torque, power and coefficients of a QPROP prop file over RPM x J (or V),
    /// or on a motor (`--motor`) at voltages, currents or thrusts: RPM, current and g/W too.
    #[command(after_help = concat!(
        "Example:\n  propbet predict --prop props/cam6x3/cam6x3.qprop --rpm 4000,6000 --j 0:0.6:0.05\n\n",
        "Exit status: 0 done; 1 done, with unconverged points it reports; 2 error."
    ))]
    Predict(Box<predict::PredictArgs>),
    /// The motor: fit R, Io and Kv to a stand log's electrical columns (`propbet motor fit`).
    #[command(subcommand, after_help = concat!(
        "Example:\n  propbet motor fit --measured ../shared/data/thrust_stand/series1585_newton_steps.csv -o fitted.motor\n\n",
        "Exit status: 0 done; 2 error."
    ))]
    Motor(motor_fit::MotorCommand),
    /// Propellers side by side on one motor and battery: hover g/W, current and endurance,
    /// full-throttle thrust and current, efficiency over airspeed; ranked.
    #[command(after_help = concat!(
        "Example:\n  propbet compare-props props/cam6x3/cam6x3.qprop props/photofoil_8x4.5/QProp_8x4_5.txt \\\n",
        "    --motor props/motors/axi2204-54.motor --battery 3S,2200mAh --hover 2 -o side\n\n",
        "Exit status: 0 done; 1 done, some propeller cannot hover at that thrust; 2 error."
    ))]
    CompareProps(Box<compare_props::ComparePropsArgs>),
    /// Compare measured data (thrust stand, wind tunnel, CSV) with the prediction: metrics,
    /// plots and an HTML report.
    #[command(after_help = concat!(
        "Example:\n  propbet compare --prop props/cam6x3/cam6x3.qprop \\\n",
        "    --measured tests/data/hidden_effects/no_effect/cam6x3_tunnel.csv -o cmp\n\n",
        "Exit status: 0 done; 1 done, with dropped rows or unconverged points it reports; 2 error."
    ))]
    Compare(Box<compare::CompareArgs>),
    /// Which physical effect is missing: candidate effects fitted to the measurements, ranked
    /// by held-out error, and the ladder of effects that help.
    #[command(after_help = concat!(
        "Example:\n  propbet diagnose --prop tests/data/hidden_effects/torque_tare/cam6x3.qprop \\\n",
        "    --measured tests/data/hidden_effects/torque_tare/cam6x3_steps.csv --out dg\n\n",
        "Exit status: 0 done; 1 done, with dropped rows it reports; 2 error."
    ))]
    Diagnose(Box<diagnose::DiagnoseArgs>),
    /// The workbench: a page on 127.0.0.1 that drives the model against a case's measurements
    /// (effects on sliders, fit, the ladder step by step, pin, save).
    #[command(after_help = concat!(
        "Example:\n  propbet serve props/apcsp_10x7 --open\n\n",
        "Or with compare's flags instead of a case:\n",
        "  propbet serve --prop props/apcsp_10x7/10x7-PERF.PE0 --airfoils props/airfoils --measured props/apcsp_10x7/uiuc/*.txt\n\n",
        "It prints one URL carrying a random token; Ctrl-C ends it.\n",
        "Exit status: 0 is never returned (Ctrl-C ends it, with the signal's status); 2 error before it listens."
    ))]
    Serve(Box<serve::ServeArgs>),
    /// List the effects (built-in and user-defined) with their parameters and physics.
    #[command(after_help = concat!("Example:\n  propbet effects\n\n", "Exit status: 0 done; 2 error."))]
    Effects(diagnose::EffectsArgs),
    /// Write synthetic measurements made by the model with hidden effects and noise.
    #[command(after_help = concat!(
        "Example:\n  propbet synth --prop props/cam6x3/cam6x3.qprop --effect pitch-offset:deg=1.5 --noise 1% --out synth.csv\n\n",
        "Exit status: 0 done; 2 error."
    ))]
    Synth(Box<synth::SynthArgs>),
    /// Validation on real data: every UIUC propeller of the directory with an APC PE0 file,
    /// predicted and compared with its static and J-sweep files, before and after calibration.
    #[command(after_help = concat!(
        "Example:\n  propbet validate --uiuc ../shared/data/uiuc --pe0 ../shared/data/apc/PE0 --airfoils props/airfoils \\\n",
        "    --per3 ../shared/data/apc/PER3 -o validation\n\n",
        "Exit status: 0 done; 1 done, with problems it reports; 2 error."
    ))]
    Validate(Box<propbet_api::commands::validate::ValidateRequest>),
    /// Hidden effects in real measurements: known effects (thrust and torque tares, an RPM
    /// scale, the air's density) added to validate's measured files (or one stand log: `hidden
    /// log`) at several sizes, and how the diagnosis answers each: found with its size, one of a
    /// group it cannot separate, below its detection limit, or another effect named.
    #[command(subcommand_negates_reqs = true, args_conflicts_with_subcommands = true, after_help = concat!(
        "Example:\n  propbet hidden --uiuc ../shared/data/uiuc --pe0 ../shared/data/apc/PE0 --airfoils props/airfoils \\\n",
        "    --only apce_10x5,apcsp_10x7 --sizes 0.05 -o hidden\n\n",
        "One stand log with its propeller's file:\n  propbet hidden log --prop ../shared/data/photofoil/QProp_8x4_5.txt \\\n",
        "    --measured ../shared/data/photofoil/StepsTestV2_2022-01-18_153833.csv --inject torque-tare -o hidden_log\n\n",
        "Exit status: 0 done; 1 done, with props it could not diagnose; 2 error."
    ))]
    Hidden(Box<hidden::HiddenArgs>),
    /// Flight-simulator files from a prediction or from measurements: Gazebo's motor model,
    /// PX4 SIH's thruster parameters, a JSBSim propeller, a CT/CP map (CSV, JSON).
    #[command(after_help = concat!(
        "Example:\n  propbet export --to all --prop props/cam6x3/cam6x3.qprop --rpm 4000,6000 --j 0:0.6:0.05 -o sim\n\n",
        "From a static thrust-stand log:\n  propbet export --to gazebo --measured log.csv --diameter 5in -o sim\n\n",
        "Exit status: 0 done; 2 error (an export the data cannot support: what is missing, nothing written)."
    ))]
    Export(Box<export::ExportArgs>),
    /// Inspect a QPROP prop file: stations, warnings; optionally write it back normalised.
    #[command(after_help = concat!("Example:\n  propbet prop props/cam6x3/cam6x3.qprop\n\n", "Exit status: 0 done; 2 error."))]
    Prop(prop::PropArgs),
    /// Shell completions for bash, zsh, fish, elvish or PowerShell, on standard output.
    #[command(
        after_help = "Example:\n  propbet completions bash > /etc/bash_completion.d/propbet\n\nExit status: 0 done; 2 error."
    )]
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// The manual page (roff), on standard output.
    #[command(after_help = "Example:\n  propbet man > propbet.1 && man ./propbet.1\n\nExit status: 0 done; 2 error.")]
    Man,
}

/// Runs a parsed command line: `Ok(true)` done, `Ok(false)` done with problems it reported
/// (exit 1), `Err` an error (exit 2).
pub fn run(cli: Cli) -> anyhow::Result<bool> {
    if let Some(n) = cli.threads {
        // More threads than a machine has cores gains nothing; thousands exhaust its
        // processes (pid_max) and take minutes to start.
        const MAX_THREADS: usize = 256;
        if n == 0 || n > MAX_THREADS {
            anyhow::bail!(
                "--threads {n}: from 1 to {MAX_THREADS} (this machine has {} cores)",
                std::thread::available_parallelism().map_or(1, |c| c.get())
            );
        }
        rayon::ThreadPoolBuilder::new().num_threads(n).build_global()?;
    }
    dispatch(cli.command)
}

/// Runs `propbet` with these arguments (the program's name first) in this process, as the
/// binary would: flags an error of clap's as an error (its message as clap prints it).
pub fn execute<I, T>(argv: I) -> anyhow::Result<bool>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = parse_args(argv).map_err(clap_error)?;
    run(cli)
}

/// The command line's definition: every flag of one value takes a value that starts with a
/// dash as it is (`--temp -10C`, `--drag-factor -1` reaching its range check), as
/// `--flag=value` does.
pub fn command() -> clap::Command {
    fn hyphens(c: clap::Command) -> clap::Command {
        c.mut_args(|a| {
            let one = a.get_long().is_some()
                && matches!(a.get_action(), clap::ArgAction::Set)
                && a.get_num_args().is_none_or(|n| n.max_values() == 1);
            if one {
                a.allow_hyphen_values(true)
            } else {
                a
            }
        })
        .mut_subcommands(hyphens)
    }
    hyphens(<Cli as clap::CommandFactory>::command())
}

/// The arguments (the program's name first) as a [`Cli`], by [`command`] (what the binary,
/// [`execute`] and [`api`] parse with).
pub fn parse_args<I, T>(argv: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let matches = command().try_get_matches_from(argv)?;
    <Cli as clap::FromArgMatches>::from_arg_matches(&matches)
}

/// A command-line error of clap's as an error, its message as clap prints it.
pub(crate) fn clap_error(e: clap::Error) -> anyhow::Error {
    anyhow::anyhow!("{}", e.render().to_string().trim_end())
}

/// Runs one command.
fn dispatch(command: Command) -> anyhow::Result<bool> {
    match command {
        Command::Run(a) => run::run(&a),
        Command::Validate(a) => validate::run(&a).map(|(ok, _)| ok),
        Command::Hidden(a) => hidden::run(&a),
        Command::Predict(a) => predict::run(&a),
        Command::Motor(c) => motor_fit::run(&c),
        Command::CompareProps(a) => compare_props::run(&a),
        Command::Prop(a) => prop::run(&a),
        Command::Export(a) => export::run(&a),
        Command::Polar(a) => polar::run_polar(&a),
        Command::Polars(a) => polar::run_polars(&a),
        Command::Compare(a) => compare::run(&a),
        Command::Diagnose(a) => diagnose::run(&a),
        Command::Serve(a) => serve::run(&a),
        Command::Effects(a) => diagnose::list(&a),
        Command::Synth(a) => synth::run(&a),
        Command::Scan(a) => scan::run(&a),
        Command::Completions { shell } => {
            let mut cmd = <Cli as clap::CommandFactory>::command();
            clap_complete::generate(shell, &mut cmd, "propbet", &mut std::io::stdout());
            Ok(true)
        }
        Command::Man => {
            let cmd = <Cli as clap::CommandFactory>::command();
            let mut out = Vec::new();
            clap_mangen::Man::new(cmd).render(&mut out)?;
            std::io::Write::write_all(&mut std::io::stdout(), &out)?;
            Ok(true)
        }
    }
}

#[cfg(test)]
mod case_keys;
mod settings_flags;
#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use propbet_api::spec::StageSpec;

    use super::*;

    /// The stage spec a stage's command line means (the commands `propbet run` and `propbet
    /// validate` print for their stages).
    pub(crate) fn stage_spec(command: &Command) -> anyhow::Result<Option<propbet_api::spec::StageSpec>> {
        use propbet_api::spec::StageSpec;
        Ok(Some(match command {
            Command::Scan(a) => StageSpec::Scan(a.spec()?),
            Command::Polars(a) => StageSpec::Polars(a.spec()?),
            Command::Predict(a) if a.motor.motor.is_some() => StageSpec::Powered(a.powered_spec()?),
            Command::Predict(a) => StageSpec::Predict(a.spec()?),
            Command::Compare(a) => StageSpec::Compare(a.spec()?),
            Command::Diagnose(a) => StageSpec::Diagnose(a.spec()?),
            _ => return Ok(None),
        }))
    }

    /// Every subcommand's help ends with an example that parses and the exit codes; the
    /// completions and the manual page are generated from the same definition.
    #[test]
    fn every_help_has_an_example_that_parses_and_the_exit_codes() {
        use clap::CommandFactory;
        let cmd = Cli::command();
        let names: Vec<String> = cmd.get_subcommands().map(|c| c.get_name().to_string()).collect();
        // Workflow order: the main job first, the tools after.
        assert_eq!(&names[..3], ["run", "scan", "polars"]);
        for sub in cmd.get_subcommands() {
            let help = sub.get_after_help().map(|h| h.to_string()).unwrap_or_default();
            assert!(help.contains("Exit status: 0"), "{}: {help}", sub.get_name());
            let example = help
                .split("Example:\n")
                .nth(1)
                .and_then(|e| e.split("\n\n").next())
                .unwrap_or_else(|| panic!("{}: no example", sub.get_name()));
            let line = example.replace("\\\n", " ");
            let line = line.split('>').next().unwrap().split("&&").next().unwrap();
            let argv: Vec<&str> = line.split_whitespace().collect();
            assert_eq!(argv[1], sub.get_name());
            parse_args(&argv).unwrap_or_else(|e| panic!("{line}: {e}"));
        }
        let mut bash = Vec::new();
        clap_complete::generate(clap_complete::Shell::Bash, &mut Cli::command(), "propbet", &mut bash);
        assert!(String::from_utf8(bash).unwrap().contains("validate"));
        let mut man = Vec::new();
        clap_mangen::Man::new(Cli::command()).render(&mut man).unwrap();
        assert!(String::from_utf8(man).unwrap().contains(".TH propbet"));
    }

    /// The export command a report prints for a prediction parses as `propbet export`.
    #[test]
    fn a_predictions_export_command_parses() {
        let mut spec = propbet_api::spec::PredictSpec {
            model: propbet_api::spec::ModelSpec::prop("r/polars/prop.qprop".into()),
            omegas: vec![400.0, 600.0],
            axis: propbet_api::spec::SweepAxis::J(vec![0.0, 0.3]),
            air: Default::default(),
            format: propbet_api::spec::TableFormat::Json,
            out: Some("r/predict/sweep.csv".into()),
            stations: None,
            band: true,
        };
        spec.model.polars = Some("r/polars/polars.json".into());
        spec.model.effects = vec!["pitch-offset:deg=1.2".into()];
        spec.model.dbeta = 0.01;
        let cmd = crate::argv::export_command(&spec, std::path::Path::new("r/export"));
        let argv: Vec<&str> = cmd.split_whitespace().collect();
        let cli = parse_args(&argv).unwrap_or_else(|e| panic!("{cmd}: {e}"));
        let Command::Export(a) = cli.command else {
            panic!("{cmd}")
        };
        assert_eq!(a.to, ["all"]);
        assert_eq!(a.out, std::path::PathBuf::from("r/export"));
        assert_eq!(a.model.effect, ["pitch-offset:deg=1.2"]);
        assert!(a.model.polars.is_some() && a.j.is_some());
    }

    /// A spec's printed command line parses back to the same spec.
    pub(crate) fn check(spec: &StageSpec) {
        let argv = crate::argv::argv(spec);
        let cli = parse_args(std::iter::once("propbet".to_string()).chain(argv.iter().cloned()))
            .unwrap_or_else(|e| panic!("{}: {e}", crate::argv::command(spec)));
        let back = stage_spec(&cli.command).unwrap().expect("a stage");
        assert_eq!(&back, spec, "{}", crate::argv::command(spec));
    }

    pub(crate) fn repo() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
    }

    #[test]
    fn every_stage_of_the_shipped_cases_is_a_command_that_parses_back() {
        let xfoil = propbet_api::ProcessRequest {
            xfoil: Some("/usr/bin/xfoil".into()),
            cache: Some("/tmp/cache dir".into()),
            no_cache: false,
            quiet: true,
            budget: Some(600.0),
            engine: Some("auto".into()),
            neuralfoil_size: Some("large".into()),
        };
        let mut n = 0;
        for case in ["apcsf_10x4.7", "photofoil_8x4.5", "cam6x3"] {
            let plan = propbet_api::case::plan(
                &repo().join("props").join(case),
                Path::new("out"),
                &xfoil.spec().unwrap(),
            )
            .unwrap();
            for s in plan.stages() {
                check(&s);
                n += 1;
            }
        }
        assert_eq!(n, 5 + 3 + 2);
    }

    #[test]
    fn specs_with_every_flag_parse_back() {
        let parse = |line: &[&str]| -> StageSpec {
            let cli = parse_args(std::iter::once("propbet").chain(line.iter().copied())).unwrap();
            stage_spec(&cli.command).unwrap().unwrap()
        };
        for line in [
            &[
                "predict",
                "--prop",
                "p.qprop",
                "--rpm",
                "2400,6512",
                "--v",
                "0:20/7",
                "--temp",
                "22C",
                "--pressure",
                "1009hPa",
                "--humidity",
                "40",
                "--dbeta=-1.5",
                "--units",
                "in",
                "--qprop-compat",
                "--no-tip-loss",
                "--effect",
                "pitch-offset:deg=1.2",
                "--format",
                "json",
                "--out-stations",
                "s.csv",
            ][..],
            &[
                "compare",
                "--prop",
                "p.qprop",
                "--measured",
                "a.csv",
                "b.txt",
                "--poles",
                "14",
                "--rpm-source",
                "electrical",
                "--atmosphere",
                "22,1009hPa,40",
                "--rho",
                "1.1648",
                "--columns",
                "c.toml",
                "-o",
                "o",
            ],
            &[
                "predict",
                "--prop",
                "p.qprop",
                "--motor",
                "m.motor",
                "--throttle",
                "0.4:1:0.2",
                "--battery",
                "4S,1300mAh,R=3mOhm,usable=75%",
                "--esc-ohms",
                "0.01",
                "--v",
                "0:20/3",
                "--rho",
                "1.2",
                "--format",
                "json",
                "--band",
                "-o",
                "o.json",
            ],
            &[
                "predict",
                "--prop",
                "p.qprop",
                "--motor",
                "m.motor",
                "--rpm",
                "7000,9000.5",
            ],
            &[
                "diagnose",
                "--prop",
                "p.qprop",
                "--measured",
                "a.csv",
                "--effects",
                "pitch-offset,torque-tare",
                "--folds",
                "4",
                "--max-steps",
                "2",
                "-o",
                "o",
            ],
            &[
                "polars",
                "--geometry",
                "g.qprop",
                "--units",
                "mm",
                "--airfoil",
                "naca4412",
                "--thickness",
                "8%",
                "--rpm",
                "6000,8000",
                "--j",
                "0:0.5:0.1",
                "--ncrit",
                "6",
                "--alpha=-4:12:0.5",
                "--panels",
                "160",
                "--iter",
                "50",
                "--no-cache",
                "--xfoil-budget",
                "90",
                "--out-prop",
                "o.qprop",
            ],
            &[
                "scan",
                "x.ply",
                "-o",
                "o",
                "--units",
                "in",
                "--stations",
                "0.2:0.9/8",
                "--planar",
                "--slab",
                "0.5",
                "--slab-points",
                "0",
                "--blade-colour",
                "orange,#102030",
                "--colour-threshold",
                "40",
                "--box",
                "50.8x48.26x50.8",
                "--box-seeds=1,2,3;4,5,6",
                "--crop=-80,-200,-200,200,200,200",
                "--outliers",
                "10,3",
                "--root-point=1,2,3",
                "--tip-point=4,5,6",
                "--rotate=0,1,2",
                "--known-length",
                "0,0,0,2,0,0,25",
            ],
        ] {
            check(&parse(line));
        }
    }
}
