//! Parameter sweeps (`rodnet sweep`, Python's `rodnet.sweep`): a base scene or the hemisphere
//! generator, the parameters to vary (a grid, zipped lists, or both), one independent solve
//! per point, each point's results JSON named by its parameters, and one merged table
//! (docs/sweep.md).
//!
//! Every point is built and checked before anything is solved, so that a wrong path or value
//! stops the sweep at once; a point that then fails is recorded and the others go on.

pub mod generator;
pub mod path;
pub mod run;
pub mod slurm;
pub mod table;
pub mod value;

use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde_json::Value as Json;

use crate::scene::{self, Scene, SceneError};
pub use generator::Hemisphere;
pub use value::{OrderedMap, Value};

/// Most points one sweep may have.
pub const MAX_POINTS: usize = 100_000;

/// The sweep file (RON, or JSON from Python).
#[derive(Debug, Deserialize)]
#[serde(rename = "Sweep", deny_unknown_fields)]
struct SweepFile {
    /// Base scene file, relative to the sweep file.
    #[serde(default)]
    scene: Option<PathBuf>,
    /// Base scene given inline (RON text; Python's scenes).
    #[serde(default)]
    scene_ron: Option<String>,
    /// Or the hemisphere generator with its fixed options.
    #[serde(default)]
    hemisphere: Option<OrderedMap<Value>>,
    /// Every combination of these lists' values.
    #[serde(default)]
    grid: OrderedMap<Vec<Value>>,
    /// Lists of one length, varied together (combined with every grid point).
    #[serde(default)]
    zip: OrderedMap<Vec<Value>>,
    /// Results JSON paths to put in the table (defaults in `table::default_quantities`).
    #[serde(default)]
    quantities: Option<Vec<String>>,
    /// Output folder, relative to the sweep file [default: the sweep file's name without
    /// extension].
    #[serde(default)]
    output: Option<PathBuf>,
}

/// What every point starts from.
#[derive(Debug, Clone)]
pub enum Base {
    /// The scene, its text and name (for located errors), and its JSON form (where parameters
    /// are set).
    Scene {
        scene: Box<Scene>,
        json: Json,
    },
    Hemisphere(OrderedMap<Value>),
}

/// One point of a sweep.
#[derive(Debug, Clone)]
pub struct Point {
    pub index: usize,
    pub parameters: Vec<(String, Value)>,
    /// File name (without `.json`) of its results: its parameters as `name=value,...`.
    pub name: String,
}

/// What one point solves.
#[derive(Debug, Clone)]
pub enum Job {
    Scene(Box<Scene>),
    Hemisphere(Box<Hemisphere>),
}

/// A checked sweep: every point's job builds.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The sweep file (or the label of a sweep given as text).
    pub file: String,
    /// The sweep file's text, for re-reading it elsewhere (Dask workers, Slurm tasks).
    pub source: String,
    /// Directory that relative paths in the sweep are taken from.
    pub base_dir: PathBuf,
    pub base: Base,
    pub parameters: Vec<String>,
    pub points: Vec<Point>,
    pub quantities: Vec<String>,
    pub output: PathBuf,
    /// How much of the machine each point's solve may take (none unless the caller sets them:
    /// `rodnet sweep` from its options).
    pub limits: crate::pipeline::Limits,
}

/// A sweep error, located in the sweep file where it can be.
pub fn error(file: &str, src: &str, needle: Option<&str>, message: String) -> SceneError {
    let pos = needle.and_then(|n| locate(src, n));
    SceneError {
        file: file.to_string(),
        line: pos.map(|p| p.0),
        column: pos.map(|p| p.1),
        message,
    }
}

/// Line and column (1-based) of the first `"needle"` (quoted, as sweep keys are written).
fn locate(src: &str, needle: &str) -> Option<(usize, usize)> {
    let at = src.find(&format!("\"{needle}\""))?;
    let line = src[..at].matches('\n').count() + 1;
    let col = at - src[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    Some((line, col))
}

impl Sweep {
    /// Reads and checks a sweep file.
    pub fn load(path: &Path) -> Result<Sweep, SceneError> {
        let src = scene::read_text(path, "sweep", scene::validate::MAX_SCENE_BYTES)?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let stem = path.file_stem().map(PathBuf::from);
        Sweep::parse(&path.display().to_string(), &src, &dir, stem)
    }

    /// Parses and checks a sweep from RON (or JSON, which starts with `{`) text; relative paths
    /// are taken from `base_dir`, and `default_output` is the output folder when none is given.
    pub fn parse(
        file: &str,
        src: &str,
        base_dir: &Path,
        default_output: Option<PathBuf>,
    ) -> Result<Sweep, SceneError> {
        let f: SweepFile = if src.trim_start().starts_with('{') {
            serde_json::from_str(src).map_err(|e| SceneError {
                file: file.into(),
                line: Some(e.line()),
                column: Some(e.column()),
                message: e.to_string(),
            })?
        } else {
            ron::Options::default()
                .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
                .from_str(src)
                .map_err(|e| SceneError {
                    file: file.into(),
                    line: Some(e.span.start.line),
                    column: Some(e.span.start.col),
                    message: e.code.to_string(),
                })?
        };
        let err = |needle: Option<&str>, msg: String| error(file, src, needle, msg);
        let base =
            match (&f.scene, &f.scene_ron, &f.hemisphere) {
                (Some(p), None, None) => {
                    let (sc, _) = scene::load(&base_dir.join(p))?;
                    scene_base(sc)
                }
                (None, Some(text), None) => {
                    scene_base(scene::parse(&format!("{file} (scene_ron)"), text)?)
                }
                (None, None, Some(h)) => Base::Hemisphere(h.clone()),
                _ => return Err(err(
                    None,
                    "give exactly one base: `scene` (a scene file), `scene_ron` or `hemisphere` \
                     (the generator's options)"
                        .into(),
                )),
            };
        let output = match (f.output, default_output) {
            (Some(o), _) => {
                // A sweep file from elsewhere must not write among the user's other files: its
                // relative `output` stays in its folder (`--output` or an absolute path choose
                // any place explicitly).
                if let Err(folder) = scene::stays_inside(base_dir, &o) {
                    return Err(err(
                        Some("output"),
                        format!(
                            "`output`: {:?} leads outside the sweep file's folder ({}); give \
                             an absolute path or --output to write elsewhere",
                            o.display().to_string(),
                            folder.display()
                        ),
                    ));
                }
                base_dir.join(o)
            }
            (None, Some(d)) => base_dir.join(d),
            (None, None) => return Err(err(None, "`output`: missing (the output folder)".into())),
        };
        let points = points(&f.grid, &f.zip).map_err(|(name, m)| err(name.as_deref(), m))?;
        let parameters: Vec<String> = f
            .grid
            .0
            .iter()
            .chain(&f.zip.0)
            .map(|(k, _)| k.clone())
            .collect();
        let quantities = f
            .quantities
            .unwrap_or_else(|| table::default_quantities(matches!(base, Base::Hemisphere(_))));
        for q in &quantities {
            path::segments(q).map_err(|m| err(Some(q), format!("quantities: {m}")))?;
        }
        let sweep = Sweep {
            file: file.into(),
            source: src.into(),
            base_dir: base_dir.into(),
            base,
            parameters,
            points,
            quantities,
            output,
            limits: crate::pipeline::Limits::NONE,
        };
        for p in &sweep.points {
            sweep.job(p.index)?;
        }
        Ok(sweep)
    }

    /// The job of point `i`; an error names the parameter (and is located in the sweep file).
    pub fn job(&self, i: usize) -> Result<Job, SceneError> {
        let p = &self.points[i];
        let at = |name: &str, m: String| {
            error(
                &self.file,
                &self.source,
                Some(name),
                format!("parameter `{name}` (point {i}, {}): {m}", p.name),
            )
        };
        match &self.base {
            Base::Scene { json, .. } => {
                let mut v = json.clone();
                for (name, value) in &p.parameters {
                    path::set(&mut v, name, value.to_json()).map_err(|m| at(name, m))?;
                }
                let sc: Scene = serde_path_to_error::deserialize(v).map_err(|e| {
                    // The parameter whose value alone breaks the type is the one to name.
                    let name = p
                        .parameters
                        .iter()
                        .find(|(n, val)| {
                            let mut alone = json.clone();
                            path::set(&mut alone, n, val.to_json()).is_ok()
                                && serde_json::from_value::<Scene>(alone).is_err()
                        })
                        .map_or("", |(n, _)| n.as_str());
                    at(name, format!("{}: {}", e.path(), e.inner()))
                })?;
                scene::validate::validate(&sc).map_err(|e| {
                    let name = p
                        .parameters
                        .iter()
                        .find(|(n, val)| {
                            let mut alone = json.clone();
                            path::set(&mut alone, n, val.to_json()).is_ok()
                                && serde_json::from_value::<Scene>(alone)
                                    .is_ok_and(|s| scene::validate::validate(&s).is_err())
                        })
                        .map_or("", |(n, _)| n.as_str());
                    at(name, format!("{}: {}", e.path(), e.message))
                })?;
                Ok(Job::Scene(Box::new(sc)))
            }
            Base::Hemisphere(fixed) => {
                let mut o = fixed.clone();
                for (name, value) in &p.parameters {
                    match o.0.iter_mut().find(|(k, _)| k == name) {
                        Some(slot) => slot.1 = value.clone(),
                        None => o.0.push((name.clone(), value.clone())),
                    }
                }
                // `section_ratio` varied over a base that fixes `section` replaces it.
                if p.parameters
                    .iter()
                    .any(|(n, _)| n == generator::SECTION_RATIO)
                {
                    o.0.retain(|(k, _)| k != "section");
                }
                generator::hemisphere(&o)
                    .map(|h| Job::Hemisphere(Box::new(h)))
                    .map_err(|(name, m)| at(&name, m))
            }
        }
    }

    /// Where point `i`'s results go.
    pub fn point_file(&self, i: usize) -> PathBuf {
        self.output.join(format!("{}.json", self.points[i].name))
    }
}

fn scene_base(sc: Scene) -> Base {
    let json = serde_json::to_value(&sc).expect("a scene serializes to JSON");
    Base::Scene {
        scene: Box::new(sc),
        json,
    }
}

/// The grid's combinations (first parameter slowest) times the zipped lists' elements.
fn points(
    grid: &OrderedMap<Vec<Value>>,
    zip: &OrderedMap<Vec<Value>>,
) -> Result<Vec<Point>, (Option<String>, String)> {
    for (name, values) in grid.0.iter().chain(&zip.0) {
        if values.is_empty() {
            return Err((Some(name.clone()), format!("`{name}`: no values")));
        }
        path::segments(name).map_err(|m| (Some(name.clone()), m))?;
    }
    if let Some((name, _)) = grid.0.iter().find(|(k, _)| zip.get(k).is_some()) {
        return Err((
            Some(name.clone()),
            format!("`{name}` is in both `grid` and `zip`"),
        ));
    }
    let zip_len = match zip.0.first() {
        Some((first, v)) => {
            if let Some((other, w)) = zip.0.iter().find(|(_, w)| w.len() != v.len()) {
                return Err((
                    Some(other.clone()),
                    format!(
                        "zip: `{other}` has {} values, `{first}` {}: zipped lists have one length",
                        w.len(),
                        v.len()
                    ),
                ));
            }
            v.len()
        }
        None => 1,
    };
    let grid_len = grid
        .0
        .iter()
        .try_fold(1usize, |n, (_, v)| n.checked_mul(v.len()));
    let total = grid_len
        .and_then(|g| g.checked_mul(zip_len))
        .unwrap_or(usize::MAX);
    if total > MAX_POINTS {
        return Err((
            None,
            format!("the sweep has {total} points, above the limit of {MAX_POINTS}"),
        ));
    }
    if grid.is_empty() && zip.is_empty() {
        return Err((None, "nothing to vary: give `grid` or `zip`".into()));
    }
    let mut out: Vec<Point> = Vec::with_capacity(total);
    let mut seen: std::collections::HashMap<String, usize> = Default::default();
    for index in 0..total {
        let mut rest = index / zip_len;
        let mut parameters: Vec<(String, Value)> = Vec::new();
        let mut grid_part: Vec<(String, Value)> = Vec::new();
        for (name, values) in grid.0.iter().rev() {
            grid_part.push((name.clone(), values[rest % values.len()].clone()));
            rest /= values.len();
        }
        parameters.extend(grid_part.into_iter().rev());
        for (name, values) in &zip.0 {
            parameters.push((name.clone(), values[index % zip_len].clone()));
        }
        let name = point_name(&parameters);
        if let Some(other) = seen.insert(name.clone(), index) {
            return Err((
                None,
                format!(
                    "points {other} and {index} have the same parameters ({name}): a value is \
                     listed twice"
                ),
            ));
        }
        out.push(Point {
            index,
            parameters,
            name,
        });
    }
    Ok(out)
}

/// `name=value,...`, with characters that file systems or shells treat specially replaced.
fn point_name(parameters: &[(String, Value)]) -> String {
    let text = parameters
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(",");
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "=,.+-_[]".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}
