//! The examples in the docs work: every ```ron block of docs/scene-format.md (and the contract's
//! example, when ../shared is beside the repository) parses and validates, and every command in
//! the ```sh blocks of docs/cli.md runs and succeeds.

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
    let p = Path::new("../shared/contract.md");
    let Ok(md) = std::fs::read_to_string(p) else {
        // The contract lives beside the repository, not in it; nothing to check without it.
        return;
    };
    let scenes = blocks(&md, "ron");
    assert!(!scenes.is_empty());
    for src in scenes {
        rodnet::scene::parse("contract.md", &src).unwrap_or_else(|e| panic!("{e}"));
    }
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
