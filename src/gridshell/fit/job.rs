//! The fit job: net and footprint on a target mesh, form finding from the net, comparison with
//! the target and the net.
//!
//! The form finding starts from the net itself: every node of the footprint goes to the net
//! point of its parameters (an isometric placement of the rods, as the hemisphere job's
//! `start_cap = 1`), the ends on their boundary points. Newton then finds the equilibrium
//! nearest the net; where that is a saddle, Newton leaves it along negative curvature (its
//! saddle escape) until the Hessian is positive definite, and the report says so. Should
//! Newton fail from the net, the footprint's own path is taken: flat start, ends moved by the
//! continuation, `buckle_toward` the surface's side (what `rodnet solve` does with
//! `--scene-out`'s scene).

use std::sync::Arc;
use std::time::Instant;

use super::footprint::{footprint, FitFootprint, FitSpec, Plane};
use super::net::{EndKind, Family, Net};
use crate::gridshell::formfind::turn_frames;
use crate::io::results::Results;
use crate::math::vec::{dot, norm, sub};
use crate::network::equilibrium::NetBlock;
use crate::network::{Network, NetworkProblem};
use crate::pipeline::{self, Limits};
use crate::scene::FieldError;
use crate::solver::{NewtonReport, NewtonSettings, Progress};
use crate::surface::Surface;

pub struct FitRun {
    pub spec: FitSpec,
    pub footprint: FitFootprint,
    pub network: Network,
    pub report: NewtonReport,
    pub results: Results,
    pub net_block: NetBlock,
    /// The solve started from the net (false: from the flat footprint, after a failure).
    pub from_net: bool,
    /// Net and footprint, s; form finding, s.
    pub net_seconds: f64,
    pub form_seconds: f64,
}

pub enum FitError {
    /// The options or the surface allow no net.
    Net(String),
    Scene(FieldError),
}

pub fn run(
    surface: &Arc<Surface>,
    mesh_path: &str,
    spec: &FitSpec,
    progress: Option<Progress>,
    limits: &Limits,
) -> Result<FitRun, FitError> {
    let t0 = Instant::now();
    let fp = footprint(surface, mesh_path, spec, limits.memory).map_err(FitError::Net)?;
    crate::scene::validate::validate(&fp.scene).map_err(FitError::Scene)?;
    let net_seconds = t0.elapsed().as_secs_f64();
    let mut settings = limits.settings_of(&fp.scene);
    settings.progress = progress;
    let mut from_net = true;
    let mut form_seconds = 0.0;
    let mut net_block = None;
    let solution = pipeline::run(
        &fp.scene,
        &settings,
        |network, settings| {
            let t = Instant::now();
            let start = network.model.state.clone();
            let r = from_the_net(network, settings, &fp, surface);
            let r = if r.converged {
                r
            } else {
                from_net = false;
                network.model.state = start;
                crate::network::solve(&mut network.model, settings)
            };
            form_seconds = t.elapsed().as_secs_f64();
            r
        },
        |network, eq| {
            let b = net_block_of(network, &fp);
            if let Some(t) = eq.target.as_mut() {
                t.net = Some(b.clone());
            }
            net_block = Some(b);
        },
    )
    .map_err(FitError::Scene)?;
    Ok(FitRun {
        spec: spec.clone(),
        report: solution.report,
        results: solution.results,
        network: solution.network,
        net_block: net_block.expect("the pipeline measures"),
        footprint: fp,
        from_net,
        net_seconds,
        form_seconds,
    })
}

/// Newton from the net: nodes on the net points of their footprint parameters.
fn from_the_net(
    network: &mut Network,
    settings: &NewtonSettings,
    fp: &FitFootprint,
    surface: &Surface,
) -> NewtonReport {
    let model = &mut network.model;
    let flat = model.world_positions();
    let placed: Vec<[f64; 3]> = flat
        .iter()
        .map(|&x| net_point(&fp.net, &fp.plane, x))
        .collect();
    let normals: Vec<[f64; 3]> = placed.iter().map(|&p| surface.closest(p).normal).collect();
    for (n, p) in placed.iter().enumerate() {
        model.set_world_position(n, *p);
    }
    turn_frames(model, &|_| fp.plane.side, &normals);
    for p in &mut model.prescribed {
        p.start = model.state.q[p.var];
    }
    model.commit();
    let mut problem = NetworkProblem::new(model);
    problem.solve(&settings.clone().load_steps(1))
}

/// The net point of the footprint point `x`: on the U rod through it when there is one, else on
/// the V rod.
fn net_point(net: &Net, plane: &Plane, x: [f64; 3]) -> [f64; 3] {
    let d = sub(x, plane.base);
    let (u, v) = (dot(d, plane.e1), dot(d, plane.e2));
    let tol = 1e-9 * net.spacing;
    let on = |family: Family, offset: f64, t: f64| {
        net.rods.iter().find(|r| {
            r.family == family
                && (r.offset - offset).abs() <= tol
                && r.ends[0].param - tol <= t
                && t <= r.ends[1].param + tol
        })
    };
    if let Some(r) = on(Family::U, v, u) {
        return r.point_at(u);
    }
    on(Family::V, u, v).map_or(x, |r| r.point_at(v))
}

/// The `net` block: the net's size and angles, and each joint's distance to its crossing.
fn net_block_of(network: &Network, fp: &FitFootprint) -> NetBlock {
    let (mut max, mut sum2) = (0.0f64, 0.0);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (j, &c) in network.joints.iter().zip(&fp.crossings) {
        let crossing = &fp.net.crossings[c];
        let d = norm(sub(network.model.world_position(j.node), crossing.point));
        max = max.max(d);
        sum2 += d * d;
        lo = lo.min(crossing.angle);
        hi = hi.max(crossing.angle);
    }
    let count = network.joints.len().max(1) as f64;
    NetBlock {
        spacing: fp.net.spacing,
        rods: fp.scene.rods.len(),
        joints: network.joints.len(),
        min_angle_deg: lo.to_degrees(),
        max_angle_deg: hi.to_degrees(),
        max_net_distance: max,
        rms_net_distance: (sum2 / count).sqrt(),
    }
}

impl FitRun {
    /// Rods that stop inside the surface, and why: "u3 end: net locks … at (x, y, z)".
    pub fn stops(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (rod, &ri) in self.footprint.scene.rods.iter().zip(&self.footprint.rods) {
            let r = &self.footprint.net.rods[ri];
            for (side, e) in ["start", "end"].iter().zip(&r.ends) {
                if e.kind != EndKind::Boundary {
                    let p = e.point;
                    out.push(format!(
                        "{} {side} stopped at ({:.4}, {:.4}, {:.4}) m: {}",
                        rod.name,
                        p[0],
                        p[1],
                        p[2],
                        e.kind.describe()
                    ));
                }
            }
        }
        out
    }

    /// The rods as the footprint lays them out, for the cut list and the drawing.
    pub fn footprint_rods(&self) -> Vec<crate::io::footprint::FootprintRod> {
        let fp = &self.footprint;
        let mut crossings: Vec<Vec<(String, f64)>> = vec![Vec::new(); fp.scene.rods.len()];
        let index = |name: &str| fp.scene.rods.iter().position(|r| r.name == name);
        for (joint, &c) in fp.scene.joints.iter().zip(&fp.crossings) {
            let uv = fp.net.crossings[c].uv;
            for (rod, _) in &joint.at {
                let Some(k) = index(rod) else { continue };
                let r = &fp.net.rods[fp.rods[k]];
                let t = if r.family == Family::U { uv[0] } else { uv[1] };
                crossings[k].push((joint.name.clone(), t - r.ends[0].param));
            }
        }
        fp.scene
            .rods
            .iter()
            .zip(&fp.rods)
            .zip(crossings)
            .map(|((rod, &ri), crossings)| {
                let r = &fp.net.rods[ri];
                let at = |t: f64| match r.family {
                    Family::U => [t, r.offset],
                    Family::V => [r.offset, t],
                };
                crate::io::footprint::FootprintRod {
                    name: rod.name.clone(),
                    family: r.family.name(),
                    offset: r.offset,
                    ends: [at(r.ends[0].param), at(r.ends[1].param)],
                    crossings,
                }
            })
            .collect()
    }

    pub fn summary(&self) -> String {
        super::report::summary(self)
    }
}
