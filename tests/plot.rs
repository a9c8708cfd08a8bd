//! `rodnet plot`: a PNG of the requested size whose rods are coloured by bending stress, from a
//! full results JSON or one with only the contract's keys; bad JSON is a located error.

use std::path::{Path, PathBuf};
use std::process::Command;

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-plot-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Width, height and RGB pixels of a PNG.
fn decode(p: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(p).unwrap()));
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let px = buf[..info.buffer_size()]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, px)
}

/// Pixels in the views (above the colour scale) within a few levels of the colour of some
/// stress fraction in [t0, t1].
fn count(w: u32, h: u32, px: &[[u8; 3]], t0: f64, t1: f64) -> usize {
    let views = (w * (h - rodnet::io::plot::LEGEND_H)) as usize;
    let colours: Vec<[u8; 3]> = (0..=50)
        .map(|i| rodnet::io::plot::colour(t0 + (t1 - t0) * i as f64 / 50.0))
        .collect();
    px[..views]
        .iter()
        .filter(|p| {
            colours
                .iter()
                .any(|c| (0..3).all(|k| (p[k] as i32 - c[k] as i32).abs() <= 3))
        })
        .count()
}

#[test]
fn plot_colours_rods_by_stress() {
    let d = tmpdir("colours");
    let (json, png) = (d.join("r.json"), d.join("view.png"));
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--quiet", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let out = rodnet()
        .arg("plot")
        .arg(&json)
        .arg("-o")
        .arg(&png)
        .args(["--width", "800", "--height", "600"])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (w, h, px) = decode(&png);
    assert_eq!((w, h), (800, 600));
    // The clamp end carries the largest stress (top of the scale); the last of the 40 segments
    // before the free end, 1/40 of it. Each is drawn in four views.
    let high = count(w, h, &px, 0.97, 1.0);
    let low = count(w, h, &px, 0.0, 0.03);
    assert!(high > 4, "{high} high-stress pixels");
    assert!(low > 4, "{low} low-stress pixels");

    // Only the contract's keys: every rod drawn in the colour of zero stress.
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let rods: Vec<serde_json::Value> = v["rods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| serde_json::json!({"name": r["name"], "points": r["points"], "twist": r["twist"]}))
        .collect();
    let bare = d.join("bare.json");
    std::fs::write(&bare, serde_json::json!({ "rods": rods }).to_string()).unwrap();
    let png2 = d.join("bare.png");
    let out = rodnet()
        .arg("plot")
        .arg(&bare)
        .arg("-o")
        .arg(&png2)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let (w, h, px) = decode(&png2);
    assert_eq!((w, h), (1200, 900));
    assert!(count(w, h, &px, 0.0, 0.0) > 100);
    assert_eq!(count(w, h, &px, 0.03, 1.0), 0);
}

#[test]
fn bad_results_are_located() {
    let d = tmpdir("bad");
    let cases = [
        (
            "syntax.json",
            "{\n  \"rods\": [\n    {\"points\": [[0, 0, 0]],,}\n",
            ":3:",
        ),
        ("norods.json", "{\"converged\": true}", "no `rods` array"),
        (
            "badpoint.json",
            "{\"rods\": [{\"points\": [[0, 0, 0], [1, \"x\", 0]]}]}",
            "rods[0].points[1]",
        ),
        (
            "stress.json",
            "{\"rods\": [{\"points\": [[0, 0, 0], [1, 0, 0]], \"bending_stress\": [1.0]}]}",
            "rods[0].bending_stress: 1 values for 2 points",
        ),
    ];
    for (name, text, needle) in cases {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        let png = d.join(format!("{name}.png"));
        let out = rodnet()
            .arg("plot")
            .arg(&p)
            .arg("-o")
            .arg(&png)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(name) && err.contains(needle), "{name}: {err}");
        assert!(!png.exists(), "{name}: picture written for bad input");
    }
}

/// Pixels of exactly `c` in the views.
fn exact(w: u32, h: u32, px: &[[u8; 3]], c: [u8; 3]) -> usize {
    let views = (w * (h - rodnet::io::plot::LEGEND_H)) as usize;
    px[..views].iter().filter(|p| **p == c).count()
}

fn plot(json: &Path, png: &Path, extra: &[&str]) -> std::process::Output {
    rodnet()
        .arg("plot")
        .arg(json)
        .arg("-o")
        .arg(png)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn plot_draws_rest_shape_supports_loads_and_real_text() {
    use rodnet::io::plot::{LOAD, REST, SUPPORT};
    let d = tmpdir("marks");
    let json = d.join("r.json");
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--quiet", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let png = d.join("v.png");
    let out = plot(&json, &png, &["--width", "800", "--height", "600"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (w, h, px) = decode(&png);
    assert_eq!((w, h), (800, 600));
    // The straight rest beam, in three of the views (the side view sees it end on).
    assert!(exact(w, h, &px, REST) > 300, "{}", exact(w, h, &px, REST));
    // The clamp's square (12 × 12 in each view) and the tip load's arrows.
    assert!(
        exact(w, h, &px, SUPPORT) > 4 * 100,
        "{}",
        exact(w, h, &px, SUPPORT)
    );
    assert!(exact(w, h, &px, LOAD) > 60, "{}", exact(w, h, &px, LOAD));
    // Anti-aliased text: greys between the text colour and white (a bitmap font has none).
    let greys = px
        .iter()
        .filter(|p| p[0] == p[1] && p[1] == p[2] && (60..230).contains(&p[0]));
    assert!(greys.count() > 200);

    // Displacements drawn three times larger: another picture, the rest shape still in it.
    let png3 = d.join("v3.png");
    let out = plot(
        &json,
        &png3,
        &[
            "--width",
            "800",
            "--height",
            "600",
            "--deflection-scale",
            "3",
        ],
    );
    assert_eq!(out.status.code(), Some(0));
    let (_, _, px3) = decode(&png3);
    assert_ne!(px, px3);
    assert!(exact(w, h, &px3, REST) > 100);

    // Results without the extensions: no rest shape, supports or loads to draw.
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let rods: Vec<serde_json::Value> = v["rods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| serde_json::json!({"name": r["name"], "points": r["points"], "twist": r["twist"]}))
        .collect();
    let bare = d.join("bare.json");
    std::fs::write(&bare, serde_json::json!({ "rods": rods }).to_string()).unwrap();
    let out = plot(&bare, &png, &[]);
    assert_eq!(out.status.code(), Some(0));
    let (w, h, px) = decode(&png);
    for c in [REST, SUPPORT, LOAD] {
        assert_eq!(exact(w, h, &px, c), 0, "{c:?}");
    }
}

#[test]
fn colour_quantities_are_drawn_or_refused_by_name() {
    let d = tmpdir("quantities");
    let json = d.join("r.json");
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--quiet", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let png = d.join("axial.png");
    let out = plot(&json, &png, &["--color", "axial"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        said.contains("axial force") && said.ends_with(" N\n"),
        "{said}"
    );
    let (w, h, px) = decode(&png);
    // The tip's edge carries almost no axial force, the clamp's the most (the tip load bends
    // the beam until it pulls along it).
    assert!(count(w, h, &px, 0.97, 1.0) > 4);
    assert!(count(w, h, &px, 0.0, 0.03) > 4);

    // The cantilever's material has no yield strength and its scene no target.
    for (q, needle) in [
        ("utilization", "rods[0].forces[0].utilization: missing"),
        ("distance", "rods[0].target_distance: missing"),
    ] {
        let png = d.join(format!("{q}.png"));
        let out = plot(&json, &png, &["--color", q]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{q}: {err}");
        assert!(err.contains("r.json") && err.contains(needle), "{q}: {err}");
        assert!(!png.exists());
    }
    let bare = d.join("bare.json");
    std::fs::write(&bare, r#"{"rods": [{"points": [[0, 0, 0], [1, 0, 0]]}]}"#).unwrap();
    for (args, needle) in [
        (
            &["--color", "bending"][..],
            "rods[0].bending_stress: missing",
        ),
        (&["--color", "axial"][..], "rods[0].forces: missing"),
        (&["--deflection-scale", "2"][..], "no `rest_points`"),
    ] {
        let out = plot(&bare, &png, args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("bare.json") && err.contains(needle),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn distance_to_the_target_colours_a_gridshell() {
    let d = tmpdir("distance");
    let json = d.join("r.json");
    let out = rodnet()
        .args([
            "solve",
            "networks/hemisphere_flat_n2.ron",
            "--quiet",
            "--json",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert!(
        out.status.code().is_some_and(|c| c <= 1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let png = d.join("d.png");
    let out = plot(&json, &png, &["--color", "distance"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(said.contains("distance to the target"), "{said}");
    let (w, h, px) = decode(&png);
    assert!(count(w, h, &px, 0.0, 0.03) > 4 && count(w, h, &px, 0.97, 1.0) > 4);
}
