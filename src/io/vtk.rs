//! VTK XML output of an equilibrium: `.vtp` PolyData (ParaView, VTK) or `.vtu`
//! UnstructuredGrid (the same data for readers without PolyData, such as meshio 5).
//!
//! Written by hand rather than with `vtkio` (a release candidate, 0.7.0-rc2): the files are
//! ASCII, a few dozen lines of XML. Numbers use Rust's shortest round-trip form, so a reader
//! gets the results JSON's values exactly.
//!
//! Each rod's nodes are the points, rod after rod, in the order of the results' `rods` (nodes
//! shared at joints appear once per rod). Each edge is one 2-point line cell, so that per-edge
//! quantities are exact cell data; the `rod` and `edge` cell fields give each cell's rod and
//! its place along it (ParaView's Tube filter draws the cells as one tube per edge).

use std::fmt::Write;
use std::path::Path;

use crate::io::results::{Results, RodJson};

/// Which VTK XML dataset to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    PolyData,
    UnstructuredGrid,
}

impl Format {
    /// The format a file name asks for: `.vtp` or `.vtu`.
    pub fn of(path: &Path) -> Result<Format, String> {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("vtp") => Ok(Format::PolyData),
            Some(e) if e.eq_ignore_ascii_case("vtu") => Ok(Format::UnstructuredGrid),
            _ => Err(format!(
                "{}: name the VTK file .vtp (PolyData: ParaView) or .vtu (UnstructuredGrid: \
                 ParaView, meshio)",
                path.display()
            )),
        }
    }
}

/// A data array: name, components per tuple and the values, tuple after tuple.
enum Values {
    Float(Vec<f64>),
    Int(Vec<i64>),
}

struct Field {
    name: &'static str,
    components: usize,
    values: Values,
}

/// Edges of a rod as (first node, second node) indices in its `points`: closed rods (as many
/// twist angles as nodes) close back to their first node.
fn edges(r: &RodJson) -> Vec<(usize, usize)> {
    let n = r.points.len();
    let m = if r.twist.len() == n {
        n
    } else {
        n.saturating_sub(1)
    };
    (0..m).map(|k| (k, (k + 1) % n)).collect()
}

/// The per-node fields every rod has, in the rods' order.
fn point_fields(r: &Results) -> Vec<Field> {
    let rods = &r.rods;
    let mut out = vec![
        int_field("rod", rods, |i, rod| vec![i as i64; rod.points.len()]),
        int_field("node", rods, |_, rod| {
            (0..rod.points.len() as i64).collect()
        }),
    ];
    let full = |f: fn(&RodJson) -> usize| rods.iter().all(|rod| f(rod) == rod.points.len());
    if full(|rod| rod.bending_stress.len()) {
        out.push(float_field("bending_stress", 1, rods, |rod| {
            rod.bending_stress.clone()
        }));
    }
    if full(|rod| rod.rest_points.len()) {
        out.push(float_field("displacement", 3, rods, |rod| {
            rod.points
                .iter()
                .zip(&rod.rest_points)
                .flat_map(|(p, q)| [p[0] - q[0], p[1] - q[1], p[2] - q[2]])
                .collect()
        }));
    }
    if full(|rod| rod.target_distance.len()) {
        out.push(float_field("target_distance", 1, rods, |rod| {
            rod.target_distance.clone()
        }));
    }
    out
}

/// The per-edge fields every rod has.
fn cell_fields(r: &Results) -> Vec<Field> {
    let rods = &r.rods;
    let mut out = vec![
        int_field("rod", rods, |i, rod| vec![i as i64; edges(rod).len()]),
        int_field("edge", rods, |_, rod| {
            (0..edges(rod).len() as i64).collect()
        }),
    ];
    let full = |f: fn(&RodJson) -> usize| rods.iter().all(|rod| f(rod) == edges(rod).len());
    if full(|rod| rod.twist.len()) {
        out.push(float_field("twist", 1, rods, |rod| rod.twist.clone()));
    }
    if full(|rod| rod.forces.len()) {
        let each = |g: fn(&crate::io::results::EdgeForceJson) -> Vec<f64>| {
            move |rod: &RodJson| rod.forces.iter().flat_map(g).collect()
        };
        out.push(float_field("axial", 1, rods, each(|f| vec![f.axial])));
        out.push(float_field("shear", 2, rods, each(|f| f.shear.to_vec())));
        out.push(float_field("moment", 2, rods, each(|f| f.moment.to_vec())));
        out.push(float_field("torsion", 1, rods, each(|f| vec![f.torsion])));
        // Only when every edge has one: a filler value would read as a utilization.
        if rods
            .iter()
            .flat_map(|rod| &rod.forces)
            .all(|f| f.utilization.is_some())
        {
            out.push(float_field(
                "utilization",
                1,
                rods,
                each(|f| f.utilization.into_iter().collect()),
            ));
        }
    }
    out
}

fn int_field(
    name: &'static str,
    rods: &[RodJson],
    f: impl Fn(usize, &RodJson) -> Vec<i64>,
) -> Field {
    let values = rods.iter().enumerate().flat_map(|(i, r)| f(i, r)).collect();
    Field {
        name,
        components: 1,
        values: Values::Int(values),
    }
}

fn float_field(
    name: &'static str,
    components: usize,
    rods: &[RodJson],
    f: impl Fn(&RodJson) -> Vec<f64>,
) -> Field {
    Field {
        name,
        components,
        values: Values::Float(rods.iter().flat_map(f).collect()),
    }
}

/// The VTK XML file of the results. The caller checks that every number is finite
/// ([`Results::all_finite`]): XML has no NaN either.
pub fn to_vtk(r: &Results, format: Format) -> String {
    let n_points: usize = r.rods.iter().map(|rod| rod.points.len()).sum();
    let (mut connectivity, mut offsets) = (Vec::new(), Vec::new());
    let mut base = 0;
    for rod in &r.rods {
        for (a, b) in edges(rod) {
            connectivity.extend([(base + a) as i64, (base + b) as i64]);
            offsets.push(connectivity.len() as i64);
        }
        base += rod.points.len();
    }
    let n_cells = offsets.len();
    let (kind, piece) = match format {
        Format::PolyData => (
            "PolyData",
            format!(
                "NumberOfPoints=\"{n_points}\" NumberOfVerts=\"0\" NumberOfLines=\"{n_cells}\" \
                 NumberOfStrips=\"0\" NumberOfPolys=\"0\""
            ),
        ),
        Format::UnstructuredGrid => (
            "UnstructuredGrid",
            format!("NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\""),
        ),
    };
    let mut s = String::from("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(
        s,
        "<VTKFile type=\"{kind}\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n<{kind}>\n<Piece {piece}>"
    );
    section(&mut s, "PointData", &point_fields(r));
    section(&mut s, "CellData", &cell_fields(r));
    let points = Field {
        name: "points",
        components: 3,
        values: Values::Float(r.rods.iter().flat_map(|rod| rod.points.concat()).collect()),
    };
    section(&mut s, "Points", &[points]);
    let mut cells = vec![
        Field {
            name: "connectivity",
            components: 1,
            values: Values::Int(connectivity),
        },
        Field {
            name: "offsets",
            components: 1,
            values: Values::Int(offsets),
        },
    ];
    let cells_tag = match format {
        Format::PolyData => "Lines",
        Format::UnstructuredGrid => {
            // VTK_LINE.
            cells.push(Field {
                name: "types",
                components: 1,
                values: Values::Int(vec![3; n_cells]),
            });
            "Cells"
        }
    };
    section(&mut s, cells_tag, &cells);
    let _ = writeln!(s, "</Piece>\n</{kind}>\n</VTKFile>");
    s
}

fn section(s: &mut String, tag: &str, fields: &[Field]) {
    let _ = writeln!(s, "<{tag}>");
    for f in fields {
        data_array(s, f);
    }
    let _ = writeln!(s, "</{tag}>");
}

fn data_array(s: &mut String, f: &Field) {
    let ty = match (&f.values, f.name) {
        (Values::Float(_), _) => "Float64",
        // VTK's cell types are bytes.
        (Values::Int(_), "types") => "UInt8",
        (Values::Int(_), _) => "Int64",
    };
    let _ = writeln!(
        s,
        "<DataArray type=\"{ty}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">",
        f.name, f.components
    );
    let per_line = 3 * f.components.max(2);
    let line = |k: usize, s: &mut String| {
        s.push(if k > 0 && k.is_multiple_of(per_line) {
            '\n'
        } else {
            ' '
        });
    };
    match &f.values {
        // `{:e}` without a precision is the shortest form that reads back to the same double.
        Values::Float(v) => v.iter().enumerate().for_each(|(k, x)| {
            line(k, s);
            let _ = write!(s, "{x:e}");
        }),
        Values::Int(v) => v.iter().enumerate().for_each(|(k, x)| {
            line(k, s);
            let _ = write!(s, "{x}");
        }),
    }
    let _ = writeln!(s, "\n</DataArray>");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_picks_the_dataset() {
        assert_eq!(Format::of(Path::new("a/b.vtp")), Ok(Format::PolyData));
        assert_eq!(Format::of(Path::new("b.VTU")), Ok(Format::UnstructuredGrid));
        let e = Format::of(Path::new("b.vtk")).unwrap_err();
        assert!(e.contains("b.vtk") && e.contains(".vtp"), "{e}");
    }

    #[test]
    fn shortest_exponent_form_reads_back_exactly() {
        for x in [0.1f64, -1.0 / 3.0, 1e-300, 6.02214076e23, 0.0] {
            let t = format!("{x:e}");
            assert_eq!(t.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{t}");
        }
    }
}
