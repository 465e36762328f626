//! `propbet serve`: the workbench, a page on 127.0.0.1 that drives the model against a case's
//! measurements. The engine is [`propbet_api::workbench`]; this crate is its HTTP door: the
//! page and its assets (built into the binary, uPlot vendored from npm), the JSON API and the
//! guards every request passes.
//!
//! **API** (every `/api/` request carries the token: `?token=` or the `X-Propbet-Token`
//! header; every request's `Host` is a loopback name):
//!
//! | request | body | answer |
//! |---|---|---|
//! | `GET /api/session` | | the case, its starting state, the effects offered, whether Save can write a case |
//! | `POST /api/evaluate` | a state | `compare`'s `summary.json` for it, the curves and points |
//! | `POST /api/fit` | `{"state": ..., "effect": id}` | the effect fitted, the new state |
//! | `POST /api/diagnose` | a state | `diagnosis.json`'s document (the ladder from the state) |
//! | `POST /api/save` | `{"state": ..., "name": folder}` | the case folder written |
//! | `POST /api/export` | `{"state": ..., "name": folder}` | the simulator files written, one line each |
//!
//! A state is `{"effects": ["pitch-offset:deg=-0.8"]}` (a case file's keys). An error is a
//! 4xx answer `{"error": message}`, the message the command line prints.

use std::io::{Read as _, Write as _};
use std::path::PathBuf;
use std::sync::Arc;

use propbet_api::console::Console;
use propbet_api::spec::{MeasuredSpec, ModelSpec, XfoilProcessSpec};
use propbet_api::workbench::{State, Workbench};
use propbet_api::{CommandError, CommandResult};
use serde::Deserialize;
use tiny_http::{Header, Method, Request, Response, Server};

/// The largest request body read [bytes].
pub const MAX_BODY: usize = 1 << 20;

/// The header a script may carry the token in.
pub const TOKEN_HEADER: &str = "X-Propbet-Token";

const INDEX: &str = include_str!("../assets/index.html");
const APP_JS: &str = include_str!("../assets/app.js");
const APP_CSS: &str = include_str!("../assets/app.css");
const UPLOT_JS: &str = include_str!("../assets/vendor/uplot/uPlot.iife.min.js");
const UPLOT_CSS: &str = include_str!("../assets/vendor/uplot/uPlot.min.css");
const UPLOT_LICENSE: &str = include_str!("../assets/vendor/uplot/LICENSE");

/// Where the workbench's model and measurements come from.
#[derive(Debug)]
pub enum Source {
    /// A case folder holding `case.toml` with `[measured]` files (None: the shipped default
    /// case, `props/apcsp_10x7`).
    Case(Option<PathBuf>),
    /// `compare`'s flags: a model and measurements.
    Flags(Box<(ModelSpec, MeasuredSpec)>),
}

/// `propbet serve`'s own flags.
#[derive(Debug, clap::Args)]
pub struct ServeOptions {
    /// Port on 127.0.0.1 (default: a free one).
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// Open the page in the browser (`$BROWSER`, else `xdg-open`).
    #[arg(long)]
    pub open: bool,
    /// Folder the page's Save writes its case folders into (each a new folder in it).
    #[arg(long, default_value = ".")]
    pub save_to: PathBuf,
    /// Read files the case names outside its folder.
    #[arg(long)]
    pub inputs_anywhere: bool,
}

/// Runs `propbet serve`: the model and measurements of `source` read (the polars from the
/// cache or `xfoil`'s engine), the URL printed (one line on standard output), then requests
/// answered until the process ends; returns only on an error before it listens.
pub fn run(source: &Source, xfoil: &XfoilProcessSpec, a: &ServeOptions, console: &dyn Console) -> CommandResult<()> {
    if !a.save_to.is_dir() {
        return Err(CommandError::Message(format!(
            "--save-to {}: not a folder",
            a.save_to.display()
        )));
    }
    let server = bind(a.port).map_err(CommandError::Message)?;
    let port = port_of(&server);
    eprintln!("propbet serve: reading the model and the measurements (polars from the cache or XFOIL) ...");
    let workbench = match source {
        Source::Case(dir) => Workbench::open(dir.as_deref(), xfoil, a.inputs_anywhere)?,
        Source::Flags(specs) => Workbench::of_specs(&specs.0, &specs.1, console)?,
    };
    let token = token().map_err(|e| CommandError::io("/dev/urandom", e))?;
    let url = format!("http://127.0.0.1:{port}/?token={token}");
    println!("{url}");
    let _ = std::io::stdout().flush();
    eprintln!(
        "propbet serve: {} on 127.0.0.1:{port}; Save writes into {}; Ctrl-C ends it",
        workbench.name,
        a.save_to.display()
    );
    if a.open {
        let browser = std::env::var("BROWSER").unwrap_or_else(|_| "xdg-open".into());
        if let Err(e) = std::process::Command::new(&browser).arg(&url).spawn() {
            eprintln!("propbet serve: warning: {browser} did not start ({e}); open the URL above");
        }
    }
    let bench = Bench {
        workbench,
        token,
        save_root: a.save_to.clone(),
        port,
    };
    serve(server, Arc::new(bench));
    Ok(())
}

/// A running workbench: the engine, its token, where Save writes.
pub struct Bench {
    /// The engine.
    pub workbench: Workbench,
    /// The token every API request must carry.
    pub token: String,
    /// Where Save writes its case folders.
    pub save_root: PathBuf,
    /// The port it listens on (the Host header must name it).
    pub port: u16,
}

/// A random token: 16 bytes of the system's random source, in hex.
pub fn token() -> std::io::Result<String> {
    let mut b = [0u8; 16];
    std::fs::File::open("/dev/urandom")?.read_exact(&mut b)?;
    Ok(b.iter().map(|x| format!("{x:02x}")).collect())
}

/// Binds 127.0.0.1 on `port` (0: a free one).
pub fn bind(port: u16) -> Result<Server, String> {
    Server::http(("127.0.0.1", port)).map_err(|e| format!("cannot listen on 127.0.0.1:{port}: {e}"))
}

/// The port `server` listens on.
pub fn port_of(server: &Server) -> u16 {
    server.server_addr().to_ip().map_or(0, |a| a.port())
}

/// Answers requests until the process ends, each on its own thread.
pub fn serve(server: Server, bench: Arc<Bench>) {
    for request in server.incoming_requests() {
        let bench = bench.clone();
        std::thread::spawn(move || {
            let answer = handle(&bench, request);
            if let Err(e) = answer {
                eprintln!("propbet serve: a request could not be answered: {e}");
            }
        });
    }
}

/// An answer: status and JSON or a page.
struct Answer {
    status: u16,
    kind: &'static str,
    body: Vec<u8>,
}

impl Answer {
    fn json(status: u16, v: &serde_json::Value) -> Self {
        Answer {
            status,
            kind: "application/json",
            body: serde_json::to_vec(v).unwrap_or_default(),
        }
    }
    fn error(status: u16, message: impl std::fmt::Display) -> Self {
        Self::json(status, &serde_json::json!({ "error": message.to_string() }))
    }
    fn text(kind: &'static str, body: &str) -> Self {
        Answer {
            status: 200,
            kind,
            body: body.as_bytes().to_vec(),
        }
    }
}

fn handle(bench: &Bench, mut request: Request) -> std::io::Result<()> {
    let answer = answer(bench, &mut request);
    let mut response = Response::from_data(answer.body).with_status_code(answer.status);
    for (k, v) in [
        ("Content-Type", answer.kind),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
        ("Referrer-Policy", "no-referrer"),
    ] {
        if let Ok(h) = Header::from_bytes(k.as_bytes(), v.as_bytes()) {
            response.add_header(h);
        }
    }
    request.respond(response)
}

fn header<'r>(request: &'r Request, name: &str) -> Option<&'r str> {
    request
        .headers()
        .iter()
        .find(|h| h.field.as_str().as_str().eq_ignore_ascii_case(name))
        .map(|h| h.value.as_str())
}

/// Whether `host` (a Host header) names this machine's loopback at `port`: the guard against
/// a page of another site reaching the server through a name it rebinds to 127.0.0.1.
pub fn loopback_host(host: &str, port: u16) -> bool {
    let (name, p) = match host.rsplit_once(':') {
        Some((n, p)) if !n.ends_with(']') || host.starts_with('[') => (n, p.parse::<u16>().ok()),
        _ => (host, None),
    };
    let name_ok = matches!(name, "127.0.0.1" | "localhost" | "[::1]");
    name_ok && p == Some(port)
}

/// The query's `token` value, if any.
fn query_token(url: &str) -> Option<&str> {
    let q = url.split_once('?')?.1;
    q.split('&').find_map(|kv| kv.strip_prefix("token="))
}

fn answer(bench: &Bench, request: &mut Request) -> Answer {
    let host = header(request, "Host").unwrap_or("");
    if !loopback_host(host, bench.port) {
        return Answer::error(403, format!("refused: Host {host:?} is not this machine's loopback"));
    }
    let url = request.url().to_string();
    let path = url.split('?').next().unwrap_or("");
    let method = request.method().clone();
    let token = header(request, TOKEN_HEADER).or_else(|| query_token(&url));
    let authorised = token.is_some_and(|t| same(t, &bench.token));
    match (&method, path) {
        (Method::Get, "/assets/app.js") => return Answer::text("text/javascript; charset=utf-8", APP_JS),
        (Method::Get, "/assets/app.css") => return Answer::text("text/css; charset=utf-8", APP_CSS),
        (Method::Get, "/assets/uPlot.iife.min.js") => return Answer::text("text/javascript; charset=utf-8", UPLOT_JS),
        (Method::Get, "/assets/uPlot.min.css") => return Answer::text("text/css; charset=utf-8", UPLOT_CSS),
        (Method::Get, "/assets/uPlot-LICENSE") => return Answer::text("text/plain; charset=utf-8", UPLOT_LICENSE),
        _ => {}
    }
    if !authorised {
        return Answer::error(401, "refused: the request does not carry this workbench's token");
    }
    if method == Method::Get && path == "/" {
        return Answer::text("text/html; charset=utf-8", INDEX);
    }
    if method == Method::Get && path == "/api/session" {
        let w = &bench.workbench;
        return Answer::json(
            200,
            &serde_json::json!({
                "name": w.name, "case": w.dir.display().to_string(), "start": w.start, "effects": w.offers(),
                "can_save": w.from_case,
            }),
        );
    }
    if method != Method::Post {
        return Answer::error(404, format!("no such page: {} {path}", method.as_str()));
    }
    let body = match read_body(request) {
        Ok(b) => b,
        Err(a) => return a,
    };
    let w = &bench.workbench;
    let result = match path {
        "/api/evaluate" => parse::<State>(&body).and_then(|s| w.evaluate(&s).map_err(|e| e.to_string())),
        "/api/fit" => parse::<FitRequest>(&body).and_then(|f| {
            let (spec, state) = w.fit(&f.state, &f.effect).map_err(|e| e.to_string())?;
            Ok(serde_json::json!({"effect": spec, "state": state}))
        }),
        "/api/diagnose" => parse::<State>(&body).and_then(|s| w.diagnose(&s).map_err(|e| e.to_string())),
        "/api/save" => parse::<SaveRequest>(&body).and_then(|r| {
            let folder = w.save(&r.state, &bench.save_root, &r.name).map_err(|e| e.to_string())?;
            Ok(serde_json::json!({"folder": folder.display().to_string()}))
        }),
        "/api/export" => parse::<SaveRequest>(&body).and_then(|r| {
            let (folder, files) = w
                .export(&r.state, &bench.save_root, &r.name)
                .map_err(|e| e.to_string())?;
            Ok(serde_json::json!({"folder": folder.display().to_string(), "files": files}))
        }),
        _ => return Answer::error(404, format!("no such API: {path}")),
    };
    match result {
        Ok(v) => Answer::json(200, &v),
        Err(e) => Answer::error(400, e),
    }
}

/// Compares two tokens in time independent of where they differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

fn read_body(request: &mut Request) -> Result<Vec<u8>, Answer> {
    if request.body_length().is_some_and(|n| n > MAX_BODY) {
        return Err(Answer::error(
            413,
            format!("refused: a request body is at most {MAX_BODY} bytes"),
        ));
    }
    let mut body = Vec::new();
    let read = request.as_reader().take(MAX_BODY as u64 + 1).read_to_end(&mut body);
    if let Err(e) = read {
        return Err(Answer::error(400, format!("the request body could not be read: {e}")));
    }
    if body.len() > MAX_BODY {
        return Err(Answer::error(
            413,
            format!("refused: a request body is at most {MAX_BODY} bytes"),
        ));
    }
    Ok(body)
}

fn parse<T: for<'de> Deserialize<'de>>(body: &[u8]) -> Result<T, String> {
    serde_json::from_slice(body).map_err(|e| format!("the request is not a state the workbench reads: {e}"))
}

/// `POST /api/fit`'s body.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FitRequest {
    state: State,
    effect: String,
}

/// `POST /api/save`'s body.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SaveRequest {
    state: State,
    name: String,
}

#[cfg(test)]
mod tests;
