//! The output formats of an equilibrium, listed once: every solving command offers each as a
//! `--NAME FILE` option (`cli/output.rs` builds the options from this list) and writes it through
//! [`Format::bytes`]; Python's `Results.write_*` take the same bytes. A new format is its file
//! in `io/` and one entry in [`FORMATS`].

use std::path::Path;

use crate::io::results::Results;
use crate::network::equilibrium::Equilibrium;

/// What a format is made from: the results, and the equilibrium where the command has it.
pub struct Solved<'a> {
    pub results: &'a Results,
    pub equilibrium: Option<&'a Equilibrium>,
    /// The results JSON to write instead of `results` alone (a gridshell's adds its block).
    pub json: Option<&'a [u8]>,
}

/// A check of a file name, before anything is solved.
pub type PathCheck = fn(&Path) -> Result<(), String>;

/// One output format.
pub struct Format {
    /// The option's name, as sweeps and clap know it.
    pub name: &'static str,
    /// The command-line flag.
    pub flag: &'static str,
    /// The option's value name in the help.
    pub value_name: &'static str,
    /// The help of `rodnet solve`'s option (clap's style: no final full stop).
    pub help: &'static str,
    /// The help where the gridshell commands' differs (they refer to `rodnet solve`'s).
    pub gridshell_help: Option<&'static str>,
    /// Written next to the gridshell commands' default JSON in `--out-dir` (as STEM.EXT).
    pub default_ext: Option<&'static str>,
    /// Whether it needs the equilibrium (only commands that keep it offer it).
    pub needs_equilibrium: bool,
    /// Refuses a file name before anything is solved (checked when the options are parsed).
    pub check: Option<PathCheck>,
    /// The file's bytes.
    pub bytes: fn(&Path, &Solved) -> Result<Vec<u8>, String>,
}

/// Every format, in the order the options are listed and the files written.
pub const FORMATS: &[Format] = &[
    Format {
        name: "json",
        flag: "--json",
        value_name: "JSON",
        help: "Write the results JSON here",
        gridshell_help: None,
        default_ext: Some("json"),
        needs_equilibrium: false,
        check: None,
        bytes: |_, s| match s.json {
            Some(b) => Ok(b.to_vec()),
            None => serde_json::to_vec_pretty(s.results)
                .map_err(|e| format!("cannot encode the results as JSON: {e}")),
        },
    },
    Format {
        name: "obj",
        flag: "--obj",
        value_name: "OBJ",
        help: "Write the equilibrium as OBJ polylines here",
        gridshell_help: None,
        default_ext: Some("obj"),
        needs_equilibrium: false,
        check: None,
        bytes: |_, s| Ok(crate::io::obj::to_obj(s.results).into_bytes()),
    },
    Format {
        name: "vtk",
        flag: "--vtk",
        value_name: "F.vtp",
        help: "Write the equilibrium as VTK XML here: .vtp PolyData (ParaView) or .vtu \
               UnstructuredGrid (ParaView, meshio); one line cell per edge, per-node and \
               per-edge fields",
        gridshell_help: Some(
            "Write the equilibrium as VTK XML here (.vtp or .vtu, as `rodnet solve --vtk`)",
        ),
        default_ext: None,
        needs_equilibrium: false,
        check: Some(|p| crate::io::vtk::Format::of(p).map(|_| ())),
        bytes: |p, s| {
            let format = crate::io::vtk::Format::of(p)?;
            Ok(crate::io::vtk::to_vtk(s.results, format).into_bytes())
        },
    },
    Format {
        name: "csv",
        flag: "--csv",
        value_name: "CSV",
        help: "Write one CSV row per node here",
        gridshell_help: None,
        default_ext: None,
        needs_equilibrium: true,
        check: None,
        bytes: |_, s| Ok(crate::io::csv::to_csv(equilibrium(s)?).into_bytes()),
    },
    Format {
        name: "forces_csv",
        flag: "--forces-csv",
        value_name: "FILE.csv",
        help: "Write one CSV row per edge here: its internal forces, von Mises stress and \
               utilization",
        gridshell_help: None,
        default_ext: None,
        needs_equilibrium: true,
        check: None,
        bytes: |_, s| Ok(crate::io::csv::to_forces_csv(equilibrium(s)?).into_bytes()),
    },
];

/// The format of that option name.
pub fn named(name: &str) -> Option<&'static Format> {
    FORMATS.iter().find(|f| f.name == name)
}

fn equilibrium<'a>(s: &Solved<'a>) -> Result<&'a Equilibrium, String> {
    s.equilibrium
        .ok_or_else(|| "this output needs the equilibrium, which this command does not keep".into())
}
