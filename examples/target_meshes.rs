//! Writes the validation target meshes of docs/gridshell.md ("Gridshells on target meshes")
//! into a folder: `cargo run --release --example target_meshes -- DIR [RINGS]`.

use rodnet::surface::shapes;

fn main() {
    let mut args = std::env::args().skip(1);
    let dir = std::path::PathBuf::from(args.next().unwrap_or_else(|| "targets".into()));
    let n: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(48);
    std::fs::create_dir_all(&dir).expect("create the folder");
    for (name, mesh) in [
        ("hemisphere", shapes::hemisphere(1.0, n)),
        ("paraboloid", shapes::paraboloid(1.0, 0.6, n)),
        ("spheroid", shapes::spheroid(1.0, 0.6, n)),
        ("vault", shapes::vault(1.0, 2.0, n / 2)),
        ("saddle", shapes::saddle(1.0, 1.5, n)),
    ] {
        let p = dir.join(format!("{name}.obj"));
        std::fs::write(&p, shapes::to_obj(&mesh)).expect("write the mesh");
        println!("{} ({} triangles)", p.display(), mesh.1.len());
    }
}
