//! The examples in the docs work: every ```ron block of docs/scene-format.md and docs/contract.md
//! (and of the shared contract, when ../shared is beside the repository) parses and validates,
//! and every command in the ```sh blocks of docs/cli.md runs and succeeds. docs/contract.md keeps
//! every name of the shared contract and names every key the results JSON can contain.

use std::path::Path;
use std::process::Command;

/// The bodies of the fenced blocks of `lang` in a Markdown text.
fn blocks(md: &str, lang: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current: Option<String> = None;
    for line in md.lines() {
        match &mut current {
            None if line.trim_start() == format!("```{lang}") => current = Some(String::new()),
            Some(body) if line.trim_start().starts_with("```") => {
                out.push(std::mem::take(body));
                current = None;
            }
            Some(body) => {
                body.push_str(line);
                body.push('\n');
            }
            None => {}
        }
    }
    out
}

#[test]
fn scene_format_examples_parse_and_validate() {
    let md = std::fs::read_to_string("docs/scene-format.md").unwrap();
    let scenes = blocks(&md, "ron");
    assert!(scenes.len() >= 2, "found {} ron blocks", scenes.len());
    for (k, src) in scenes.iter().enumerate() {
        let sc = rodnet::scene::parse(&format!("docs/scene-format.md block {k}"), src)
            .unwrap_or_else(|e| panic!("{e}\n{src}"));
        // Building catches what only the builder checks (joint positions, hinge axes).
        rodnet::network::build(&sc).unwrap_or_else(|e| panic!("block {k}: {e:?}"));
    }
}

#[test]
fn contract_example_parses() {
    let own = std::fs::read_to_string("docs/contract.md").unwrap();
    // The shared contract lives beside the repository, not in it; checked when it is there.
    let shared = std::fs::read_to_string("../shared/contract.md").ok();
    for (name, md) in [
        ("docs/contract.md", Some(own)),
        ("../shared/contract.md", shared),
    ] {
        let Some(md) = md else { continue };
        let scenes = blocks(&md, "ron");
        assert!(!scenes.is_empty(), "{name}: no ron block");
        for src in scenes {
            rodnet::scene::parse(name, &src).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}

/// The names in the code of a Markdown text (inline `code` spans and fenced blocks): runs of
/// letters, digits and `_` with at least one letter, and `--options`.
fn code_names(md: &str) -> std::collections::BTreeSet<String> {
    let mut code = String::new();
    let mut fenced = false;
    for line in md.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if fenced {
            code.push_str(line);
            code.push('\n');
        } else {
            for (k, span) in line.split('`').enumerate() {
                if k % 2 == 1 {
                    code.push_str(span);
                    code.push('\n');
                }
            }
        }
    }
    let mut names = std::collections::BTreeSet::new();
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    for token in code.split(|c: char| !(word(c) || c == '-')) {
        for part in token.split("--").filter(|p| !p.is_empty()) {
            for w in part.split('-') {
                if w.chars().any(|c| c.is_ascii_alphabetic()) && w.chars().all(word) {
                    names.insert(w.to_string());
                }
            }
        }
        if let Some(opt) = token.strip_prefix("--") {
            if !opt.is_empty() {
                names.insert(format!("--{opt}"));
            }
        }
    }
    names
}

#[test]
fn own_contract_keeps_every_shared_name() {
    // CI always has ../shared beside the clone; without it this check would pass unseen.
    let shared = std::fs::read_to_string("../shared/contract.md").expect(
        "../shared/contract.md must sit beside the clone (the outside contract this test compares against)",
    );
    let own = code_names(&std::fs::read_to_string("docs/contract.md").unwrap());
    let missing: Vec<String> = code_names(&shared)
        .into_iter()
        .filter(|n| !own.contains(n))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/contract.md lacks names of ../shared/contract.md: {missing:?}"
    );
}

/// Every key of a JSON value, recursively (array elements included).
fn json_keys(v: &serde_json::Value, out: &mut std::collections::BTreeSet<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                out.insert(k.clone());
                json_keys(x, out);
            }
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| json_keys(x, out)),
        _ => {}
    }
}

#[test]
fn own_contract_names_every_results_key() {
    let own = code_names(&std::fs::read_to_string("docs/contract.md").unwrap());
    let d = std::env::temp_dir().join(format!("rodnet-keys-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let mut runs: Vec<Vec<String>> = [
        "star.ron",                // joints
        "cantilever_elastica.ron", // reference
        "rod_over_sphere.ron",     // contacts, kkt
        "cantilever_stop.ron",     // bounds
        "hemisphere_flat_n2.ron",  // target
    ]
    .iter()
    .enumerate()
    .map(|(k, s)| {
        let out = d.join(format!("{k}.json"));
        vec![
            "solve".into(),
            format!("networks/{s}"),
            "--json".into(),
            out.display().to_string(),
            "--quiet".into(),
        ]
    })
    .collect();
    let gridshell = d.join("gridshell.json");
    runs.push(
        [
            "gridshell",
            "hemisphere",
            "--rods",
            "2",
            "--subdivide",
            "2",
            "--quiet",
            "--json",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([gridshell.display().to_string()])
        .collect(),
    );
    // A gridshell fitted to a mesh: the mesh target block and the net.
    let mesh = d.join("cap.obj");
    std::fs::write(
        &mesh,
        rodnet::surface::shapes::to_obj(&rodnet::surface::shapes::paraboloid(1.0, 0.5, 12)),
    )
    .unwrap();
    runs.push(vec![
        "gridshell".into(),
        "fit".into(),
        mesh.display().to_string(),
        "--spacing".into(),
        "0.3".into(),
        "--quiet".into(),
        "--json".into(),
        d.join("fit.json").display().to_string(),
    ]);
    let mut keys = std::collections::BTreeSet::new();
    for args in &runs {
        let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
            .args(args)
            .output()
            .unwrap();
        assert!(
            matches!(out.status.code(), Some(0 | 1)),
            "{args:?}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json = args.iter().find(|a| a.ends_with(".json")).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
        json_keys(&v, &mut keys);
    }
    let _ = std::fs::remove_dir_all(&d);
    for k in [
        "contacts",
        "kkt",
        "reference",
        "target",
        "gridshell",
        "bound",
        "mean_signed_distance",
        "min_angle_deg",
    ] {
        assert!(keys.contains(k), "no run produced the key {k}");
    }
    let missing: Vec<&String> = keys.iter().filter(|k| !own.contains(*k)).collect();
    assert!(
        missing.is_empty(),
        "results JSON keys not named in docs/contract.md: {missing:?}"
    );
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

#[test]
fn cli_examples_run() {
    let md = std::fs::read_to_string("docs/cli.md").unwrap();
    let commands: Vec<String> = blocks(&md, "sh")
        .iter()
        .flat_map(|b| b.lines().map(str::to_string).collect::<Vec<_>>())
        .filter(|l| l.starts_with("rodnet "))
        .collect();
    assert!(commands.len() >= 5, "found {} commands", commands.len());
    let d = std::env::temp_dir().join(format!("rodnet-docs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    copy_dir(Path::new("networks"), &d.join("networks"));
    for c in commands {
        let args: Vec<&str> = c.split_whitespace().skip(1).collect();
        let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
            .args(&args)
            .current_dir(&d)
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(0),
            "{c}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    assert!(d.join("vault.png").exists() && d.join("portal.obj").exists());
}
