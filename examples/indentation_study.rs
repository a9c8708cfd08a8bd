//! The study behind docs/indentation.md: the linear indentation stiffness K at the top of the
//! hemispherical gridshell (form-found on its cap-net path, pushed down at its highest joint,
//! everything else free) over rods per family n, slenderness r/R, joint kind and ν, with a
//! least-squares fit K = C · E R · n^a · (r/R)^b per joint kind.
//!
//! cargo run --release --example indentation_study -- [even|odd] [CSV_PATH]
//! cargo run --release --example indentation_study -- plot CSV... PNG_DIR
//!
//! `even` (the default) is the main table; `odd` the nets with a crossing at the pole (odd n)
//! instead of a cell centre; `plot` reads their CSVs, fits even and odd n apart and together (with
//! a factor for odd n), and draws K/(E R) against n and against r/R into PNG_DIR.

use rodnet::gridshell::footprint::{HemisphereSpec, JointChoice};
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::run;
use rodnet::io::xy_plot::{chart, Axis, Marker, Series};
use rodnet::network::indent::linear_stiffness;
use rodnet::scene::types::Section;

const NS: [usize; 7] = [8, 10, 12, 14, 16, 20, 24];
const ODD_NS: [usize; 6] = [9, 11, 13, 15, 17, 21];
const RATIOS: [f64; 4] = [1e-3, 2e-3, 5e-3, 1e-2];
/// E R of the study (E = 1 GPa, R = 1 m), N/m.
const ER: f64 = 1e9;

#[derive(Debug, Clone)]
struct Row {
    n: usize,
    ratio: f64,
    joint: String,
    nu: f64,
    apex: f64,
    spacing: f64,
    k: Option<f64>,
    seconds: f64,
}

fn one(n: usize, ratio: f64, joint: JointChoice, nu: f64) -> Row {
    let t0 = std::time::Instant::now();
    let mut spec = HemisphereSpec::new(1.0, n, 4);
    spec.joint = joint;
    spec.section = Section::Circle { radius: ratio };
    spec.poisson_ratio = nu;
    let mut r = run(
        &spec,
        DEFAULT_START_CAP,
        None,
        &rodnet::pipeline::Limits::NONE,
    )
    .expect("valid footprint");
    let ok = r.form.report.converged && r.form.report.stable;
    let (node, apex) = r
        .network
        .joints
        .iter()
        .map(|j| (j.node, r.network.model.position(j.node)[2]))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("joints");
    let k = ok
        .then(|| linear_stiffness(&mut r.network, node, [0.0, 0.0, -1.0]).ok())
        .flatten();
    Row {
        n,
        ratio,
        joint: joint.name().into(),
        nu,
        apex,
        spacing: r.footprint.net.spacing,
        k,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Least squares of y on the columns x (each row starts with its own 1 for the intercept):
/// coefficients, their standard errors and the largest relative residual of exp(y).
fn fit(rows: &[(Vec<f64>, f64)]) -> (Vec<f64>, Vec<f64>, f64) {
    let p = rows[0].0.len();
    let mut a = vec![vec![0.0; p]; p];
    let mut b = vec![0.0; p];
    for (x, y) in rows {
        for i in 0..p {
            b[i] += x[i] * y;
            for j in 0..p {
                a[i][j] += x[i] * x[j];
            }
        }
    }
    let inv = invert(a);
    let c: Vec<f64> = (0..p)
        .map(|i| (0..p).map(|j| inv[i][j] * b[j]).sum())
        .collect();
    let res: Vec<f64> = rows
        .iter()
        .map(|(x, y)| y - (0..p).map(|i| c[i] * x[i]).sum::<f64>())
        .collect();
    let rss: f64 = res.iter().map(|r| r * r).sum();
    let s2 = rss / (rows.len() as f64 - p as f64).max(1.0);
    let worst = res.iter().map(|r| r.exp_m1().abs()).fold(0.0, f64::max);
    let se = (0..p).map(|i| (s2 * inv[i][i]).sqrt()).collect();
    (c, se, worst)
}

/// Gauss–Jordan with partial pivoting (the normal equations are at most 4 × 4 here).
fn invert(mut a: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let p = a.len();
    let mut inv: Vec<Vec<f64>> = (0..p)
        .map(|i| (0..p).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for col in 0..p {
        let piv = (col..p)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .expect("a row");
        a.swap(col, piv);
        inv.swap(col, piv);
        let d = a[col][col];
        for j in 0..p {
            a[col][j] /= d;
            inv[col][j] /= d;
        }
        for i in (0..p).filter(|&i| i != col) {
            let f = a[i][col];
            for j in 0..p {
                a[i][j] -= f * a[col][j];
                inv[i][j] -= f * inv[col][j];
            }
        }
    }
    inv
}

/// The largest n each joint kind's fit keeps: rigid form finding from n = 20 on reaches other
/// states (apex 0.87 R) or takes 10–27 s (docs/indentation.md).
fn n_max(joint: &str) -> usize {
    match joint {
        "rigid" => 17,
        _ => 24,
    }
}

const JOINTS: [(&str, [u8; 3]); 4] = [
    ("ball", [31, 119, 180]),
    ("hinge", [44, 160, 44]),
    ("elastic", [230, 120, 20]),
    ("rigid", [214, 39, 40]),
];

/// The fitted law K/(E R) = C n^a (r/R)^b of one parity (None: both, with a factor for odd n).
struct Law {
    c: Vec<f64>,
}

impl Law {
    fn at(&self, n: f64, ratio: f64, odd: bool) -> f64 {
        let f = if odd && self.c.len() > 3 {
            self.c[3]
        } else {
            0.0
        };
        (self.c[0] + self.c[1] * n.ln() + self.c[2] * ratio.ln() + f).exp()
    }
}

fn fits(rows: &[Row]) -> Vec<(String, Law)> {
    let mut laws = Vec::new();
    for (joint, _) in JOINTS {
        for (what, parity) in [("even", Some(0)), ("odd", Some(1)), ("all", None)] {
            let pts: Vec<(Vec<f64>, f64)> = rows
                .iter()
                .filter(|r| r.joint == joint && r.nu == 0.3 && r.n <= n_max(joint))
                .filter(|r| parity.is_none_or(|p| r.n % 2 == p))
                .filter_map(|r| {
                    let mut x = vec![1.0, (r.n as f64).ln(), r.ratio.ln()];
                    if parity.is_none() {
                        x.push((r.n % 2) as f64);
                    }
                    r.k.map(|k| (x, (k / ER).ln()))
                })
                .collect();
            // Too few points, or (all n) only one parity: no fit.
            let one_parity = parity.is_none() && pts.iter().all(|p| p.0[3] == pts[0].0[3]);
            if pts.len() < 5 || one_parity {
                continue;
            }
            let (c, se, worst) = fit(&pts);
            let odd = if c.len() > 3 {
                format!(
                    ", odd n × {:.4} (ln {:.4} ± {:.4})",
                    c[3].exp(),
                    c[3],
                    se[3]
                )
            } else {
                String::new()
            };
            println!(
                "{joint} {what} n: K/(E R) = {:.3e} · n^({:.3} ± {:.3}) · (r/R)^({:.3} ± {:.3}){odd}; {} points, prefactor ln {:.3} ± {:.3}, largest residual {:.1} %",
                c[0].exp(),
                c[1],
                se[1],
                c[2],
                se[2],
                pts.len(),
                c[0],
                se[0],
                100.0 * worst
            );
            if what == "even" {
                laws.push((joint.to_string(), Law { c }));
            }
        }
    }
    laws
}

fn compute(odd: bool) -> Vec<Row> {
    let mut rows = Vec::new();
    let ns: &[usize] = if odd { &ODD_NS } else { &NS };
    for joint in [JointChoice::Ball, JointChoice::Rigid] {
        for &n in ns
            .iter()
            .filter(|&&n| joint == JointChoice::Ball || n <= 16 || !odd)
        {
            for &ratio in &RATIOS {
                rows.push(one(n, ratio, joint, 0.3));
            }
        }
    }
    for joint in [JointChoice::Hinge, JointChoice::Elastic] {
        for &n in ns.iter().filter(|&&n| n <= 16) {
            for &ratio in &RATIOS {
                rows.push(one(n, ratio, joint, 0.3));
            }
        }
    }
    let nus: &[usize] = if odd { &[9, 13] } else { &[8, 12, 16] };
    for &n in nus {
        rows.push(one(n, 5e-3, JointChoice::Ball, 0.0));
        rows.push(one(n, 5e-3, JointChoice::Ball, 0.5));
    }
    rows
}

fn to_csv(rows: &[Row]) -> String {
    let mut out =
        String::from("joint,nu,n,r_over_R,spacing_over_R,apex_over_R,K_N_per_m,seconds\n");
    for r in rows {
        let k = r.k.map_or("none".into(), |k| format!("{k:.4e}"));
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            r.joint, r.nu, r.n, r.ratio, r.spacing, r.apex, k, r.seconds
        ));
    }
    out
}

fn from_csv(text: &str) -> Vec<Row> {
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f[i].parse::<f64>().expect("a number");
            Row {
                joint: f[0].into(),
                nu: num(1),
                n: f[2].parse().expect("n"),
                ratio: num(3),
                spacing: num(4),
                apex: num(5),
                k: f[6].parse().ok(),
                seconds: num(7),
            }
        })
        .collect()
}

fn print_table(rows: &[Row]) {
    println!("| joint | ν | n | r/R | spacing a/R | apex z/R | K (N/m) | K/(E R) | s |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let k = r.k.map_or("none".into(), |k| format!("{k:.4e}"));
        let kn = r.k.map_or("none".into(), |k| format!("{:.4e}", k / ER));
        println!(
            "| {} | {} | {} | {} | {:.4} | {:.4} | {k} | {kn} | {:.2} |",
            r.joint, r.nu, r.n, r.ratio, r.spacing, r.apex, r.seconds
        );
    }
}

/// K/(E R) against n at r/R = 5e-3 and against r/R at n = 12 (and 13), each joint kind's points
/// (dots even n, rings odd n) with its even-n law, and Reissner's shell formula for the net's
/// equivalent thickness (grey, dashed).
fn plot(rows: &[Row], laws: &[(String, Law)], dir: &str) {
    let grey = [110, 110, 110];
    let keep = |r: &&Row| r.nu == 0.3 && r.n <= n_max(&r.joint) && r.k.is_some();
    let reissner = |r: &Row| 4.0 * std::f64::consts::PI * r.ratio.powi(3) / r.spacing;
    let mut by_n = Vec::new();
    let mut by_ratio = Vec::new();
    for (joint, colour) in JOINTS {
        let law = &laws.iter().find(|l| l.0 == joint).expect("a law").1;
        let sel = |odd: bool, f: &dyn Fn(&Row) -> bool| -> Vec<&Row> {
            rows.iter()
                .filter(keep)
                .filter(|r| r.joint == joint && (r.n % 2 == 1) == odd && f(r))
                .collect()
        };
        for (odd, marker) in [(false, Marker::Dot), (true, Marker::Ring)] {
            let pts = |v: Vec<&Row>, x: &dyn Fn(&Row) -> f64| -> Vec<(f64, f64)> {
                v.iter().map(|r| (x(r), r.k.unwrap_or(0.0) / ER)).collect()
            };
            let name = format!("{joint}, {} n", if odd { "odd" } else { "even" });
            by_n.push(Series {
                name: name.clone(),
                colour,
                points: pts(sel(odd, &|r| r.ratio == 5e-3), &|r| r.n as f64),
                line: false,
                dashed: false,
                marker,
            });
            let n = if odd { 13 } else { 12 };
            by_ratio.push(Series {
                name: format!("{joint}, n = {n}"),
                colour,
                points: pts(sel(odd, &|r| r.n == n), &|r| r.ratio),
                line: false,
                dashed: false,
                marker,
            });
        }
        let n_hi = rows
            .iter()
            .filter(keep)
            .filter(|r| r.joint == joint && r.n % 2 == 0)
            .map(|r| r.n as f64)
            .fold(8.0, f64::max);
        by_n.push(Series {
            name: format!("{joint}: even-n law"),
            colour,
            points: (0..=20)
                .map(|k| 8.0 + (n_hi - 8.0) * k as f64 / 20.0)
                .map(|n| (n, law.at(n, 5e-3, false)))
                .collect(),
            line: true,
            dashed: false,
            marker: Marker::None,
        });
        by_ratio.push(Series {
            name: format!("{joint}: even-n law, n = 12"),
            colour,
            points: [1e-3, 1e-2].map(|q| (q, law.at(12.0, q, false))).to_vec(),
            line: true,
            dashed: false,
            marker: Marker::None,
        });
    }
    let mut reissner_n: Vec<(f64, f64)> = rows
        .iter()
        .filter(keep)
        .filter(|r| r.joint == "ball" && r.ratio == 5e-3 && r.n % 2 == 0)
        .map(|r| (r.n as f64, reissner(r)))
        .collect();
    reissner_n.sort_by(|a, b| a.0.total_cmp(&b.0));
    by_n.push(Series {
        name: "Reissner, t from EI/a and EA/a".into(),
        colour: grey,
        points: reissner_n,
        line: true,
        dashed: true,
        marker: Marker::None,
    });
    let mut reissner_q: Vec<(f64, f64)> = rows
        .iter()
        .filter(keep)
        .filter(|r| r.joint == "ball" && r.n == 12)
        .map(|r| (r.ratio, reissner(r)))
        .collect();
    reissner_q.sort_by(|a, b| a.0.total_cmp(&b.0));
    by_ratio.push(Series {
        name: "Reissner, n = 12".into(),
        colour: grey,
        points: reissner_q,
        line: true,
        dashed: true,
        marker: Marker::None,
    });
    let y = Axis {
        label: "K / (E R)".into(),
        log: true,
        ticks: None,
    };
    let xn = Axis {
        label: "rods per family n".into(),
        log: true,
        ticks: Some(vec![8.0, 10.0, 12.0, 16.0, 20.0, 24.0]),
    };
    let xr = Axis {
        label: "rod radius over sphere radius r/R".into(),
        log: true,
        ticks: None,
    };
    for (name, series, x, title) in [
        (
            "indentation_k_n.png",
            &by_n,
            &xn,
            "Apex stiffness of hemispherical gridshells against n, r/R = 5e-3",
        ),
        (
            "indentation_k_ratio.png",
            &by_ratio,
            &xr,
            "Apex stiffness against r/R, n = 12 and 13",
        ),
    ] {
        let png = chart(series, (x, &y), title, (1000, 760)).expect("a chart");
        let path = format!("{dir}/{name}");
        std::fs::write(&path, png).expect("write the PNG");
        println!("wrote {path}");
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("plot") => {
            let (dir, csvs) = args[1..].split_last().expect("plot CSV... PNG_DIR");
            let rows: Vec<Row> = csvs
                .iter()
                .flat_map(|p| from_csv(&std::fs::read_to_string(p).expect("read the CSV")))
                .collect();
            let laws = fits(&rows);
            plot(&rows, &laws, dir);
        }
        mode => {
            let odd = mode == Some("odd");
            let csv = match mode {
                Some("odd" | "even") => args.get(1),
                _ => args.first(),
            };
            let rows = compute(odd);
            print_table(&rows);
            fits(&rows);
            if let Some(p) = csv {
                std::fs::write(p, to_csv(&rows)).expect("write the CSV");
            }
        }
    }
}
