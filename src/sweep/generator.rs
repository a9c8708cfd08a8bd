//! The hemisphere gridshell generator as a sweep's base (and as Python's
//! `rodnet.gridshell.hemisphere`): its options are those of `rodnet gridshell hemisphere`,
//! parsed and checked by the same code, so that a sweep accepts exactly what the command does.

use clap::{CommandFactory, Parser};

use super::value::{OrderedMap, Value};
use crate::cli::{hemisphere_spec, HemisphereArgs};
use crate::gridshell::footprint::HemisphereSpec;

#[derive(Parser, Debug)]
#[command(name = "hemisphere", no_binary_name = true)]
struct Options {
    #[command(flatten)]
    args: HemisphereArgs,
}

/// Options that choose files or the process's behaviour, not the gridshell.
const NOT_OPTIONS: &[&str] = &[
    "scene_out",
    "json",
    "obj",
    "vtk",
    "report",
    "out_dir",
    "quiet",
    "max_memory",
    "time_limit",
];

/// A sweep-only shorthand: the radius of a circular section over R (`--section circle:r`).
pub const SECTION_RATIO: &str = "section_ratio";

/// One hemisphere to form-find.
#[derive(Debug, Clone)]
pub struct Hemisphere {
    pub spec: HemisphereSpec,
    pub start_cap: f64,
    /// Lowest eigenvalues to compute at the dome (`--modes`).
    pub modes: Option<usize>,
}

/// The generator's option names, as a sweep writes them (`rods`, `young_modulus`, ...).
pub fn option_names() -> Vec<String> {
    let cmd = Options::command();
    let mut names: Vec<String> = cmd
        .get_arguments()
        .map(|a| a.get_id().as_str().to_string())
        .filter(|n| !NOT_OPTIONS.contains(&n.as_str()) && n != "help")
        .collect();
    names.push(SECTION_RATIO.into());
    names
}

/// The hemisphere the options describe; an error names the option (`rods: ...`).
pub fn hemisphere(options: &OrderedMap<Value>) -> Result<Hemisphere, (String, String)> {
    let known = option_names();
    let mut argv: Vec<String> = Vec::new();
    if options.get(SECTION_RATIO).is_some() && options.get("section").is_some() {
        return Err((
            SECTION_RATIO.into(),
            "give either `section_ratio` (a circle's r/R) or `section`, not both".into(),
        ));
    }
    for (name, value) in &options.0 {
        if !known.contains(name) {
            return Err((
                name.clone(),
                format!(
                    "not an option of the hemisphere generator (options: {})",
                    known.join(", ")
                ),
            ));
        }
        match (name.as_str(), value) {
            (SECTION_RATIO, Value::Int(_) | Value::Float(_)) => {
                argv.push("--section".into());
                argv.push(format!("circle:{value}"));
            }
            (SECTION_RATIO, _) => {
                return Err((
                    name.clone(),
                    format!("expected a number (r/R), got {value:?}"),
                ))
            }
            (_, Value::Bool(_)) => {
                return Err((name.clone(), format!("expected a value, got {value}")));
            }
            _ => {
                argv.push(format!("--{}", name.replace('_', "-")));
                argv.push(value.to_string());
            }
        }
    }
    let parsed = Options::try_parse_from(&argv).map_err(|e| {
        let text = e.render().to_string();
        let first = text
            .lines()
            .next()
            .unwrap_or("")
            .trim_start_matches("error: ");
        let name = options
            .0
            .iter()
            .map(|(n, _)| n)
            .find(|n| first.contains(&format!("--{}", n.replace('_', "-"))))
            .cloned()
            .unwrap_or_default();
        (name, first.to_string())
    })?;
    let a = parsed.args;
    let spec = hemisphere_spec(&a).map_err(|msg| {
        // The message starts with the flag it is about.
        let name = msg
            .strip_prefix("--")
            .and_then(|m| m.split([' ', ':']).next())
            .map(|f| f.replace('-', "_"))
            .unwrap_or_default();
        (name, msg)
    })?;
    Ok(Hemisphere {
        spec,
        start_cap: a.start_cap,
        modes: a.modes.map(|k| k as usize),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(v: &[(&str, Value)]) -> OrderedMap<Value> {
        OrderedMap(v.iter().map(|(k, v)| (k.to_string(), v.clone())).collect())
    }

    #[test]
    fn options_are_the_commands_and_errors_name_them() {
        let h = hemisphere(&opts(&[
            ("rods", Value::Int(6)),
            ("section_ratio", Value::Float(0.01)),
            ("joint", Value::Str("hinge".into())),
        ]))
        .unwrap();
        assert_eq!(h.spec.rods, 6);
        assert_eq!(
            h.spec.section,
            crate::scene::types::Section::Circle { radius: 0.01 }
        );
        let (name, msg) = hemisphere(&opts(&[("rods", Value::Float(6.5))])).unwrap_err();
        assert_eq!(name, "rods", "{msg}");
        let (name, msg) = hemisphere(&opts(&[("rods", Value::Int(0))])).unwrap_err();
        assert_eq!(name, "rods", "{msg}");
        let (name, _) = hemisphere(&opts(&[("json", Value::Str("x".into()))])).unwrap_err();
        assert_eq!(name, "json");
    }
}
