//! `cargo xtask dist`: builds the wasm crate, runs wasm-bindgen (and wasm-opt when
//! available) and copies the page into `dist/`.

use crate::setup::{self, WASM_LD, WasmToolchain};
use crate::util::{root, run};
use std::path::{Path, PathBuf};
use std::process::Command;

const TARGET: &str = "wasm32-unknown-unknown";

/// Builds `dist/`; `fast` skips LTO and wasm-opt for quicker iteration. Returns the dist path.
pub fn dist(fast: bool) -> Result<PathBuf, String> {
    dist_with(fast, false, false)
}

/// [`dist`], and with `opt` wasm-opt even where the system has none recent enough:
/// then binaryen from npm (its JavaScript build: minutes on two cores, so only on
/// request: `cargo xtask dist --opt`). With `names` the wasm keeps its name
/// section (`cargo xtask dist --names`, about twice the size: for CPU profiles
/// that name each function, see `tests/browser/profile.mjs`). Prints the wasm's
/// size, raw and gzipped, before and after.
pub fn dist_with(fast: bool, opt: bool, names: bool) -> Result<PathBuf, String> {
    let root = root();
    let profile = if fast { "web-fast" } else { "web-release" };
    let target_dir = root.join("target/wasm");
    let toolchain = setup::wasm_toolchain()?;
    let mut cargo = match toolchain {
        WasmToolchain::Rustup => Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())),
        WasmToolchain::Debian => {
            let mut c = Command::new("/usr/bin/cargo");
            c.env("RUSTC", "/usr/bin/rustc")
                .env("RUSTDOC", "/usr/bin/rustdoc")
                .env("RUSTC_BOOTSTRAP", "1")
                .env("CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER", WASM_LD)
                .env_remove("RUSTUP_TOOLCHAIN")
                .env_remove("CARGO")
                .args(["-Zbuild-std=std,panic_abort"]);
            c
        }
    };
    // 128-bit SIMD (in every current browser: Chrome/Edge 91, Firefox 89, Safari
    // 16.4): the row parser's line search, the batched FK's lanes and the float
    // work elsewhere vectorise.
    let mut rustflags = String::from("-C target-feature=+simd128");
    if uses_size_flags(toolchain, fast) {
        rustflags.push(' ');
        rustflags.push_str(SIZE_FLAGS);
        cargo.arg(STD_SIZE_FEATURES);
    }
    cargo.env("CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS", rustflags);
    cargo
        .current_dir(&root)
        .args(["build", "-p", "mocap-web", "--lib", "--target", TARGET, "--profile", profile, "--target-dir"])
        .arg(&target_dir);
    run(&mut cargo)?;
    let wasm = target_dir.join(TARGET).join(profile).join("mocap_web.wasm");
    if !fast {
        optimize(&wasm, opt, names);
    }

    let dist = root.join("dist");
    let _ = std::fs::remove_dir_all(&dist);
    let pkg = dist.join("pkg");
    std::fs::create_dir_all(&pkg).map_err(|e| format!("{}: {e}", pkg.display()))?;
    let bindgen = setup::wasm_bindgen_cli()?;
    let mut bindgen = Command::new(bindgen);
    bindgen.args(["--target", "web", "--remove-producers-section"]);
    if !names {
        bindgen.arg("--remove-name-section");
    }
    run(bindgen.arg("--out-dir").arg(&pkg).arg(&wasm))?;
    let (raw, gz) = sizes(&pkg.join("mocap_web_bg.wasm"));
    println!("xtask: mocap_web_bg.wasm {raw} bytes, {gz} gzipped");
    copy(&root.join("index.html"), &dist.join("index.html"))?;
    copy_dir(&root.join("web"), &dist.join("web"))?;
    bundle_video_export(&root, &dist);
    // The worker's template is filled in after minifying (which would drop its placeholders).
    let template = dist.join("web/sw.js");
    let worker = std::fs::read_to_string(&template).map_err(|e| format!("{}: {e}", template.display()))?;
    let _ = std::fs::remove_file(&template);
    if !fast {
        minify_js(&dist);
    }
    write_service_worker(&dist, &worker)?;
    println!("dist: {}", dist.display());
    Ok(dist)
}

/// Size flags for the release build where std is built with it (the Debian
/// toolchain's `-Zbuild-std`; a rustup target's std is prebuilt and stable rustc
/// refuses `-Z`). Measured on the web-release wasm, gzipped: 2,244,935 bytes
/// without them, 2,118,629 with the first two, 2,065,809 with all.
/// - `-Zfmt-debug=shallow`: derived `Debug` prints type and variant names only
///   (nothing user-facing prints a derived `Debug` of a value with fields);
/// - `-Zlocation-detail=none`: no file names, lines and columns kept for panics;
/// - `-Cpanic=immediate-abort`: a panic traps at once without formatting its
///   message. The page installs no panic hook, so a message was never shown:
///   the browser reports "unreachable" either way.
const SIZE_FLAGS: &str = "-Zfmt-debug=shallow -Zlocation-detail=none -Zunstable-options -Cpanic=immediate-abort";

/// The standard library built for size where it is built from source (with
/// [`SIZE_FLAGS`]): `optimize_for_size` swaps std's sorts for a merge sort
/// (stable) and a heapsort (unstable), both O(n log n), instead of driftsort and
/// ipnsort, each monomorphised per element type, and picks smaller integer
/// formatting, string escaping and slice rotation. The core's hot float parsing
/// is its own (`decimal.rs`, fast_float2), so std's float parser losing its fast
/// path costs only header numbers. Measured on the web-release wasm, gzipped:
/// 2,046,971 -> 1,998,030 bytes.
const STD_SIZE_FEATURES: &str = "-Zbuild-std-features=optimize_for_size";

/// Whether a build with `toolchain` gets [`SIZE_FLAGS`] (release builds with std
/// built from source).
fn uses_size_flags(toolchain: WasmToolchain, fast: bool) -> bool {
    toolchain == WasmToolchain::Debian && !fast
}

/// Oldest wasm-opt trusted with current Rust output: 108 (Debian 12) breaks the
/// externref table when run after wasm-bindgen and grows the gzipped size before it.
const MIN_WASM_OPT: u32 = 116;

/// Shrinks the cargo output with `wasm-opt -Os --strip-debug` (before
/// wasm-bindgen) when a recent enough binaryen is available (the system's, or with
/// `npm_fallback` npm's); keeps the input on any failure. With `names` it keeps
/// the name section (`-g` for `--strip-debug`).
fn optimize(wasm: &Path, npm_fallback: bool, names: bool) {
    let system = setup::wasm_opt().map(PathBuf::from).filter(|w| wasm_opt_version(w) >= MIN_WASM_OPT);
    let Some(wasm_opt) = system.or_else(|| npm_fallback.then(setup::npm_wasm_opt).flatten()) else {
        eprintln!(
            "xtask: no wasm-opt {MIN_WASM_OPT} or newer (cargo xtask dist --opt uses npm's binaryen); skipping size optimisation"
        );
        return;
    };
    let out = wasm.with_extension("opt.wasm");
    let features = [
        "--enable-bulk-memory",
        "--enable-nontrapping-float-to-int",
        "--enable-sign-ext",
        "--enable-mutable-globals",
        "--enable-reference-types",
        "--enable-multivalue",
        "--enable-simd",
    ];
    let before = sizes(wasm);
    let started = std::time::Instant::now();
    let debug = if names { "-g" } else { "--strip-debug" };
    let ok = run(Command::new(&wasm_opt).args(["-Os", debug]).args(features).arg(wasm).arg("-o").arg(&out)).is_ok();
    if ok && std::fs::rename(&out, wasm).is_ok() {
        let after = sizes(wasm);
        println!(
            "xtask: wasm-opt -Os in {:.0} s: {} -> {} bytes raw, {} -> {} gzipped",
            started.elapsed().as_secs_f64(),
            before.0,
            after.0,
            before.1,
            after.1
        );
        return;
    }
    let _ = std::fs::remove_file(&out);
    eprintln!("xtask: wasm-opt failed; keeping the unoptimised wasm");
}

/// Writes the service worker (`web/sw.js`) at the root of `dist/` (its scope is
/// the folder it is served from) with the list of the page's files to cache
/// (everything in `dist/` but the API examples) and a version that changes with
/// their contents, so that a new build replaces the cache.
fn write_service_worker(dist: &Path, text: &str) -> Result<(), String> {
    let mut files = Vec::new();
    let mut dirs = vec![dist.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for path in entries.flatten().map(|e| e.path()) {
            if path.is_dir() {
                if !path.ends_with("examples") {
                    dirs.push(path);
                }
            } else if let Ok(rel) = path.strip_prefix(dist) {
                files.push(rel.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    files.sort();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for f in &files {
        for b in f.bytes().chain(std::fs::read(dist.join(f)).unwrap_or_default()) {
            hash = (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    let list: Vec<String> = std::iter::once("'./'".to_owned()).chain(files.iter().map(|f| format!("'{f}'"))).collect();
    let text = text.replace("/*FILES*/", &list.join(", ")).replace("/*VERSION*/", &format!("{hash:016x}"));
    let out = dist.join("sw.js");
    std::fs::write(&out, text).map_err(|e| format!("{}: {e}", out.display()))
}

/// Bundles `web/video-export.js` with its npm packages (mediabunny, gifenc from
/// `tests/browser/node_modules`) into one module in `dist/web/`: the page loads
/// it on first export, from its own origin (the CSP allows nothing else).
/// Without esbuild the unbundled file stays and the page says video export
/// could not start.
fn bundle_video_export(root: &Path, dist: &Path) {
    let Some(esbuild) = setup::esbuild() else {
        eprintln!("xtask: no esbuild (npm install in tests/browser); video export is not bundled");
        return;
    };
    let out = dist.join("web/video-export.js");
    let ok = run(Command::new(&esbuild)
        .arg(root.join("web/video-export.js"))
        .args(["--bundle", "--format=esm", "--log-level=warning"])
        .arg(format!("--outfile={}", out.display()))
        .env("NODE_PATH", root.join("tests/browser/node_modules")))
    .is_ok();
    if ok {
        println!("xtask: bundled {}: {} bytes gzipped", out.display(), sizes(&out).1);
    } else {
        eprintln!("xtask: esbuild could not bundle web/video-export.js; video export will not start");
    }
}

/// Minifies the page's JavaScript in `dist/` (wasm-bindgen's glue and `web/*.js`)
/// with esbuild from npm (`tests/browser`'s packages): 38 -> 27 KB gzipped. The
/// sources stay as they are; without esbuild the files are served unminified.
fn minify_js(dist: &Path) {
    let Some(esbuild) = setup::esbuild() else {
        eprintln!("xtask: no esbuild (npm install in tests/browser); the page's JavaScript stays unminified");
        return;
    };
    let mut files = vec![dist.join("pkg/mocap_web.js")];
    if let Ok(entries) = std::fs::read_dir(dist.join("web")) {
        files.extend(entries.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "js")));
    }
    for file in files {
        let before = sizes(&file);
        let out = file.with_extension("min.js");
        let ok = run(Command::new(&esbuild)
            .arg(&file)
            .args(["--minify", "--format=esm", "--log-level=warning"])
            .arg(format!("--outfile={}", out.display())))
        .is_ok();
        if ok && std::fs::rename(&out, &file).is_ok() {
            let after = sizes(&file);
            println!("xtask: minified {}: {} -> {} bytes gzipped", file.display(), before.1, after.1);
        } else {
            let _ = std::fs::remove_file(&out);
            eprintln!("xtask: esbuild failed on {}; kept as it is", file.display());
        }
    }
}

/// A wasm-opt's version number (0 when it cannot say).
fn wasm_opt_version(wasm_opt: &Path) -> u32 {
    crate::util::output(Command::new(wasm_opt).arg("--version"))
        .and_then(|v| v.split_whitespace().nth(2).and_then(|n| n.parse::<u32>().ok()))
        .unwrap_or(0)
}

/// Most the page may weigh, gzipped: 2.5 MB (issue 34's limit once glTF and
/// retargeting are in the page; 2.0 MB before), read as the stricter decimal
/// 2,500,000 bytes.
pub const DOWNLOAD_AIM: u64 = 2_500_000;

/// The page's download, gzipped (`gzip -9 -n`): every wasm, JavaScript, HTML and CSS
/// file in `dist` (the API examples' pages too). `bench-web` prints it and
/// `cargo xtask test` checks it against [`DOWNLOAD_AIM`].
pub fn download_size(dist: &Path) -> u64 {
    let mut total = 0;
    let mut dirs = vec![dist.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| ["wasm", "js", "html", "css"].iter().any(|x| e == *x)) {
                total += sizes(&path).1;
            }
        }
    }
    total
}

/// Fails when the release page built with the size flags ([`SIZE_FLAGS`]: the
/// Debian toolchain's build) weighs more than [`DOWNLOAD_AIM`] gzipped, or when
/// nothing could be measured (no gzip). A rustup build, without the flags, is
/// only reported.
pub fn check_download_size(dist: &Path) -> Result<(), String> {
    let total = download_size(dist);
    let flagged = setup::wasm_toolchain().is_ok_and(|t| uses_size_flags(t, false));
    println!("xtask: the page's download is {total} bytes gzipped (aim: at most {DOWNLOAD_AIM})");
    if total == 0 {
        return Err("download size: nothing measured (is gzip installed?)".into());
    }
    if flagged && total > DOWNLOAD_AIM {
        return Err(format!(
            "download size: {total} bytes gzipped, over the {DOWNLOAD_AIM}-byte aim (see docs/performance.md)"
        ));
    }
    Ok(())
}

/// A file's size raw and gzipped (`gzip -9 -n`: no name stored; 0 when gzip is missing).
pub fn sizes(file: &Path) -> (u64, u64) {
    let raw = std::fs::metadata(file).map_or(0, |m| m.len());
    let gz =
        crate::util::output(Command::new("sh").arg("-c").arg(format!("gzip -9 -n -c '{}' | wc -c", file.display())))
            .and_then(|s| s.trim().parse().ok())
            .unwrap_or(0);
    (raw, gz)
}

fn copy(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::copy(from, to).map(|_| ()).map_err(|e| format!("copy {} -> {}: {e}", from.display(), to.display()))
}

fn copy_dir(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries.flatten() {
        let path = entry.path();
        let dest = to.join(entry.file_name());
        if path.is_dir() { copy_dir(&path, &dest)? } else { copy(&path, &dest)? }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn download_size_counts_the_page_files_in_every_folder_and_nothing_else() {
        let dir = std::env::temp_dir().join(format!("xtask-download-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("web/examples")).unwrap();
        let text = "let a = 1;\n".repeat(200);
        for f in ["index.html", "web/main.js", "web/examples/x.css", "pkg.wasm"] {
            std::fs::write(dir.join(f), &text).unwrap();
        }
        std::fs::write(dir.join("types.d.ts"), "x".repeat(10_000)).unwrap();
        std::fs::write(dir.join("notes.txt"), "x".repeat(10_000)).unwrap();
        let one = super::sizes(&dir.join("index.html")).1;
        assert!(one > 0, "gzip measured something");
        assert_eq!(super::download_size(&dir), 4 * one);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
