//! Convergence under subdivision: one problem solved at successively finer subdivisions (every
//! rod's `subdivide` doubled per level), with the discretization error of each level measured
//! against the scene's analytic `reference` or, without one, against the Richardson
//! extrapolate of the finest levels (docs/convergence.md).
//!
//! The quantity compared across levels must exist at every level: for scenes, the positions of
//! the input vertices (vertex k of a rod is node k·subdivide); for the gridshell, whose levels
//! are separate footprints, the positions of its joints (the net's crossings).

use std::collections::HashMap;
use std::time::Instant;

use crate::gridshell::footprint::{footprint, HemisphereSpec};
use crate::gridshell::job as gridshell_job;
use crate::math::vec::{norm, sub};
use crate::network::Network;
use crate::pipeline::{self, Limits};
use crate::scene::{validate, FieldError, Scene, SceneError};
use crate::solver::{Ordering, Progress};
use crate::study::richardson::{self, Extrapolation};

/// Largest number of levels (the node limit stops most scenes well before).
pub const MAX_LEVELS: usize = 16;

/// What is refined.
pub enum Problem {
    /// A scene file: `file` and its text `src` locate errors.
    Scene {
        file: String,
        src: String,
        scene: Box<Scene>,
    },
    /// The hemispherical gridshell job of `rodnet gridshell hemisphere`, with `spec.subdivide`
    /// (edges per crossing spacing) doubled per level.
    Hemisphere {
        spec: HemisphereSpec,
        start_cap: f64,
    },
}

/// The scene's reference vertex, with its rest distance from the reference position.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceInfo {
    pub rod: String,
    pub vertex: usize,
    /// |x_ref − x_rest|, m: the length the reference error is relative to.
    pub displacement: f64,
}

/// A point followed across the levels.
#[derive(Debug, Clone, PartialEq)]
enum Probe {
    /// Input vertex k of a rod.
    Vertex(String, usize),
    /// A joint, by name.
    Joint(String),
}

/// What each level solves.
enum Levels {
    Scenes(Vec<Scene>),
    Hemisphere {
        specs: Vec<HemisphereSpec>,
        start_cap: f64,
    },
}

/// The validated problems of every level, ready to solve.
pub struct Plan {
    pub label: String,
    /// How a level refines the previous one, in words.
    pub refinement: &'static str,
    levels: Levels,
    /// Edges per input segment of the first rod at each level (gridshell: per crossing
    /// spacing).
    pub subdivide: Vec<usize>,
    probes: Vec<Probe>,
    /// Rest position of each probe.
    rest: Vec<[f64; 3]>,
    pub reference: Option<ReferenceInfo>,
    /// The limits every level was checked against in [`plan`] and is solved within.
    limits: Limits,
}

/// One solved level.
#[derive(Debug, Clone)]
pub struct Level {
    /// 1 for the base scene.
    pub level: usize,
    pub subdivide: usize,
    pub nodes: usize,
    pub dofs: usize,
    pub iterations: usize,
    /// Wall time of the solve alone (not building the network or collecting results), s.
    pub seconds: f64,
    pub converged: bool,
    pub residual: f64,
    /// Why the solve stopped, when it did not converge.
    pub message: Option<String>,
    /// Probe positions; `None` when the state is not finite.
    pub positions: Option<Vec<[f64; 3]>>,
    pub reference_error: Option<f64>,
    /// Max |radial deviation| / R from the scene's target sphere.
    pub sphere_deviation: Option<f64>,
    /// Filled in by [`analyse`].
    pub richardson_error: Option<f64>,
    /// Observed order of the primary error between the previous level and this one.
    pub order: Option<f64>,
}

impl Level {
    /// Converged with finite positions: fit for the error analysis.
    pub fn usable(&self) -> bool {
        self.converged && self.positions.is_some()
    }
}

/// Checks the levels, and generates, validates and builds every level's scene, so that bad input
/// (including a level over the node limit) is refused before anything is solved.
pub fn plan(problem: &Problem, levels: usize, limits: &Limits) -> Result<Plan, String> {
    let has_reference =
        matches!(problem, Problem::Scene { scene, .. } if scene.reference.is_some());
    let min = if has_reference { 2 } else { 3 };
    if !(min..=MAX_LEVELS).contains(&levels) {
        let why = if has_reference {
            ""
        } else {
            " (without a `reference` in the scene the error comes from Richardson \
             extrapolation, which needs three levels)"
        };
        return Err(format!(
            "--levels must be in {min}..={MAX_LEVELS}, got {levels}{why}"
        ));
    }
    let at = |level: usize| {
        format!(
            "level {level} (every subdivide × {})",
            1usize << (level - 1)
        )
    };
    // The levels below a refused one still make a study.
    let fewer = |level: usize| {
        if level > min {
            format!(" (use --levels {} or fewer)", level - 1)
        } else {
            String::new()
        }
    };
    match problem {
        Problem::Scene { file, src, scene } => {
            let describe = |level: usize, e: &FieldError| {
                let mut err = SceneError::from_field(file, src, e);
                err.message = format!("{}, at {}{}", err.message, at(level), fewer(level));
                err.to_string()
            };
            let mut scenes = Vec::with_capacity(levels);
            for level in 1..=levels {
                let factor = 1usize << (level - 1);
                let mut s = Scene::clone(scene);
                for (i, r) in s.rods.iter_mut().enumerate() {
                    r.subdivide = r.subdivide.checked_mul(factor).ok_or_else(|| {
                        let e = FieldError::new("rods", i, "subdivide", "overflows".into());
                        describe(level, &e)
                    })?;
                }
                validate::validate(&s).map_err(|e| describe(level, &e))?;
                scenes.push(s);
            }
            // The memory lower bound of every level, before any level is built.
            for (i, s) in scenes.iter().enumerate() {
                pipeline::check_scene_memory(s, limits.memory).map_err(|e| describe(i + 1, &e))?;
            }
            // The builder checks what depends on the nodes (joint positions, hinge axes, rest
            // shape outside the obstacles), and finer levels have new nodes. It allocates, so it
            // runs once every level has passed the cheap checks (the node limit).
            // Each level is also checked against the memory limit here, so that no solve is
            // refused once the study has begun.
            for (i, s) in scenes.iter().enumerate() {
                pipeline::build_within_limit(s, Ordering::Auto, limits.memory)
                    .map_err(|e| describe(i + 1, &e))?;
            }
            let (mut probes, mut rest) = (Vec::new(), Vec::new());
            for r in &scene.rods {
                for (k, p) in r.points.iter().enumerate() {
                    probes.push(Probe::Vertex(r.name.clone(), k));
                    rest.push(*p);
                }
            }
            let reference = scene.reference.as_ref().map(|r| {
                let rod = scene
                    .rods
                    .iter()
                    .find(|x| x.name == r.rod)
                    .expect("validated");
                ReferenceInfo {
                    rod: r.rod.clone(),
                    vertex: r.vertex,
                    displacement: norm(sub(r.position, rod.points[r.vertex])),
                }
            });
            Ok(Plan {
                label: file.clone(),
                refinement: "every rod's subdivide doubled per level",
                subdivide: scenes.iter().map(|s| s.rods[0].subdivide).collect(),
                levels: Levels::Scenes(scenes),
                probes,
                rest,
                reference,
                limits: *limits,
            })
        }
        Problem::Hemisphere { spec, start_cap } => {
            check_gridshell_levels(spec, levels)?;
            let mut specs = Vec::with_capacity(levels);
            let mut scenes = Vec::with_capacity(levels);
            let invalid = |level: usize, e: &FieldError| {
                format!(
                    "the generated scene is invalid at {}: {}: {}{}",
                    at(level),
                    e.path(),
                    e.message,
                    fewer(level)
                )
            };
            for level in 1..=levels {
                let mut s = spec.clone();
                s.subdivide = spec
                    .subdivide
                    .checked_mul(1 << (level - 1))
                    .ok_or_else(|| format!("--subdivide overflows at {}", at(level)))?;
                let fp = footprint(&s);
                validate::validate(&fp.scene)
                    .and_then(|_| pipeline::check_scene_memory(&fp.scene, limits.memory))
                    .map_err(|e| invalid(level, &e))?;
                scenes.push(fp.scene);
                specs.push(s);
            }
            // Built once every level has passed the cheap checks (the builder allocates).
            for (i, s) in scenes.iter().enumerate() {
                pipeline::build_within_limit(s, Ordering::Auto, limits.memory)
                    .map_err(|e| invalid(i + 1, &e))?;
            }
            let base = scenes.into_iter().next();
            // The crossings are the same at every level; their rest places are in the
            // footprint.
            let base = base.expect("at least one level");
            let (mut probes, mut rest) = (Vec::new(), Vec::new());
            for j in &base.joints {
                let (rod, k) = &j.at[0];
                let r = base
                    .rods
                    .iter()
                    .find(|r| &r.name == rod)
                    .expect("validated");
                probes.push(Probe::Joint(j.name.clone()));
                rest.push(r.points[*k]);
            }
            Ok(Plan {
                label: format!(
                    "hemispherical gridshell, n = {}, {} joints",
                    spec.rods,
                    spec.joint.name()
                ),
                refinement: "edges per crossing spacing doubled per level, end segments by \
                             length, as `rodnet gridshell hemisphere --subdivide K`",
                subdivide: specs.iter().map(|s| s.subdivide).collect(),
                levels: Levels::Hemisphere {
                    specs,
                    start_cap: *start_cap,
                },
                probes,
                rest,
                reference: None,
                limits: *limits,
            })
        }
    }
}

/// Refuses, before any footprint is generated (each level's allocates its nodes), the
/// gridshell levels whose footprint would pass the node limit, naming `--levels`.
fn check_gridshell_levels(spec: &HemisphereSpec, levels: usize) -> Result<(), String> {
    for level in 1..=levels {
        let k = spec.subdivide.saturating_mul(1 << (level - 1));
        let nodes = crate::gridshell::footprint::estimated_nodes(spec.rods, k);
        if nodes > validate::MAX_NODES {
            let fewer = if level > 3 {
                format!("use --levels {} or fewer", level - 1)
            } else {
                "reduce --subdivide or --rods".into()
            };
            return Err(format!(
                "--levels {levels}: level {level} (subdivide {k}) would have about {nodes} \
                 nodes (1.5 n² K), above the limit of {}; {fewer}",
                validate::MAX_NODES
            ));
        }
    }
    Ok(())
}

impl Plan {
    pub fn levels(&self) -> usize {
        self.subdivide.len()
    }

    /// Load steps of each solve (for progress displays).
    pub fn load_steps(&self) -> usize {
        match &self.levels {
            Levels::Scenes(s) => s[0].solver.load_steps,
            Levels::Hemisphere { specs, .. } => specs[0].load_steps,
        }
    }

    /// The sphere radius, for gridshells: their errors are over R rather than over the largest
    /// displacement.
    pub fn radius(&self) -> Option<f64> {
        match &self.levels {
            Levels::Scenes(_) => None,
            Levels::Hemisphere { specs, .. } => Some(specs[0].radius),
        }
    }

    /// Builds and solves level `index` (0-based).
    pub fn solve(&self, index: usize, progress: Option<Progress>) -> Level {
        let (network, results, seconds, reference_error) = match &self.levels {
            Levels::Scenes(scenes) => {
                let scene = &scenes[index];
                let mut settings = self.limits.settings_of(scene);
                settings.progress = progress;
                let mut seconds = 0.0;
                // `plan` built every level, and building is deterministic.
                let solution = pipeline::run(
                    scene,
                    &settings,
                    |net, s| {
                        let t0 = Instant::now();
                        let toward = scene.solver.buckle_toward;
                        let report = crate::network::solve_toward(net, s, toward);
                        seconds = t0.elapsed().as_secs_f64();
                        report
                    },
                    |_, _| {},
                )
                .expect("built in `plan`");
                let reference_error = solution.equilibrium.reference.as_ref().map(|r| r.error);
                (solution.network, solution.results, seconds, reference_error)
            }
            Levels::Hemisphere { specs, start_cap } => {
                let run = gridshell_job::run(&specs[index], *start_cap, progress, &self.limits)
                    .expect("built in `plan`");
                // The form finding's own clock: the cap start and the solve.
                let seconds = run.form.seconds;
                (run.network, run.results, seconds, None)
            }
        };
        let finite = results.all_finite();
        Level {
            level: index + 1,
            subdivide: self.subdivide[index],
            nodes: network.n_nodes(),
            dofs: network.model.n_free,
            iterations: results.iterations,
            seconds,
            converged: results.converged && finite,
            residual: results.residual,
            message: match (finite, results.solver.message) {
                (false, m) => Some(format!(
                    "diverged (non-finite state){}",
                    m.map(|m| format!(": {m}")).unwrap_or_default()
                )),
                (true, m) => m,
            },
            positions: finite.then(|| self.probe_positions(&network)),
            reference_error: reference_error.filter(|_| finite),
            sphere_deviation: results
                .target
                .filter(|_| finite)
                .and_then(|t| t.max_abs_radial_deviation),
            richardson_error: None,
            order: None,
        }
    }

    fn probe_positions(&self, net: &Network) -> Vec<[f64; 3]> {
        let at = |n: usize| net.model.world_position(n);
        let rods: HashMap<&str, _> = net.rods.iter().map(|r| (r.name.as_str(), r)).collect();
        let joints: HashMap<&str, usize> = net
            .joints
            .iter()
            .map(|j| (j.name.as_str(), j.node))
            .collect();
        self.probes
            .iter()
            .map(|p| match p {
                Probe::Vertex(rod, k) => {
                    let r = rods[rod.as_str()];
                    at(r.vertex_node(*k).expect("validated vertex"))
                }
                Probe::Joint(name) => at(joints[name.as_str()]),
            })
            .collect()
    }
}

/// Which error the table's `order` and the observed order are about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    Reference,
    Richardson,
}

/// The Richardson extrapolation of the finest usable levels.
#[derive(Debug, Clone)]
pub struct Richardson {
    /// Levels (1-based) of the three solutions used.
    pub levels: [usize; 3],
    pub extrapolation: Extrapolation,
    /// The length the Richardson errors are divided by, m.
    pub scale: f64,
    /// What `scale` is.
    pub scale_name: &'static str,
    /// What the errors are the largest over.
    pub points: &'static str,
}

/// A study: the levels with their errors and what they add up to.
#[derive(Debug, Clone)]
pub struct Study {
    pub label: String,
    pub refinement: &'static str,
    pub levels: Vec<Level>,
    pub measure: Measure,
    pub reference: Option<ReferenceInfo>,
    pub richardson: Result<Richardson, String>,
    /// The observed order and how it was obtained.
    pub observed_order: Option<(f64, String)>,
    /// The target deviation extrapolated to infinitely fine subdivision.
    pub sphere_limit: Option<f64>,
}

impl Study {
    /// The error the order and the plot are about.
    pub fn error(&self, l: &Level) -> Option<f64> {
        match self.measure {
            Measure::Reference => l.reference_error,
            Measure::Richardson => l.richardson_error,
        }
    }

    /// Whether every level converged.
    pub fn all_converged(&self) -> bool {
        self.levels.iter().all(|l| l.converged)
    }

    /// The levels (1-based) whose solve did not converge.
    pub fn failed_levels(&self) -> Vec<usize> {
        self.levels
            .iter()
            .filter(|l| !l.converged)
            .map(|l| l.level)
            .collect()
    }
}

/// Turns the solved levels into errors, orders and the extrapolation.
pub fn analyse(plan: &Plan, mut levels: Vec<Level>) -> Study {
    let measure = if plan.reference.is_some() {
        Measure::Reference
    } else {
        Measure::Richardson
    };
    let richardson = richardson_of(plan, &levels);
    if let Ok(r) = &richardson {
        for l in levels.iter_mut().filter(|l| l.usable()) {
            let p = l.positions.as_ref().expect("usable");
            l.richardson_error =
                Some(richardson::max_distance(p, &r.extrapolation.limit) / r.scale);
        }
    }
    let error = |l: &Level| match measure {
        Measure::Reference => l.reference_error.filter(|_| l.usable()),
        Measure::Richardson => l.richardson_error,
    };
    for i in 1..levels.len() {
        levels[i].order = match (error(&levels[i - 1]), error(&levels[i])) {
            (Some(a), Some(b)) => richardson::order(a, b),
            _ => None,
        };
    }
    let observed_order = match (&measure, &richardson) {
        (Measure::Richardson, Ok(r)) => Some((
            r.extrapolation.order,
            format!(
                "from the differences between levels {}, {} and {}",
                r.levels[0], r.levels[1], r.levels[2]
            ),
        )),
        (Measure::Richardson, Err(_)) => None,
        (Measure::Reference, _) => {
            // The finest run of successive levels with an error, at most three long.
            let mut run: Vec<usize> = Vec::new();
            for (i, l) in levels.iter().enumerate().rev() {
                if error(l).is_some_and(|e| e > 0.0) && run.len() < 3 {
                    run.push(i);
                } else if !run.is_empty() {
                    break;
                }
            }
            run.reverse();
            let errors: Vec<f64> = run.iter().filter_map(|&i| error(&levels[i])).collect();
            richardson::fitted_order(&errors).map(|p| {
                (
                    p,
                    format!(
                        "least-squares fit of log2(error) over levels {}–{}",
                        run[0] + 1,
                        run[run.len() - 1] + 1
                    ),
                )
            })
        }
    };
    let sphere_limit = richardson.as_ref().ok().and_then(|r| {
        let mid = levels[r.levels[1] - 1].sphere_deviation?;
        let fine = levels[r.levels[2] - 1].sphere_deviation?;
        Some(richardson::extrapolate_scalar(
            mid,
            fine,
            r.extrapolation.order,
        ))
    });
    Study {
        label: plan.label.clone(),
        refinement: plan.refinement,
        levels,
        measure,
        reference: plan.reference.clone(),
        richardson,
        observed_order,
        sphere_limit,
    }
}

fn richardson_of(plan: &Plan, levels: &[Level]) -> Result<Richardson, String> {
    if levels.len() < 3 {
        return Err("it needs three levels".into());
    }
    let fine = (2..levels.len())
        .rev()
        .find(|&i| levels[i - 2..=i].iter().all(Level::usable))
        .ok_or("no three successive levels converged")?;
    let pos = |i: usize| levels[i].positions.as_deref().expect("usable");
    let extrapolation = richardson::extrapolate(pos(fine - 2), pos(fine - 1), pos(fine))?;
    let (scale, scale_name, points) = match plan.radius() {
        Some(r) => (r, "the sphere radius R", "joints"),
        None => (
            richardson::max_distance(&extrapolation.limit, &plan.rest),
            "the largest displacement of an input vertex",
            "input vertices",
        ),
    };
    if scale == 0.0 {
        return Err("no input vertex moves, so there is no displacement to compare with".into());
    }
    // Differences at round-off say nothing about the discretization.
    if extrapolation.coarse_difference <= 1e-13 * scale {
        return Err(format!(
            "levels {} and {} agree to round-off ({:.3e} m): no discretization error to measure",
            fine - 1,
            fine,
            extrapolation.coarse_difference
        ));
    }
    Ok(Richardson {
        levels: [fine - 1, fine, fine + 1],
        extrapolation,
        scale,
        scale_name,
        points,
    })
}
