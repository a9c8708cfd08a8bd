//! `rodnet solve SCENE.ron` and `rodnet solve --network NET.obj`: solve, report, write results.

use std::path::{Path, PathBuf};

use super::network::{self, NetworkArgs};
use super::output::{atomic_write, bad, check_outputs, diagnostic, given};
use super::output::{ResultOutputs, SolveFormats};
use super::output::{EXIT_BAD_INPUT, EXIT_NOT_CONVERGED, EXIT_OK};
use super::progress::{self, show_progress};
use crate::io::atomic;
use crate::io::formats::Solved;
use crate::pipeline::{self as job, Limits};
use crate::scene::{self, FieldError, Scene, SceneError};

/// The result files asked for.
pub(super) struct Outputs {
    pub results: ResultOutputs<SolveFormats>,
    /// The eigen-analysis asked for (`--modes K`) and where its mode shapes go.
    pub modes: Option<usize>,
    pub modes_obj: Option<PathBuf>,
    /// `--initial`: an earlier results JSON of the same scene to start from (an input, checked
    /// with the outputs so that no output replaces it).
    pub initial: Option<PathBuf>,
    /// `--extrapolate [--levels L]`: the scene and its doubled (and quadrupled) subdivision,
    /// extrapolated from L levels (`study::extrapolate`).
    pub extrapolate: Option<usize>,
}

impl Outputs {
    fn list(&self) -> Vec<(&'static str, &Path)> {
        let mut list = self.results.list();
        list.extend(given(&[("--modes-obj", &self.modes_obj)]));
        list
    }

    /// The results files of one solution, each at its path with `.STAGE` before the extension
    /// when `stage` is named.
    fn results_files(
        &self,
        sol: &job::Solution,
        stage: Option<&str>,
    ) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
        let solved = Solved {
            results: &sol.results,
            equilibrium: Some(&sol.equilibrium),
            json: None,
        };
        self.results.files(&solved, |p| {
            stage.map_or_else(|| p.to_path_buf(), |s| stage_path(p, s))
        })
    }
}

/// Where a stage's copy of an output goes: `out.json` → `out.STAGE.json`.
fn stage_path(p: &Path, stage: &str) -> PathBuf {
    let stem = p
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match p.extension() {
        Some(e) => format!("{stem}.{stage}.{}", e.to_string_lossy()),
        None => format!("{stem}.{stage}"),
    };
    p.with_file_name(name)
}

/// Where the scene came from, to turn errors found while building it into messages.
enum Source {
    Scene { file: String, src: String },
    Network(Box<network::NetworkScene>),
}

impl Source {
    fn describe(&self, e: &FieldError) -> String {
        match self {
            Source::Scene { file, src } => SceneError::from_field(file, src, e).to_string(),
            Source::Network(n) => n.describe(e),
        }
    }
}

/// Solves the scene file, or the scene built from `--network`.
pub(super) fn run(
    scene: Option<PathBuf>,
    outputs: Outputs,
    quiet: bool,
    network: &NetworkArgs,
    limits: &Limits,
) -> i32 {
    match (scene, &network.network) {
        (Some(path), _) => match network.first_given() {
            Some(flag) => bad(format_args!(
                "{flag} builds a scene from --network NET.obj; it does not apply to the \
                 scene file {} (edit the scene instead)",
                path.display()
            )),
            None => solve(&path, outputs, quiet, limits),
        },
        (None, Some(net)) => solve_network(net, network, outputs, quiet, limits),
        // clap requires one of the two.
        (None, None) => EXIT_BAD_INPUT,
    }
}

fn solve(path: &Path, outputs: Outputs, quiet: bool, limits: &Limits) -> i32 {
    let mut inputs = vec![path];
    inputs.extend(outputs.initial.as_deref());
    if let Err(e) = check_outputs(&outputs.list(), &inputs) {
        return bad(e);
    }
    let (sc, src) = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    if !sc.stages.is_empty() {
        if let Some(f) = &outputs.initial {
            return bad(format_args!(
                "--initial {}: a scene with `stages` starts from rest (restarting a staged run \
                 is not supported yet); remove --initial or the stages",
                f.display()
            ));
        }
        // Every stage but the last writes its own copies of the outputs.
        let staged: Vec<(String, PathBuf)> = (0..sc.stages.len())
            .flat_map(|k| {
                let name = sc.stage_name(k).to_string();
                outputs
                    .list()
                    .into_iter()
                    .filter(|(flag, _)| *flag != "--modes-obj")
                    .map(move |(flag, p)| (format!("{flag} (stage {name})"), stage_path(p, &name)))
            })
            .collect();
        let mut all: Vec<(&str, &Path)> = outputs.list();
        all.extend(staged.iter().map(|(f, p)| (f.as_str(), p.as_path())));
        if let Err(e) = check_outputs(&all, &inputs) {
            return bad(e);
        }
    }
    let file = path.display().to_string();
    for w in scene::validate::warnings(&sc) {
        eprintln!("warning: {}", SceneError::from_field(&file, &src, &w));
    }
    let source = Source::Scene { file, src };
    solve_and_write(
        &path.display().to_string(),
        &sc,
        &source,
        outputs,
        quiet,
        limits,
    )
}

fn solve_network(
    path: &Path,
    args: &NetworkArgs,
    outputs: Outputs,
    quiet: bool,
    limits: &Limits,
) -> i32 {
    let mut all = outputs.list();
    if let Some(p) = &args.scene_out {
        all.push(("--scene-out", p));
    }
    let mut inputs = vec![path];
    inputs.extend(outputs.initial.as_deref());
    if let Err(e) = check_outputs(&all, &inputs) {
        return bad(e);
    }
    let net = match network::load(path, args, limits.memory) {
        Ok(n) => n,
        Err(e) => return bad(e),
    };
    if let Some(p) = &args.scene_out {
        let command: Vec<String> = std::env::args().collect();
        let text = match network::scene_ron(&net, &command.join(" ")) {
            Ok(t) => t,
            Err(e) => return bad(e),
        };
        if let Err(e) = atomic_write(p, text.as_bytes()) {
            return bad(e);
        }
        if args.scene_only {
            return EXIT_OK;
        }
    }
    let scene = net.scene().clone();
    let label = path.display().to_string();
    solve_and_write(
        &label,
        &scene,
        &Source::Network(Box::new(net)),
        outputs,
        quiet,
        limits,
    )
}

fn solve_and_write(
    label: &str,
    sc: &Scene,
    source: &Source,
    outputs: Outputs,
    quiet: bool,
    limits: &Limits,
) -> i32 {
    let mut settings = limits.settings_of(sc);
    let tracker = progress::Tracker::begin(settings.load_steps, show_progress(quiet));
    settings.progress = Some(tracker.hook());
    let mut stage_error = None;
    let result = match (&outputs.initial, outputs.extrapolate) {
        (None, Some(levels)) => crate::study::extrapolate::solve_levels(sc, &settings, levels)
            .map_err(|e| match e {
                job::JobError::Scene(e) => source.describe(&e),
                job::JobError::Refused(m) => format!("--extrapolate: {m}"),
            }),
        (None, None) => job::solve_stages(sc, &settings, |sol| {
            // A stage's results are written as it completes (the last with the others below).
            let name = sol.results.stage.as_ref().map_or("", |s| s.name.as_str());
            let written = outputs
                .results_files(sol, Some(name))
                .and_then(|files| write_files(&files));
            if let Err(e) = written {
                stage_error.get_or_insert(e);
            }
            if let Some(st) = &sol.results.stage {
                if !quiet {
                    eprintln!(
                        "rodnet: stage {} \"{}\" converged in {} iterations, energy {:.9e} J",
                        st.index, st.name, st.iterations, st.energy
                    );
                }
            }
        })
        .map_err(|e| source.describe(&e)),
        (Some(f), _) => match read_initial(f) {
            Ok(init) => {
                job::solve_scene_from_joints(sc, &settings, &init.rods, init.joints.as_deref())
                    .map_err(|e| match e {
                        job::JobError::Scene(e) => source.describe(&e),
                        job::JobError::Refused(m) => format!("--initial {}: {m}", f.display()),
                    })
            }
            Err(e) => Err(e),
        },
    };
    let seen = tracker.finish();
    let mut sol = match result {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    if let Some(e) = stage_error {
        return bad(e);
    }
    let modes = match outputs.modes {
        Some(k) if sol.results.all_finite() => match crate::jobs::analyse_modes(&mut sol, k) {
            Ok(st) => Some(st),
            Err(e) => return bad(format_args!("{label}: eigen-analysis: {e}")),
        },
        _ => None,
    };
    let r = &sol.results;
    let steps = settings.load_steps;
    // Where the solve was when it stopped, for failure messages.
    let stage = || {
        let step = seen.last.map_or(1, |s| s.step);
        let largest = match seen.largest_in_step {
            Some(b) => format!(
                "; largest relative residual in load step {step}/{steps}: {:.3e} (iteration {})",
                b.residual, b.iteration
            ),
            None => String::new(),
        };
        (step, largest)
    };
    let diagnostic = diagnostic(&sol.report.message);
    if !r.all_finite() {
        let (step, largest) = stage();
        eprintln!(
            "error: {label}: the Newton solve diverged at load step {step}/{steps} (non-finite \
             values: {diagnostic}){largest}; no results written"
        );
        return EXIT_NOT_CONVERGED;
    }
    let mut files = match outputs.results_files(&sol, None) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
    if let (Some(p), Some(st)) = (&outputs.modes_obj, &modes) {
        let labels: Vec<String> = st
            .eigenvalues
            .iter()
            .enumerate()
            .map(|(i, l)| format!("mode_{} eigenvalue {l:.6e} N/m", i + 1))
            .collect();
        files.push((
            p.clone(),
            crate::jobs::modes_obj(&sol.network, &labels, &st.modes).into_bytes(),
        ));
    }
    if let Err(e) = write_files(&files) {
        return bad(e);
    }
    println!(
        "{label}: {} in {} iterations over {} load step(s), relative residual {:.3e}, energy {:.9e} J, {:.3} s{}",
        if r.converged { "converged" } else { "NOT converged" },
        r.iterations,
        r.load_steps,
        r.residual,
        r.energy.total,
        r.seconds,
        if !r.converged || r.solver.stable {
            ""
        } else if r.solver.stability_note.is_some() {
            " (stability not decided: dead moments are not conservative; solver.stability_note)"
        } else if r.solver.zero_modes > 0 {
            " (neutral, not stable: zero-stiffness modes that the loads leave alone, e.g. a rod \
             free to turn about the line through its supports; solver.zero_modes)"
        } else {
            " (unstable: the Hessian has a direction of negative curvature)"
        }
    );
    for e in &r.path_events {
        let stage = e
            .stage
            .as_ref()
            .map_or(String::new(), |s| format!(" of stage \"{s}\""));
        eprintln!(
            "warning: {label}: the load path passed a {} at load factor {:.6}{stage}: {}",
            e.kind.name(),
            e.load_factor,
            e.detail
        );
    }
    if let Some(x) = &r.extrapolation {
        print_extrapolation(label, x);
    }
    if let Some(st) = &modes {
        print_modes(label, st);
    }
    if r.converged {
        if let Some(m) = &sol.report.message {
            eprintln!("rodnet: {m}");
        }
        EXIT_OK
    } else {
        let (step, largest) = stage();
        eprintln!(
            "error: {label}: the Newton solve stopped at load step {step}/{steps}: {diagnostic}\
             {largest}; results written with \"converged\": false"
        );
        EXIT_NOT_CONVERGED
    }
}

/// The `--modes` eigenvalues and verdict on stderr, as the results JSON's `stability` has them.
fn print_modes(label: &str, st: &crate::network::stability::Stability) {
    let values: Vec<String> = st.eigenvalues.iter().map(|l| format!("{l:.6e}")).collect();
    let verdict = match (&st.zero_kind, st.stable) {
        _ if st.negative > 0 => format!(
            "unstable ({}{} negative)",
            if st.negative_at_least {
                "at least "
            } else {
                ""
            },
            st.negative
        ),
        (Some(kind), _) => format!(
            "{} ({} zero mode(s), {kind})",
            if st.stable { "stable" } else { "not stable" },
            st.zero_modes
        ),
        (None, true) => "stable".to_string(),
        (None, false) => "not stable".to_string(),
    };
    eprintln!(
        "{label}: lowest {} eigenvalue(s) (N/m): {}; {verdict}{}",
        values.len(),
        values.join(", "),
        if st.converged {
            ""
        } else {
            " (eigenvalues not settled)"
        }
    );
}

fn write_files(files: &[(PathBuf, Vec<u8>)]) -> Result<(), String> {
    atomic::write_all(files).map_err(|(p, e)| format!("cannot write {}: {e}", p.display()))
}

/// The rods of an earlier results JSON (`--initial`).
fn read_initial(f: &Path) -> Result<crate::io::initial::Initial, String> {
    let text = scene::read_text(f, "initial results", super::plot::MAX_JSON_BYTES)
        .map_err(|e| e.to_string())?;
    crate::io::initial::parse(&text).map_err(|e| format!("--initial {}: {e}", f.display()))
}

fn print_extrapolation(label: &str, x: &crate::io::results::ExtrapolationJson) {
    let iterations = match x.middle_iterations {
        Some(m) => format!("{} + {m} + {}", x.coarse_iterations, x.fine_iterations),
        None => format!("{} + {}", x.coarse_iterations, x.fine_iterations),
    };
    let (levels, order) = if x.levels == 3 {
        let observed = x
            .observed_order
            .map_or("not measurable".to_string(), |p| format!("{p:.2}"));
        (
            "×1, ×2 and ×4",
            format!("orders 2 and 3 removed, observed order {observed}"),
        )
    } else {
        ("×1 and ×2", format!("order {}", x.order))
    };
    println!(
        "{label}: extrapolated from subdivisions {levels} ({order}): the finest solve's error \
         estimated at {:.3e} m ({:.3e} of the structure's size); {iterations} iterations, \
         {:.3} s in all",
        x.error_estimate, x.relative_error_estimate, x.seconds
    );
    if let Some(e) = x.extrapolate_error_estimate {
        println!("{label}: the extrapolate's own error is at most about {e:.3e} m");
    }
}
