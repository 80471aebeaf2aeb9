//! Node-table capacity is a const generic: the firmware's default (16 nodes) and the host's
//! 256 nodes (a profile exported from an optimal-control solver), with a typed error beyond.

use guidance_core::energy::{EARTH_MU_M3_S2, EARTH_RADIUS_M, EnergyNormalizer};
use guidance_core::guidance::{Command, Guidance, GuidanceConfig, HostGuidance};
use guidance_core::interp::{Interpolation, Interpolator};
use guidance_core::nodes::{
    AngleBounds, DEFAULT_NODE_CAPACITY, HOST_NODE_CAPACITY, HostNodeTable, Independent, Node,
    NodeTable, NodeTableError,
};
use guidance_core::{GuidanceError, NavState};

const DEG: f64 = std::f64::consts::PI / 180.0;

/// A smooth time-indexed profile of `n` nodes over 0..1275 s: alpha 40 -> 15 deg, bank a
/// slow sine between 20 and 70 deg (what a collocation solver might export).
fn profile(n: usize) -> Vec<Node<f64>> {
    (0..n)
        .map(|i| {
            let u = i as f64 / (n - 1) as f64;
            Node {
                x: 1275.0 * u,
                alpha_rad: (40.0 - 25.0 * u) * DEG,
                sigma_rad: (45.0 + 25.0 * (6.0 * u).sin()) * DEG,
            }
        })
        .collect()
}

fn bounds() -> AngleBounds<f64> {
    AngleBounds::thesis_default()
}

fn energy() -> EnergyNormalizer<f64> {
    EnergyNormalizer::new(
        EARTH_MU_M3_S2,
        EARTH_RADIUS_M,
        EARTH_RADIUS_M + 122_000.0,
        7435.5,
    )
    .unwrap()
}

fn nav(t: f64) -> NavState<f64> {
    NavState {
        time_s: t,
        radius_m: EARTH_RADIUS_M + 80_000.0,
        speed_m_s: 7000.0,
        flight_path_angle_rad: 0.0,
        heading_rad: 0.0,
        latitude_rad: 0.0,
        longitude_rad: 0.0,
    }
}

// The host takes at least 256 nodes; the firmware keeps 16 (checked at compile time).
const _: () = assert!(HOST_NODE_CAPACITY >= 256 && DEFAULT_NODE_CAPACITY == 16);

/// 256 nodes build in the host table; every node is reproduced exactly by all three
/// interpolants, and between nodes the linear interpolant is the chord of its segment.
#[test]
fn a_256_node_table_builds_and_interpolates() {
    let nodes = profile(256);
    let t = HostNodeTable::new(Independent::TimeS, &nodes, bounds()).unwrap();
    assert_eq!(t.len(), 256);
    assert_eq!(t.interior().len(), 254);
    for kind in [
        Interpolation::Linear,
        Interpolation::NaturalCubic,
        Interpolation::CardinalHermite { tension: 0.3 },
    ] {
        let i = Interpolator::new(&t, kind).unwrap();
        for n in &nodes {
            let c = i.evaluate(n.x);
            assert_eq!(
                (c.alpha_rad, c.sigma_rad),
                (n.alpha_rad, n.sigma_rad),
                "{kind:?}"
            );
        }
        // Between nodes 200 and 201 the splines stay within a hair of the chord (smooth data).
        let (a, b) = (nodes[200], nodes[201]);
        let mid = i.evaluate(0.5 * (a.x + b.x));
        let chord = 0.5 * (a.sigma_rad + b.sigma_rad);
        let tol = if kind == Interpolation::Linear {
            1e-15
        } else {
            1e-4
        };
        assert!((mid.sigma_rad - chord).abs() <= tol, "{kind:?}: {mid:?}");
    }
}

/// The 256-node table flies in `Guidance` (host capacity): every tick's command is the
/// interpolated value rate-limited against the previous one, inside the bounds, finite.
#[test]
fn a_256_node_table_flies_in_guidance() {
    let nodes = profile(256);
    let table = HostNodeTable::new(Independent::TimeS, &nodes, bounds()).unwrap();
    let reference = Interpolator::new(&table, Interpolation::NaturalCubic).unwrap();
    let mut g: HostGuidance<f64> = Guidance::new(
        GuidanceConfig::thesis_default(),
        table,
        Interpolation::NaturalCubic,
        energy(),
        Command::from_deg(40.0, 45.0).unwrap(),
    )
    .unwrap();
    let (da, ds) = (5.0 * DEG * 2.0, 15.0 * DEG * 2.0);
    let mut prev = g.command();
    for k in 0..=640 {
        let t = 2.0 * f64::from(k);
        let out = g.update(&nav(t)).unwrap();
        assert!(out.ticked);
        let want = reference.evaluate(t);
        let c = out.command;
        let clamp = |p: f64, w: f64, d: f64| w.clamp(p - d, p + d);
        assert_eq!(
            c.alpha_rad,
            clamp(prev.alpha_rad, want.alpha_rad, da),
            "t = {t}"
        );
        assert_eq!(
            c.sigma_rad,
            clamp(prev.sigma_rad, want.sigma_rad, ds),
            "t = {t}"
        );
        assert!(bounds().alpha_ok(c.alpha_rad) && bounds().sigma_ok(c.sigma_rad));
        prev = c;
    }
    // The slow profile never needs the limiter: the command followed the table to its end.
    assert_eq!(g.command().sigma_rad, nodes[255].sigma_rad);
}

/// One node more than the capacity is a typed error, for the default and the host capacity;
/// node indices beyond 255 are reported as they are.
#[test]
fn capacity_overflow_is_a_typed_error() {
    let e = Independent::TimeS;
    let nodes = profile(HOST_NODE_CAPACITY + 1);
    assert_eq!(
        HostNodeTable::new(e, &nodes, bounds()),
        Err(NodeTableError::TooManyNodes)
    );
    assert_eq!(
        NodeTable::<f64>::new(e, &nodes[..DEFAULT_NODE_CAPACITY + 1], bounds()),
        Err(NodeTableError::TooManyNodes)
    );
    assert!(NodeTable::<f64>::new(e, &nodes[..DEFAULT_NODE_CAPACITY], bounds()).is_ok());
    // A fixed-end table with too many interior nodes, and the row constructor, too.
    let interior = &nodes[1..HOST_NODE_CAPACITY];
    assert_eq!(
        HostNodeTable::with_fixed_ends(e, nodes[0], interior, nodes[HOST_NODE_CAPACITY], bounds()),
        Err(NodeTableError::TooManyNodes)
    );
    let rows: Vec<(f64, f64, f64)> = (0..=DEFAULT_NODE_CAPACITY)
        .map(|i| (i as f64, 10.0, 10.0))
        .collect();
    assert_eq!(
        NodeTable::<f64>::from_deg(e, &rows, bounds()),
        Err(NodeTableError::TooManyNodes)
    );
    // Guidance reports it as a guidance error.
    let err: GuidanceError = NodeTableError::TooManyNodes.into();
    assert_eq!(err, GuidanceError::NodeTable(NodeTableError::TooManyNodes));
    // Node indices are reported as they are (u16: no saturation at 255 in a wider table).
    let mut big = profile(HOST_NODE_CAPACITY);
    big[250].sigma_rad = 95.0 * DEG;
    assert_eq!(
        HostNodeTable::new(e, &big, bounds()),
        Err(NodeTableError::SigmaOutOfBounds { index: 250 })
    );
    let wide = NodeTable::<f64, 512>::new(e, &profile(400), bounds()).unwrap();
    assert_eq!(wide.len(), 400);
    let mut bad = profile(400);
    bad[300].x = bad[299].x;
    assert_eq!(
        NodeTable::<f64, 512>::new(e, &bad, bounds()),
        Err(NodeTableError::NotMonotone { index: 300 })
    );
}
