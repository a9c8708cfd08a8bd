//! `--vtk`: the VTK XML file of a solve reads back with the results JSON's points, one line
//! cell per edge (closed rods back to their first node) and the JSON's values exactly; a file
//! name that is neither .vtp nor .vtu is refused before anything is solved or written.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-vtk-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A small reader of ASCII VTK XML: the attributes of its `Piece` and its data arrays by
/// section (`PointData/bending_stress`, `Points/points`, `Lines/offsets`, ...).
struct Vtk {
    kind: String,
    piece: HashMap<String, String>,
    arrays: HashMap<String, Vec<String>>,
}

fn attrs(tag: &str) -> HashMap<String, String> {
    tag.split_whitespace()
        .skip(1)
        .filter_map(|a| a.split_once('='))
        .map(|(k, v)| {
            (
                k.to_string(),
                v.trim_end_matches('>').trim_matches('"').to_string(),
            )
        })
        .collect()
}

fn read(p: &Path) -> Vtk {
    let text = std::fs::read_to_string(p).unwrap();
    let tag = |name: &str| {
        let i = text
            .find(&format!("<{name} "))
            .unwrap_or_else(|| panic!("no <{name}"));
        attrs(&text[i..i + text[i..].find('>').unwrap()])
    };
    let kind = tag("VTKFile")["type"].clone();
    let piece = tag("Piece");
    let mut arrays = HashMap::new();
    let mut section = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find('<') {
        let end = i + rest[i..].find('>').unwrap();
        let t = &rest[i + 1..end];
        rest = &rest[end + 1..];
        if let Some(a) = t.strip_prefix("DataArray ") {
            let a = attrs(&format!("x {a}"));
            let close = rest.find("</DataArray>").unwrap();
            let values = rest[..close].split_whitespace().map(String::from).collect();
            arrays.insert(format!("{section}/{}", a["Name"]), values);
            rest = &rest[close..];
        } else if !t.starts_with('/') && !t.starts_with('?') {
            section = t.split_whitespace().next().unwrap().to_string();
        }
    }
    Vtk {
        kind,
        piece,
        arrays,
    }
}

impl Vtk {
    fn floats(&self, name: &str) -> Vec<f64> {
        self.arrays[name]
            .iter()
            .map(|x| x.parse().unwrap())
            .collect()
    }
    fn ints(&self, name: &str) -> Vec<usize> {
        self.arrays[name]
            .iter()
            .map(|x| x.parse().unwrap())
            .collect()
    }
}

fn solve(scene: &str, d: &Path, name: &str) -> serde_json::Value {
    let json = d.join(format!("{name}.json"));
    let out = rodnet()
        .args(["solve", scene, "--quiet", "--json"])
        .arg(&json)
        .arg("--vtk")
        .arg(d.join(format!("{name}.vtp")))
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap()
}

#[test]
fn cantilever_reads_back_with_its_results() {
    let d = tmpdir("cantilever");
    let r = solve("networks/cantilever.ron", &d, "c");
    let v = read(&d.join("c.vtp"));
    assert_eq!(v.kind, "PolyData");
    let rod = &r["rods"][0];
    let n = rod["points"].as_array().unwrap().len();
    assert_eq!(v.piece["NumberOfPoints"], n.to_string());
    assert_eq!(v.piece["NumberOfLines"], (n - 1).to_string());
    let xyz: Vec<f64> = rod["points"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|p| p.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect();
    assert_eq!(v.floats("Points/points"), xyz);
    let conn = v.ints("Lines/connectivity");
    assert_eq!(conn.len(), 2 * (n - 1));
    assert!(conn.chunks(2).enumerate().all(|(k, c)| c == [k, k + 1]));
    assert_eq!(v.ints("Lines/offsets").last(), Some(&(2 * (n - 1))));
    let axial: Vec<f64> = rod["forces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["axial"].as_f64().unwrap())
        .collect();
    // Exactly: the file's numbers are the shortest forms of the same doubles.
    assert_eq!(v.floats("CellData/axial"), axial);
    let tip = v.floats("PointData/displacement");
    let (p, q) = (&rod["points"][n - 1], &rod["rest_points"][n - 1]);
    let dy = p[1].as_f64().unwrap() - q[1].as_f64().unwrap();
    assert_eq!(tip[3 * (n - 1) + 1], dy);
    assert!(dy < -0.4, "the tip moves down: {dy}");
}

/// An open rod clamped at one end and a closed ring pinned at three points, both loaded.
const TWO_RODS: &str = r#"Scene(
    materials: { "m": Material(young_modulus: 1e7, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [
        Rod(name: "arm", material: "m", points: [(0.0, 0.0, 0.0), (0.5, 0.0, 0.0), (1.0, 0.2, 0.0)], subdivide: 6),
        Rod(name: "ring", material: "m", points: [(2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (3.0, 1.0, 0.0), (2.0, 1.0, 0.0)],
            subdivide: 5, closed: true),
    ],
    supports: [
        Support(rod: "arm", vertex: 0, kind: Clamp),
        Support(rod: "ring", vertex: 0, kind: Pin),
        Support(rod: "ring", vertex: 1, kind: Pin),
        Support(rod: "ring", vertex: 3, kind: Pin),
    ],
    loads: [
        Force(rod: "arm", vertex: 2, force: (0.0, 0.0, -0.5)),
        Force(rod: "ring", vertex: 2, force: (0.3, 0.3, -0.2)),
    ],
)"#;

#[test]
fn closed_rods_close_their_cells_and_vtu_names_line_cells() {
    let d = tmpdir("closed");
    let scene = d.join("two.ron");
    std::fs::write(&scene, TWO_RODS).unwrap();
    let scene = scene.to_str().unwrap();
    let r = solve(scene, &d, "f");
    let out = rodnet()
        .args(["solve", scene, "--quiet", "--vtk"])
        .arg(d.join("f.vtu"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let u = read(&d.join("f.vtu"));
    assert_eq!(u.kind, "UnstructuredGrid");
    let rods = r["rods"].as_array().unwrap();
    let edges: usize = rods
        .iter()
        .map(|r| r["twist"].as_array().unwrap().len())
        .sum();
    assert_eq!(u.piece["NumberOfCells"], edges.to_string());
    assert!(u.ints("Cells/types").iter().all(|&t| t == 3));
    let (rod, conn) = (u.ints("CellData/rod"), u.ints("Cells/connectivity"));
    let mut base = 0;
    for (i, r) in rods.iter().enumerate() {
        let n = r["points"].as_array().unwrap().len();
        let cells: Vec<usize> = (0..rod.len()).filter(|&c| rod[c] == i).collect();
        let last = *cells.last().unwrap();
        let closed = r["twist"].as_array().unwrap().len() == n;
        let back = if closed { base } else { base + n - 1 };
        assert_eq!(conn[2 * last + 1], back, "rod {i}, closed {closed}");
        assert_eq!(closed, r["name"] == "ring");
        base += n;
    }
}

#[test]
fn other_extensions_are_refused_up_front() {
    let d = tmpdir("ext");
    let (json, bad) = (d.join("r.json"), d.join("r.vtk"));
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--quiet", "--json"])
        .arg(&json)
        .arg("--vtk")
        .arg(&bad)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("r.vtk") && err.contains(".vtu"), "{err}");
    assert!(!json.exists() && !bad.exists());
}
