//! Project tasks: `cargo xtask <command>`.
//!
//! - `gen-walk`            regenerate `data/walk.bvh` (our procedural walk cycle) and
//!                         `data/walk.bva` (the same walk converted by `mocap`)
//! - `gen-fonts`           regenerate `data/fonts/` (the viewer's fonts, made from egui's)
//! - `dist [--fast|--opt]`  build the web viewer into `dist/` (static, relative URLs; --opt: wasm-opt from npm when the system's is too old)
//! - `serve [--port P]`    build, then serve `dist/` on http://127.0.0.1:P (default 8080)
//! - `test`                `cargo test --workspace`, then the headless browser tests
//! - `bench-web`           drop-to-first-frame, frame time and transfer size in the browser
//! - `setup`               install what the web build and browser tests need
//! - `shape`               the code's shape: import circles, file lengths, shared runs (limits in `shape.rs`)
//! - `gltf-files DIR`      write the glTF files the browser suite checks into DIR (`gltf_files.rs`)
//!
//! Missing tools are installed on first use (apt-get packages, wasm-bindgen-cli,
//! chromium, npm `playwright-core`).

mod browser;
mod dist;
mod fonts;
mod gltf_files;
mod python;
mod serve;
mod setup;
mod shape;
mod util;
mod walk;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("gen-walk") => gen_walk(),
        Some("gen-fonts") => fonts::gen_fonts(),
        Some("dist") => {
            let flag = |name: &str| args.iter().any(|a| a == name);
            dist::dist_with(flag("--fast"), flag("--opt"), flag("--names")).map(|_| ())
        }
        Some("serve") => serve::serve_command(&args[1..]),
        Some("test") => browser::test_all(&args[1..]),
        Some("bench-web") => browser::bench(),
        Some("setup") => setup::setup_all(),
        Some("shape") => shape::report(&util::root()),
        Some("gltf-files") => match args.get(1) {
            Some(dir) => {
                let corpus = util::root().join("../shared/corpus");
                gltf_files::write(std::path::Path::new(dir), corpus.is_dir().then_some(corpus.as_path())).map(|d| {
                    println!("wrote {}", d.display());
                })
            }
            None => Err("usage: cargo xtask gltf-files DIR".into()),
        },
        _ => Err("usage: cargo xtask <gen-walk | gen-fonts | dist [--fast|--opt] | serve [--port P] | test | bench-web | setup | shape | gltf-files DIR>".to_string()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn gen_walk() -> Result<(), String> {
    for (name, text) in [("data/walk.bvh", walk::walk_bvh()), ("data/walk.bva", walk::walk_bva()?)] {
        let path = util::root().join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
