//! `propbet serve` over HTTP: the guards (loopback Host, token, body size), every bad request a
//! 4xx with the command line's message and the server still answering, and an evaluation equal
//! to `propbet compare --effect` of the same state. On the PhotoFoil case (a QPROP file: no
//! XFOIL).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Stdio};

use super::*;

/// A running `propbet serve`, killed when dropped.
struct Server {
    child: Child,
    port: u16,
    token: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(case: &Path, save_to: &Path) -> Server {
    start_with(&[case.to_str().unwrap()], save_to)
}

/// `propbet serve` with `args` (a case, or `compare`'s flags) and `--save-to save_to`.
fn start_with(args: &[&str], save_to: &Path) -> Server {
    let mut child = bin()
        .arg("serve")
        .args(args)
        .args(["--save-to", save_to.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("propbet serve starts");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line.trim();
    let rest = url
        .strip_prefix("http://127.0.0.1:")
        .unwrap_or_else(|| panic!("printed {url:?}"));
    let (port, token) = rest.split_once("/?token=").unwrap();
    Server {
        child,
        port: port.parse().unwrap(),
        token: token.to_string(),
    }
}

/// One HTTP/1.1 request: (status, body).
fn request(port: u16, method: &str, path: &str, headers: &[(&str, &str)], body: &[u8]) -> (u16, String) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    if !headers.iter().any(|(k, _)| *k == "Host") {
        head.push_str(&format!("Host: 127.0.0.1:{port}\r\n"));
    }
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    s.write_all(head.as_bytes()).unwrap();
    let _ = s.write_all(body);
    let mut answer = Vec::new();
    let _ = s.read_to_end(&mut answer);
    let text = String::from_utf8_lossy(&answer).to_string();
    let status = text.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
    let body = text
        .split_once("\r\n\r\n")
        .map_or(String::new(), |(_, b)| b.to_string());
    (status, body)
}

/// A POST to `path` carrying the server's token.
fn post(s: &Server, path: &str, body: &[u8]) -> (u16, String) {
    request(s.port, "POST", path, &[("X-Propbet-Token", &s.token)], body)
}

fn evaluate(s: &Server, body: &[u8]) -> (u16, String) {
    post(s, "/api/evaluate", body)
}

fn photofoil() -> PathBuf {
    repo().join("props/photofoil_8x4.5")
}

#[test]
fn requests_without_the_token_or_from_another_host_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let s = start(&photofoil(), dir.path());
    let state = br#"{"effects": []}"#;
    assert_eq!(request(s.port, "POST", "/api/evaluate", &[], state).0, 401);
    let wrong = [("X-Propbet-Token", "0123"), ("Host", "")];
    assert_eq!(request(s.port, "POST", "/api/evaluate", &wrong[..1], state).0, 401);
    // A name another site rebinds to 127.0.0.1 carries its own Host.
    let rebound = [("X-Propbet-Token", s.token.as_str()), ("Host", "attacker.example:80")];
    let (code, body) = request(s.port, "POST", "/api/evaluate", &rebound, state);
    assert_eq!(code, 403, "{body}");
    assert!(body.contains("not this machine's loopback"), "{body}");
    // The page needs the token too; the token in the query string is taken.
    assert_eq!(request(s.port, "GET", "/", &[], b"").0, 401);
    let (code, page) = request(s.port, "GET", &format!("/?token={}", s.token), &[], b"");
    assert_eq!(code, 200);
    assert!(page.contains("propbet workbench"));
    assert_eq!(evaluate(&s, state).0, 200);
}

#[test]
fn a_bad_request_gets_the_command_lines_message_and_the_server_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let s = start(&photofoil(), dir.path());
    for (body, says) in [
        (&b"{not json"[..], "not a state"),
        (br#"{"effects": ["nope:x=1"]}"#, "unknown effect `nope`"),
        (br#"{"effects": ["pitch-offset:deg=-80"]}"#, "outside its bounds"),
        (
            br#"{"effects": ["pitch-offset:deg=1", "pitch-offset:deg=1"]}"#,
            "given twice",
        ),
        (br#"{"effects": ["pitch-offset:deg=NaN"]}"#, "pitch-offset"),
        (br#"{"effect": []}"#, "unknown field"),
    ] {
        let (code, answer) = evaluate(&s, body);
        assert_eq!(code, 400, "{}: {answer}", String::from_utf8_lossy(body));
        assert!(answer.contains(says), "{}: {answer}", String::from_utf8_lossy(body));
    }
    let big = vec![b' '; propbet_serve_max_body() + 10];
    assert_eq!(evaluate(&s, &big).0, 413);
    // Save refuses a name that is not one plain folder name, and writes nothing.
    let save = |name: &str| {
        let body = format!(r#"{{"state": {{"effects": []}}, "name": "{name}"}}"#);
        post(&s, "/api/save", body.as_bytes())
    };
    assert_eq!(save("../escape").0, 400);
    assert_eq!(save("a/b").0, 400);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // Random bytes and mangled states: an answer each, never a dropped connection.
    let seed = br#"{"effects": ["drag-scale:factor=1.2", "tip-loss:strength=1.5"]}"#;
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for k in 0..150 {
        let mut b = seed.to_vec();
        for _ in 0..(1 + k % 6) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let at = (x as usize) % b.len();
            b[at] = (x >> 32) as u8;
        }
        let (code, _) = evaluate(&s, &b);
        assert!(code == 200 || code == 400, "{code} for {}", String::from_utf8_lossy(&b));
    }
    assert_eq!(evaluate(&s, br#"{"effects": []}"#).0, 200);
}

/// The bound `propbet_serve::MAX_BODY` (1 MiB), as the guide states it.
fn propbet_serve_max_body() -> usize {
    1 << 20
}

/// `compare`'s flags for the PhotoFoil case's prop and log.
fn photofoil_flags() -> Vec<String> {
    let case = photofoil();
    vec![
        "--prop".into(),
        case.join("QProp_8x4_5.txt").display().to_string(),
        "--measured".into(),
        case.join("StepsTestV2_2022-01-18_153833.csv").display().to_string(),
        "--rho".into(),
        "1.1648".into(),
    ]
}

/// The server's evaluation of `effects` against `propbet compare --effect ...` of the same
/// prop and log: the accuracy and the headline equal.
fn evaluation_is_compares(s: &Server, effects: &[&str], dir: &Path) {
    let state = serde_json::json!({ "effects": effects }).to_string();
    let (code, body) = evaluate(s, state.as_bytes());
    assert_eq!(code, 200, "{body}");
    let api: serde_json::Value = serde_json::from_str(&body).unwrap();
    let mut args = vec!["compare".to_string()];
    args.extend(photofoil_flags());
    args.extend(["-o".into(), "cmp".into()]);
    for e in effects {
        args.push("--effect".into());
        args.push(e.to_string());
    }
    let out = run(&args.iter().map(String::as_str).collect::<Vec<_>>(), dir);
    assert!(
        out.status.code().unwrap_or(2) < 2,
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let cli: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("cmp/summary.json")).unwrap()).unwrap();
    for k in ["ct_median_error", "cp_median_error", "points"] {
        assert_eq!(api["accuracy"][k], cli["accuracy"][k], "{effects:?}: {k}");
    }
    assert_eq!(api["headline"], cli["headline"]);
}

#[test]
fn an_evaluation_is_what_compare_gives_for_the_same_effects() {
    let dir = tempfile::tempdir().unwrap();
    let s = start(&photofoil(), dir.path());
    evaluation_is_compares(&s, &["drag-scale:factor=1.6", "tip-loss:strength=2.2"], dir.path());
}

#[test]
fn a_workbench_of_compares_flags_evaluates_as_compare_and_saves_no_case() {
    let dir = tempfile::tempdir().unwrap();
    let flags = photofoil_flags();
    let s = start_with(&flags.iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
    for effects in [
        &[][..],
        &["pitch-offset:deg=-0.8"][..],
        &["drag-scale:factor=1.3", "thrust-tare:k=0.02"][..],
    ] {
        evaluation_is_compares(&s, effects, dir.path());
    }
    let (code, answer) = post(&s, "/api/save", br#"{"state": {"effects": []}, "name": "kept"}"#);
    assert_eq!(code, 400, "{answer}");
    assert!(answer.contains("start `propbet serve CASE_DIR`"), "{answer}");
    assert!(!dir.path().join("kept").exists());
}

#[test]
fn the_cases_user_effects_are_offered_and_a_saved_case_keeps_the_state() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case");
    std::fs::create_dir(&case).unwrap();
    for f in ["QProp_8x4_5.txt", "StepsTestV2_2022-01-18_153833.csv", "case.toml"] {
        std::fs::copy(photofoil().join(f), case.join(f)).unwrap();
    }
    std::fs::copy(repo().join("docs/user_effects.toml"), case.join("effects.toml")).unwrap();
    let text = std::fs::read_to_string(case.join("case.toml")).unwrap();
    let text = text.replace(
        "files = [\"StepsTestV2_2022-01-18_153833.csv\"]",
        "files = [\"StepsTestV2_2022-01-18_153833.csv\"]\nuser_effects = \"effects.toml\"",
    );
    std::fs::write(case.join("case.toml"), text).unwrap();
    let saves = dir.path().join("saves");
    std::fs::create_dir(&saves).unwrap();
    let s = start(&case, &saves);
    let (code, session) = request(s.port, "GET", "/api/session", &[("X-Propbet-Token", &s.token)], b"");
    assert_eq!(code, 200, "{session}");
    let session: serde_json::Value = serde_json::from_str(&session).unwrap();
    let ids: Vec<&str> = session["effects"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["id"].as_str().unwrap())
        .collect();
    assert!(ids.contains(&"windage") && ids.contains(&"pitch-offset"), "{ids:?}");
    let body = r#"{"state": {"effects": ["drag-scale:factor=1.5"]}, "name": "kept"}"#;
    let save = || post(&s, "/api/save", body.as_bytes());
    let (code, answer) = save();
    assert_eq!(code, 200, "{answer}");
    let saved = std::fs::read_to_string(saves.join("kept/case.toml")).unwrap();
    assert!(saved.contains("effects = [\"drag-scale:factor=1.5\"]"), "{saved}");
    assert!(saves.join("kept/effects.toml").is_file());
    // A second save of the same name writes nothing over the first.
    let (code, answer) = save();
    assert_eq!(code, 400);
    assert!(answer.contains("exists"), "{answer}");
}

#[test]
fn export_writes_what_propbet_export_writes_for_the_state() {
    // A static log: the state's prediction at the log's three RPMs (the measurements' cover)
    // over J 0 to 1, byte for byte what `propbet export --to all` writes of the same flags
    // and effects.
    let dir = tempfile::tempdir().unwrap();
    let flags = photofoil_flags();
    let s = start_with(&flags.iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
    let body = br#"{"state": {"effects": ["drag-scale:factor=1.3"]}, "name": "sim"}"#;
    let (code, answer) = post(&s, "/api/export", body);
    assert_eq!(code, 200, "{answer}");
    assert!(answer.contains("gazebo: gazebo_motor_model.sdf"), "{answer}");
    let map = std::fs::read_to_string(dir.path().join("sim/map.csv")).unwrap();
    assert!(
        map.contains("effects drag-scale:factor=1.3) at 6000,9300,12500 rpm"),
        "{map}"
    );
    let mut args = vec!["export".to_string()];
    args.extend(flags.iter().take(2).cloned());
    args.extend(
        [
            "--rpm",
            "6000,9300,12500",
            "--j",
            "0:1/21",
            "--rho",
            "1.1648",
            "--effect",
            "drag-scale:factor=1.3",
            "--to",
            "all",
            "-o",
            "cli",
        ]
        .map(String::from),
    );
    let out = run(&args.iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    let mut names: Vec<_> = std::fs::read_dir(dir.path().join("cli"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(names.len(), 5, "{names:?}");
    for n in names {
        let a = std::fs::read(dir.path().join("sim").join(&n)).unwrap();
        let b = std::fs::read(dir.path().join("cli").join(&n)).unwrap();
        assert!(a == b, "{n:?} differs");
    }
    // The folder exists now: a second export of that name writes nothing.
    let (code, answer) = post(&s, "/api/export", body);
    assert_eq!(code, 400, "{answer}");
    assert!(answer.contains("exists; nothing was written"), "{answer}");
}
