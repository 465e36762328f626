//! What a person and a script see: the tour's commands under a terminal, and one line per
//! message into a pipe.

use super::*;

/// The tour's commands as a person runs them, under a terminal (`script` gives them a pty):
/// no line over 160 characters, no progress bar left on a line of its own or glued to the next
/// (a bar that is drawn is cleared), the bar named after the engine that makes the polars, and
/// a NeuralFoil run of the default case that exits 0 (its notes are no problems).
#[test]
fn the_tours_commands_under_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let exe = env!("CARGO_BIN_EXE_propbet");
    let p = |rel: &str| repo().join(rel).display().to_string();
    let cam = p("props/cam6x3/cam6x3.qprop");
    let commands = [
        format!("{exe} run --engine neuralfoil -o nf"),
        format!("{exe} run {} --engine neuralfoil -o sf", p("props/apcsf_10x4.7")),
        format!(
            "{exe} predict --prop {} --rpm 5000 --j 0:0.8:0.1 --engine neuralfoil --out pe0.csv",
            p("props/apcsp_10x7/10x7-PERF.PE0")
        ),
        format!("{exe} predict --prop {cam} --rpm 4000,6000 --j 0:0.6:0.05 --band --out sweep.csv"),
        format!("{exe} synth --prop {cam} --effect pitch-offset:deg=1.5 --noise 1% --out synth.csv"),
        format!("{exe} diagnose --prop {cam} --measured synth.csv --out diag"),
        format!("{exe} --help"),
        format!("{exe} run --help"),
        format!("{exe} predict --help"),
    ];
    for cmd in &commands {
        let o = std::process::Command::new("script")
            .args(["-qefc", cmd, "/dev/null"])
            .current_dir(dir.path())
            .output()
            .expect("script (util-linux) gives the command a terminal");
        let text = String::from_utf8_lossy(&o.stdout).into_owned();
        assert_eq!(o.status.code(), Some(0), "`{cmd}`: {text}");
        // What stays on the screen: each line as its last carriage return leaves it.
        for raw in text.split('\n') {
            let shown = raw.trim_end_matches('\r').rsplit('\r').next().unwrap_or_default();
            let shown = shown.replace("\x1b[2K", "");
            assert!(
                shown.chars().count() <= 160,
                "`{cmd}`: {} characters: {shown}",
                shown.chars().count()
            );
            assert!(
                !shown.contains(" polars, ") || !shown.contains(" left"),
                "`{cmd}`: a bar left: {shown:?}"
            );
            assert!(
                !(shown.contains("XFOIL [") && cmd.contains("neuralfoil")),
                "`{cmd}`: {shown:?}"
            );
        }
    }
}

/// Into a pipe or a file every message of propbet's is one line, whatever its length (a script
/// reads standard error line by line); under a terminal the same sentence is wrapped.
#[test]
fn a_message_is_one_line_except_under_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let pe0 = repo().join("props/apcsp_10x7/10x7-PERF.PE0").display().to_string();
    let args = [
        "predict",
        "--prop",
        &pe0,
        "--rpm",
        "5000",
        "--engine",
        "neuralfoil",
        "--out",
        "p.csv",
    ];
    let o = run(&args, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    let line = err
        .lines()
        .find(|l| l.starts_with("propbet: Expected accuracy"))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(
        line.contains("uncertainty band held") && line.chars().count() > 160,
        "{err}"
    );
    let cmd = format!(
        "{} {}",
        env!("CARGO_BIN_EXE_propbet"),
        args.join(" ").replace("p.csv", "q.csv")
    );
    let t = std::process::Command::new("script")
        .args(["-qefc", &cmd, "/dev/null"])
        .current_dir(dir.path())
        .output()
        .expect("script (util-linux) gives the command a terminal");
    let shown = String::from_utf8_lossy(&t.stdout).replace('\r', "");
    let first = shown
        .lines()
        .find(|l| l.starts_with("propbet: Expected accuracy"))
        .unwrap_or_else(|| panic!("{shown}"));
    assert!(
        first.chars().count() <= 100 && !first.contains("uncertainty band held"),
        "{shown}"
    );
}
