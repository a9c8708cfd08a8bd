//! Solving points: one job through the pipeline (also Python's solves), one point with its
//! results file, and every point on local threads, one solve per thread.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use serde_json::{json, Value as Json};

use super::{Job, Sweep};
use crate::gridshell::job::{self as gridshell_job, GridshellJson};
use crate::io::results::Results;
use crate::pipeline::{self, Limits};
use crate::scene::{FieldError, SceneError};
use crate::solver::Progress;

/// A solved job: the results JSON's content, and the gridshell block for generated domes.
pub struct Solved {
    pub results: Results,
    pub gridshell: Option<GridshellJson>,
}

impl Solved {
    /// The results JSON (with the `gridshell` block where there is one).
    pub fn to_json(&self) -> Json {
        let mut v = serde_json::to_value(&self.results).expect("results serialize");
        if let (Some(g), Json::Object(m)) = (&self.gridshell, &mut v) {
            m.insert(
                "gridshell".into(),
                serde_json::to_value(g).expect("the gridshell block serializes"),
            );
        }
        v
    }
}

/// Why a job has no results: its scene (a field the builder refuses), or the solve.
#[derive(Debug, Clone)]
pub enum Failure {
    Scene(FieldError),
    Solve(String),
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Scene(e) => write!(f, "{}: {}", e.path(), e.message),
            Failure::Solve(m) => f.write_str(m),
        }
    }
}

/// Solves a job (with the lowest `modes` eigenvalues at the equilibrium, if asked). A failure
/// is a scene the builder refuses, a failed eigen-analysis, or non-finite results; a solve that
/// does not converge is not one (its results say `converged: false`).
pub fn solve(
    job: &Job,
    modes: Option<usize>,
    progress: Option<Progress>,
    limits: &Limits,
) -> Result<Solved, Failure> {
    solve_levels(job, None, modes, progress, limits)
}

/// [`solve`] of a scene at `levels` (2 or 3) subdivisions, extrapolated (`study::extrapolate`,
/// as `rodnet solve --extrapolate --levels`); the modes are the finest equilibrium's.
pub fn solve_extrapolated(
    job: &Job,
    levels: usize,
    modes: Option<usize>,
    progress: Option<Progress>,
    limits: &Limits,
) -> Result<Solved, Failure> {
    solve_levels(job, Some(levels), modes, progress, limits)
}

fn solve_levels(
    job: &Job,
    extrapolate: Option<usize>,
    modes: Option<usize>,
    progress: Option<Progress>,
    limits: &Limits,
) -> Result<Solved, Failure> {
    let (results, gridshell) = match job {
        Job::Scene(scene) => {
            let mut settings = limits.settings_of(scene);
            settings.progress = progress;
            let mut sol = match extrapolate {
                None => pipeline::solve_scene(scene, &settings).map_err(Failure::Scene)?,
                Some(levels) => crate::study::extrapolate::solve_levels(scene, &settings, levels)
                    .map_err(|e| match e {
                    pipeline::JobError::Scene(e) => Failure::Scene(e),
                    pipeline::JobError::Refused(m) => Failure::Solve(m),
                })?,
            };
            if let (Some(k), true) = (modes, sol.results.all_finite()) {
                crate::jobs::analyse_modes(&mut sol, k)
                    .map_err(|e| Failure::Solve(format!("eigen-analysis: {e}")))?;
            }
            (sol.results, None)
        }
        Job::Hemisphere(_) if extrapolate.is_some() => {
            return Err(Failure::Solve(
                "extrapolation applies to scenes, not to a generated gridshell job".into(),
            ));
        }
        Job::Hemisphere(h) => {
            let mut run =
                gridshell_job::run(&h.spec, h.start_cap, progress, limits).map_err(|e| {
                    Failure::Solve(format!(
                        "the generated scene is invalid: {}: {}",
                        e.path(),
                        e.message
                    ))
                })?;
            if let (Some(k), true) = (h.modes.or(modes), run.results.all_finite()) {
                let st = crate::network::stability::analyse(&mut run.network, k)
                    .map_err(|e| Failure::Solve(format!("eigen-analysis: {e}")))?;
                run.results.stability = Some((&st).into());
            }
            let g = run.gridshell_json();
            (run.results, Some(g))
        }
    };
    if !results.all_finite() {
        return Err(Failure::Solve(format!(
            "the solve produced non-finite values ({})",
            results
                .solver
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        )));
    }
    Ok(Solved { results, gridshell })
}

/// The message of a caught panic.
pub fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// One point's outcome.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub index: usize,
    /// Its results file existed (from an earlier run) and was kept.
    pub skipped: bool,
    /// The point's file content: the results JSON plus the `sweep` block.
    pub record: Json,
}

/// Whether a results file holds a finished point (failed points are tried again).
pub fn finished(file: &Path) -> Option<Json> {
    let text = std::fs::read(file).ok()?;
    let v: Json = serde_json::from_slice(&text).ok()?;
    v.pointer("/sweep/error")
        .is_none_or(Json::is_null)
        .then_some(v)
}

/// FNV-1a, 64 bits: a hash that stays the same across Rust versions and platforms (the
/// standard library's does not promise to), for fingerprints written into result files.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

impl Sweep {
    /// The fingerprint of point `i`'s inputs: the base scene (as parsed, so that comments and
    /// layout do not count) or the generator's fixed options, and every parameter's value. A
    /// point file with another fingerprint was solved from other inputs and is solved again.
    pub fn fingerprint(&self, i: usize) -> String {
        let base = match &self.base {
            super::Base::Scene { json, .. } => json!({ "scene": json }),
            super::Base::Hemisphere(fixed) => json!({
                "hemisphere": fixed.0.iter().map(|(k, v)| json!([k, v.to_json()]))
                    .collect::<Vec<_>>(),
            }),
        };
        let parameters: Vec<Json> = self.points[i]
            .parameters
            .iter()
            .map(|(k, v)| json!([k, v.to_json()]))
            .collect();
        let all = json!({ "base": base, "parameters": parameters });
        let text = serde_json::to_string(&all).expect("JSON serializes");
        format!("{:016x}", fnv1a(text.as_bytes()))
    }

    /// Point `i`'s record when its file holds a finished point solved from the same inputs
    /// (its fingerprint matches): what a resumed sweep keeps.
    pub fn finished_point(&self, i: usize) -> Option<Json> {
        let record = finished(&self.point_file(i))?;
        let same = record.pointer("/sweep/fingerprint").and_then(Json::as_str)
            == Some(self.fingerprint(i).as_str());
        same.then_some(record)
    }

    /// Refuses, before anything is solved, a point whose results file could not be written
    /// where it is: a directory, a named pipe or socket, a dangling link (`io::atomic::target`).
    /// (A write that still fails later, a full disk, is the point's own error.)
    pub fn check_point_files(&self) -> Result<(), String> {
        (0..self.points.len()).try_for_each(|i| {
            let file = self.point_file(i);
            crate::io::atomic::target(&file)
                .map(|_| ())
                .map_err(|e| format!("cannot write {}: {e}", file.display()))
        })
    }

    /// Runs point `i` unless its results exist from the same inputs, and writes its file; `Err`
    /// only when the file cannot be written.
    pub fn run_point(&self, i: usize) -> Result<Outcome, String> {
        let file = self.point_file(i);
        if let Some(record) = self.finished_point(i) {
            return Ok(Outcome {
                index: i,
                skipped: true,
                record,
            });
        }
        let t0 = Instant::now();
        let solved = self.job(i).map_err(|e| e.to_string()).and_then(|job| {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                solve(&job, None, None, &self.limits).map_err(|f| f.to_string())
            }))
            .unwrap_or_else(|p| Err(format!("internal error: {}", panic_message(&*p))))
        });
        let seconds = t0.elapsed().as_secs_f64();
        let p = &self.points[i];
        let parameters: serde_json::Map<String, Json> = p
            .parameters
            .iter()
            .map(|(k, v)| (k.clone(), v.to_json()))
            .collect();
        let (mut record, error) = match solved {
            Ok(s) => (s.to_json(), Json::Null),
            Err(e) => (
                json!({"converged": false, "iterations": 0}),
                Json::String(e),
            ),
        };
        record["sweep"] = json!({
            "index": i,
            "name": p.name,
            "parameters": parameters,
            "seconds": seconds,
            "error": error,
            "fingerprint": self.fingerprint(i),
        });
        std::fs::create_dir_all(&self.output)
            .map_err(|e| format!("cannot create {}: {e}", self.output.display()))?;
        let bytes = serde_json::to_vec_pretty(&record).expect("JSON serializes");
        crate::io::atomic::write(&file, &bytes)
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        Ok(Outcome {
            index: i,
            skipped: false,
            record,
        })
    }

    /// Runs every point on `jobs` threads, one solve per thread (each thread's parallel loops
    /// run on that thread alone, so that `jobs` solves use `jobs` cores); `done` sees each
    /// outcome as it comes. Outcomes in point order.
    pub fn run(
        &self,
        jobs: usize,
        done: &(dyn Fn(&Result<Outcome, String>) + Sync),
    ) -> Vec<Result<Outcome, String>> {
        let next = AtomicUsize::new(0);
        let n = self.points.len();
        let jobs = jobs.clamp(1, n.max(1));
        let mut all: Vec<(usize, Result<Outcome, String>)> = std::thread::scope(|s| {
            let workers: Vec<_> = (0..jobs)
                .map(|_| {
                    s.spawn(|| {
                        let pool = rayon::ThreadPoolBuilder::new()
                            .num_threads(1)
                            .build()
                            .expect("a one-thread pool builds");
                        let mut mine = Vec::new();
                        loop {
                            let i = next.fetch_add(1, Ordering::Relaxed);
                            if i >= n {
                                break;
                            }
                            let r = pool.install(|| self.run_point(i));
                            done(&r);
                            mine.push((i, r));
                        }
                        mine
                    })
                })
                .collect();
            workers
                .into_iter()
                .flat_map(|w| w.join().expect("sweep workers catch their panics"))
                .collect()
        });
        all.sort_by_key(|(i, _)| *i);
        all.into_iter().map(|(_, r)| r).collect()
    }

    /// The sweep's manifest: what `merge` needs to build the table from the points' files.
    pub fn manifest(&self) -> Json {
        let abs = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        json!({
            "sweep": abs(Path::new(&self.file)),
            "output": abs(&self.output),
            "parameters": self.parameters,
            "quantities": self.quantities,
            "points": self.points.iter().map(|p| json!({
                "index": p.index,
                "name": p.name,
                "fingerprint": self.fingerprint(p.index),
                "parameters": p.parameters.iter().map(|(k, v)| (k.clone(), v.to_json()))
                    .collect::<serde_json::Map<_, _>>(),
            })).collect::<Vec<_>>(),
        })
    }

    /// Writes the manifest into the output folder (created).
    pub fn write_manifest(&self) -> Result<(), SceneError> {
        let fail = |m: String| super::error(&self.file, "", None, m);
        std::fs::create_dir_all(&self.output)
            .map_err(|e| fail(format!("cannot create {}: {e}", self.output.display())))?;
        let p = self.output.join(super::table::MANIFEST);
        let bytes = serde_json::to_vec_pretty(&self.manifest()).expect("JSON serializes");
        crate::io::atomic::write(&p, &bytes)
            .map_err(|e| fail(format!("cannot write {}: {e}", p.display())))
    }
}
