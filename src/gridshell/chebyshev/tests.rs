use super::*;

fn max_abs_diff(p: Vec3, q: Vec3) -> f64 {
    (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f64::max)
}

fn distance(p: Vec3, q: Vec3) -> f64 {
    norm([p[0] - q[0], p[1] - q[1], p[2] - q[2]])
}

fn mirror_x(p: Vec3) -> Vec3 {
    [-p[0], p[1], p[2]]
}

fn mirror_y(p: Vec3) -> Vec3 {
    [p[0], -p[1], p[2]]
}

/// Deterministic sample of parameters in [-span, span].
fn samples(count: usize, span: f64) -> Vec<(f64, f64)> {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * span - span
    };
    (0..count).map(|_| (next(), next())).collect()
}

#[test]
fn gridshell_counts_and_half_lengths() {
    let net = HemisphereNet::new(1.0, 12);
    let inside = (0..12)
        .flat_map(|i| (0..12).map(move |j| (i, j)))
        .filter(|&(i, j)| net.crossing_inside(i, j))
        .count();
    assert_eq!(inside, 112);

    let mut ends = 0;
    for k in 0..12 {
        for positive in [true, false] {
            for p in [
                net.end_point(k, positive),
                mirror_uv(net.end_point(k, positive)),
            ] {
                assert!((norm(p) - 1.0).abs() <= 1e-15, "end off the sphere: {p:?}");
                if p[2] == 0.0 {
                    ends += 1;
                }
            }
        }
        // The ends come from a root find along the rod, so compare with the point()
        // path at the same parameters: both are accurate to ~5e-14.
        let p = net.point(net.half_lengths[k], net.offsets[k]);
        assert!(p[2].abs() <= 1e-13, "rod {k}: z = {:e}", p[2]);
        assert!(max_abs_diff(p, net.end_point(k, true)) <= 1e-13);
    }
    assert_eq!(ends, 48);

    for k in [5, 6] {
        assert!((net.half_lengths[k] - 1.559389).abs() < 1e-6);
    }
    for k in [0, 11] {
        assert!((net.half_lengths[k] - 0.585462).abs() < 1e-6);
    }
}

#[test]
fn all_points_lie_on_the_sphere() {
    for radius in [1.0, 0.37, 2.5] {
        for n in [1, 2, 7, 12, 16] {
            let net = HemisphereNet::new(radius, n);
            let off = |p: Vec3| (norm(p) - radius).abs() / radius;
            for i in 0..n {
                for j in 0..n {
                    assert!(off(net.crossing(i, j)) <= 1e-12);
                }
                assert!(off(net.end_point(i, true)) <= 1e-12);
                assert!(off(net.end_point(i, false)) <= 1e-12);
            }
            for (u, v) in samples(20, 2.0 * radius) {
                assert!(off(net.point(u, v)) <= 1e-12);
            }
        }
    }
}

#[test]
fn generators_are_the_great_circles() {
    let radius = 1.7;
    let net = HemisphereNet::new(radius, 12);
    for (t, _) in samples(20, 2.0 * radius) {
        let (s, c) = (t / radius).sin_cos();
        let expected_u = [radius * s, 0.0, radius * c];
        let expected_v = [0.0, radius * s, radius * c];
        assert!(max_abs_diff(net.point(t, 0.0), expected_u) <= 1e-13 * radius);
        assert!(max_abs_diff(net.point(0.0, t), expected_v) <= 1e-13 * radius);
        assert_eq!(net.angle(t, 0.0), FRAC_PI_2);
        assert_eq!(net.angle(0.0, t), FRAC_PI_2);
    }
}

/// Polyline length of rod `k` over `[from, to]`. A chord misses `κ²h³/24 + O(h⁵)` of its
/// arc, so the sum has an even error expansion in `1/m`; two Richardson steps over `m`,
/// `2m`, `4m` chords leave `O(m⁻⁶)`.
fn rod_arclength(net: &HemisphereNet, k: usize, from: f64, to: f64, m: usize) -> f64 {
    let chord_sum = |m: usize| {
        let us: Vec<f64> = (0..=m)
            .map(|q| from + (to - from) * q as f64 / m as f64)
            .collect();
        let pts = net.rod_points(k, &us);
        pts.windows(2).map(|w| distance(w[0], w[1])).sum::<f64>()
    };
    richardson2(chord_sum(m), chord_sum(2 * m), chord_sum(4 * m))
}

/// Eliminates the `h²` and `h⁴` terms from values at `h`, `h/2`, `h/4`.
fn richardson2(coarse: f64, mid: f64, fine: f64) -> f64 {
    let a = (4.0 * mid - coarse) / 3.0;
    let b = (4.0 * fine - mid) / 3.0;
    (16.0 * b - a) / 15.0
}

#[test]
fn crossings_are_one_spacing_apart_along_every_rod() {
    // The polyline error left after Richardson is O(m⁻⁶), negligible; what remains is the
    // position error (≤ 6e-14): along a smooth error field the chord sum changes by about
    // the error at the two ends, so ≤ 1.2e-13, times ≈ 2 for the Richardson weights.
    let net = HemisphereNet::new(1.0, 12);
    let mut worst: f64 = 0.0;
    for k in 0..12 {
        for i in 0..11 {
            let len = rod_arclength(&net, k, net.offsets[i], net.offsets[i + 1], 16);
            worst = worst.max((len - net.spacing).abs());
        }
        // The rod is arclength-parametrised all the way to its equator ends.
        let half = rod_arclength(&net, k, 0.0, net.half_lengths[k], 64);
        worst = worst.max((half - net.half_lengths[k]).abs());
    }
    assert!(worst <= 1e-12, "arclength error {worst:e}");
}

#[test]
fn symmetries_are_exact() {
    // Only one octant is ever integrated and the rest is sign flips and swaps, so these
    // hold bit for bit (stricter than a 1e-12 tolerance would check).
    for n in [7, 12] {
        let net = HemisphereNet::new(1.3, n);
        for i in 0..n {
            for j in 0..n {
                let p = net.crossing(i, j);
                assert_eq!(p, mirror_uv(net.crossing(j, i)));
                assert_eq!(p, mirror_x(net.crossing(n - 1 - i, j)));
                assert_eq!(p, mirror_y(net.crossing(i, n - 1 - j)));
            }
            assert_eq!(net.crossing(i, i)[0], net.crossing(i, i)[1]);
            assert_eq!(net.offsets[n - 1 - i], -net.offsets[i]);
            assert_eq!(net.half_lengths[n - 1 - i], net.half_lengths[i]);
            assert_eq!(net.end_point(i, false), mirror_x(net.end_point(i, true)));
            assert_eq!(
                net.end_point(n - 1 - i, true),
                mirror_y(net.end_point(i, true))
            );
        }
        for (u, v) in samples(30, 2.0 * 1.3) {
            let p = net.point(u, v);
            assert_eq!(p, mirror_uv(net.point(v, u)));
            assert_eq!(p, mirror_x(net.point(-u, v)));
            assert_eq!(p, mirror_y(net.point(u, -v)));
            assert_eq!(net.angle(u, v), net.angle(v, u));
            assert!((net.angle(-u, v) - (PI - net.angle(u, v))).abs() <= 1e-15);
        }
    }
}

#[test]
fn crossings_rod_points_and_points_are_the_point_function_to_round_off() {
    let net = HemisphereNet::new(1.0, 12);
    for i in 0..12 {
        for j in 0..12 {
            assert_eq!(
                net.crossing(i, j),
                net.point(net.offsets[i], net.offsets[j])
            );
        }
    }
    let uv: Vec<[f64; 2]> = (-20..=20)
        .flat_map(|i| (-20..=20).map(move |j| [i as f64 * 0.08, j as f64 * 0.08]))
        .chain([[f64::NAN, 0.1], [1e12, 0.2], [0.3, 0.3]])
        .collect();
    let mut worst: f64 = 0.0;
    let points = net.points(&uv);
    for (k, (p, &[u, v])) in points.iter().zip(&uv).enumerate() {
        let q = net.point(u, v);
        if q[0].is_nan() {
            assert!(p[0].is_nan(), "{u} {v}: {p:?}");
            continue;
        }
        worst = worst.max(norm([p[0] - q[0], p[1] - q[1], p[2] - q[2]]));
        // The u↔v symmetry is exact, not within integration error: (v, u) is the point
        // (j, i) of the grid when (u, v) is (i, j).
        if k < 41 * 41 {
            let (i, j) = (k / 41, k % 41);
            assert_eq!(mirror_uv(*p), points[41 * j + i], "{u} {v}");
        }
    }
    assert!(worst < 1e-13, "points against point: {worst:.2e}");
    let us: Vec<f64> = (-40..=40).map(|q| q as f64 * 0.04).collect();
    for k in [0, 3, 6, 11] {
        let pts = net.rod_points(k, &us);
        for (p, &u) in pts.iter().zip(&us) {
            assert_eq!(*p, net.point(u, net.offsets[k]));
        }
    }
}

/// Signed area of the spherical polygon with geodesic edges through `pts` (unit sphere),
/// summed over triangles fanned from the normalised vertex mean.
fn polygon_area(pts: &[Vec3]) -> f64 {
    let mut c = [0.0; 3];
    for p in pts {
        c = [c[0] + p[0], c[1] + p[1], c[2] + p[2]];
    }
    let c = scaled(c, 1.0 / norm(c));
    let mut area = 0.0;
    for (q, &a) in pts.iter().enumerate() {
        let b = pts[(q + 1) % pts.len()];
        let triple = dot(c, cross(a, b));
        area += 2.0 * triple.atan2(1.0 + dot(c, a) + dot(a, b) + dot(b, c));
    }
    area
}

/// Area of the net quadrilateral `[u0,u1]×[v0,v1]` on the unit sphere, from its boundary
/// sampled at `m`, `2m` and `4m` points per side. The geodesic polygon misses
/// `κ_g h³/12 + O(h⁵)` per edge: an even expansion, so Richardson applies.
fn net_quad_area(net: &HemisphereNet, u: (f64, f64), v: (f64, f64), m: usize) -> f64 {
    let area = |m: usize| {
        let mut pts = Vec::with_capacity(4 * m);
        let t = |q: usize| q as f64 / m as f64;
        pts.extend((0..m).map(|q| net.point(u.0 + (u.1 - u.0) * t(q), v.0)));
        pts.extend((0..m).map(|q| net.point(u.1, v.0 + (v.1 - v.0) * t(q))));
        pts.extend((0..m).map(|q| net.point(u.1 + (u.0 - u.1) * t(q), v.1)));
        pts.extend((0..m).map(|q| net.point(u.0, v.1 + (v.0 - v.1) * t(q))));
        polygon_area(&pts)
    };
    richardson2(area(m), area(2 * m), area(4 * m))
}

#[test]
fn hazzidakis_area_equals_angle_excess() {
    // K·Area = ∫∫ K sin ω du dv = −∫∫ ω_uv du dv = ω(u1,v0) + ω(u0,v1) − ω(u0,v0) − ω(u1,v1).
    // The interior angles are ω at (u0,v0) and (u1,v1), where both edges leave along
    // +r_u, +r_v or −r_u, −r_v, and π − ω at the other two corners, so this is
    // K·Area = 2π − Σ interior angles (the opposite sign of a geodesic polygon's excess).
    // Bound: position error (≤ 6e-14) times the perimeter (≤ 5), times ≈ 2
    // for the Richardson weights, plus 4 angle errors of 2e-16: ≤ 6e-13.
    let net = HemisphereNet::new(1.0, 12);
    let c = &net.offsets;
    let quads = [
        ((c[5], c[6]), (c[5], c[6])), // the cell around the pole
        ((c[6], c[7]), (c[8], c[9])),
        ((c[2], c[3]), (c[9], c[10])),
        ((c[0], c[1]), (c[4], c[5])),
        ((c[9], c[10]), (c[1], c[2])),
        ((-0.4, 0.9), (0.1, 1.2)),
    ];
    for &(u, v) in &quads {
        let area = net_quad_area(&net, u, v, 32);
        let w = |a: f64, b: f64| net.angle(a, b);
        let hazzidakis = w(u.1, v.0) + w(u.0, v.1) - w(u.0, v.0) - w(u.1, v.1);
        let interior = w(u.0, v.0) + (PI - w(u.1, v.0)) + w(u.1, v.1) + (PI - w(u.0, v.1));
        assert!(area > 0.0);
        assert!(
            (area - hazzidakis).abs() <= 1e-12,
            "quad {u:?}x{v:?}: area {area} vs {hazzidakis}"
        );
        assert!((area - (2.0 * PI - interior)).abs() <= 1e-12);
    }
}

#[test]
fn angle_matches_the_geometry() {
    // Central differences with one Richardson step (δ = 1e-3): truncation ~δ⁴|r⁽⁵⁾|/30
    // ≈ 1e-13, but the position error (≤ 6e-14, not smooth across grid nodes) is amplified
    // by ≈ 1.5/δ, so up to ≈ 1e-10, including points past the fold.
    let net = HemisphereNet::new(1.0, 12);
    let d = 1e-3;
    let derivative = |f: &dyn Fn(f64) -> Vec3| -> Vec3 {
        let (p1, m1, p2, m2) = (f(d), f(-d), f(2.0 * d), f(-2.0 * d));
        std::array::from_fn(|c| {
            (4.0 * (p1[c] - m1[c]) / (2.0 * d) - (p2[c] - m2[c]) / (4.0 * d)) / 3.0
        })
    };
    let mut pts = samples(12, 1.5);
    pts.extend([(1.5, 1.5), (1.2, -1.6), (0.3, 0.2)]);
    for (u, v) in pts {
        let ru = derivative(&|t| net.point(u + t, v));
        let rv = derivative(&|t| net.point(u, v + t));
        let normal = net.point(u, v);
        let signed = dot(cross(ru, rv), normal).atan2(dot(ru, rv));
        // atan2 gives (−π, π]; past the fold with uv < 0 the profile exceeds π.
        let wrap = (signed - net.angle(u, v) + PI).rem_euclid(2.0 * PI) - PI;
        assert!((norm(ru) - 1.0).abs() <= 1e-10 && (norm(rv) - 1.0).abs() <= 1e-10);
        assert!(
            wrap.abs() <= 1e-10,
            "({u}, {v}): geometric {signed} vs {}",
            net.angle(u, v)
        );
    }
}

#[test]
fn scaling_by_two_is_exact() {
    let one = HemisphereNet::new(1.0, 12);
    let two = HemisphereNet::new(2.0, 12);
    let double = |p: Vec3| scaled(p, 2.0);
    assert_eq!(two.spacing, 2.0 * one.spacing);
    for i in 0..12 {
        assert_eq!(two.offsets[i], 2.0 * one.offsets[i]);
        assert_eq!(two.half_lengths[i], 2.0 * one.half_lengths[i]);
        assert_eq!(two.end_point(i, true), double(one.end_point(i, true)));
        for j in 0..12 {
            assert_eq!(two.crossing(i, j), double(one.crossing(i, j)));
        }
    }
    for (u, v) in samples(20, 2.0) {
        assert_eq!(two.point(2.0 * u, 2.0 * v), double(one.point(u, v)));
        assert_eq!(two.angle(2.0 * u, 2.0 * v), one.angle(u, v));
    }
}

/// Discrete compass net on the unit sphere, `(nmax+1)²` nodes of step `h`: each new node
/// is the mirror image of the opposite corner in the plane through the centre and its two
/// neighbours, i.e. the other point at equal chord distance from both.
fn compass_net(h: f64, nmax: usize) -> Vec<Vec3> {
    let w = nmax + 1;
    let mut g = vec![[0.0; 3]; w * w];
    for i in 0..w {
        let (s, c) = (i as f64 * h).sin_cos();
        g[i * w] = [s, 0.0, c];
        g[i] = [0.0, s, c];
    }
    for i in 1..w {
        for j in 1..w {
            let o = g[(i - 1) * w + j - 1];
            let nrm = cross(g[i * w + j - 1], g[(i - 1) * w + j]);
            let k = 2.0 * dot(o, nrm) / dot(nrm, nrm);
            g[i * w + j] = [o[0] - k * nrm[0], o[1] - k * nrm[1], o[2] - k * nrm[2]];
        }
    }
    g
}

#[test]
fn independent_compass_construction_agrees() {
    // The compass error is second order, so two Richardson steps over h = a/8, a/16, a/32
    // leave the next term of the expansion and the compass round-off (which grows with the
    // cell count), both below the tolerance.
    let n = 12;
    let net = HemisphereNet::new(1.0, n);
    let a = PI / (n + 1) as f64;
    let quadrant: Vec<usize> = (n / 2..n).collect();
    let mut levels = Vec::new();
    for m in [8usize, 16, 32] {
        let nmax = (2 * n - n - 1) * m / 2;
        let g = compass_net(a / m as f64, nmax);
        let node = |k: usize| (2 * (k + 1) - (n + 1)) * m / 2;
        let values: Vec<Vec3> = quadrant
            .iter()
            .flat_map(|&i| quadrant.iter().map(move |&j| (i, j)))
            .map(|(i, j)| g[node(i) * (nmax + 1) + node(j)])
            .collect();
        levels.push(values);
    }
    let exact: Vec<Vec3> = quadrant
        .iter()
        .flat_map(|&i| quadrant.iter().map(move |&j| (i, j)))
        .map(|(i, j)| net.crossing(i, j))
        .collect();
    let error = |vals: &[Vec3]| {
        vals.iter()
            .zip(&exact)
            .map(|(p, q)| max_abs_diff(*p, *q))
            .fold(0.0, f64::max)
    };
    let order = (error(&levels[0]) / error(&levels[1])).log2();
    assert!((order - 2.0).abs() < 0.01, "compass order {order}");
    let combine = |fine: &[Vec3], coarse: &[Vec3], f: f64| -> Vec<Vec3> {
        fine.iter()
            .zip(coarse)
            .map(|(p, q)| std::array::from_fn(|c| (f * p[c] - q[c]) / (f - 1.0)))
            .collect()
    };
    let r01 = combine(&levels[1], &levels[0], 4.0);
    let r12 = combine(&levels[2], &levels[1], 4.0);
    let r = combine(&r12, &r01, 16.0);
    assert!(
        error(&r) <= 1e-11,
        "compass/Richardson disagrees by {:e}",
        error(&r)
    );
}

#[test]
fn angle_profile_matches_high_precision_reference() {
    // 40-digit values (rounded to f64) from the power series at s = 0 (s ≤ 2.25) and 80-term
    // re-expansions (s ≥ 3.5), computed independently with mpmath.
    let reference = [
        (0.3, 1.2722869479746892, -0.9851558430415446),
        (1.0, 0.6227635630548913, -0.8507241336855917),
        (1.5, 0.2334159451765729, -0.7027823575902886),
        (2.25, -0.20496092513869799, -0.4683465323070939),
        (3.5, -0.581202344658288, -0.15440441145467665),
        (4.0, -0.6348639994258749, -0.06331701338385444),
    ];
    let profile = AngleProfile::new();
    for (s, f, df) in reference {
        assert!((profile.value(s) - f).abs() <= 1e-15, "f({s})");
        assert!((profile.slope(s) - df).abs() <= 1e-15, "f'({s})");
    }
    assert!(profile.value(1.86159167731546).abs() <= 1e-15);
    assert_eq!(profile.value(0.0), FRAC_PI_2);
}

#[test]
fn integration_error_is_below_the_stated_tolerance() {
    // The scheme with half the step and two more levels is ~2^12 times more accurate in
    // truncation, so the difference measures the default's error, at crossings and
    // half-lengths and over |u|, |v| ≤ 2 (fold included).
    let net = HemisphereNet::new(1.0, 12);
    let fine = HemisphereNet::with_scheme(
        1.0,
        12,
        Scheme {
            step: 0.1,
            levels: 8,
        },
    );
    for i in 0..12 {
        assert!((net.half_lengths[i] - fine.half_lengths[i]).abs() <= 1e-13);
        assert!(max_abs_diff(net.end_point(i, true), fine.end_point(i, true)) <= 1e-13);
        for j in 0..12 {
            assert!(max_abs_diff(net.crossing(i, j), fine.crossing(i, j)) <= 1e-13);
        }
    }
    for (u, v) in samples(200, 2.0) {
        assert!(
            max_abs_diff(net.point(u, v), fine.point(u, v)) <= 1e-13,
            "({u}, {v})"
        );
    }
}

#[test]
fn smallest_nets_are_the_generators() {
    let net = HemisphereNet::new(3.0, 1);
    assert_eq!(net.offsets, vec![0.0]);
    assert_eq!(net.crossing(0, 0), [0.0, 0.0, 3.0]);
    assert!((net.half_lengths[0] - 1.5 * PI).abs() <= 1e-13 * 3.0);
    assert!(max_abs_diff(net.end_point(0, true), [3.0, 0.0, 0.0]) <= 1e-13 * 3.0);

    let net = HemisphereNet::new(1.0, 2);
    assert!((net.offsets[1] - PI / 6.0).abs() <= 1e-16);
    assert!(net.crossing_inside(0, 1) && net.crossing_inside(1, 1));
}

#[test]
fn unreachable_parameters_give_nan() {
    let net = HemisphereNet::new(1.0, 4);
    for (u, v) in [
        (f64::NAN, 0.0),
        (0.0, f64::INFINITY),
        (1e9, 0.3),
        (0.2, -65.0),
    ] {
        assert!(net.point(u, v).iter().all(|c| c.is_nan()));
    }
    let pts = net.rod_points(1, &[0.1, f64::NEG_INFINITY, 1e12]);
    assert!(pts[0].iter().all(|c| c.is_finite()));
    assert!(pts[1..].iter().flatten().all(|c| c.is_nan()));
}

#[test]
#[should_panic(expected = "at least one rod")]
fn zero_rods_panics() {
    let _ = HemisphereNet::new(1.0, 0);
}

#[test]
#[should_panic(expected = "positive and finite")]
fn non_positive_radius_panics() {
    let _ = HemisphereNet::new(0.0, 3);
}

#[test]
#[should_panic(expected = "positive and finite")]
fn non_finite_radius_panics() {
    let _ = HemisphereNet::new(f64::NAN, 3);
}
