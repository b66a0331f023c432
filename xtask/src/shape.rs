//! The code's shape, measured (issue 33's "how we know it is done"): import
//! circles between a crate's files, product files' length before their tests,
//! loose files at the core's top level, hidden doc hooks, runs of lines shared
//! by the CLI and the viewer, and the README's length. `cargo xtask shape`
//! prints the report; the tests below hold the limits.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::path::{Path, PathBuf};

/// Widest import circle allowed between the files of one crate.
pub const MAX_CIRCLE: usize = 3;
/// Longest product file allowed, in lines before its `#[cfg(test)]` module.
pub const MAX_LINES: usize = 700;
/// Most `.rs` files allowed at the top of `crates/mocap/src`.
pub const MAX_LOOSE_CORE_FILES: usize = 12;
/// Longest README allowed, in lines.
pub const MAX_README_LINES: usize = 400;
/// A run of this many lines in both the CLI and the viewer counts as shared code.
pub const SHARED_RUN: usize = 6;

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![dir.to_path_buf()];
    while let Some(d) = dirs.pop() {
        for entry in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// A file's source before its test module, without comment lines.
fn product_source(text: &str) -> String {
    let before_tests = text.split("#[cfg(test)]").next().unwrap_or("");
    before_tests.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n")
}

/// The module path of a file under a crate's `src` (`viewer::apply`; the crate root is empty).
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap_or(file).with_extension("");
    let mut parts: Vec<String> = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib" || p == "main") {
        parts.pop();
    }
    parts.join("::")
}

/// The paths (`a::b::C`) a source names after `prefix` (`crate::`), brace groups
/// (`crate::{a, b::c}`) expanded one level.
fn paths_after(source: &str, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = source;
    while let Some(at) = rest.find(prefix) {
        let before = rest[..at].chars().next_back();
        rest = &rest[at + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        let path: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':').collect();
        let path = path.trim_end_matches(':').to_owned();
        let after = &rest[path.len()..].trim_start_matches(':');
        if after.starts_with('{') {
            let group: String = after[1..].chars().take_while(|c| *c != '}').collect();
            for item in group.split(',') {
                let item = item.trim().split(' ').next().unwrap_or("").trim_matches(|c| c == '{' || c == ':');
                if !item.is_empty() {
                    out.push(if path.is_empty() { item.to_owned() } else { format!("{path}::{item}") });
                }
            }
        } else if !path.is_empty() {
            out.push(path);
        }
    }
    out
}

/// The import graph of one crate: each file's module to the modules it uses
/// (through `crate::` and `super::` paths, and names imported from them).
pub fn import_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let files: Vec<(String, String)> = rust_files(src)
        .into_iter()
        .map(|f| (module_of(src, &f), product_source(&std::fs::read_to_string(&f).unwrap_or_default())))
        .collect();
    let modules: HashSet<&str> = files.iter().map(|(m, _)| m.as_str()).collect();
    let resolve = |path: &str| -> Option<String> {
        let mut parts: Vec<&str> = path.split("::").collect();
        while !parts.is_empty() {
            let candidate = parts.join("::");
            if modules.contains(candidate.as_str()) {
                return Some(candidate);
            }
            parts.pop();
        }
        None
    };
    let mut graph = BTreeMap::new();
    for (module, source) in &files {
        let is_folder = rust_files(src).iter().any(|f| module_of(src, f) == *module && f.ends_with("mod.rs"));
        let parent: Vec<&str> = if is_folder || module.is_empty() {
            module.split("::").filter(|s| !s.is_empty()).collect()
        } else {
            let mut p: Vec<&str> = module.split("::").collect();
            p.pop();
            p
        };
        let mut paths = paths_after(source, "crate::");
        for p in paths_after(source, "super::") {
            let mut base = parent.clone();
            if is_folder {
                base.pop();
            }
            let mut p = p.as_str();
            while let Some(rest) = p.strip_prefix("super::") {
                base.pop();
                p = rest;
            }
            base.push(p);
            paths.push(base.join("::"));
        }
        // `use crate::ui;` then `ui::side::show`: follow names bound to modules.
        let mut more = Vec::new();
        for path in &paths {
            let path = path.strip_suffix("::self").unwrap_or(path);
            if resolve(path).as_deref() == Some(path) {
                let name = path.rsplit("::").next().unwrap_or(path);
                for inner in paths_after(source, &format!("{name}::")) {
                    more.push(format!("{path}::{inner}"));
                }
            }
        }
        paths.extend(more);
        let uses: BTreeSet<String> =
            paths.iter().filter_map(|p| resolve(p)).filter(|t| t != module && !t.is_empty()).collect();
        graph.insert(module.clone(), uses);
    }
    graph
}

/// The graph's import circles (strongly connected sets of more than one file), widest first.
pub fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    // Iterative Tarjan: no recursion on a depth the code controls.
    let names: Vec<&String> = graph.keys().collect();
    let index_of: HashMap<&str, usize> = names.iter().enumerate().map(|(i, n)| (n.as_str(), i)).collect();
    let edges: Vec<Vec<usize>> =
        names.iter().map(|n| graph[*n].iter().filter_map(|t| index_of.get(t.as_str()).copied()).collect()).collect();
    let n = names.len();
    let (mut index, mut low, mut on_stack) = (vec![usize::MAX; n], vec![0; n], vec![false; n]);
    let (mut stack, mut next, mut out) = (Vec::new(), 0, Vec::new());
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        let mut work = vec![(root, 0usize)];
        while let Some(&mut (v, ref mut edge)) = work.last_mut() {
            if *edge == 0 && index[v] == usize::MAX {
                index[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on_stack[v] = true;
            }
            if let Some(&w) = edges[v].get(*edge) {
                *edge += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut set = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    set.push(names[w].clone());
                    if w == v {
                        break;
                    }
                }
                if set.len() > 1 {
                    set.sort();
                    out.push(set);
                }
            }
        }
    }
    out.sort_by_key(|s| std::cmp::Reverse(s.len()));
    out
}

/// Product files longer than [`MAX_LINES`] before their tests: (file, lines).
pub fn long_files(root: &Path) -> Vec<(PathBuf, usize)> {
    crate_sources(root)
        .iter()
        .flat_map(|src| rust_files(src))
        .filter_map(|f| {
            let text = std::fs::read_to_string(&f).ok()?;
            let lines = text.split("#[cfg(test)]").next().unwrap_or("").lines().count();
            (lines > MAX_LINES).then_some((f, lines))
        })
        .collect()
}

/// Every crate's `src` folder (the crates and xtask).
pub fn crate_sources(root: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    out.push(root.join("xtask/src"));
    out.sort();
    out
}

/// Files naming `#[doc(hidden)]` in product code.
pub fn hidden_hooks(root: &Path) -> Vec<PathBuf> {
    crate_sources(root)
        .iter()
        .flat_map(|src| rust_files(src))
        .filter(|f| std::fs::read_to_string(f).is_ok_and(|t| product_source(&t).contains("#[doc(hidden)]")))
        .collect()
}

/// The `.rs` files at the top of the core's `src`.
pub fn loose_core_files(root: &Path) -> Vec<PathBuf> {
    let src = root.join("crates/mocap/src");
    rust_files(&src).into_iter().filter(|f| f.parent() == Some(src.as_path())).collect()
}

/// Runs of [`SHARED_RUN`] code lines (trimmed; blank lines, comments and lone
/// brackets left out) found in both `a` and `b`: one line of each run.
pub fn shared_runs(a: &Path, b: &Path) -> Vec<String> {
    let runs = |dir: &Path| -> HashMap<Vec<String>, String> {
        let mut out = HashMap::new();
        for f in rust_files(dir) {
            let text = std::fs::read_to_string(&f).unwrap_or_default();
            let lines: Vec<String> = product_source(&text)
                .lines()
                .map(|l| l.trim().to_owned())
                .filter(|l| l.len() > 2 && !l.starts_with("use ") && !l.starts_with('#'))
                .collect();
            for w in lines.windows(SHARED_RUN) {
                out.entry(w.to_vec()).or_insert_with(|| format!("{}: {}", f.display(), w[0]));
            }
        }
        out
    };
    let (ra, rb) = (runs(a), runs(b));
    let mut shared: Vec<String> = ra.iter().filter(|(k, _)| rb.contains_key(*k)).map(|(_, v)| v.clone()).collect();
    shared.sort();
    shared
}

/// Prints the report (`cargo xtask shape`); fails when a limit is passed.
pub fn report(root: &Path) -> Result<(), String> {
    let mut problems = Vec::new();
    for src in crate_sources(root) {
        let widest = circles(&import_graph(&src));
        let width = widest.first().map_or(0, Vec::len);
        println!("{}: widest import circle {width} files {:?}", src.display(), widest.first().unwrap_or(&Vec::new()));
        if width > MAX_CIRCLE {
            problems.push(format!("{}: an import circle of {width} files", src.display()));
        }
    }
    for (f, lines) in long_files(root) {
        problems.push(format!("{}: {lines} lines before its tests (at most {MAX_LINES})", f.display()));
    }
    for f in hidden_hooks(root) {
        problems.push(format!("{}: #[doc(hidden)] in product code", f.display()));
    }
    let loose = loose_core_files(root).len();
    println!("core: {loose} loose files at the top (at most {MAX_LOOSE_CORE_FILES})");
    if loose > MAX_LOOSE_CORE_FILES {
        problems.push(format!("core: {loose} loose files at the top"));
    }
    for run in shared_runs(&root.join("crates/mocap-cli/src"), &root.join("crates/mocap-viewer/src")) {
        problems.push(format!("a {SHARED_RUN}-line run shared by the CLI and the viewer, from {run}"));
    }
    let readme = std::fs::read_to_string(root.join("README.md")).map_or(0, |t| t.lines().count());
    println!("README: {readme} lines (at most {MAX_README_LINES})");
    if readme > MAX_README_LINES {
        problems.push(format!("README.md: {readme} lines"));
    }
    if problems.is_empty() { Ok(()) } else { Err(problems.join("\n")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the repository").to_path_buf()
    }

    #[test]
    fn the_code_keeps_its_shape() {
        report(&root()).unwrap();
    }

    #[test]
    fn a_circle_is_found_through_braces_names_and_super() {
        let dir = std::env::temp_dir().join(format!("xtask-shape-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("ui")).unwrap();
        std::fs::write(dir.join("lib.rs"), "mod a; mod ui;\n").unwrap();
        std::fs::write(dir.join("a.rs"), "use crate::{ui, b::B};\nfn f() { ui::panel::show(); }\n").unwrap();
        std::fs::write(dir.join("b.rs"), "// use crate::a;\npub struct B;\n").unwrap();
        std::fs::write(dir.join("ui/mod.rs"), "pub mod panel;\n").unwrap();
        std::fs::write(dir.join("ui/panel.rs"), "use super::super::a::X;\npub fn show() {}\n").unwrap();
        let graph = import_graph(&dir);
        assert_eq!(graph["a"], ["b", "ui", "ui::panel"].into_iter().map(String::from).collect());
        assert!(graph["b"].is_empty(), "comments are not imports");
        assert_eq!(circles(&graph), vec![vec!["a".to_owned(), "ui::panel".to_owned()]]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_run_of_six_lines_in_both_folders_is_found() {
        let dir = std::env::temp_dir().join(format!("xtask-shared-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (a, b) = (dir.join("a"), dir.join("b"));
        std::fs::create_dir_all(&a).unwrap();
        std::fs::create_dir_all(&b).unwrap();
        let run: String = (0..6).map(|i| format!("    let x{i} = f({i});\n")).collect();
        std::fs::write(a.join("one.rs"), format!("fn a() {{\n{run}}}\n")).unwrap();
        std::fs::write(b.join("two.rs"), format!("fn b() {{\n    // moved here\n{run}}}\n")).unwrap();
        assert_eq!(shared_runs(&a, &b).len(), 1);
        std::fs::write(b.join("two.rs"), format!("fn b() {{\n{}}}\n", &run[..run.len() - 20])).unwrap();
        assert!(shared_runs(&a, &b).is_empty(), "five lines are not a run");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
