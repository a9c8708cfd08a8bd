//! rodnet's layers (docs/architecture.md): each top-level module of `src/` may import only the
//! modules listed for it, up to `cli`, which may import all. Reads the sources as text: every `crate::<module>` path outside a
//! `#[cfg(test)] mod tests` block counts, doc links included.

use std::collections::BTreeSet;
use std::path::Path;

const LAYERS: &[(&str, &[&str])] = &[
    ("math", &[]),
    ("rod", &["math"]),
    ("surface", &["math"]),
    ("scene", &["math", "rod", "surface"]),
    ("variables", &["math", "rod"]),
    ("energy", &["math", "rod", "variables"]),
    ("solver", &[]),
    (
        "network",
        &[
            "math",
            "rod",
            "scene",
            "surface",
            "variables",
            "energy",
            "solver",
        ],
    ),
    ("io", &["math", "network", "scene", "solver"]),
    ("pipeline", &["io", "network", "scene", "solver"]),
    // The commands' jobs beyond a plain solve (buckle, states, indent, modes): each runs the
    // pipeline's flow, and the pipeline knows none of them.
    ("jobs", &["io", "network", "scene", "solver", "pipeline"]),
    // The jobs above the pipeline: nothing below `cli` imports `cli`, so that sweeps and Python
    // share the jobs' options and checks without the command line.
    (
        "gridshell",
        &[
            "math",
            "rod",
            "surface",
            "scene",
            "variables",
            "energy",
            "solver",
            "network",
            "io",
            "pipeline",
            "jobs",
        ],
    ),
    (
        "study",
        &[
            "math",
            "rod",
            "surface",
            "scene",
            "variables",
            "energy",
            "solver",
            "network",
            "io",
            "pipeline",
            "jobs",
            "gridshell",
        ],
    ),
    (
        "sweep",
        &[
            "math",
            "rod",
            "surface",
            "scene",
            "variables",
            "energy",
            "solver",
            "network",
            "io",
            "pipeline",
            "jobs",
            "gridshell",
            "study",
        ],
    ),
    (
        "cli",
        &[
            "math",
            "rod",
            "surface",
            "scene",
            "variables",
            "energy",
            "solver",
            "network",
            "io",
            "pipeline",
            "jobs",
            "gridshell",
            "study",
            "sweep",
        ],
    ),
];

/// Every module of `src/` has its row: a new module states its layer.
#[test]
fn every_module_has_a_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    for e in std::fs::read_dir(&src).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        if name == "lib" || name == "main" {
            continue;
        }
        assert!(
            LAYERS.iter().any(|(l, _)| *l == name),
            "src/{name} is in no layer of tests/layers.rs (docs/architecture.md, Layers)"
        );
    }
}

fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn imports(text: &str) -> BTreeSet<String> {
    let code = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    code.match_indices("crate::")
        .map(|(i, _)| {
            code[i + 7..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect()
        })
        .collect()
}

#[test]
fn lower_layers_import_nothing_above_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut bad = Vec::new();
    for (layer, allowed) in LAYERS {
        let mut files = Vec::new();
        let dir = src.join(layer);
        if dir.is_dir() {
            sources(&dir, &mut files);
        } else {
            files.push(src.join(format!("{layer}.rs")));
        }
        assert!(!files.is_empty(), "no sources for layer {layer}");
        for f in files {
            let text = std::fs::read_to_string(&f).unwrap();
            for m in imports(&text) {
                if m != *layer && !allowed.contains(&m.as_str()) {
                    bad.push(format!("{} imports crate::{m}", f.display()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "layer violations:\n{}", bad.join("\n"));
}

/// The modules of `network/` (by file or folder) that module `m` names, through
/// `crate::network::X` or `super::X` (`super::super::X` inside a folder), outside comments and
/// its tests.
fn network_uses(text: &str, in_folder: bool) -> BTreeSet<String> {
    let code = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    let code: String = code
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    let prefixes: &[&str] = if in_folder {
        &["crate::network::", "super::super::"]
    } else {
        &["crate::network::", "super::"]
    };
    let mut out = BTreeSet::new();
    for p in prefixes {
        for (i, _) in code.match_indices(p) {
            let name: String = code[i + p.len()..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            out.insert(name);
        }
    }
    out
}

/// `network/`'s modules form no import cycle (docs/architecture.md): each may use those below
/// it, never one that uses it back.
#[test]
fn network_modules_have_no_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/network");
    let mut graph: std::collections::BTreeMap<String, BTreeSet<String>> = Default::default();
    let mut files = Vec::new();
    sources(&root, &mut files);
    for f in &files {
        let rel = f.strip_prefix(&root).unwrap();
        let top = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        if top == "mod" {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        let uses = network_uses(&text, rel.components().count() > 1);
        graph.entry(top.clone()).or_default().extend(uses);
    }
    let names: BTreeSet<String> = graph.keys().cloned().collect();
    for v in graph.values_mut() {
        v.retain(|d| names.contains(d));
    }
    let reaches = |from: &str, to: &str| {
        let mut stack = vec![from.to_string()];
        let mut seen = BTreeSet::new();
        while let Some(v) = stack.pop() {
            for w in &graph[&v] {
                if w == to {
                    return true;
                }
                if seen.insert(w.clone()) {
                    stack.push(w.clone());
                }
            }
        }
        false
    };
    let cycles: Vec<String> = graph
        .iter()
        .flat_map(|(a, ds)| ds.iter().filter(move |b| *b != a).map(move |b| (a, b)))
        .filter(|(a, b)| reaches(b, a))
        .map(|(a, b)| format!("network::{a} uses network::{b}, which leads back to it"))
        .collect();
    assert!(cycles.is_empty(), "{}", cycles.join("\n"));
}
