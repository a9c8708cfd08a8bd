//! Indentation: a solved scene pushed at one point by displacement control (`rodnet indent`).

use crate::pipeline::{build_for, solve_scene, Limits, Solution};
use crate::scene::{FieldError, Scene};

/// What `rodnet indent` measures: the results as its `--json` writes them, and the curve.
pub struct Indentation {
    pub json: crate::io::indent::IndentJson,
    pub curve: crate::network::indent::Curve,
}

/// Why an indentation has no results.
pub enum IndentError {
    /// A field the builder refuses.
    Scene(FieldError),
    /// The scene's own solve did not converge (its message): nothing was pushed.
    NotConverged(String),
    /// The point to push (`at`), the depth or the direction is not one.
    At(String),
    /// The push could not be set up.
    Push(String),
}

/// Solves a validated scene, then pushes the point `at` (a joint's name, `ROD:VERTEX` or
/// `apex`) by `depth` m along `direction` in `steps` displacement-controlled steps: the linear
/// stiffness there, the force–depth curve and its limit points (`rodnet indent`).
pub fn indent(
    sc: &Scene,
    at: &str,
    direction: [f64; 3],
    depth: f64,
    steps: usize,
    limits: &Limits,
) -> Result<Indentation, IndentError> {
    use crate::network::indent::{linear_stiffness, push_built, Push};
    let n = direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    if !(n.is_finite() && n > 1e-150) {
        return Err(IndentError::At(format!(
            "direction must be finite and non-zero, got {direction:?}"
        )));
    }
    let direction = direction.map(|d| d / n);
    if !(depth.is_finite() && depth > 0.0) || steps == 0 {
        return Err(IndentError::At(format!(
            "depth must be a positive length in m and steps at least 1, got {depth} and {steps}"
        )));
    }
    let settings = limits.settings_of(sc);
    let mut sol = solve_scene(sc, &settings).map_err(IndentError::Scene)?;
    if !sol.results.converged {
        return Err(IndentError::NotConverged(
            sol.report.message.clone().unwrap_or_default(),
        ));
    }
    let (rod, vertex, joint) = locate(at, sc, &sol, direction).map_err(IndentError::At)?;
    let Some(node) = sol.network.rod(&rod).and_then(|r| r.vertex_node(vertex)) else {
        return Err(IndentError::At("no such vertex".into()));
    };
    let position = sol.network.model.world_position(node);
    let k = linear_stiffness(&mut sol.network, node, direction);
    let how = Push {
        rod: rod.clone(),
        vertex,
        direction,
        depth,
        steps,
    };
    // The push holds every stage's loads at their full values.
    let curve = push_built(&sc.all_stages(), &sol.network, &how, &settings, |s| {
        build_for(s, &settings).map_err(|e| e.message)
    })
    .map_err(IndentError::Push)?;
    let (pts, lims) = crate::io::indent::IndentJson::curve_of(&curve);
    let (curve_stability, bifurcations) = crate::io::indent::IndentJson::stability_of(&curve);
    let json = crate::io::indent::IndentJson {
        rod,
        vertex,
        joint,
        position,
        direction,
        depth,
        linear_stiffness: k.as_ref().ok().copied(),
        linear_stiffness_note: k.as_ref().err().cloned(),
        frictionless: curve.frictionless,
        max_lateral_force: curve.lateral,
        curve: pts,
        limit_points: lims,
        curve_stability,
        bifurcations,
        path_events: crate::io::indent::IndentJson::events_of(&curve),
        complete: curve.complete,
        message: curve.message.clone(),
        solve_iterations: sol.report.iterations,
        iterations: curve.iterations,
        seconds: curve.seconds,
    };
    Ok(Indentation { json, curve })
}

/// The pushed point of `rodnet indent --at` as (rod, input vertex, joint name).
fn locate(
    at: &str,
    sc: &Scene,
    sol: &Solution,
    d: [f64; 3],
) -> Result<(String, usize, Option<String>), String> {
    let along = |p: [f64; 3]| p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
    if at == "apex" {
        let net = &sol.network;
        let best = if sc.joints.is_empty() {
            net.rods
                .iter()
                .flat_map(|r| {
                    (0..r.nodes.len().div_ceil(r.subdivide.max(1)))
                        .filter_map(move |v| r.vertex_node(v).map(|n| (r.name.clone(), v, n)))
                })
                .map(|(r, v, n)| (along(net.model.position(n)), r, v, None))
                .min_by(|a, b| a.0.total_cmp(&b.0))
        } else {
            sc.joints
                .iter()
                .filter_map(|j| {
                    let info = net.joints.iter().find(|i| i.name == j.name)?;
                    let (r, v) = j.at[0].clone();
                    Some((
                        along(net.model.position(info.node)),
                        r,
                        v,
                        Some(j.name.clone()),
                    ))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
        };
        return best
            .map(|(_, r, v, j)| (r, v, j))
            .ok_or_else(|| "the scene has no vertex to push".into());
    }
    if let Some(j) = sc.joints.iter().find(|j| j.name == at) {
        let (r, v) = j.at[0].clone();
        return Ok((r, v, Some(j.name.clone())));
    }
    if let Some((rod, v)) = at.rsplit_once(':') {
        let v: usize = v
            .parse()
            .map_err(|_| format!("expected ROD:VERTEX with a vertex number, got {at:?}"))?;
        if sc.rods.iter().any(|r| r.name == rod) {
            return Ok((rod.to_string(), v, None));
        }
        return Err(format!("no rod named {rod:?}"));
    }
    Err("expected a joint's name, ROD:VERTEX or apex".into())
}
