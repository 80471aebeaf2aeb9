//! The figures of a synthetic mode: every file written and non-empty, the PNGs decodable,
//! the SVGs carrying their marks.

use super::*;

fn report(n: u32) -> ModeReport {
    let flights = (0..n)
        .map(|i| {
            let t = f64::from(i);
            Flight {
                id: i,
                miss_km: (t * 0.37).sin().abs() * 3.0 + t / 100.0,
                downrange_km: (t * 0.37).sin() * 3.0,
                crossrange_km: (t * 0.11).cos(),
                limit_ratios: [0.8 + 0.003 * t, 0.7, 1.1 - 0.002 * t],
            }
        })
        .collect::<Vec<_>>();
    let traces = worst::worst_flights(&flights, TRACED_WORST)
        .into_iter()
        .map(|i| {
            let f = &flights[i];
            ErrorTrace {
                id: f.id,
                miss_km: f.miss_km,
                points: (0..=100)
                    .map(|k| {
                        let s = f64::from(100 - k) * 10.0;
                        TracePoint {
                            time_to_go_s: s,
                            downrange_km: f.downrange_km * (1.0 + s / 500.0),
                            crossrange_km: f.crossrange_km + (s / 100.0).sin(),
                        }
                    })
                    .collect(),
            }
        })
        .collect();
    ModeReport {
        scenario: "srm-glide".into(),
        mode: "replan-estimation".into(),
        flights,
        failed: 1,
        nominal_km: Some((0.1, -0.2)),
        traces,
        trace_reference: [
            "to the undispersed flight".into(),
            "off the great circle".into(),
        ],
    }
}

#[test]
fn every_figure_is_written_in_both_formats() {
    let r = report(200);
    let files = mode_figures(&r).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    for stem in figure_stems("replan-estimation") {
        for ext in ["svg", "png"] {
            let name = format!("{stem}.{ext}");
            let (_, bytes) = files.iter().find(|(n, _)| *n == name).unwrap_or_else(|| {
                panic!("{name} missing from {names:?}");
            });
            assert!(bytes.len() > 1000, "{name}: {} bytes", bytes.len());
            if ext == "png" {
                assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{name}");
                let dec = png::Decoder::new(std::io::Cursor::new(bytes.clone()));
                let info = dec.read_info().unwrap();
                assert!(info.info().width >= 900, "{name}");
            }
        }
    }
    let svg = |stem: &str| {
        let (_, b) = files
            .iter()
            .find(|(n, _)| n == &format!("{stem}-replan-estimation.svg"))
            .unwrap();
        String::from_utf8(b.clone()).unwrap()
    };
    let fp = svg("footprint");
    for needle in [
        "1-sigma",
        "2-sigma",
        "3-sigma",
        "target",
        "downrange error [km]",
        "200 flights, 1 failed",
    ] {
        assert!(fp.contains(needle), "footprint: {needle}");
    }
    // The five worst cases are labelled with their id.
    for i in worst::worst_flights(&r.flights, LABELLED_WORST) {
        assert!(fp.contains(&format!("#{}", r.flights[i].id)), "case {i}");
    }
    let cdf = svg("miss-cdf");
    let p = miss_cdf::marked_percentiles(&r).unwrap();
    for (name, v) in ["p50", "p90", "p99", "p99.9"].into_iter().zip(p) {
        assert!(cdf.contains(&format!("{name} = {v:.2} km")), "cdf: {name}");
    }
    let lim = svg("limit-ratios");
    for q in limits::QUANTITIES {
        assert!(lim.contains(&format!("peak {q} / limit")), "{q}");
    }
    // Heat flux: 0.8 + 0.003 i > 1 for i >= 67: 133 over; g-load rate 1.1 - 0.002 i > 1 for
    // i < 50: 50 over.
    assert!(lim.contains("worst 1.397, 133 over"), "heat flux count");
    assert!(lim.contains("g-load, worst 0.700, 0 over"));
    assert!(lim.contains("g-load rate, worst 1.100, 50 over"));
    let ttg = svg("errors-time-to-go");
    assert!(ttg.contains("time to go [s]") && ttg.contains("crossrange error [km]"));
    // One legend (the crossrange panel's) names each flight.
    assert_eq!(ttg.matches("(miss ").count(), TRACED_WORST);
}

/// A mode without flights (all failed) still draws its figures.
#[test]
fn empty_mode_draws() {
    let mut r = report(0);
    r.failed = 3;
    let files = mode_figures(&r).unwrap();
    assert_eq!(files.len(), 8);
    assert!(files.iter().all(|(_, b)| !b.is_empty()));
}

/// `REPORT_FIGURES_DIR=DIR cargo test -p host-sim --lib report::campaign` writes the
/// synthetic figures to DIR to look at.
#[test]
fn write_figures_to_look_at() {
    if let Some(dir) = std::env::var_os("REPORT_FIGURES_DIR") {
        for (name, bytes) in mode_figures(&report(200)).unwrap() {
            std::fs::write(std::path::Path::new(&dir).join(name), bytes).unwrap();
        }
    }
}

/// The miss axis is logarithmic for a tail beyond 20 times the median, linear otherwise.
#[test]
fn miss_axis_is_logarithmic_for_a_heavy_tail() {
    let mut r = report(100);
    assert!(!miss_cdf::figure(&r).panels[0].x_log10);
    let median = miss_cdf::marked_percentiles(&r).unwrap()[0];
    r.flights[7].miss_km = 25.0 * median;
    let f = miss_cdf::figure(&r);
    assert!(f.panels[0].x_log10);
    assert!(f.svg("cdf.svg").unwrap().contains("(logarithmic)"));
}
