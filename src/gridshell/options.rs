//! The hemisphere job's options as plain data: their defaults, their parsing from text (as a
//! sweep or Python gives them) and their checks. `rodnet gridshell hemisphere`'s clap options
//! (`cli/gridshell.rs`) fill the same struct, so that every caller accepts exactly the same.

use crate::gridshell::footprint::{self, HemisphereSpec, JointChoice, DEFAULT_SECTION_RATIO};
use crate::gridshell::formfind::{FormPath, DEFAULT_START_CAP};
use crate::scene::types::Section;
use crate::scene::validate::{MAX_LOAD_STEPS, MAX_MAGNITUDE, MAX_NODES};

/// Default rods per family of the gridshell job.
pub const DEFAULT_RODS: usize = 12;
/// Default edges per segment between crossings of the gridshell job.
pub const DEFAULT_SUBDIVIDE: usize = 4;
/// Largest n accepted (the net generator is tested up to 200).
pub const MAX_RODS: usize = 200;
/// Range of the radius, m.
pub const MIN_RADIUS: f64 = 1e-6;
pub const MAX_RADIUS: f64 = 1e6;
/// Largest section dimension, in units of R.
pub const MAX_SECTION_RATIO: f64 = 1.0;
/// Largest number of eigenvalues asked for.
pub const MAX_MODES: usize = 200;

/// The options' names, in the order of the command's options, with the value name its help
/// shows (`--modes <K>`).
pub const OPTIONS: &[(&str, &str)] = &[
    ("radius", "RADIUS"),
    ("rods", "RODS"),
    ("subdivide", "SUBDIVIDE"),
    ("joint", "JOINT"),
    ("section", "SECTION"),
    ("young_modulus", "YOUNG_MODULUS"),
    ("poisson_ratio", "POISSON_RATIO"),
    ("load_steps", "LOAD_STEPS"),
    ("tolerance", "TOLERANCE"),
    ("start_cap", "START_CAP"),
    ("path", "PATH"),
    ("modes", "K"),
];

/// One hemisphere job, as asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct HemisphereOptions {
    /// Sphere radius R, m.
    pub radius: f64,
    pub rods: usize,
    pub subdivide: usize,
    pub joint: JointChoice,
    /// Dimensions in units of R.
    pub section: SectionRatio,
    pub young_modulus: f64,
    pub poisson_ratio: f64,
    pub load_steps: usize,
    pub tolerance: Option<f64>,
    /// Radius of the starting cap over R; 0 starts from the flat footprint.
    pub start_cap: f64,
    pub path: FormPath,
    /// Lowest eigenvalues to compute at the dome.
    pub modes: Option<usize>,
}

impl Default for HemisphereOptions {
    fn default() -> Self {
        HemisphereOptions {
            radius: 1.0,
            rods: DEFAULT_RODS,
            subdivide: DEFAULT_SUBDIVIDE,
            joint: JointChoice::Ball,
            section: SectionRatio(Section::Circle {
                radius: DEFAULT_SECTION_RATIO,
            }),
            young_modulus: 1e9,
            poisson_ratio: 0.3,
            load_steps: 1,
            tolerance: None,
            start_cap: DEFAULT_START_CAP,
            path: FormPath::CapNets,
            modes: None,
        }
    }
}

/// A cross-section with its dimensions in units of the sphere radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionRatio(pub Section);

impl SectionRatio {
    fn dims(self) -> Vec<f64> {
        match self.0 {
            Section::Circle { radius } => vec![radius],
            Section::Ellipse { a, b } => vec![a, b],
            Section::Rectangle { width, height } => vec![width, height],
        }
    }

    fn scaled(self, r: f64) -> Section {
        match self.0 {
            Section::Circle { radius } => Section::Circle { radius: radius * r },
            Section::Ellipse { a, b } => Section::Ellipse { a: a * r, b: b * r },
            Section::Rectangle { width, height } => Section::Rectangle {
                width: width * r,
                height: height * r,
            },
        }
    }
}

/// `circle:r`, `ellipse:a,b` or `rectangle:w,h`.
pub fn parse_section(s: &str) -> Result<SectionRatio, String> {
    let (kind, dims) = s
        .split_once(':')
        .ok_or_else(|| format!("expected circle:r, ellipse:a,b or rectangle:w,h, got {s:?}"))?;
    let dims: Vec<f64> = dims
        .split(',')
        .map(|d| {
            d.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| format!("section dimension {d:?} is not a positive number"))
        })
        .collect::<Result<_, _>>()?;
    let section = match (kind, dims.as_slice()) {
        ("circle", &[radius]) => Section::Circle { radius },
        ("ellipse", &[a, b]) => Section::Ellipse { a, b },
        ("rectangle", &[width, height]) => Section::Rectangle { width, height },
        _ => {
            return Err(format!(
                "expected circle:r, ellipse:a,b or rectangle:w,h, got {s:?}"
            ))
        }
    };
    Ok(SectionRatio(section))
}

impl HemisphereOptions {
    /// Sets option `name` (one of [`OPTIONS`]) from its text, parsed as the command line
    /// parses it; the error is worded as the command line's.
    pub fn set(&mut self, name: &str, text: &str) -> Result<(), String> {
        let value_name = OPTIONS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
            .ok_or_else(|| format!("not an option of the hemisphere generator: {name}"))?;
        let invalid = |why: Option<String>| {
            let flag = format!("--{} <{value_name}>", name.replace('_', "-"));
            match why {
                Some(w) => format!("invalid value '{text}' for '{flag}': {w}"),
                None => format!("invalid value '{text}' for '{flag}'"),
            }
        };
        let float = || {
            text.parse::<f64>()
                .map_err(|e| invalid(Some(e.to_string())))
        };
        let count = || {
            text.parse::<usize>()
                .map_err(|e| invalid(Some(e.to_string())))
        };
        match name {
            "radius" => self.radius = float()?,
            "rods" => self.rods = count()?,
            "subdivide" => self.subdivide = count()?,
            "joint" => self.joint = joint(text).ok_or_else(|| invalid(None))?,
            "section" => self.section = parse_section(text).map_err(|e| invalid(Some(e)))?,
            "young_modulus" => self.young_modulus = float()?,
            "poisson_ratio" => self.poisson_ratio = float()?,
            "load_steps" => self.load_steps = count()?,
            "tolerance" => self.tolerance = Some(float()?),
            "start_cap" => self.start_cap = float()?,
            "path" => {
                self.path = match text {
                    "cap-nets" => FormPath::CapNets,
                    "straight" => FormPath::Straight,
                    _ => return Err(invalid(None)),
                }
            }
            _ => {
                let k = text
                    .parse::<i64>()
                    .map_err(|e| invalid(Some(e.to_string())))?;
                if !(1..=MAX_MODES as i64).contains(&k) {
                    return Err(invalid(Some(format!("{k} is not in 1..={MAX_MODES}"))));
                }
                self.modes = Some(k as usize);
            }
        }
        Ok(())
    }

    /// Checks the numbers their types do not; the error starts with the option's flag.
    pub fn spec(&self) -> Result<HemisphereSpec, String> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        // Every length of the footprint is R times a ratio of order one; outside this range its
        // squares and the section's rigidities (r⁴ E) leave the doubles, and the net's sizes with
        // them (a non-finite length once asked for endless subdivisions).
        if !(MIN_RADIUS..=MAX_RADIUS).contains(&self.radius) {
            return Err(format!(
                "--radius must lie in [{MIN_RADIUS:e}, {MAX_RADIUS:e}] m, got {:e}",
                self.radius
            ));
        }
        if !(1..=MAX_RODS).contains(&self.rods) {
            return Err(format!(
                "--rods must be in 1..={MAX_RODS}, got {}",
                self.rods
            ));
        }
        if self.subdivide == 0 {
            return Err("--subdivide must be at least 1".into());
        }
        let nodes = footprint::estimated_nodes(self.rods, self.subdivide);
        if nodes > MAX_NODES {
            return Err(format!(
                "--rods {} --subdivide {} would give about {} nodes (1.5 n² K), above the limit \
                 of {}; reduce --subdivide",
                self.rods, self.subdivide, nodes, MAX_NODES
            ));
        }
        if let Some(d) = self
            .section
            .dims()
            .into_iter()
            .find(|&d| d > MAX_SECTION_RATIO)
        {
            return Err(format!(
                "--section dimensions are in units of R and must be at most {MAX_SECTION_RATIO} \
                 (a rod as thick as the sphere), got {d:e}"
            ));
        }
        if !(positive(self.young_modulus) && self.young_modulus <= MAX_MAGNITUDE) {
            return Err(format!(
                "--young-modulus must be positive and finite (at most {:e} Pa), got {}",
                MAX_MAGNITUDE, self.young_modulus
            ));
        }
        let nu = self.poisson_ratio;
        if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
            return Err(format!("--poisson-ratio must lie in (-1, 0.5], got {nu}"));
        }
        if self.load_steps == 0 || self.load_steps > MAX_LOAD_STEPS {
            return Err(format!("--load-steps must be in 1..={MAX_LOAD_STEPS}"));
        }
        if let Some(t) = self.tolerance.filter(|t| !positive(*t)) {
            return Err(format!("--tolerance must be positive, got {t}"));
        }
        let cap = self.start_cap;
        if !(cap == 0.0 || (cap.is_finite() && cap >= 1.0)) {
            return Err(format!(
                "--start-cap must be 0 (flat start), 1 (the analytic net) or a finite ratio above 1, got {cap}"
            ));
        }
        let mut spec = HemisphereSpec::new(self.radius, self.rods, self.subdivide);
        spec.path = self.path;
        spec.joint = self.joint;
        spec.section = self.section.scaled(self.radius);
        spec.young_modulus = self.young_modulus;
        spec.poisson_ratio = self.poisson_ratio;
        spec.load_steps = self.load_steps;
        spec.tolerance = self.tolerance;
        Ok(spec)
    }
}

/// A joint kind by its name on the command line.
fn joint(name: &str) -> Option<JointChoice> {
    [
        JointChoice::Ball,
        JointChoice::Hinge,
        JointChoice::Rigid,
        JointChoice::Elastic,
    ]
    .into_iter()
    .find(|j| j.name() == name)
}
