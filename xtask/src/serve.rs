//! A minimal static file server for `dist/` (std only). `/data/…` falls back to the
//! repository's `data/`, so `?url=data/walk.bvh` works out of the box, and
//! `/corpus/…` to `../shared/corpus` when it is there (`?url=corpus/asf_amc/cmu/01.asf&url=corpus/asf_amc/cmu/01_01.amc`).

use crate::util::root;
use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};

/// `cargo xtask serve [--port P] [--no-build]`.
pub fn serve_command(args: &[String]) -> Result<(), String> {
    let port = match args.iter().position(|a| a == "--port") {
        Some(i) => args.get(i + 1).and_then(|p| p.parse().ok()).ok_or("--port needs a number")?,
        None => 8080,
    };
    let dist = if args.iter().any(|a| a == "--no-build") {
        root().join("dist")
    } else {
        crate::dist::dist(args.iter().any(|a| a == "--fast"))?
    };
    let listener = TcpListener::bind(("127.0.0.1", port)).map_err(|e| format!("port {port}: {e}"))?;
    println!("serving {} on http://127.0.0.1:{port}/", dist.display());
    serve_forever(listener, dist);
    Ok(())
}

/// Serves `dir` on an already bound listener until the process ends.
pub fn serve_forever(listener: TcpListener, dir: PathBuf) {
    for stream in listener.incoming().flatten() {
        let dir = dir.clone();
        std::thread::spawn(move || {
            let _ = handle(stream, &dir);
        });
    }
}

fn handle(mut stream: TcpStream, dir: &Path) -> std::io::Result<()> {
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut request = String::new();
    reader.read_line(&mut request)?;
    loop {
        let mut header = String::new();
        if reader.read_line(&mut header)? == 0 || header == "\r\n" || header == "\n" {
            break;
        }
    }
    let path = request.split_whitespace().nth(1).unwrap_or("/");
    let path = path.split(['?', '#']).next().unwrap_or("/");
    let file = resolve(dir, path)
        .or_else(|| resolve(&root().join("data"), path.strip_prefix("/data/")?))
        .or_else(|| resolve(&root().join("../shared/corpus"), path.strip_prefix("/corpus/")?))
        // The benchmark's three.js page and three itself (tests/browser/node_modules).
        .or_else(|| resolve(&root().join("tests/browser"), path.strip_prefix("/bench/")?));
    match file.and_then(|f| std::fs::read(&f).ok().map(|b| (f, b))) {
        Some((f, body)) => {
            let head = format!(
                "HTTP/1.1 200 OK\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n",
                mime(&f),
                body.len()
            );
            stream.write_all(head.as_bytes())?;
            stream.write_all(&body)
        }
        None => stream.write_all(b"HTTP/1.1 404 Not Found\r\nContent-Length: 9\r\nConnection: close\r\n\r\nnot found"),
    }
}

/// Maps a URL path to a file under `dir`, refusing `..`.
fn resolve(dir: &Path, url_path: &str) -> Option<PathBuf> {
    let rel = Path::new(url_path.trim_start_matches('/'));
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return None;
    }
    let p = dir.join(rel);
    let p = if p.is_dir() { p.join("index.html") } else { p };
    p.is_file().then_some(p)
}

fn mime(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript",
        Some("wasm") => "application/wasm",
        Some("css") => "text/css",
        Some("json") => "application/json",
        Some("png") => "image/png",
        Some("svg") => "image/svg+xml",
        Some("bvh" | "BVH") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}
