//! The trajectory CSV: one row per sample, units in the column names.

use std::fmt::Write as _;

use crate::sim::{Sample, SampleKind};

/// Trajectory CSV with labelled units, one row per sample.
#[must_use]
pub fn trajectory_csv(samples: &[Sample]) -> String {
    let mut s = String::from(
        "time_s,altitude_km,longitude_deg,latitude_deg,speed_m_s,gamma_deg,heading_deg,mach,\
         density_kg_m3,dynamic_pressure_pa,alpha_deg,sigma_deg,cl,cd,lift_n,drag_n,\
         heat_flux_kw_m2,heat_load_mj_m2,g_load,normalized_energy,flown_range_deg,event\n",
    );
    for p in samples {
        let c = &p.conditions;
        let st = &p.state;
        let ev = match p.kind {
            SampleKind::Start => "start",
            SampleKind::Output => "",
            SampleKind::Exit => "exit",
            SampleKind::Entry => "entry",
            SampleKind::End => "end",
        };
        let _ = writeln!(
            s,
            "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6e},{:.6},{:.6},{:.6},{:.6},{:.6},{:.3},{:.3},{:.6},{:.6},{:.6},{:.8},{:.6},{}",
            p.time_s,
            c.altitude_m / 1e3,
            st.longitude_rad.to_degrees(),
            st.latitude_rad.to_degrees(),
            st.speed_m_s,
            st.flight_path_angle_rad.to_degrees(),
            st.heading_rad.to_degrees(),
            c.mach,
            c.density_kg_m3,
            c.dynamic_pressure_pa,
            p.attitude.alpha_rad.to_degrees(),
            p.attitude.sigma_rad.to_degrees(),
            c.cl,
            c.cd,
            c.lift_n,
            c.drag_n,
            c.heat_flux_w_m2 / 1e3,
            p.heat_load_j_m2 / 1e6,
            c.g_load,
            p.normalized_energy,
            p.flown_range_rad.to_degrees(),
            ev
        );
    }
    s
}
