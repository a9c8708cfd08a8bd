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
