//! What `rodnet plot` draws, read from a results JSON: each rod's drawn and rest shapes, the
//! quantity that colours its edges, the supports and the point loads. Only `rods[].points` is
//! required; what a picture leaves out when a field is missing (and what it refuses) is in
//! docs/cli.md.

use crate::io::results::{Results, RodJson};
use crate::network::support::{Marker, SupportTag};

/// The quantity that colours the rods (`--color`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Extreme-fibre bending stress, Pa (node values; an edge shows the larger of its ends).
    Bending,
    /// Axial force, N, tension positive (edge values).
    Axial,
    /// Von Mises stress over yield strength (edge values).
    Utilization,
    /// Signed distance to the scene's target, m (node values; an edge shows their mean).
    Distance,
}

impl Quantity {
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Bending => "bending",
            Quantity::Axial => "axial",
            Quantity::Utilization => "utilization",
            Quantity::Distance => "distance",
        }
    }

    /// Caption of the colour scale and the unit of its end labels.
    pub fn caption(self) -> (&'static str, &'static str) {
        match self {
            Quantity::Bending => ("extreme-fibre bending stress", "Pa"),
            Quantity::Axial => ("axial force (tension positive)", "N"),
            Quantity::Utilization => ("utilization (von Mises / yield strength)", ""),
            Quantity::Distance => ("signed distance to the target", "m"),
        }
    }
}

/// One rod to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotRod {
    pub name: String,
    /// Drawn nodes: the rest shape plus the displacement times the deflection scale.
    pub points: Vec<[f64; 3]>,
    /// The rest shape, when the results have one.
    pub rest: Option<Vec<[f64; 3]>>,
    /// The colouring quantity on each edge.
    pub values: Vec<f64>,
    pub closed: bool,
}

/// A support, at its drawn position.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    pub at: [f64; 3],
    pub kind: SupportKindRead,
}

/// A support kind as a results JSON gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum SupportKindRead {
    Known(SupportTag),
    /// A name this build does not know, kept for the legend ("support" when the results do not
    /// say); drawn as a pin.
    Other(String),
}

impl SupportKindRead {
    fn of(name: Option<&str>) -> SupportKindRead {
        let name = name.unwrap_or("support");
        SupportTag::from_name(name).map_or_else(
            || SupportKindRead::Other(name.into()),
            SupportKindRead::Known,
        )
    }

    /// What the legend calls it.
    pub fn name(&self) -> &str {
        match self {
            SupportKindRead::Known(t) => t.name(),
            SupportKindRead::Other(name) => name,
        }
    }

    pub fn marker(&self) -> Marker {
        match self {
            SupportKindRead::Known(t) => t.marker(),
            SupportKindRead::Other(_) => Marker::Triangle,
        }
    }
}

/// A point load at its drawn position: force N, moment N·m.
#[derive(Debug, Clone, PartialEq)]
pub struct PointLoad {
    pub at: [f64; 3],
    pub force: [f64; 3],
    pub moment: [f64; 3],
}

#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    pub rods: Vec<PlotRod>,
    pub supports: Vec<Support>,
    pub loads: Vec<PointLoad>,
    pub quantity: Quantity,
    /// The values at the two ends of the colour scale.
    pub range: (f64, f64),
    pub deflection_scale: f64,
}

/// Reads a results JSON for a picture coloured by `quantity` (`None`: bending stress, or zero
/// where the results have none) with displacements drawn `scale` times their size. Errors name
/// the file and the offending key.
pub fn read(
    file: &str,
    text: &str,
    quantity: Option<Quantity>,
    scale: f64,
) -> Result<Picture, String> {
    let results = parse(file, text)?;
    let q = quantity.unwrap_or(Quantity::Bending);
    let mut rods = Vec::with_capacity(results.rods.len());
    for (i, r) in results.rods.iter().enumerate() {
        rods.push(plot_rod(i, r, q, quantity.is_some(), scale).map_err(|e| format!("{file}: {e}")))
    }
    let rods = rods.into_iter().collect::<Result<Vec<_>, _>>()?;
    let supports = results
        .reactions
        .iter()
        .enumerate()
        .filter_map(|(j, s)| s.node.map(|k| (j, s, k)))
        .map(|(j, s, k)| {
            let at = node_at(&rods, &s.rod, k).map_err(|e| format!("{file}: reactions[{j}]{e}"))?;
            let kind = SupportKindRead::of(s.kind.as_deref());
            Ok(Support { at, kind })
        })
        .collect::<Result<Vec<_>, String>>()?;
    let loads = results
        .loads
        .iter()
        .enumerate()
        .map(|(j, l)| {
            let at =
                node_at(&rods, &l.rod, l.node).map_err(|e| format!("{file}: loads[{j}]{e}"))?;
            let (force, moment) = (l.force, l.moment);
            Ok(PointLoad { at, force, moment })
        })
        .collect::<Result<Vec<_>, String>>()?;
    let values = || rods.iter().flat_map(|r| r.values.iter().copied());
    let hi = values().fold(0.0, f64::max);
    let range = match q {
        Quantity::Bending | Quantity::Utilization => (0.0, hi),
        Quantity::Axial | Quantity::Distance => (values().fold(0.0, f64::min), hi),
    };
    Ok(Picture {
        rods,
        supports,
        loads,
        quantity: q,
        range,
        deflection_scale: scale,
    })
}

fn parse(file: &str, text: &str) -> Result<Results, String> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let results: Results = serde_path_to_error::deserialize(de).map_err(|e| {
        let inner = e.inner();
        if e.path().iter().next().is_none() && inner.to_string().starts_with("missing field `rods`")
        {
            format!("{file}: no `rods` array: not a rodnet results JSON")
        } else {
            format!(
                "{file}:{}:{}: {}: {inner}",
                inner.line(),
                inner.column(),
                e.path()
            )
        }
    })?;
    if results.rods.is_empty() {
        return Err(format!("{file}: `rods` is empty: nothing to draw"));
    }
    Ok(results)
}

/// Drawn position of node `k` of the rod named `rod` (errors continue a located key).
fn node_at(rods: &[PlotRod], rod: &str, k: usize) -> Result<[f64; 3], String> {
    let r = rods
        .iter()
        .find(|r| r.name == rod)
        .ok_or_else(|| format!(".rod: no rod named {rod:?}"))?;
    r.points.get(k).copied().ok_or_else(|| {
        format!(
            ".node: {k} is beyond rod {rod:?}'s {} nodes",
            r.points.len()
        )
    })
}

fn plot_rod(
    i: usize,
    r: &RodJson,
    q: Quantity,
    asked: bool,
    scale: f64,
) -> Result<PlotRod, String> {
    let n = r.points.len();
    if n < 2 {
        return Err(format!("rods[{i}].points: needs at least 2 points"));
    }
    let rest = match r.rest_points.len() {
        0 => None,
        m if m == n => Some(r.rest_points.clone()),
        m => return Err(format!("rods[{i}].rest_points: {m} points for {n} points")),
    };
    let points = match &rest {
        Some(rest) => r
            .points
            .iter()
            .zip(rest)
            .map(|(p, q)| [0, 1, 2].map(|k| q[k] + scale * (p[k] - q[k])))
            .collect(),
        None if scale != 1.0 => {
            return Err(format!(
            "rods[{i}]: no `rest_points`, so displacements cannot be scaled (--deflection-scale \
                 needs results written by this rodnet version)"
        ))
        }
        None => r.points.clone(),
    };
    // Closed rods have as many edges (twist angles) as nodes.
    let closed = r.twist.len() == n;
    let edges = if closed { n } else { n - 1 };
    let values = edge_values(i, r, q, asked, edges)?;
    if let Some(k) = values.iter().position(|x| !x.is_finite()) {
        return Err(format!("rods[{i}]: {} value {k} is not finite", q.name()));
    }
    Ok(PlotRod {
        name: r.name.clone(),
        points,
        rest,
        values,
        closed,
    })
}

/// The quantity on each of the rod's `m` edges; node values are combined over each edge's ends.
fn edge_values(
    i: usize,
    r: &RodJson,
    q: Quantity,
    asked: bool,
    m: usize,
) -> Result<Vec<f64>, String> {
    let n = r.points.len();
    let missing = |key: &str| {
        format!(
            "rods[{i}].{key}: missing, so --color {} cannot be drawn (results of a scene without \
             it, or without rodnet's extensions)",
            q.name()
        )
    };
    let count = |key: &str, got: usize, want: usize| {
        format!(
            "rods[{i}].{key}: {got} values for {want} {}",
            if want == n { "points" } else { "edges" }
        )
    };
    let ends =
        |v: &[f64], f: fn(f64, f64) -> f64| (0..m).map(|k| f(v[k], v[(k + 1) % n])).collect();
    match q {
        Quantity::Bending => match r.bending_stress.len() {
            0 if asked => Err(missing("bending_stress")),
            // Contract-only results: the rod's maximum if given, else zero.
            0 => Ok(vec![r.max_bending_stress; m]),
            // Node stresses are zero at rod ends, also at clamped ones, where the moment is often
            // largest: an edge shows its larger end.
            k if k == n => Ok(ends(&r.bending_stress, f64::max)),
            k => Err(count("bending_stress", k, n)),
        },
        Quantity::Distance => match r.target_distance.len() {
            0 => Err(missing("target_distance")),
            k if k == n => Ok(ends(&r.target_distance, |a, b| 0.5 * (a + b))),
            k => Err(count("target_distance", k, n)),
        },
        Quantity::Axial | Quantity::Utilization => {
            if r.forces.is_empty() {
                return Err(missing("forces"));
            }
            if r.forces.len() != m {
                return Err(count("forces", r.forces.len(), m));
            }
            if q == Quantity::Axial {
                return Ok(r.forces.iter().map(|f| f.axial).collect());
            }
            r.forces
                .iter()
                .enumerate()
                .map(|(k, f)| {
                    f.utilization
                        .ok_or_else(|| missing(&format!("forces[{k}].utilization")))
                })
                .collect()
        }
    }
}
