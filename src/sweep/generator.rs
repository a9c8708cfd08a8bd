//! The hemisphere gridshell generator as a sweep's base (and as Python's
//! `rodnet.gridshell.hemisphere`): its options are those of `rodnet gridshell hemisphere`,
//! parsed and checked by the same code (`gridshell::options`), so that a sweep accepts exactly
//! what the command does.

use super::value::{OrderedMap, Value};
use crate::gridshell::footprint::HemisphereSpec;
use crate::gridshell::options::{HemisphereOptions, OPTIONS};

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
    let mut names: Vec<String> = OPTIONS.iter().map(|(n, _)| n.to_string()).collect();
    names.push(SECTION_RATIO.into());
    names
}

/// The hemisphere the options describe; an error names the option (`rods: ...`).
pub fn hemisphere(options: &OrderedMap<Value>) -> Result<Hemisphere, (String, String)> {
    let known = option_names();
    // (option set, its text, the parameter named in an error): all checked by name and kind
    // before any is parsed, as the command line does.
    let mut given: Vec<(&str, String, &String)> = Vec::new();
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
                given.push(("section", format!("circle:{value}"), name));
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
            _ => given.push((name, value.to_string(), name)),
        }
    }
    let mut h = HemisphereOptions::default();
    for (option, text, name) in given {
        h.set(option, &text).map_err(|m| (name.clone(), m))?;
    }
    let spec = h.spec().map_err(|msg| {
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
        start_cap: h.start_cap,
        modes: h.modes,
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
        // A negative number is a value, not a command-line flag.
        let (name, msg) = hemisphere(&opts(&[("tolerance", Value::Float(-1.0))])).unwrap_err();
        assert_eq!(name, "tolerance", "{msg}");
        assert!(msg.contains("must be positive"), "{msg}");
    }
}
